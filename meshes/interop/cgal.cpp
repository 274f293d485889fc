#include "meshes/interop/cgal.h"

#include <string>

#include "core/errors.h"

namespace patchwork {
namespace {

using VertexIndex = CgalSurfaceMesh::Vertex_index;

std::string corners_text(std::span<const std::uint32_t> face) {
  std::string text;
  for (std::uint32_t v : face) {
    if (!text.empty()) text += ' ';
    text += std::to_string(v);
  }
  return text;
}

// Why CGAL refused face f (all faces before it were added, so face indices are our ids).
std::string refusal_reason(const CgalSurfaceMesh& sm, std::span<const std::uint32_t> face) {
  for (std::size_t k = 0; k < face.size(); ++k) {
    for (std::size_t j = k + 1; j < face.size(); ++j) {
      if (face[k] == face[j]) return detail::message("it uses vertex ", face[k], " more than once");
    }
  }
  for (std::size_t k = 0; k < face.size(); ++k) {
    const std::uint32_t a = face[k];
    const std::uint32_t b = face[(k + 1) % face.size()];
    const auto h = sm.halfedge(VertexIndex(a), VertexIndex(b));
    if (h != CgalSurfaceMesh::null_halfedge() && !sm.is_border(h)) {
      return detail::message("edge (", a, ",", b, ") is already walked from ", a, " to ", b, " by face ",
                             static_cast<std::uint32_t>(sm.face(h)),
                             " (an edge with three faces, or inconsistent orientation)");
    }
  }
  for (std::uint32_t v : face) {
    const VertexIndex vi(v);
    if (!sm.is_isolated(vi) && !sm.is_border(vi)) {
      return detail::message("vertex ", v, " is already surrounded by faces (a non-manifold vertex)");
    }
  }
  return "its vertices' fans cannot be linked (a non-manifold vertex)";
}

Positions positions_of(const std::vector<CgalPoint>& points) {
  Positions positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (int k = 0; k < 3; ++k) positions(static_cast<Eigen::Index>(v), k) = points[v][k];
  }
  return positions;
}

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
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    corners.clear();
    for (std::uint32_t v : face) corners.push_back(VertexIndex(v));
    if (sm.add_face(corners) == CgalSurfaceMesh::null_face()) {
      throw TopologyError(detail::message("to_cgal_surface_mesh: CGAL cannot add face ", f, " (", corners_text(face),
                                          "): ", refusal_reason(sm, face)));
    }
  }
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
  return FaceVertexMesh(positions_of(points), std::move(sizes), std::move(indices));
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
  return FaceVertexMesh(positions_of(soup.points), std::move(sizes), std::move(indices));
}

}  // namespace patchwork
