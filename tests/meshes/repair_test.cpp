// Repair of polygon soups: degenerate corners merged, non-manifold vertices and edges split,
// orientation made consistent where possible, every change reported and no face lost.

#include "meshes/repair.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>

#include "meshes/halfedge_mesh.h"
#include "meshes/topology.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

// A face's corners with consecutive repeats merged (cyclically): step 1 of repair().
std::vector<std::uint32_t> merged(std::span<const std::uint32_t> face) {
  std::vector<std::uint32_t> corners;
  for (std::uint32_t v : face) {
    if (corners.empty() || corners.back() != v) corners.push_back(v);
  }
  while (corners.size() > 1 && corners.front() == corners.back()) corners.pop_back();
  return corners;
}

std::size_t distinct_corners(std::span<const std::uint32_t> face) {
  return std::set<std::uint32_t>(face.begin(), face.end()).size();
}

// Checks everything a repair report promises against its input; returns "" or what is wrong.
std::string check_report(const FaceVertexMesh& input, const RepairReport& r) {
  const FaceVertexMesh& out = r.mesh;
  // No face lost: every input face is kept (in order) or listed as removed, and only faces with
  // fewer than 3 distinct corners are removed.
  std::vector<std::uint32_t> all = r.face_source;
  all.insert(all.end(), r.removed_faces.begin(), r.removed_faces.end());
  std::sort(all.begin(), all.end());
  std::vector<std::uint32_t> every(input.face_count());
  for (std::uint32_t f = 0; f < every.size(); ++f) every[f] = f;
  if (all != every) return "faces kept and removed do not partition the input";
  if (!std::is_sorted(r.face_source.begin(), r.face_source.end())) return "face order changed";
  if (out.face_count() != r.face_source.size()) return "face_source size";
  for (std::uint32_t f : r.removed_faces) {
    if (distinct_corners(input.face(f)) >= 3) return "removed face " + std::to_string(f) + " had 3 distinct corners";
  }
  // Vertices: the input's first, copies appended, each at its source's position.
  if (r.source_vertex.size() != out.vertex_count()) return "source_vertex size";
  for (std::uint32_t v = 0; v < out.vertex_count(); ++v) {
    if (v < input.vertex_count() && r.source_vertex[v] != v) return "input vertex renumbered";
    if (out.position(v) != input.position(r.source_vertex[v])) return "position moved";
  }
  std::set<std::uint32_t> split;
  for (std::uint32_t v = static_cast<std::uint32_t>(input.vertex_count()); v < out.vertex_count(); ++v) {
    split.insert(r.source_vertex[v]);
  }
  if (std::vector<std::uint32_t>(split.begin(), split.end()) != r.split_vertices) return "split_vertices wrong";
  // Each kept face is its input face, merged, maybe flipped (first corner first), through source_vertex.
  const std::set<std::uint32_t> flipped(r.flipped_faces.begin(), r.flipped_faces.end());
  std::set<std::uint32_t> merged_faces;
  for (std::uint32_t f = 0; f < out.face_count(); ++f) {
    const std::uint32_t source = r.face_source[f];
    std::vector<std::uint32_t> expected = merged(input.face(source));
    if (expected.size() != input.face(source).size()) merged_faces.insert(source);
    if (flipped.count(source) != 0) std::reverse(expected.begin() + 1, expected.end());
    std::vector<std::uint32_t> got;
    for (std::uint32_t v : out.face(f)) got.push_back(r.source_vertex[v]);
    if (got != expected) return "face " + std::to_string(f) + " does not match input face " + std::to_string(source);
  }
  merged_faces.insert(r.removed_faces.begin(), r.removed_faces.end());  // < 3 corners left of >= 3
  if (std::vector<std::uint32_t>(merged_faces.begin(), merged_faces.end()) != r.merged_corner_faces) {
    return "merged_corner_faces wrong";
  }
  // The result is a manifold; oriented when orientable, and then a half-edge mesh.
  const TopologyReport topology = analyze(out);
  if (!topology.manifold) return "result is not a manifold";
  if (topology.orientable != r.orientable) return "orientable disagrees with analyze()";
  if (r.orientable) {
    if (!consistently_oriented(out)) return "result not consistently oriented";
    HalfedgeMesh built(out);
    built.validate();
  } else {
    for (const auto& cycle : r.non_orientable_cycles) {
      if (!proves_non_orientable(out, cycle)) return "a non-orientable cycle proves nothing";
    }
    if (r.non_orientable_cycles.empty()) return "non-orientable without a cycle";
  }
  return "";
}

