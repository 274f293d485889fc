// Orientation (seed Def 47-49): consistent orientation by flipping, proof cycles for
// non-orientable meshes, outward orientation by signed volume, edge-connected components.

#include "meshes/orientation.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "tests/meshes/mesh_generators.h"
#include "tests/meshes/reference_topology.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

// The unit cube, quads counter-clockwise seen from outside.
FaceVertexMesh unit_cube() { return sphere({}).mesh; }

std::vector<FaceId> face_ids(std::initializer_list<std::uint32_t> faces) {
  std::vector<FaceId> ids;
  for (std::uint32_t f : faces) ids.push_back(FaceId(f));
  return ids;
}

// Relabelled, reordered and rotated, but no face flipped: the orientation of the input.
FaceVertexMesh shuffled(const FaceVertexMesh& mesh, Random& random) {
  FaceVertexMesh result = relabel_vertices(mesh, random_permutation(mesh.vertex_count(), random));
  result = reorder_faces(result, random_permutation(result.face_count(), random));
  std::vector<std::uint32_t> shift(result.face_count());
  for (std::uint32_t& s : shift) s = random.below(8);
  return rotate_corners(result, shift);
}

TEST(Orientation, FlipsTheFaceThatDisagrees) {
  // (0,1,2) and (0,3,2) both walk the diagonal from 2 to 0; the second face is flipped to (0,2,3).
  const FaceVertexMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  const Orientation result = orient(mesh);
  EXPECT_EQ(result.flipped, face_ids({1}));
  EXPECT_EQ(result.mesh, make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(result.component_orientable, std::vector<bool>{true});
  EXPECT_TRUE(result.non_orientable_cycles.empty());
}

TEST(Orientation, FirstFaceOfEachComponentKeepsItsOrientation) {
  // A cube with every face but the first reversed: those five are flipped back.
  std::vector<bool> flip(6, true);
  flip[0] = false;
  const Orientation result = orient(flip_faces(unit_cube(), flip));
  EXPECT_EQ(result.flipped, face_ids({1, 2, 3, 4, 5}));
  EXPECT_EQ(result.mesh, unit_cube());
  // With the first face reversed instead, the other five follow it: the whole cube inside out.
  std::vector<bool> first(6, false);
  first[0] = true;
  const Orientation inside_out = orient(flip_faces(unit_cube(), first));
  EXPECT_EQ(inside_out.flipped, face_ids({1, 2, 3, 4, 5}));
  EXPECT_EQ(inside_out.mesh, flip_faces(unit_cube(), std::vector<bool>(6, true)));
  EXPECT_EQ(signed_volume(inside_out.mesh), -1.0);
}

TEST(Orientation, MoebiusBandIsReportedWithItsCycle) {
  const FaceVertexMesh band = mobius_band(2, 5).mesh;
  const Orientation result = orient(band);
  EXPECT_EQ(result.component_orientable, std::vector<bool>{false});
  ASSERT_EQ(result.non_orientable_cycles.size(), 1u);
  EXPECT_TRUE(proves_non_orientable(band, result.non_orientable_cycles[0]));
  EXPECT_TRUE(proves_non_orientable(result.mesh, result.non_orientable_cycles[0]));
  // The band's quads come in 5 columns; a cycle around the band passes through all of them.
  EXPECT_GE(result.non_orientable_cycles[0].size(), 5u);
  // The hemi-cube's faces share two edges each: a two-face cycle proves it.
  const FaceVertexMesh hemi = hemi_cube().mesh;
  const Orientation hemi_result = orient(hemi);
  ASSERT_EQ(hemi_result.non_orientable_cycles.size(), 1u);
  EXPECT_TRUE(proves_non_orientable(hemi, hemi_result.non_orientable_cycles[0]));
}

TEST(Orientation, SignedVolumeOfClosedForms) {
  EXPECT_EQ(signed_volume(unit_cube()), 1.0);
  // Integer lattice points: every determinant is an exact integer, so the volume is exact.
  EXPECT_EQ(signed_volume(sphere({2, 3, 4}).mesh), 24.0);
  EXPECT_EQ(signed_volume(genus_surface(2, {1, 1, 1}).mesh), 13.0);  // 5g + 3 voxels
  const FaceVertexMesh tetrahedron =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  // Four cones from the origin: three are flat (exactly 0), one is det = 1 divided by 6.
  EXPECT_EQ(signed_volume(tetrahedron), 1.0 / 6.0);
  // Translation does not change the volume of a closed surface (exact for these coordinates).
  std::vector<Vec3> points = points_of(unit_cube());
  for (Vec3& p : points) p += Vec3(3, -5, 7);
  EXPECT_EQ(signed_volume(make_mesh(points, faces_of(unit_cube()))), 1.0);
}

TEST(Orientation, OutwardFlipsInsideOutClosedComponentsOnly) {
  const FaceVertexMesh inside_out = flip_faces(unit_cube(), std::vector<bool>(6, true));
  const Orientation result = orient_outward(inside_out);
  EXPECT_EQ(result.mesh, unit_cube());
  EXPECT_EQ(result.flipped, face_ids({0, 1, 2, 3, 4, 5}));
  // Faces 0 and 2 reversed: orient() follows face 0 (five flips), then the volume is negative and
  // everything flips: net against the input, faces 0 and 2.
  std::vector<bool> two(6, false);
  two[0] = two[2] = true;
  const Orientation net = orient_outward(flip_faces(unit_cube(), two));
  EXPECT_EQ(net.mesh, unit_cube());
  EXPECT_EQ(net.flipped, face_ids({0, 2}));
  // An outward cube beside an inside-out one: only the second is flipped.
  const KnownSurface cubes = disjoint_union(sphere({}), {"inside out", inside_out, 2, 0, 1, true, 0, std::nullopt});
  const Orientation both = orient_outward(cubes.mesh);
  EXPECT_EQ(both.flipped, face_ids({6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(signed_volume(both.mesh), 2.0);
  // An open surface has no inside: a disk facing -z stays as it is.
  const FaceVertexMesh down = flip_faces(disk(2, 2).mesh, std::vector<bool>(4, true));
  EXPECT_EQ(orient_outward(down).mesh, down);
  EXPECT_TRUE(orient_outward(down).flipped.empty());
}

TEST(Orientation, ComponentsAreNumberedBySmallestFace) {
  // Faces interleaved from a torus (T) and a cube (C): T C T C ... T T T.
  const KnownSurface both = disjoint_union(sphere({}), torus(3, 3));
  std::vector<std::uint32_t> order;
  for (std::uint32_t k = 0; k < 6; ++k) {
    order.push_back(6 + k);
    order.push_back(k);
  }
  for (std::uint32_t k = 12; k < 15; ++k) order.push_back(k);
  const std::vector<std::uint32_t> component = face_components(reorder_faces(both.mesh, order));
  std::vector<std::uint32_t> expected;
  for (std::uint32_t k = 0; k < 6; ++k) {
    expected.push_back(0);  // the torus has face 0
    expected.push_back(1);
  }
  for (int k = 0; k < 3; ++k) expected.push_back(0);
  EXPECT_EQ(component, expected);
  EXPECT_TRUE(face_components(FaceVertexMesh()).empty());
  EXPECT_TRUE(orient(FaceVertexMesh()).component_orientable.empty());
}

RC_GTEST_PROP(Orientation, RestoresRandomFlipsFollowingEachComponentsFirstFace, ()) {
  Random random(*seed());
  KnownSurface surface = orientable_surface(random, 2);
  if (random.coin()) surface = disjoint_union(surface, orientable_surface(random, 1));
  const FaceVertexMesh oriented = shuffled(surface.mesh, random);
  RC_ASSERT(consistently_oriented(oriented));  // the generators build oriented surfaces
  const std::vector<bool> flags = random_flags(oriented.face_count(), random);
  const Orientation result = orient(flip_faces(oriented, flags));
  // Expected: face f ends up as its component's first face was given.
  const std::vector<std::uint32_t> component = reference_components(oriented);
  std::vector<std::int64_t> first(static_cast<std::size_t>(surface.components), -1);
  std::vector<bool> keep(oriented.face_count());
  std::vector<FaceId> expected_flipped;
  for (std::uint32_t f = 0; f < oriented.face_count(); ++f) {
    if (first[component[f]] < 0) first[component[f]] = f;
    keep[f] = flags[static_cast<std::size_t>(first[component[f]])];
    if (flags[f] != keep[f]) expected_flipped.push_back(FaceId(f));
  }
  RC_ASSERT(result.mesh == flip_faces(oriented, keep));
  RC_ASSERT(result.flipped == expected_flipped);
  RC_ASSERT(result.component_orientable == std::vector<bool>(static_cast<std::size_t>(surface.components), true));
  RC_ASSERT(result.non_orientable_cycles.empty());
}

RC_GTEST_PROP(Orientation, MakesSharedEdgesOppositeAndIsIdempotent, ()) {
  Random random(*seed());
  const KnownSurface surface = orientable_surface(random, 2);
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const Orientation once = orient(mesh);
  RC_ASSERT(consistently_oriented(once.mesh));  // Def 47
  const Orientation twice = orient(once.mesh);
  RC_ASSERT(twice.flipped.empty());
  RC_ASSERT(twice.mesh == once.mesh);
  // Only the corner order changed: same sizes, same first corners, same corner sets.
  RC_ASSERT(once.mesh.face_sizes() == mesh.face_sizes());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    RC_ASSERT(once.mesh.face(f)[0] == mesh.face(f)[0]);
    std::vector<std::uint32_t> a(mesh.face(f).begin(), mesh.face(f).end()),
        b(once.mesh.face(f).begin(), once.mesh.face(f).end());
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    RC_ASSERT(a == b);
  }
}

RC_GTEST_PROP(Orientation, OutwardRestoresClosedSurfacesExactly, ()) {
  Random random(*seed());
  KnownSurface surface = closed_orientable_surface(random, 2);
  if (random.coin()) surface = disjoint_union(surface, closed_orientable_surface(random, 1));
  const FaceVertexMesh outward = shuffled(surface.mesh, random);
  // Lattice coordinates: every determinant is an exact integer, so the volume is exact.
  RC_ASSERT(signed_volume(outward) == *surface.volume);
  RC_ASSERT(orient_outward(outward).flipped.empty());
  const std::vector<bool> flags = random_flags(outward.face_count(), random);
  const Orientation result = orient_outward(flip_faces(outward, flags));
  RC_ASSERT(result.mesh == outward);
  std::vector<FaceId> expected;
  for (std::uint32_t f = 0; f < flags.size(); ++f) {
    if (flags[f]) expected.push_back(FaceId(f));
  }
  RC_ASSERT(result.flipped == expected);
  RC_ASSERT(signed_volume(result.mesh) > 0.0);
}

RC_GTEST_PROP(Orientation, NonOrientableComponentsComeWithAProof, ()) {
  Random random(*seed());
  KnownSurface surface = non_orientable_surface(random);
  if (random.coin()) surface = disjoint_union(surface, any_surface(random, 1));
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const Orientation result = orient(mesh);
  const auto non_orientable = std::count(result.component_orientable.begin(), result.component_orientable.end(), false);
  RC_ASSERT(non_orientable >= 1);
  RC_ASSERT(result.non_orientable_cycles.size() == static_cast<std::size_t>(non_orientable));
  for (const auto& cycle : result.non_orientable_cycles) {
    RC_ASSERT(proves_non_orientable(mesh, cycle));
    RC_ASSERT(proves_non_orientable(result.mesh, cycle));  // flips cannot undo a proof
  }
  // Orientable components still come out consistent: edges with an inconsistent pair of walks
  // lie in non-orientable components only.
  const std::vector<std::uint32_t> component = face_components(mesh);
  for (const auto& [key, walks] : edge_walks(result.mesh)) {
    if (walks.size() == 2 && walks[0].from == walks[1].from) {
      RC_ASSERT(!result.component_orientable[component[walks[0].face]]);
    }
  }
}

RC_GTEST_PROP(Orientation, ComponentsMatchAReferenceUnionFind, ()) {
  Random random(*seed());
  KnownSurface surface = any_surface(random, 1);
  for (int extra = random_int(random, 0, 2); extra > 0; --extra) {
    surface = disjoint_union(surface, any_surface(random, 1), Vec3(0, 0, 50.0 * extra));
  }
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const std::vector<std::uint32_t> component = face_components(mesh);
  RC_ASSERT(component == reference_components(mesh));
  RC_ASSERT(static_cast<Count>(*std::max_element(component.begin(), component.end()) + 1) == surface.components);
}

// The flips, the orientability and the proof cycles are those of the plain breadth-first walk
// (orient() only walks breadth-first where a class is non-orientable), on any soup.
RC_GTEST_PROP(Orientation, MatchesTheBreadthFirstReferenceOnAnySoup, ()) {
  Random random(*seed());
  const FaceVertexMesh mesh = any_soup(random);
  const Orientation result = orient(mesh);
  const Orientation reference = reference_orient(mesh);
  RC_CLASSIFY(!reference.non_orientable_cycles.empty(), "non-orientable");
  RC_ASSERT(result.flipped == reference.flipped);
  RC_ASSERT(result.component_orientable == reference.component_orientable);
  RC_ASSERT(result.non_orientable_cycles == reference.non_orientable_cycles);
  RC_ASSERT(face_components(mesh) == reference_components(mesh));
}

}  // namespace
}  // namespace patchwork
