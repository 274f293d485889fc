#include "meshes/interop/openmesh.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/errors.h"

namespace patchwork {
namespace {

std::string corners_text(std::span<const std::uint32_t> face) {
  std::string text;
  for (std::uint32_t v : face) {
    if (!text.empty()) text += ' ';
    text += std::to_string(v);
  }
  return text;
}

// Why OpenMesh refused face f (all faces before it were added, so face handles are our ids).
std::string refusal_reason(const OpenMeshPolyMesh& om, std::span<const std::uint32_t> face) {
  for (std::size_t k = 0; k < face.size(); ++k) {
    const std::uint32_t a = face[k];
    const std::uint32_t b = face[(k + 1) % face.size()];
    const auto h = om.find_halfedge(om.vertex_handle(a), om.vertex_handle(b));
    if (h.is_valid() && !om.is_boundary(h)) {
      return detail::message("edge (", a, ",", b, ") is already walked from ", a, " to ", b, " by face ",
                             om.face_handle(h).idx(), " (an edge with three faces, or inconsistent orientation)");
    }
  }
  for (std::uint32_t v : face) {
    const auto vh = om.vertex_handle(v);
    if (!om.is_isolated(vh) && !om.is_boundary(vh)) {
      return detail::message("vertex ", v, " is already surrounded by faces (a non-manifold vertex)");
    }
  }
  return "its vertices' fans cannot be linked (a non-manifold vertex)";
}

}  // namespace

OpenMeshPolyMesh to_openmesh(const FaceVertexMesh& mesh) {
  // OpenMesh asserts (or corrupts its edges) on a face that repeats a vertex: check them all first.
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    std::vector<std::uint32_t> corners(mesh.face(f).begin(), mesh.face(f).end());
    std::sort(corners.begin(), corners.end());
    const auto repeated = std::adjacent_find(corners.begin(), corners.end());
    if (repeated != corners.end()) {
      throw TopologyError(detail::message("to_openmesh: face ", f, " (", corners_text(mesh.face(f)), ") uses vertex ",
                                          *repeated, " more than once"));
    }
  }
  OpenMeshPolyMesh om;
  om.reserve(mesh.vertex_count(), mesh.face_indices().size() / 2 + 1, mesh.face_count());
  const Positions& positions = mesh.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    om.add_vertex(OpenMeshPolyMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  std::vector<OpenMeshPolyMesh::VertexHandle> corners;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    corners.clear();
    for (std::uint32_t v : face) corners.push_back(om.vertex_handle(v));
    if (!om.add_face(corners).is_valid()) {
      throw TopologyError(detail::message("to_openmesh: OpenMesh cannot add face ", f, " (", corners_text(face),
                                          "): ", refusal_reason(om, face)));
    }
  }
  return om;
}

FaceVertexMesh from_openmesh(const OpenMeshPolyMesh& om) {
  constexpr std::uint32_t none = 0xffffffffu;
  std::vector<std::uint32_t> number(om.n_vertices(), none);
  std::vector<OpenMeshPolyMesh::Point> points;
  points.reserve(om.n_vertices());
  for (const auto v : om.vertices()) {  // skips deleted vertices when the mesh has status
    number[static_cast<std::size_t>(v.idx())] = static_cast<std::uint32_t>(points.size());
    points.push_back(om.point(v));
  }
  Positions positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (int k = 0; k < 3; ++k) positions(static_cast<Eigen::Index>(v), k) = points[v][k];
  }
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  sizes.reserve(om.n_faces());
  indices.reserve(om.n_halfedges() / 2 + om.n_faces());
  for (const auto f : om.faces()) {
    // The stored half-edge runs from the last corner to the first: walk targets from there.
    const auto start = om.halfedge_handle(f);
    auto h = start;
    std::uint32_t size = 0;
    do {
      indices.push_back(number[static_cast<std::size_t>(om.to_vertex_handle(h).idx())]);
      ++size;
      h = om.next_halfedge_handle(h);
    } while (h != start);
    sizes.push_back(size);
  }
  return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
}

}  // namespace patchwork
