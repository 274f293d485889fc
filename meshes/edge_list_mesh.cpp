#include "meshes/edge_list_mesh.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

#include "core/errors.h"

namespace patchwork {

EdgeListMesh::EdgeListMesh(const FaceVertexMesh& mesh) : positions_(mesh.positions()) {
  std::unordered_map<std::uint64_t, std::uint32_t> edge_of;
  edge_of.reserve(mesh.face_indices().size());
  face_edges_.resize(mesh.face_count());
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::uint32_t a = face[k];
      const std::uint32_t b = face[(k + 1) % face.size()];
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      const auto [it, inserted] = edge_of.try_emplace(key, static_cast<std::uint32_t>(edges_.size()));
      if (inserted) {
        edges_.push_back({VertexId(a), VertexId(b)});
        left_.emplace_back();
        right_.emplace_back();
      }
      const std::uint32_t e = it->second;
      FaceId& side = edges_[e][0].value == a ? left_[e] : right_[e];
      if (side.valid()) {
        throw TopologyError(detail::message("EdgeListMesh: edge (", a, ",", b, ") walked from ", a, " by faces ", side.value,
                                            " and ", f, (left_[e].valid() && right_[e].valid() ? " (and a third face)" : ""),
                                            ": more than two faces or inconsistent orientation"));
      }
      side = FaceId(f);
      face_edges_[f].push_back(EdgeId(e));
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
