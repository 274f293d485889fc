#include "meshes/interop/openmesh.h"

#include <vector>

#include "core/errors.h"
#include "meshes/interop/add_faces.h"

namespace patchwork {

OpenMeshPolyMesh to_openmesh(const FaceVertexMesh& mesh) {
  // OpenMesh asserts (or corrupts its edges) on a face that repeats a vertex: check them all first.
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    if (const auto repeated = repeated_vertex(mesh.face(f))) {
      throw TopologyError(detail::message("to_openmesh: face ", f, " (", detail::corners_text(mesh.face(f)),
                                          ") uses vertex ", *repeated, " more than once"));
    }
  }
  OpenMeshPolyMesh om;
  om.reserve(mesh.vertex_count(), mesh.face_indices().size() / 2 + 1, mesh.face_count());
  const Positions& positions = mesh.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    om.add_vertex(OpenMeshPolyMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  std::vector<OpenMeshPolyMesh::VertexHandle> corners;
  const auto add_face = [&](std::span<const std::uint32_t> face) {
    corners.clear();
    for (std::uint32_t v : face) corners.push_back(om.vertex_handle(v));
    return om.add_face(corners).is_valid();
  };
  const auto face_walking = [&](std::uint32_t a, std::uint32_t b) -> std::int64_t {
    const auto h = om.find_halfedge(om.vertex_handle(a), om.vertex_handle(b));
    return h.is_valid() && !om.is_boundary(h) ? om.face_handle(h).idx() : -1;
  };
  const auto surrounded = [&](std::uint32_t v) {
    return !om.is_isolated(om.vertex_handle(v)) && !om.is_boundary(om.vertex_handle(v));
  };
  detail::add_faces(mesh, "to_openmesh", {"OpenMesh", add_face, face_walking, surrounded});
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
  return FaceVertexMesh(detail::positions_of(points), std::move(sizes), std::move(indices));
}

}  // namespace patchwork
