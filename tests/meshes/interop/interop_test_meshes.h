#pragma once
// The meshes both interop test files cross-check, one per topological class, each with its
// closed-form topology (so a test checks our analyze() against the closed form and against
// CGAL or OpenMesh, and a wrong answer shared by both sides still fails).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"
#include "meshes/orientation.h"
#include "meshes/polygon.h"
#include "meshes/topology.h"
#include "tests/meshes/face_lists.h"

namespace patchwork::test {

using testing::bowtie;       // two triangles touching at vertex 0: V=5 E=6 F=2 chi=1
using testing::make_mesh;
using testing::tetrahedron;  // normals out: V=4 E=6 F=4 chi=2

/// The closed-form topology of a test mesh (our conventions, meshes/topology.h).
struct Expected {
  Count vertices;  // referenced by a face
  Count edges;
  Count faces;
  Count components;
  Count boundary_loops;
  bool closed;
  bool orientable;
  bool manifold;
  /// Oriented as given: every edge with two faces is walked both ways (no flip needed).
  bool oriented;
};

struct NamedMesh {
  std::string name;
  FaceVertexMesh mesh;
  Expected expected;
};

/// The faces of `mesh` in reverse corner order (normals flipped), first corner kept.
inline FaceVertexMesh reversed(const FaceVertexMesh& mesh, const std::vector<std::uint32_t>& which) {
  std::vector<std::uint32_t> indices = mesh.face_indices();
  std::size_t offset = 0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::size_t size = mesh.face_sizes()[f];
    if (std::find(which.begin(), which.end(), f) != which.end()) {
      std::reverse(indices.begin() + static_cast<std::ptrdiff_t>(offset + 1),
                   indices.begin() + static_cast<std::ptrdiff_t>(offset + size));
    }
    offset += size;
  }
  return FaceVertexMesh(mesh.positions(), mesh.face_sizes(), std::move(indices));
}

inline FaceVertexMesh reversed(const FaceVertexMesh& mesh) {
  std::vector<std::uint32_t> all(mesh.face_count());
  for (std::uint32_t f = 0; f < all.size(); ++f) all[f] = f;
  return reversed(mesh, all);
}

/// Whether OpenMesh's and CGAL's add_face take the faces in order: no edge walked twice in one
/// direction and no face repeating a vertex, that is an edge-manifold mesh oriented as given.
/// Both link a non-manifold vertex when the face order allows it (it does for the bowtie; a
/// face touching a vertex whose fan is already closed is refused: the tests of refusals).
inline bool add_face_accepts(const FaceVertexMesh& mesh) {
  const TopologyReport r = analyze(mesh);
  return r.edge_manifold && r.faces_repeating_a_vertex.empty() && r.orientable && orient(mesh).flipped.empty();
}

/// Each polygon triangulated by triangulate_faces (meshes/polygon.h; CGAL's is_outward_oriented
/// and volume want triangles).
inline FaceVertexMesh triangulated(const FaceVertexMesh& mesh) {
  return FaceVertexMesh::uniform(mesh.positions(), 3, triangulate_faces(mesh));
}

