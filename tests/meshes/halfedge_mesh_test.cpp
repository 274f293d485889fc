// The half-edge mesh (seed Def 55): construction on small meshes with every link known by hand,
// the TopologyError for each kind of non-manifold input, and the half-edge invariants as
// RapidCheck properties on surfaces of known topology.

#include "meshes/halfedge_mesh.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "core/errors.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

// The message of the TopologyError that building `mesh` throws ("" if it builds).
std::string build_error(const FaceVertexMesh& mesh) {
  return error_message<TopologyError>([&] { HalfedgeMesh built(mesh); });
}

// The half-edge from a to b, found by search (invalid if there is none).
HalfedgeId find_halfedge(const HalfedgeMesh& mesh, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t h = 0; h < mesh.halfedge_count(); ++h) {
    if (mesh.origin(HalfedgeId(h)) == VertexId(a) && mesh.destination(HalfedgeId(h)) == VertexId(b))
      return HalfedgeId(h);
  }
  return HalfedgeId();
}

TEST(HalfedgeMesh, SquareOfTwoTriangles) {
  const HalfedgeMesh mesh(square());
  mesh.validate();
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.edge_count(), 5u);  // four sides and the diagonal
  EXPECT_EQ(mesh.halfedge_count(), 10u);
  EXPECT_EQ(mesh.face_count(), 2u);
  // Edges numbered by first use, half-edge 2e in the direction of that use: 0->1, 1->2, 2->0, 2->3, 3->0.
  EXPECT_EQ(mesh.origin(HalfedgeId(0)), VertexId(0));
  EXPECT_EQ(mesh.destination(HalfedgeId(0)), VertexId(1));
  EXPECT_EQ(mesh.origin(HalfedgeId(4)), VertexId(2));
  EXPECT_EQ(mesh.destination(HalfedgeId(4)), VertexId(0));
  EXPECT_EQ(HalfedgeMesh::twin(HalfedgeId(4)), HalfedgeId(5));
  EXPECT_EQ(HalfedgeMesh::edge(HalfedgeId(5)), EdgeId(2));
  EXPECT_EQ(HalfedgeMesh::halfedge(EdgeId(2), 1), HalfedgeId(5));
  // The diagonal: 2->0 in f0, 0->2 in f1; it is the only interior edge.
  EXPECT_EQ(mesh.face(HalfedgeId(4)), FaceId(0));
  EXPECT_EQ(mesh.face(HalfedgeId(5)), FaceId(1));
  EXPECT_FALSE(mesh.is_boundary(EdgeId(2)));
  for (std::uint32_t e : {0u, 1u, 3u, 4u}) EXPECT_TRUE(mesh.is_boundary(EdgeId(e))) << e;
  // Face cycles.
  EXPECT_EQ(mesh.face_vertices(FaceId(0)), (std::vector<VertexId>{VertexId(0), VertexId(1), VertexId(2)}));
  EXPECT_EQ(mesh.face_vertices(FaceId(1)), (std::vector<VertexId>{VertexId(0), VertexId(2), VertexId(3)}));
  EXPECT_EQ(mesh.face_size(FaceId(1)), 3u);
  EXPECT_EQ(mesh.next(find_halfedge(mesh, 0, 1)), find_halfedge(mesh, 1, 2));
  EXPECT_EQ(mesh.prev(find_halfedge(mesh, 0, 1)), find_halfedge(mesh, 2, 0));
  // The boundary loop runs the other way round: 0 -> 3 -> 2 -> 1 -> 0.
  const HalfedgeId outer = find_halfedge(mesh, 0, 3);
  ASSERT_TRUE(mesh.is_boundary(outer));
  EXPECT_EQ(mesh.next(outer), find_halfedge(mesh, 3, 2));
  EXPECT_EQ(mesh.next(mesh.next(outer)), find_halfedge(mesh, 2, 1));
  EXPECT_EQ(mesh.next(mesh.next(mesh.next(outer))), find_halfedge(mesh, 1, 0));
  EXPECT_EQ(mesh.next(mesh.next(mesh.next(mesh.next(outer)))), outer);
  // On the boundary, a vertex's half-edge is its outgoing boundary half-edge.
  for (std::uint32_t v = 0; v < 4; ++v) {
    EXPECT_TRUE(mesh.is_boundary(VertexId(v)));
    EXPECT_TRUE(mesh.is_boundary(mesh.halfedge(VertexId(v))));
    EXPECT_EQ(mesh.origin(mesh.halfedge(VertexId(v))), VertexId(v));
  }
  // Around 0, from the boundary half-edge towards 3, rotating by twin(prev(h)) from face to face
  // (outer face, f0, f1, each by its half-edge leaving 0): 3, 1, 2, the counter-clockwise order.
  EXPECT_EQ(mesh.vertex_neighbours(VertexId(0)), (std::vector<VertexId>{VertexId(3), VertexId(1), VertexId(2)}));
  EXPECT_EQ(mesh.vertex_neighbours(VertexId(1)), (std::vector<VertexId>{VertexId(0), VertexId(2)}));
}