TEST(Repair, CleanMeshIsLeftAlone) {
  const FaceVertexMesh mesh = torus(3, 4).mesh;
  const RepairReport r = repair(mesh);
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(r.mesh, mesh);
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(check_report(mesh, r), "");
  EXPECT_EQ(describe(r), "nothing to repair\n");
}

TEST(Repair, BowtieVertexIsSplit) {
  const RepairReport r = repair(bowtie());
  EXPECT_EQ(check_report(bowtie(), r), "");
  EXPECT_EQ(r.split_vertices, std::vector<std::uint32_t>{0});
  EXPECT_EQ(r.mesh.vertex_count(), 6u);
  EXPECT_EQ(faces_of(r.mesh), (FaceList{{0, 1, 2}, {5, 3, 4}}));  // the second fan gets the copy
  EXPECT_TRUE(r.changed());
  EXPECT_NE(describe(r).find("vertices split (non-manifold or pinched) (1): 0"), std::string::npos) << describe(r);
}

TEST(Repair, BookOfThreePagesFallsApart) {
  // Three triangles on edge (0,1): joined only across edges of exactly two faces, each page is
  // its own fan at 0 and at 1: three separate triangles, chi = 3.
  const RepairReport r = repair(book());
  EXPECT_EQ(check_report(book(), r), "");
  EXPECT_EQ(r.split_vertices, (std::vector<std::uint32_t>{0, 1}));
  const TopologyReport t = analyze(r.mesh);
  EXPECT_EQ(t.components, 3);
  EXPECT_EQ(t.euler, 3);
  EXPECT_EQ(t.vertices, 9);
}

TEST(Repair, PinchedSpheresComeApart) {
  // Two cubes glued at one corner (two closed fans at vertex 0): split into two spheres.
  KnownSurface two = disjoint_union(sphere({}), sphere({}), Vec3(-1, -1, -1));
  // The second cube spans [-1, 0]^3: its corner at the origin is glued to the first cube's.
  FaceList faces = faces_of(two.mesh);
  std::uint32_t outer = 0, inner = 0;
  for (std::uint32_t v = 0; v < two.mesh.vertex_count(); ++v) {
    if (two.mesh.position(v) == Vec3::Zero()) (v < 8 ? outer : inner) = v;
  }
  for (auto& face : faces) std::replace(face.begin(), face.end(), inner, outer);
  const FaceVertexMesh pinched = make_mesh(points_of(two.mesh), faces);
  const TopologyReport before = analyze(pinched);
  EXPECT_EQ(before.non_manifold_vertices, std::vector<std::uint32_t>{outer});
  const RepairReport r = repair(pinched);
  EXPECT_EQ(check_report(pinched, r), "");
  EXPECT_EQ(r.split_vertices, std::vector<std::uint32_t>{outer});
  const TopologyReport after = analyze(r.mesh);
  EXPECT_EQ(after.components, 2);
  EXPECT_EQ(after.euler, 4);
  EXPECT_EQ(after.genus, std::optional<Count>(0));
  EXPECT_TRUE(after.closed);
}

