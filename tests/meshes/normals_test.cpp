// Face normals, vertex normals with uniform, angle and area weights (seed 4.4.1), and normals
// split at creases.

#include "meshes/normals.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

// The icosahedron: vertices (0, +-1, +-phi) and cyclic shifts; faces are the triples of vertices
// pairwise 2 apart, oriented outward.
FaceVertexMesh icosahedron() {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> points;
  for (double a : {-1.0, 1.0}) {
    for (double b : {-phi, phi}) {
      points.emplace_back(0, a, b);
      points.emplace_back(a, b, 0);
      points.emplace_back(b, 0, a);
    }
  }
  FaceList faces;
  const auto edge = [&](std::uint32_t i, std::uint32_t j) {
    return std::abs((points[i] - points[j]).norm() - 2) < 1e-9;
  };
  for (std::uint32_t i = 0; i < 12; ++i) {
    for (std::uint32_t j = i + 1; j < 12; ++j) {
      for (std::uint32_t k = j + 1; k < 12; ++k) {
        if (!edge(i, j) || !edge(j, k) || !edge(i, k)) continue;
        const Vec3 n = (points[j] - points[i]).cross(points[k] - points[i]);
        faces.push_back(n.dot(points[i]) > 0 ? std::vector<std::uint32_t>{i, j, k}
                                             : std::vector<std::uint32_t>{i, k, j});
      }
    }
  }
  return make_mesh(points, faces);
}

// The sum of the outward normals of the box faces that point p of [0,x] x [0,y] x [0,z] lies
// on, normalised: the vertex normal of a box surface in closed form (see VertexNormalsOfBoxes).
Vec3 box_normal(const Vec3& p, const Resolution& res) {
  const Vec3 size(res.x, res.y, res.z);
  Vec3 n = Vec3::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    if (p[axis] == 0) n[axis] = -1;
    if (p[axis] == size[axis]) n[axis] = 1;
  }
  return n.normalized();
}

TEST(Normals, FaceNormalsOfTheCubeAreTheAxes) {
  const FaceVertexMesh cube = sphere({}).mesh;
  std::vector<Vec3> expected;
  for (std::size_t f = 0; f < cube.face_count(); ++f) {
    // A face of the unit cube has one coordinate constant, 0 (normal -axis) or 1 (normal +axis).
    const auto face = cube.face(f);
    for (int axis = 0; axis < 3; ++axis) {
      const double c = cube.position(face[0])[axis];
      if (cube.position(face[1])[axis] == c && cube.position(face[2])[axis] == c) {
        expected.push_back((c == 0 ? -1.0 : 1.0) * Vec3::Unit(axis));
      }
    }
  }
  EXPECT_EQ(face_normals(cube), expected);
  // A degenerate face has no normal.
  const FaceVertexMesh flat = make_mesh({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 1, 2}});
  EXPECT_EQ(face_normal(flat, 0), Vec3::Zero());
}

TEST(Normals, VertexNormalWeightings) {
  // A roof over vertex 0 = origin along edge 0 -> 1 = (0,1,0):
  //   face 0 = (0, 2, 1), 2 = (2,0,0): normal +z, area 1,   angle at 0 pi/2
  //   face 1 = (0, 1, 3), 3 = (0,-1,1): normal +x, area 1/2, angle at 0 3pi/4
  const FaceVertexMesh roof = make_mesh({{0, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, -1, 1}}, {{0, 2, 1}, {0, 1, 3}});
  const Vec3 uniform = vertex_normals(roof, NormalWeighting::uniform)[0];
  const Vec3 angle = vertex_normals(roof, NormalWeighting::angle)[0];
  const Vec3 area = vertex_normals(roof, NormalWeighting::area)[0];
  // Sums of two axis vectors with weights that are a few roundings from exact: 1e-15.
  EXPECT_LT((uniform - Vec3(1, 0, 1).normalized()).norm(), 1e-15);
  EXPECT_LT((angle - Vec3(3, 0, 2).normalized()).norm(), 1e-15);  // (3pi/4, 0, pi/2)
  EXPECT_LT((area - Vec3(1, 0, 2).normalized()).norm(), 1e-15);   // (1/2, 0, 1)
  // The default is angle weighting.
  EXPECT_EQ(vertex_normals(roof)[0], angle);
  // Vertex 2 is only in face 0: its normal is that face's.
  EXPECT_EQ(vertex_normals(roof, NormalWeighting::area)[2], Vec3(0, 0, 1));
}

