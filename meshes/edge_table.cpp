#include "meshes/edge_table.h"

#include <algorithm>
#include <unordered_map>

namespace patchwork {

EdgeTable build_edge_table(const FaceVertexMesh& mesh) {
  EdgeTable table;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_of;
  edge_of.reserve(mesh.face_indices().size());
  table.corner_edge.resize(mesh.face_indices().size());
  std::size_t corner = 0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 0; k < face.size(); ++k, ++corner) {
      const std::uint32_t a = face[k];
      const std::uint32_t b = face[(k + 1) % face.size()];
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      const auto [it, inserted] = edge_of.try_emplace(key, static_cast<std::uint32_t>(table.vertices.size()));
      if (inserted) {
        table.vertices.push_back({a, b});
        table.uses.emplace_back();
      }
      table.uses[it->second].push_back({f, table.vertices[it->second][0] == a});
      table.corner_edge[corner] = it->second;
    }
  }
  return table;
}

}  // namespace patchwork