TEST(Repair, DegenerateFacesAreMergedOrRemovedAndListed) {
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  // 0: fine; 1: (a b b c) merges to a triangle; 2: (a a b) and 3: (a b a) and 4: (c c c) keep
  // fewer than 3 corners and go; 5: (a b c a) merges cyclically to (a b c).
  const FaceVertexMesh soup =
      make_mesh(points, {{0, 1, 2}, {0, 2, 2, 3}, {1, 1, 2}, {1, 2, 1}, {3, 3, 3}, {3, 0, 1, 3}});
  const RepairReport r = repair(soup);
  EXPECT_EQ(check_report(soup, r), "");
  EXPECT_EQ(r.removed_faces, (std::vector<std::uint32_t>{2, 3, 4}));
  EXPECT_EQ(r.merged_corner_faces, (std::vector<std::uint32_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(r.face_source, (std::vector<std::uint32_t>{0, 1, 5}));
  EXPECT_EQ(faces_of(r.mesh)[1], (std::vector<std::uint32_t>{0, 2, 3}));
  const std::string text = describe(r);
  EXPECT_NE(text.find("removed faces with fewer than 3 distinct corners (3): 2 3 4"), std::string::npos) << text;
  EXPECT_NE(text.find("faces with repeated corners merged (5): 1 2 3 4 5"), std::string::npos) << text;
}

TEST(Repair, PinchedFaceGetsACopy) {
  // (0 1 0 2) visits 0 twice, not consecutively: the second visit becomes a copy of 0.
  const FaceVertexMesh soup = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 0, 2}});
  const RepairReport r = repair(soup);
  EXPECT_EQ(check_report(soup, r), "");
  EXPECT_EQ(faces_of(r.mesh), (FaceList{{0, 1, 3, 2}}));
  EXPECT_EQ(r.source_vertex, (std::vector<std::uint32_t>{0, 1, 2, 0}));
  EXPECT_EQ(r.split_vertices, std::vector<std::uint32_t>{0});
}

TEST(Repair, FlipsWhatIsOrientableAndReportsTheRest) {
  const FaceVertexMesh square = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  const RepairReport r = repair(square);
  EXPECT_EQ(check_report(square, r), "");
  EXPECT_EQ(r.flipped_faces, std::vector<std::uint32_t>{1});
  EXPECT_TRUE(r.orientable);
  const FaceVertexMesh band = mobius_band(2, 5).mesh;
  const RepairReport b = repair(band);
  EXPECT_EQ(check_report(band, b), "");
  EXPECT_FALSE(b.orientable);
  EXPECT_EQ(b.mesh.face_count(), band.face_count());
  EXPECT_TRUE(b.split_vertices.empty());
  EXPECT_NE(describe(b).find("not orientable: 1 component(s)"), std::string::npos) << describe(b);
}

TEST(Repair, EmptyMesh) {
  const RepairReport r = repair(FaceVertexMesh());
  EXPECT_FALSE(r.changed());
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(r.mesh.face_count(), 0u);
}

RC_GTEST_PROP(Repair, NeverLosesAFaceAndReturnsAManifold, ()) {
  Random random(*seed());
  KnownSurface surface = any_surface(random, 1);
  if (random.coin()) surface = disjoint_union(surface, any_surface(random, 1), Vec3(0, 0, 0));
  const FaceVertexMesh soup = damaged(surface.mesh, random);
  const RepairReport r = repair(soup);
  const std::string problem = check_report(soup, r);
  RC_ASSERT(problem == "");
  // Repairing again finds nothing to split, merge or remove; flips only on non-orientable parts.
  const RepairReport again = repair(r.mesh);
  RC_ASSERT(again.removed_faces.empty());
  RC_ASSERT(again.merged_corner_faces.empty());
  RC_ASSERT(again.split_vertices.empty());
  if (r.orientable) {
    RC_ASSERT(!again.changed());
  }
}

RC_GTEST_PROP(Repair, ChangesNothingButFlipsOnAManifold, ()) {
  Random random(*seed());
  const KnownSurface surface = any_surface(random, 2);
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const RepairReport r = repair(mesh);
  RC_ASSERT(check_report(mesh, r) == "");
  RC_ASSERT(r.removed_faces.empty());
  RC_ASSERT(r.merged_corner_faces.empty());
  RC_ASSERT(r.split_vertices.empty());
  RC_ASSERT(r.mesh.vertex_count() == mesh.vertex_count());
  RC_ASSERT(r.orientable == surface.orientable);
  const TopologyReport t = analyze(r.mesh);
  RC_ASSERT(t.euler == surface.euler);
  RC_ASSERT(t.boundary_loops == surface.boundary_loops);
  RC_ASSERT(t.genus == surface.genus);
}

}  // namespace
}  // namespace patchwork