TEST(Normals, IsolatedAndCancellingVerticesGetZero) {
  // Two copies of one triangle with opposite orientations: the normals cancel exactly (same
  // corner angles and areas computed from the same numbers).
  const FaceVertexMesh pillow = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {9, 9, 9}}, {{0, 1, 2}, {0, 2, 1}});
  for (NormalWeighting weighting : {NormalWeighting::uniform, NormalWeighting::angle, NormalWeighting::area}) {
    const std::vector<Vec3> normals = vertex_normals(pillow, weighting);
    ASSERT_EQ(normals.size(), 4u);
    for (const Vec3& n : normals) EXPECT_EQ(n, Vec3::Zero());
  }
}

TEST(Normals, IcosahedronVertexNormalsAreRadial) {
  // Five congruent faces around every vertex, symmetric about its radius: every weighting gives
  // p / |p|, up to the rounding of five unit vectors summed (1e-15).
  const FaceVertexMesh mesh = icosahedron();
  ASSERT_EQ(mesh.face_count(), 20u);
  for (NormalWeighting weighting : {NormalWeighting::uniform, NormalWeighting::angle, NormalWeighting::area}) {
    const std::vector<Vec3> normals = vertex_normals(mesh, weighting);
    for (std::size_t v = 0; v < 12; ++v) EXPECT_LT((normals[v] - mesh.position(v).normalized()).norm(), 1e-15) << v;
  }
}

TEST(Normals, SplitCubeAtItsEdges) {
  const FaceVertexMesh cube = sphere({}).mesh;
  // Neighbouring faces are 90 degrees apart. Below that threshold every edge is a crease: each
  // corner gets one copy per face, 24 vertices, each with its face's normal.
  const SplitNormals sharp = split_normals(cube, std::numbers::pi / 4);
  EXPECT_EQ(sharp.mesh.vertex_count(), 24u);
  EXPECT_EQ(sharp.normals.size(), 24u);
  const std::vector<Vec3> faces = face_normals(cube);
  for (std::size_t f = 0; f < 6; ++f) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t v = sharp.mesh.face(f)[k];
      EXPECT_EQ(sharp.normals[v], faces[f]);
      EXPECT_EQ(sharp.source_vertex[v], cube.face(f)[k]);
      EXPECT_EQ(sharp.mesh.position(v), cube.position(cube.face(f)[k]));
    }
  }
  // Above it nothing is split: 8 vertices with normals (+-1, +-1, +-1) / sqrt(3).
  const SplitNormals smooth = split_normals(cube, 0.6 * std::numbers::pi);
  EXPECT_EQ(smooth.mesh.vertex_count(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    const Vec3 p = smooth.mesh.position(v);
    EXPECT_LT((smooth.normals[v] - (p - Vec3(0.5, 0.5, 0.5)).normalized()).norm(), 1e-15);
  }
}

TEST(Normals, SplitRejectsANegativeAngle) {
  EXPECT_THROW(split_normals(sphere({}).mesh, -0.1), InvalidInput);
  EXPECT_THROW(split_normals(sphere({}).mesh, std::nan("")), InvalidInput);
}

TEST(Normals, SplitDropsIsolatedVertices) {
  const FaceVertexMesh mesh = make_mesh({{5, 5, 5}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1, 2, 3}});
  const SplitNormals split = split_normals(mesh, 0.5);
  EXPECT_EQ(split.source_vertex, (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(faces_of(split.mesh), (FaceList{{0, 1, 2}}));
  for (const Vec3& n : split.normals) EXPECT_EQ(n, Vec3(0, 0, 1));
}

// On the surface of a box of x by y by z unit squares every vertex normal is box_normal(): at a
// face's interior all faces share one normal; on a box edge the faces of each side have equal
// weight sums (2 unit squares, or angles pi, per side); at a corner likewise (1 square, pi/2).
// With triangles only the angle weights keep that balance (the angles at a vertex on one side add
// up to pi or pi/2 however the squares are cut).
RC_GTEST_PROP(Normals, VertexNormalsOfBoxes, ()) {
  Random random(*seed());
  const Resolution res = random_resolution(random, 1, 5);
  const FaceVertexMesh box = sphere(res).mesh;
  const FaceVertexMesh mesh = relabel_vertices(box, random_permutation(box.vertex_count(), random));
  // Sums of a few dozen axis vectors with weights rounded once: 1e-14.
  for (NormalWeighting weighting : {NormalWeighting::uniform, NormalWeighting::angle, NormalWeighting::area}) {
    const std::vector<Vec3> normals = vertex_normals(mesh, weighting);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      RC_ASSERT((normals[v] - box_normal(mesh.position(v), res)).norm() <= 1e-14);
    }
  }
  const FaceVertexMesh cut = triangulated(mesh, random);
  const std::vector<Vec3> normals = vertex_normals(cut, NormalWeighting::angle);
  for (std::size_t v = 0; v < cut.vertex_count(); ++v) {
    RC_ASSERT((normals[v] - box_normal(cut.position(v), res)).norm() <= 1e-14);
  }
}

