#pragma once
// What the OpenMesh and CGAL conversions share: adding every face through a half-edge library's
// add_face, and turning a refusal into a TopologyError that names the face and says why, found
// from the library's state (all faces before it were added, so face indices are our ids).

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork::detail {

/// How a half-edge library sees the faces added so far.
struct HalfedgeLibrary {
  /// The library's name in messages ("OpenMesh", "CGAL").
  const char* name;
  /// Adds a face by its vertices; false if the library refuses it.
  std::function<bool(std::span<const std::uint32_t>)> add_face;
  /// The face that walks from a to b already, or -1 if none does.
  std::function<std::int64_t(std::uint32_t a, std::uint32_t b)> face_walking;
  /// Whether the faces at v close around it already.
  std::function<bool(std::uint32_t v)> surrounded;
};

/// Adds the faces of `mesh` in order. \throws TopologyError "function: library cannot add face f
/// (corners): reason" at the first face the library refuses.
void add_faces(const FaceVertexMesh& mesh, const char* function, const HalfedgeLibrary& library);

/// A face's corners for messages: "0 4 1".
std::string corners_text(std::span<const std::uint32_t> face);

/// The positions of a library's points (anything with operator[] for x, y, z).
template <class Point>
Positions positions_of(const std::vector<Point>& points) {
  Positions positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (int k = 0; k < 3; ++k) positions(static_cast<Eigen::Index>(v), k) = points[v][k];
  }
  return positions;
}

}  // namespace patchwork::detail