/// Unit cube with corner `origin`, six quads with normals out; vertex x + 2y + 4z.
inline FaceVertexMesh cube(const Vec3& origin = Vec3::Zero()) {
  std::vector<Vec3> points;
  for (int v = 0; v < 8; ++v) points.push_back(origin + Vec3(v & 1, (v >> 1) & 1, (v >> 2) & 1));
  return make_mesh(points, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
}

/// Two unit cubes, the second at x = 3 (vertices 8..15).
inline FaceVertexMesh two_cubes() {
  const FaceVertexMesh a = cube();
  const FaceVertexMesh b = cube(Vec3(3, 0, 0));
  Positions positions(16, 3);
  positions << a.positions(), b.positions();
  std::vector<std::uint32_t> indices = a.face_indices();
  for (std::uint32_t v : b.face_indices()) indices.push_back(v + 8);
  return FaceVertexMesh::uniform(std::move(positions), 4, std::move(indices));
}

/// Torus (R = 2, r = 1) as an n x m grid of quads, normals out; split into 2nm triangles when
/// `triangles`. Vertex i * m + j at angles (2 pi i/n, 2 pi j/m). V=nm E=2nm F=nm chi=0 g=1.
inline FaceVertexMesh torus(std::uint32_t n, std::uint32_t m, bool triangles = false) {
  Positions positions(static_cast<Eigen::Index>(n) * m, 3);
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = 0; j < m; ++j) {
      const double theta = 2 * std::numbers::pi * i / n;
      const double phi = 2 * std::numbers::pi * j / m;
      positions.row(static_cast<Eigen::Index>(i) * m + j) << (2 + std::cos(phi)) * std::cos(theta),
          (2 + std::cos(phi)) * std::sin(theta), std::sin(phi);
    }
  }
  const auto id = [&](std::uint32_t i, std::uint32_t j) { return (i % n) * m + (j % m); };
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(n) * m * 6);
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = 0; j < m; ++j) {
      // Counter-clockwise in (theta, phi): d/dtheta x d/dphi points out of the torus.
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles) {
        indices.insert(indices.end(), {a, b, c, a, c, d});
      } else {
        indices.insert(indices.end(), {a, b, c, d});
      }
    }
  }
  return FaceVertexMesh::uniform(std::move(positions), triangles ? 3 : 4, std::move(indices));
}

/// Planar n x m grid of quads in z = 0, normals +z. V=(n+1)(m+1) E=n(m+1)+m(n+1) F=nm chi=1.
inline FaceVertexMesh disk_grid(std::uint32_t n, std::uint32_t m) {
  std::vector<Vec3> points;
  for (std::uint32_t j = 0; j <= m; ++j) {
    for (std::uint32_t i = 0; i <= n; ++i) points.emplace_back(i, j, 0);
  }
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::uint32_t j = 0; j < m; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i;
      faces.push_back({a, a + 1, a + n + 2, a + n + 1});
    }
  }
  return make_mesh(points, faces);
}

/// A ring of n quads between radius 1 (vertex i) and 2 (vertex n + i), normals +z.
/// V=2n E=3n F=n chi=0, two boundary loops.
inline FaceVertexMesh annulus(std::uint32_t n) {
  std::vector<Vec3> points;
  for (double radius : {1.0, 2.0}) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const double angle = 2 * std::numbers::pi * i / n;
      points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0);
    }
  }
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::uint32_t i = 0; i < n; ++i) faces.push_back({i, n + i, n + (i + 1) % n, (i + 1) % n});
  return make_mesh(points, faces);
}

/// Three triangles on the edge (0,1), like pages of a book: a non-manifold edge.
/// V=5 E=7 F=3 chi=1, one edge-connected component.
inline FaceVertexMesh book() {
  return make_mesh({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}}, {{0, 2, 1}, {1, 3, 0}, {0, 4, 1}});
}

/// A Moebius band of n quads around the circle of radius 2, `rows` quads across: vertex
/// i * (rows + 1) + k sits at c(i) + w (2k/rows - 1) d(i), where d turns by half a turn over
/// the band, so column n is column 0 upside down. As a polygon soup: each quad is listed
/// counter-clockwise in (i, k), which the seam makes inconsistent. V=n(rows+1)
/// E=n(2 rows + 1) F=n rows chi=0, one boundary loop, not orientable.
inline FaceVertexMesh moebius_band(std::uint32_t n, std::uint32_t rows) {
  std::vector<Vec3> points;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double theta = 2 * std::numbers::pi * i / n;
    const Vec3 center(2 * std::cos(theta), 2 * std::sin(theta), 0);
    const Vec3 across(std::cos(theta / 2) * std::cos(theta), std::cos(theta / 2) * std::sin(theta),
                      std::sin(theta / 2));
    for (std::uint32_t k = 0; k <= rows; ++k) points.push_back(center + (2.0 * k / rows - 1.0) * 0.5 * across);
  }
  const auto id = [&](std::uint32_t i, std::uint32_t k) { return i < n ? i * (rows + 1) + k : rows - k; };
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t k = 0; k < rows; ++k) faces.push_back({id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1)});
  }
  return make_mesh(points, faces);
}

