#include "meshes/interop/cgal.h"

#include "core/errors.h"
#include "meshes/interop/add_faces.h"

namespace patchwork {
namespace {

using VertexIndex = CgalSurfaceMesh::Vertex_index;

}  // namespace

CgalSurfaceMesh to_cgal_surface_mesh(const FaceVertexMesh& mesh) {
  CgalSurfaceMesh sm;
  sm.reserve(static_cast<CgalSurfaceMesh::size_type>(mesh.vertex_count()),
             static_cast<CgalSurfaceMesh::size_type>(mesh.face_indices().size() / 2 + 1),
             static_cast<CgalSurfaceMesh::size_type>(mesh.face_count()));
  const Positions& positions = mesh.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    sm.add_vertex(CgalPoint(positions(v, 0), positions(v, 1), positions(v, 2)));
  std::vector<VertexIndex> corners;
  const auto add_face = [&](std::span<const std::uint32_t> face) {
    corners.clear();
    for (std::uint32_t v : face) corners.push_back(VertexIndex(v));
    return sm.add_face(corners) != CgalSurfaceMesh::null_face();
  };
  const auto face_walking = [&](std::uint32_t a, std::uint32_t b) -> std::int64_t {
    const auto h = sm.halfedge(VertexIndex(a), VertexIndex(b));
    if (h == CgalSurfaceMesh::null_halfedge() || sm.is_border(h)) return -1;
    return static_cast<std::uint32_t>(sm.face(h));
  };
  const auto surrounded = [&](std::uint32_t v) { return !sm.is_isolated(VertexIndex(v)) && !sm.is_border(VertexIndex(v)); };
  detail::add_faces(mesh, "to_cgal_surface_mesh", {"CGAL", add_face, face_walking, surrounded});
  return sm;
}

FaceVertexMesh from_cgal(const CgalSurfaceMesh& sm) {
  constexpr std::uint32_t none = 0xffffffffu;
  std::vector<std::uint32_t> number(sm.number_of_vertices() + sm.number_of_removed_vertices(), none);
  std::vector<CgalPoint> points;
  points.reserve(sm.number_of_vertices());
  for (const VertexIndex v : sm.vertices()) {  // skips removed vertices
    number[static_cast<std::size_t>(v)] = static_cast<std::uint32_t>(points.size());
    points.push_back(sm.point(v));
  }
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  sizes.reserve(sm.number_of_faces());
  indices.reserve(sm.number_of_halfedges() / 2 + sm.number_of_faces());
  for (const auto f : sm.faces()) {
    // The stored half-edge runs from the last corner to the first: walk targets from there.
    const auto start = sm.halfedge(f);
    auto h = start;
    std::uint32_t size = 0;
    do {
      indices.push_back(number[static_cast<std::size_t>(sm.target(h))]);
      ++size;
      h = sm.next(h);
    } while (h != start);
    sizes.push_back(size);
  }
  return FaceVertexMesh(detail::positions_of(points), std::move(sizes), std::move(indices));
}

CgalPolygonSoup to_cgal_polygon_soup(const FaceVertexMesh& mesh) {
  CgalPolygonSoup soup;
  const Positions& positions = mesh.positions();
  soup.points.reserve(mesh.vertex_count());
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    soup.points.emplace_back(positions(v, 0), positions(v, 1), positions(v, 2));
  soup.polygons.reserve(mesh.face_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    soup.polygons.emplace_back(face.begin(), face.end());
  }
  return soup;
}

FaceVertexMesh from_cgal_polygon_soup(const CgalPolygonSoup& soup) {
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  sizes.reserve(soup.polygons.size());
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const auto& polygon = soup.polygons[f];
    for (std::size_t v : polygon) {
      if (v >= soup.points.size()) {
        throw TopologyError(
            detail::message("from_cgal_polygon_soup: polygon ", f, " uses vertex ", v, " of ", soup.points.size()));
      }
      indices.push_back(static_cast<std::uint32_t>(v));
    }
    sizes.push_back(static_cast<std::uint32_t>(polygon.size()));
  }
  return FaceVertexMesh(detail::positions_of(soup.points), std::move(sizes), std::move(indices));
}

}  // namespace patchwork