TEST(HalfedgeMesh, ClosedTetrahedronHasNoBoundary) {
  const HalfedgeMesh mesh(tetrahedron());
  mesh.validate();
  EXPECT_EQ(mesh.edge_count(), 6u);
  for (std::uint32_t h = 0; h < mesh.halfedge_count(); ++h) EXPECT_FALSE(mesh.is_boundary(HalfedgeId(h)));
  for (std::uint32_t v = 0; v < 4; ++v) {
    EXPECT_FALSE(mesh.is_boundary(VertexId(v)));
    std::vector<VertexId> around = mesh.vertex_neighbours(VertexId(v));
    std::sort(around.begin(), around.end());
    std::vector<VertexId> others;
    for (std::uint32_t w = 0; w < 4; ++w) {
      if (w != v) others.push_back(VertexId(w));
    }
    EXPECT_EQ(around, others);
  }
  EXPECT_EQ(to_face_vertex_mesh(mesh), tetrahedron());
}

TEST(HalfedgeMesh, IsolatedVertexHasNoHalfedge) {
  const FaceVertexMesh input = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}}, {{0, 1, 2}});
  const HalfedgeMesh mesh(input);
  mesh.validate();
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_TRUE(mesh.is_isolated(VertexId(3)));
  EXPECT_FALSE(mesh.is_boundary(VertexId(3)));
  EXPECT_FALSE(mesh.halfedge(VertexId(3)).valid());
  EXPECT_TRUE(mesh.vertex_neighbours(VertexId(3)).empty());
  EXPECT_EQ(mesh.position(VertexId(3)), Vec3(5, 5, 5));
  EXPECT_EQ(to_face_vertex_mesh(mesh), input);
}

TEST(HalfedgeMesh, EdgeWithThreeFacesNamesTheEdgeAndFaces) {
  // Three triangles on edge (0,1): a book of three pages.
  const std::string message = build_error(book());
  EXPECT_NE(message.find("edge (0,1) used by 3 faces (0, 1, 2)"), std::string::npos) << message;
}

TEST(HalfedgeMesh, VertexWithTwoFansNamesTheVertexAndFaces) {
  // Two triangles touching at vertex 0 only (a bowtie): two boundary fans at 0.
  const std::string message = build_error(bowtie());
  EXPECT_NE(message.find("vertex 0"), std::string::npos) << message;
  EXPECT_NE(message.find("faces 0, 1"), std::string::npos) << message;
  // Two tetrahedra sharing vertex 0: two closed fans, no boundary at all.
  const std::string closed = build_error(pinched_tetrahedra());
  EXPECT_NE(closed.find("vertex 0"), std::string::npos) << closed;
  EXPECT_NE(closed.find("faces 0, 1, 3, 4, 5, 7"), std::string::npos) << closed;
}

TEST(HalfedgeMesh, FaceRepeatingAVertexIsNamed) {
  const FaceVertexMesh pinched = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 3, 0, 3}});
  const std::string message = build_error(pinched);
  EXPECT_NE(message.find("face 1 uses vertex 3 more than once"), std::string::npos) << message;
}

TEST(HalfedgeMesh, InconsistentOrientationNamesTheFacesAndEdge) {
  // (0,1,2) and (0,2,3) would be consistent; (0,3,2) walks 0 -> 3 -> 2 -> 0, so both faces walk
  // the diagonal from 2 to 0.
  const FaceVertexMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  const std::string message = build_error(mesh);
  EXPECT_NE(message.find("faces 0 and 1 both traverse edge (2,0) from 2"), std::string::npos) << message;
  EXPECT_NE(message.find("inconsistent orientation"), std::string::npos) << message;
}

TEST(HalfedgeMesh, OutOfRangeIndexIsRejectedBeforeBuilding) {
  // A FaceVertexMesh cannot hold an index past its positions, so neither can a HalfedgeMesh.
  Positions positions(3, 3);
  positions << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const std::string message = error_message<TopologyError>([&] { FaceVertexMesh(positions, {3}, {0, 1, 7}); });
  EXPECT_NE(message.find("face 0 uses vertex 7 but there are 3 vertices"), std::string::npos) << message;
}

TEST(HalfedgeMesh, ValidateCatchesNothingOnEveryKnownSurface) {
  Random random(20261123);
  for (const KnownSurface& surface :
       {sphere({2, 3, 1}), genus_surface(3, {1, 2, 1}), disk(3, 4), annulus(2, 5), torus(3, 4)}) {
    const HalfedgeMesh mesh(surface.mesh);
    EXPECT_NO_THROW(mesh.validate()) << surface.name;
    EXPECT_EQ(to_face_vertex_mesh(mesh), surface.mesh) << surface.name;
  }
}

