// The edge list (seed Def 54): edges by first use, left and right faces with -1 at the boundary,
// conversions to and from face lists and half-edge meshes; and the edge table every mesh type and
// algorithm of meshes/ is built from.

#include "meshes/edge_list_mesh.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>

#include "core/errors.h"
#include "meshes/edge_table.h"
#include "meshes/orientation.h"
#include "tests/meshes/mesh_generators.h"
#include "tests/meshes/reference_topology.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

TEST(EdgeListMesh, SquareMatchesDefinition54) {
  const EdgeListMesh mesh(square());
  mesh.validate();
  ASSERT_EQ(mesh.edge_count(), 5u);
  EXPECT_EQ(mesh.face_count(), 2u);
  // Edges in order of first use, each as first walked: (0,1), (1,2), (2,0) by f0, then (2,3), (3,0) by f1.
  const std::vector<std::array<std::uint32_t, 2>> expected{{0, 1}, {1, 2}, {2, 0}, {2, 3}, {3, 0}};
  for (std::uint32_t e = 0; e < 5; ++e) {
    EXPECT_EQ(mesh.edge(EdgeId(e))[0], VertexId(expected[e][0])) << e;
    EXPECT_EQ(mesh.edge(EdgeId(e))[1], VertexId(expected[e][1])) << e;
  }
  // The diagonal (2,0): f0 walks it 2 -> 0 (left), f1 walks 0 -> 2 (right).
  EXPECT_EQ(mesh.left(EdgeId(2)), FaceId(0));
  EXPECT_EQ(mesh.right(EdgeId(2)), FaceId(1));
  // The sides have the outer face (-1, invalid) on their right.
  for (std::uint32_t e : {0u, 1u}) {
    EXPECT_EQ(mesh.left(EdgeId(e)), FaceId(0));
    EXPECT_FALSE(mesh.right(EdgeId(e)).valid());
  }
  for (std::uint32_t e : {3u, 4u}) {
    EXPECT_EQ(mesh.left(EdgeId(e)), FaceId(1));
    EXPECT_FALSE(mesh.right(EdgeId(e)).valid());
  }
  EXPECT_EQ(mesh.face_edges(FaceId(0)), (std::vector<EdgeId>{EdgeId(0), EdgeId(1), EdgeId(2)}));
  EXPECT_EQ(mesh.face_edges(FaceId(1)), (std::vector<EdgeId>{EdgeId(2), EdgeId(3), EdgeId(4)}));
  EXPECT_EQ(to_face_vertex_mesh(mesh), square());
  EXPECT_EQ(mesh.positions(), square().positions());
}

TEST(EdgeListMesh, RejectsAThirdFaceAndARepeatedDirection) {
  const auto build_error = [](const FaceVertexMesh& mesh) {
    return error_message<TopologyError>([&] { EdgeListMesh built(mesh); });
  };
  // Faces 0 and 2 of the book both walk 0 -> 1 while face 1 is on the other side.
  const std::string pages = build_error(book());
  EXPECT_NE(pages.find("edge (0,1) walked from 0 by faces 0 and 2 (and a third face)"), std::string::npos) << pages;
  const FaceVertexMesh same_direction = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  const std::string twice = build_error(same_direction);
  EXPECT_NE(twice.find("edge (2,0) walked from 2 by faces 0 and 1"), std::string::npos) << twice;
}

TEST(EdgeListMesh, FaceWalkingAnEdgeThereAndBackRoundTrips) {
  // A square with a spike: (0, 1, 2, 4, 2, 3) walks edge {2, 4} out and back, so the face lies on
  // both sides of it; the corners must still come back in order.
  const FaceVertexMesh spike = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 0}}, {{0, 1, 2, 4, 2, 3}});
  const EdgeListMesh mesh(spike);
  mesh.validate();
  EXPECT_EQ(mesh.edge_count(), 5u);
  const EdgeId spoke = mesh.face_edges(FaceId(0))[2];
  EXPECT_EQ(mesh.left(spoke), FaceId(0));
  EXPECT_EQ(mesh.right(spoke), FaceId(0));
  EXPECT_EQ(to_face_vertex_mesh(mesh), spike);
  // A face all of whose edges are walked both ways (the path 0 - 1 - 2 as a polygon).
  const FaceVertexMesh path = make_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2, 1}});
  EXPECT_EQ(to_face_vertex_mesh(EdgeListMesh(path)), path);
}

TEST(EdgeListMesh, ConvertsToAndFromAHalfedgeMesh) {
  const FaceVertexMesh torus_faces = torus(3, 4).mesh;
  const HalfedgeMesh halfedges(torus_faces);
  const EdgeListMesh edges = to_edge_list(halfedges);
  edges.validate();
  EXPECT_EQ(edges.edge_count(), 24u);  // a 3 x 4 torus grid: E = 2 * 12
  for (std::uint32_t e = 0; e < edges.edge_count(); ++e) {
    EXPECT_TRUE(edges.left(EdgeId(e)).valid());
    EXPECT_TRUE(edges.right(EdgeId(e)).valid());
  }
  EXPECT_EQ(to_face_vertex_mesh(to_halfedge_mesh(edges)), torus_faces);
  EXPECT_THROW(EdgeListMesh{mobius_band(1, 3).mesh}, TopologyError);  // an edge walked twice one way
}

