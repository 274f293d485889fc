#pragma once
// Small face lists the meshes tests share, written out by hand, and the helper that catches an
// error's message. No test framework here: the meshes benchmark includes it too (through the
// cross-checks' meshes).

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork::testing {

using FaceList = std::vector<std::vector<std::uint32_t>>;

/// The face list of `points` and `faces` (each a list of vertex indices).
inline FaceVertexMesh make_mesh(const std::vector<Vec3>& points, const FaceList& faces) {
  Positions positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) positions.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  for (const auto& face : faces) {
    sizes.push_back(static_cast<std::uint32_t>(face.size()));
    indices.insert(indices.end(), face.begin(), face.end());
  }
  return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
}

/// The message of the Error that function() throws, "" if it throws nothing (another exception
/// goes through to the test).
template <class Error = std::exception, class Function>
std::string error_message(Function function) {
  try {
    function();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

/// The unit square as two triangles f0 = (0,1,2) and f1 = (0,2,3), counter-clockwise from +z.
///
///   3 ---- 2
///   |  f1 /|
///   |   /  |
///   | / f0 |
///   0 ---- 1
inline FaceVertexMesh square() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

/// The unit tetrahedron, normals out: V=4 E=6 F=4 chi=2.
inline FaceVertexMesh tetrahedron() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

/// Three triangles on the edge (0,1), like pages of a book: faces 0 and 2 walk it 0 -> 1, face 1
/// walks it 1 -> 0. V=5 E=7 F=3.
inline FaceVertexMesh book() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
}

/// Triangles (0,1,2) and (0,3,4) touching at vertex 0 only: two boundary fans at 0. V=5 E=6 F=2.
inline FaceVertexMesh bowtie() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
}

/// Two tetrahedra sharing vertex 0 (faces 0-3 and 4-7): two closed fans there, no boundary.
/// V=7 E=12 F=8.
inline FaceVertexMesh pinched_tetrahedra() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
                   {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 4, 5}, {0, 6, 4}, {4, 6, 5}, {0, 5, 6}});
}

}  // namespace patchwork::testing