// Walks every cycle of `next` and checks the invariants of Def 55 directly (not through validate()).
RC_GTEST_PROP(HalfedgeMesh, InvariantsHoldOnEveryOrientableSurface, ()) {
  Random random(*seed());
  KnownSurface surface = orientable_surface(random, 2);
  if (random.coin()) surface = disjoint_union(surface, orientable_surface(random, 1));
  const FaceVertexMesh faces = orient(scrambled(surface.mesh, random)).mesh;
  const HalfedgeMesh mesh(faces);
  mesh.validate();
  const ElementCounts counts = count_elements(faces);
  RC_ASSERT(static_cast<Count>(mesh.edge_count()) == counts.edges);
  RC_ASSERT(mesh.halfedge_count() == 2 * mesh.edge_count());
  RC_ASSERT(mesh.face_count() == faces.face_count());
  RC_ASSERT(mesh.vertex_count() == faces.vertex_count());
  for (std::uint32_t i = 0; i < mesh.halfedge_count(); ++i) {
    const HalfedgeId h(i);
    RC_ASSERT(HalfedgeMesh::twin(HalfedgeMesh::twin(h)) == h);
    RC_ASSERT(HalfedgeMesh::twin(h) != h);
    RC_ASSERT(mesh.next(mesh.prev(h)) == h);
    RC_ASSERT(mesh.prev(mesh.next(h)) == h);
    RC_ASSERT(mesh.origin(HalfedgeMesh::twin(h)) == mesh.destination(h));
    RC_ASSERT(mesh.origin(mesh.next(h)) == mesh.destination(h));
    RC_ASSERT(!(mesh.is_boundary(h) && mesh.is_boundary(HalfedgeMesh::twin(h))));
  }
  // Every face cycle closes after exactly its corners, visiting them in the face list's order.
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto corners = faces.face(f);
    HalfedgeId h = mesh.halfedge(FaceId(f));
    for (std::size_t k = 0; k < corners.size(); ++k) {
      RC_ASSERT(mesh.face(h) == FaceId(f));
      RC_ASSERT(mesh.origin(h) == VertexId(corners[k]));
      h = mesh.next(h);
    }
    RC_ASSERT(h == mesh.halfedge(FaceId(f)));
  }
  // Every boundary cycle closes, stays on the boundary, and there are b of them.
  std::set<std::uint32_t> seen;
  Count loops = 0;
  for (std::uint32_t i = 0; i < mesh.halfedge_count(); ++i) {
    if (!mesh.is_boundary(HalfedgeId(i)) || seen.count(i) != 0) continue;
    ++loops;
    HalfedgeId h(i);
    std::size_t steps = 0;
    do {
      RC_ASSERT(mesh.is_boundary(h));
      seen.insert(h.value);
      h = mesh.next(h);
      RC_ASSERT(++steps <= mesh.halfedge_count());
    } while (h != HalfedgeId(i));
  }
  RC_ASSERT(loops == surface.boundary_loops);
  // Every vertex's rotation visits all its outgoing half-edges: its degree in the face list.
  std::vector<std::size_t> degree(faces.vertex_count(), 0);
  for (const auto& [key, walks] : edge_walks(faces)) {
    ++degree[walks[0].from];
    ++degree[walks[0].to];
  }
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    RC_ASSERT(mesh.vertex_neighbours(VertexId(v)).size() == degree[v]);
    RC_ASSERT(mesh.is_isolated(VertexId(v)) == (degree[v] == 0));
  }
}

RC_GTEST_PROP(HalfedgeMesh, RejectsEveryInconsistentlyOrientedSurface, ()) {
  Random random(*seed());
  const KnownSurface surface = orientable_surface(random, 1);
  // Flip one face that shares an edge: that edge is then walked twice in one direction.
  const FaceVertexMesh oriented = orient(scrambled(surface.mesh, random)).mesh;
  std::vector<std::uint32_t> inner_faces;
  for (const auto& [key, walks] : edge_walks(oriented)) {
    if (walks.size() == 2) inner_faces.push_back(walks[random.below(2)].face);
  }
  RC_PRE(!inner_faces.empty());  // a single quad has no shared edge
  std::vector<bool> flip(oriented.face_count(), false);
  flip[inner_faces[random.below(inner_faces.size())]] = true;
  RC_ASSERT_THROWS_AS(HalfedgeMesh{flip_faces(oriented, flip)}, TopologyError);
}

// On any soup, a HalfedgeMesh builds exactly when analyze() finds a manifold and orient() flips
// no face (every edge of two faces walked both ways).
RC_GTEST_PROP(HalfedgeMesh, BuildsExactlyTheManifoldsOrientedAsGiven, ()) {
  Random random(*seed());
  const FaceVertexMesh mesh = random.coin() ? any_soup(random) : orient(any_surface(random, 1).mesh).mesh;
  const TopologyReport report = analyze(mesh);
  const bool buildable = report.manifold && report.orientable && orient(mesh).flipped.empty();
  RC_CLASSIFY(buildable, "buildable");
  const std::string error = build_error(mesh);
  RC_ASSERT(error.empty() == buildable);
  if (buildable) HalfedgeMesh(mesh).validate();
}

}  // namespace
}  // namespace patchwork
