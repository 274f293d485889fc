// The face list (seed Def 53): face sizes plus flat indices, positions as rows, the checks the
// constructor makes; and the strong ids of meshes/ids.h.

#include "meshes/face_vertex_mesh.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <string>
#include <unordered_set>

#include "core/errors.h"
#include "meshes/ids.h"
#include "tests/meshes/face_lists.h"

namespace patchwork {
namespace {

using testing::error_message;

Positions square_positions() {
  Positions positions(5, 3);
  positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 2, 0;
  return positions;
}

TEST(FaceVertexMesh, MixedFacesFromSizesAndIndices) {
  // A quad 0 1 2 3 and a triangle 3 2 4 on top of it (the house of Def 53's example).
  const FaceVertexMesh mesh(square_positions(), {4, 3}, {0, 1, 2, 3, 3, 2, 4});
  mesh.validate();
  EXPECT_EQ(mesh.vertex_count(), 5u);
  EXPECT_EQ(mesh.face_count(), 2u);
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.face(0).begin(), mesh.face(0).end()),
            (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.face(1).begin(), mesh.face(1).end()),
            (std::vector<std::uint32_t>{3, 2, 4}));
  EXPECT_EQ(mesh.position(4), Vec3(0.5, 2, 0));
  EXPECT_EQ(mesh.face_sizes(), (std::vector<std::uint32_t>{4, 3}));
  EXPECT_EQ(mesh.face_indices().size(), 7u);
  // Row-major storage: x y z of a vertex are adjacent, as glTF and OpenSubdiv want.
  EXPECT_EQ(mesh.positions().data()[3 * 4 + 1], 2.0);
}

TEST(FaceVertexMesh, UniformFaces) {
  const FaceVertexMesh mesh = FaceVertexMesh::uniform(square_positions(), 3, {0, 1, 2, 0, 2, 3});
  EXPECT_EQ(mesh.face_sizes(), (std::vector<std::uint32_t>{3, 3}));
  EXPECT_EQ(mesh, FaceVertexMesh(square_positions(), {3, 3}, {0, 1, 2, 0, 2, 3}));
  EXPECT_THROW(FaceVertexMesh::uniform(square_positions(), 2, {0, 1}), TopologyError);
  EXPECT_THROW(FaceVertexMesh::uniform(square_positions(), 3, {0, 1, 2, 3}), TopologyError);
}

TEST(FaceVertexMesh, EmptyMeshAndUnusedVertices) {
  const FaceVertexMesh empty;
  empty.validate();
  EXPECT_EQ(empty.vertex_count(), 0u);
  EXPECT_EQ(empty.face_count(), 0u);
  // Positions nobody uses are allowed: the type holds any soup.
  const FaceVertexMesh unused(square_positions(), {}, {});
  unused.validate();
  EXPECT_EQ(unused.vertex_count(), 5u);
  EXPECT_EQ(unused.face_count(), 0u);
}

TEST(FaceVertexMesh, RejectsBadInputNamingTheElement) {
  EXPECT_NE(error_message([] {
              FaceVertexMesh(square_positions(), {3, 2}, {0, 1, 2, 3, 4});
            }).find("face 1 has 2 corners"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              FaceVertexMesh(square_positions(), {3}, {0, 1, 2, 3});
            }).find("face sizes add up to 3 corners but 4 indices are given"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              FaceVertexMesh(square_positions(), {3, 3}, {0, 1, 2, 0, 2, 5});
            }).find("face 1 uses vertex 5 but there are 5 vertices"),
            std::string::npos);
  EXPECT_THROW(FaceVertexMesh(square_positions(), {3}, {0, 1, 5}), TopologyError);
  Positions bad = square_positions();
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_message([&bad] {
              FaceVertexMesh(bad, {3}, {0, 1, 2});
            }).find("position of vertex 2 is not finite"),
            std::string::npos);
  bad(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(FaceVertexMesh(bad, {3}, {0, 1, 3}), InvalidInput);
}

TEST(FaceVertexMesh, EqualityComparesEverything) {
  const FaceVertexMesh a(square_positions(), {4}, {0, 1, 2, 3});
  EXPECT_EQ(a, FaceVertexMesh(square_positions(), {4}, {0, 1, 2, 3}));
  EXPECT_FALSE(a == FaceVertexMesh(square_positions(), {4}, {1, 2, 3, 0}));  // same polygon, other start
  Positions moved = square_positions();
  moved(0, 0) = 1e-300;
  EXPECT_FALSE(a == FaceVertexMesh(moved, {4}, {0, 1, 2, 3}));
  EXPECT_FALSE(a == FaceVertexMesh(square_positions(), {3}, {0, 1, 2}));
}

TEST(Ids, PrintCompareAndHash) {
  std::ostringstream out;
  out << VertexId(12) << ' ' << HalfedgeId(7) << ' ' << EdgeId(3) << ' ' << FaceId(5) << ' ' << FaceId();
  EXPECT_EQ(out.str(), "v12 h7 e3 f5 f-");
  EXPECT_FALSE(VertexId().valid());
  EXPECT_TRUE(VertexId(0).valid());
  EXPECT_EQ(VertexId().value, 0xffffffffu);
  EXPECT_EQ(FaceId(9).index(), 9u);
  EXPECT_LT(EdgeId(2), EdgeId(3));
  EXPECT_EQ(std::hash<FaceId>{}(FaceId(4)), std::hash<std::uint32_t>{}(4u));
  const std::unordered_set<VertexId> ids{VertexId(1), VertexId(2), VertexId(1)};
  EXPECT_EQ(ids.size(), 2u);
  static_assert(sizeof(VertexId) == 4, "ids are 32-bit");
}

}  // namespace
}  // namespace patchwork