/// A square and a triangle on its top edge (a house in z = 0) plus vertex 5, which no face
/// uses. V=5 (6 rows) E=6 F=2 chi=1.
inline FaceVertexMesh house_with_isolated_vertex() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 1.5, 0}, {7, 7, 7}}, {{0, 1, 2, 3}, {3, 2, 4}});
}

/// An open pyramid (a closed fan of 4 triangles around apex 0), then triangle 4 touching the
/// apex only: OpenMesh and CGAL refuse face 4 (the apex is already surrounded).
inline FaceVertexMesh cone_with_extra_face() {
  return make_mesh({{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 2}, {1, 0, 2}},
                    {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {0, 5, 6}});
}

/// One quad that visits vertex 1 twice.
inline FaceVertexMesh face_repeating_a_vertex() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 1, 2, 1}});
}

/// Some triangles of the fan-triangulated n x m disk grid (keep[t] says which; t < 2nm), the
/// corners of triangle t rotated by rotation[t]. All grid vertices stay (unused ones isolated).
/// Every edge has at most two triangles, walked both ways; vertices may become non-manifold
/// (triangles touching at a corner only).
inline FaceVertexMesh grid_triangles(std::uint32_t n, std::uint32_t m, const std::vector<bool>& keep,
                                     const std::vector<std::uint32_t>& rotation) {
  const FaceVertexMesh all = triangulated(disk_grid(n, m));
  std::vector<std::uint32_t> indices;
  for (std::size_t t = 0; t < all.face_count(); ++t) {
    if (!keep[t]) continue;
    const auto face = all.face(t);
    for (std::size_t k = 0; k < 3; ++k) indices.push_back(face[(k + rotation[t]) % 3]);
  }
  return FaceVertexMesh::uniform(all.positions(), 3, std::move(indices));
}

/// Every mesh the cross-checks run on, with its closed-form topology
/// (V, E, F, components, boundary loops, closed, orientable, manifold, oriented as given).
inline std::vector<NamedMesh> crosscheck_meshes() {
  return {
      {"tetrahedron", tetrahedron(), {4, 6, 4, 1, 0, true, true, true, true}},
      {"inward tetrahedron", reversed(tetrahedron()), {4, 6, 4, 1, 0, true, true, true, true}},
      {"cube", cube(), {8, 12, 6, 1, 0, true, true, true, true}},
      {"cube with face 0 flipped", reversed(cube(), {0}), {8, 12, 6, 1, 0, true, true, true, false}},
      {"torus 6x4", torus(6, 4), {24, 48, 24, 1, 0, true, true, true, true}},
      {"triangulated torus 5x3", torus(5, 3, true), {15, 45, 30, 1, 0, true, true, true, true}},
      {"disk grid 3x2", disk_grid(3, 2), {12, 17, 6, 1, 1, false, true, true, true}},
      {"annulus 8", annulus(8), {16, 24, 8, 1, 2, false, true, true, true}},
      {"two cubes", two_cubes(), {16, 24, 12, 2, 0, true, true, true, true}},
      {"book (non-manifold edge)", book(), {5, 7, 3, 1, 2, false, true, false, true}},
      {"bowtie (non-manifold vertex)", bowtie(), {5, 6, 2, 2, 2, false, true, false, true}},
      {"moebius band 8x1", moebius_band(8, 1), {16, 24, 8, 1, 1, false, false, true, false}},
      {"moebius band 9x2", moebius_band(9, 2), {27, 45, 18, 1, 1, false, false, true, false}},
      {"house with an isolated vertex", house_with_isolated_vertex(), {5, 6, 2, 1, 1, false, true, true, true}},
  };
}

}  // namespace patchwork::test
