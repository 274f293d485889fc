#include "meshes/edge_list_mesh.h"

#include <stdexcept>

#include "core/errors.h"
#include "meshes/edge_table.h"

namespace patchwork {

EdgeListMesh::EdgeListMesh(const FaceVertexMesh& mesh) : positions_(mesh.positions()) {
  const detail::EdgeTable table(mesh);
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  // Each edge's left and right face from its uses in corner order. The first corner (of all)
  // that walks an edge in a direction another face already walks it in is the error.
  constexpr std::uint32_t none = 0xffffffffu;
  struct Conflict {
    std::uint32_t corner = none;
    std::uint32_t face = none;
    FaceId earlier;
    bool both_sides = false;
  } conflict;
  left_.assign(table.edge_count(), FaceId());
  right_.assign(table.edge_count(), FaceId());
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const std::uint32_t from = index[table.first_use(e)];
    for (const detail::EdgeUse use : table.uses(e)) {
      FaceId& side = index[use.corner] == from ? left_[e] : right_[e];
      if (side.valid()) {
        if (use.corner < conflict.corner) conflict = {use.corner, use.face, side, left_[e].valid() && right_[e].valid()};
        break;
      }
      side = FaceId(use.face);
    }
  }
  if (conflict.corner != none) {
    const std::uint32_t a = index[conflict.corner];
    const std::uint32_t b = index[table.next_corner(conflict.corner)];
    throw TopologyError(detail::message("EdgeListMesh: edge (", a, ",", b, ") walked from ", a, " by faces ",
                                        conflict.earlier.value, " and ", conflict.face,
                                        (conflict.both_sides ? " (and a third face)" : ""),
                                        ": more than two faces or inconsistent orientation"));
  }
  edges_.reserve(table.edge_count());
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const auto [from, to] = table.vertices(e);
    edges_.push_back({VertexId(from), VertexId(to)});
  }
  face_edges_.resize(mesh.face_count());
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    for (std::size_t c = mesh.first_corner(f); c < mesh.first_corner(f + 1); ++c) {
      face_edges_[f].push_back(EdgeId(table.edge_of(static_cast<std::uint32_t>(c))));
    }
  }
}

void EdgeListMesh::validate() const {
  for (std::uint32_t f = 0; f < face_edges_.size(); ++f) {
    for (EdgeId e : face_edges_[f]) {
      if (left(e) != FaceId(f) && right(e) != FaceId(f)) throw std::logic_error("EdgeListMesh::validate: face not on its edge");
    }
  }
  for (std::uint32_t e = 0; e < edges_.size(); ++e) {
    if (!left_[e].valid() && !right_[e].valid()) throw std::logic_error("EdgeListMesh::validate: edge without a face");
  }
}

FaceVertexMesh to_face_vertex_mesh(const EdgeListMesh& mesh) {
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto& edges = mesh.face_edges(FaceId(f));
    sizes.push_back(static_cast<std::uint32_t>(edges.size()));
    // The face walks e from -> to when it is the left face, else to -> from: its corner is the
    // start. A face on both sides of an edge (it walks there and back, as in a b c b) leaves the
    // direction open there, so walk from a start corner and keep the walk that closes.
    const auto walk = [&](VertexId start, std::vector<std::uint32_t>& corners) {
      VertexId corner = start;
      for (EdgeId e : edges) {
        const auto& ends = mesh.edge(e);
        const bool left = mesh.left(e) == FaceId(f), right = mesh.right(e) == FaceId(f);
        if (!((corner == ends[0] && left) || (corner == ends[1] && right))) return false;
        corners.push_back(corner.value);
        corner = corner == ends[0] ? ends[1] : ends[0];
      }
      return corner == start;
    };
    const auto& first = mesh.edge(edges[0]);
    std::vector<std::uint32_t> corners;
    if (!walk(first[0], corners)) {
      corners.clear();
      walk(first[1], corners);
    }
    indices.insert(indices.end(), corners.begin(), corners.end());
  }
  return FaceVertexMesh(mesh.positions(), std::move(sizes), std::move(indices));
}

EdgeListMesh to_edge_list(const HalfedgeMesh& mesh) { return EdgeListMesh(to_face_vertex_mesh(mesh)); }

HalfedgeMesh to_halfedge_mesh(const EdgeListMesh& mesh) { return HalfedgeMesh(to_face_vertex_mesh(mesh)); }

}  // namespace patchwork