RC_GTEST_PROP(EdgeListMesh, LeftAndRightFacesAreTheWalksOfEachEdge, ()) {
  Random random(*seed());
  const KnownSurface surface = orientable_surface(random, 2);
  const FaceVertexMesh mesh = orient(scrambled(surface.mesh, random)).mesh;
  const EdgeListMesh edges(mesh);
  edges.validate();
  const auto walks = edge_walks(mesh);
  RC_ASSERT(edges.edge_count() == walks.size());
  Count boundary = 0;
  for (std::uint32_t e = 0; e < edges.edge_count(); ++e) {
    const auto [from, to] = edges.edge(EdgeId(e));
    const auto& w = walks.at(edge_key(from.value, to.value));
    // The left face walks from -> to, the right face to -> from, -1 where no face does (Def 54).
    FaceId left, right;
    for (const Walk& walk : w) (walk.from == from.value ? left : right) = FaceId(walk.face);
    RC_ASSERT(edges.left(EdgeId(e)) == left);
    RC_ASSERT(edges.right(EdgeId(e)) == right);
    RC_ASSERT(left.valid());  // the first use defines the direction
    boundary += right.valid() ? 0 : 1;
  }
  RC_ASSERT(boundary == static_cast<Count>(std::count_if(walks.begin(), walks.end(),
                                                         [](const auto& entry) { return entry.second.size() == 1; })));
  // Each face lists its edges in walking order.
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto corners = mesh.face(f);
    const auto& list = edges.face_edges(FaceId(f));
    RC_ASSERT(list.size() == corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const auto [a, b] = edges.edge(list[k]);
      RC_ASSERT(edge_key(a.value, b.value) == edge_key(corners[k], corners[(k + 1) % corners.size()]));
    }
  }
  RC_ASSERT(to_face_vertex_mesh(edges) == mesh);
}

// The edge table against ordered maps of walks, on any soup (surfaces, damaged or not, and random
// faces with repeated corners and crowded edges): edges numbered by first use, each use's face,
// corner and direction, twins, and each corner's edge.
RC_GTEST_PROP(EdgeTable, MatchesTheEdgesByFirstUseOnAnySoup, ()) {
  Random random(*seed());
  const FaceVertexMesh mesh = random.coin() ? any_soup(random) : scrambled(any_surface(random, 1).mesh, random);
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  const detail::EdgeTable table(mesh);
  const auto edges = edges_by_first_use(mesh);
  RC_ASSERT(table.edge_count() == edges.size());
  std::vector<std::uint32_t> corner_edge(index.size(), detail::EdgeTable::none);
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    const std::vector<Walk>& walks = edges[e];
    RC_ASSERT(table.vertices(e) == (std::array<std::uint32_t, 2>{walks[0].from, walks[0].to}));
    RC_ASSERT(table.use_count(e) == walks.size());
    RC_ASSERT(table.has_two_uses(e) == (walks.size() == 2));
    std::vector<detail::EdgeUse> uses(table.uses(e).begin(), table.uses(e).end());
    RC_ASSERT(uses.size() == walks.size());
    RC_ASSERT(uses[0].corner == table.first_use(e));
    for (std::size_t k = 0; k < uses.size(); ++k) {
      const std::uint32_t c = uses[k].corner;
      if (k > 0) RC_ASSERT(c > uses[k - 1].corner);  // (RC_ASSERT evaluates both sides of ||)
      RC_ASSERT(uses[k].face == walks[k].face);
      RC_ASSERT(table.face_of(c) == walks[k].face);
      RC_ASSERT(index[c] == walks[k].from);
      RC_ASSERT(index[table.next_corner(c)] == walks[k].to);
      RC_ASSERT(table.next_corner(table.prev_corner(c)) == c);
      RC_ASSERT(table.is_first_use(c) == (k == 0));
      const std::uint32_t twin = walks.size() == 1   ? detail::EdgeTable::none
                                 : walks.size() == 2 ? uses[1 - k].corner
                                                     : detail::EdgeTable::crowded;
      RC_ASSERT(table.twin(c) == twin);
      corner_edge[c] = e;
    }
    if (walks.size() >= 2) {
      const auto two = table.first_two_uses(e);
      RC_ASSERT(two[0].corner == uses[0].corner && two[1].corner == uses[1].corner);
    }
  }
  for (std::uint32_t c = 0; c < index.size(); ++c) RC_ASSERT(table.edge_of(c) == corner_edge[c]);
}

}  // namespace
}  // namespace patchwork