// A box split at its 90-degree edges falls apart into its six sides: 2((x+1)(y+1) + (y+1)(z+1) +
// (z+1)(x+1)) vertices, each with its side's normal exactly.
RC_GTEST_PROP(Normals, SplitBoxFallsIntoItsSides, ()) {
  Random random(*seed());
  const Resolution res = random_resolution(random, 1, 5);
  const FaceVertexMesh box = sphere(res).mesh;
  const FaceVertexMesh mesh = relabel_vertices(box, random_permutation(box.vertex_count(), random));
  const double crease = random.uniform(0.01, 0.49) * std::numbers::pi;  // below the 90 degrees
  const SplitNormals split = split_normals(mesh, crease);
  const std::size_t x = static_cast<std::size_t>(res.x) + 1, y = static_cast<std::size_t>(res.y) + 1,
                    z = static_cast<std::size_t>(res.z) + 1;
  RC_ASSERT(split.mesh.vertex_count() == 2 * (x * y + y * z + z * x));
  const std::vector<Vec3> faces = face_normals(mesh);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (std::size_t k = 0; k < 4; ++k) RC_ASSERT(split.normals[split.mesh.face(f)[k]] == faces[f]);
  }
}

// On any voxel surface (every genus, triangulated or not): faces keep their corners through
// source_vertex; a vertex's copies each carry the normal of all their faces exactly (90-degree
// creases everywhere, flat elsewhere), and no two copies of a vertex carry the same normal (a
// vertex is duplicated only where needed).
RC_GTEST_PROP(Normals, SplitVoxelSurfacesOnlyWhereNeeded, ()) {
  Random random(*seed());
  const KnownSurface surface = closed_orientable_surface(random, 2);
  const FaceVertexMesh mesh = relabel_vertices(surface.mesh, random_permutation(surface.mesh.vertex_count(), random));
  const SplitNormals split = split_normals(mesh, std::numbers::pi / 4);
  RC_ASSERT(split.mesh.face_sizes() == mesh.face_sizes());
  RC_ASSERT(split.normals.size() == split.mesh.vertex_count());
  RC_ASSERT(split.source_vertex.size() == split.mesh.vertex_count());
  const std::vector<Vec3> faces = face_normals(mesh);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (std::size_t k = 0; k < mesh.face(f).size(); ++k) {
      const std::uint32_t v = split.mesh.face(f)[k];
      RC_ASSERT(split.source_vertex[v] == mesh.face(f)[k]);
      RC_ASSERT(split.mesh.position(v) == mesh.position(mesh.face(f)[k]));
      RC_ASSERT(split.normals[v] == faces[f]);
    }
  }
  std::set<std::pair<std::uint32_t, std::array<double, 3>>> copies;
  for (std::size_t v = 0; v < split.mesh.vertex_count(); ++v) {
    const Vec3& n = split.normals[v];
    RC_ASSERT(copies.insert({split.source_vertex[v], {n.x(), n.y(), n.z()}}).second);
  }
  // With no crease angle reached (>= pi), nothing is split and the normals are vertex_normals().
  const SplitNormals whole = split_normals(mesh, std::numbers::pi);
  RC_ASSERT(whole.mesh.vertex_count() == mesh.vertex_count());
  const std::vector<Vec3> expected = vertex_normals(mesh, NormalWeighting::angle);
  for (std::size_t v = 0; v < whole.mesh.vertex_count(); ++v) {
    // The same weighted terms, possibly summed in another order: 1e-14.
    RC_ASSERT((whole.normals[v] - expected[whole.source_vertex[v]]).norm() <= 1e-14);
  }
}

}  // namespace
}  // namespace patchwork
