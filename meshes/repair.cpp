#include "meshes/repair.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "meshes/edge_table.h"
#include "meshes/orientation.h"

namespace patchwork {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

// A mutable soup: faces as vertex lists, positions by source vertex.
struct Soup {
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<std::uint32_t> face_source;
  std::vector<std::uint32_t> vertex_source;

  FaceVertexMesh to_mesh(const FaceVertexMesh& input) const {
    Positions positions(static_cast<Eigen::Index>(vertex_source.size()), 3);
    for (std::size_t v = 0; v < vertex_source.size(); ++v) {
      positions.row(static_cast<Eigen::Index>(v)) = input.positions().row(vertex_source[v]);
    }
    std::vector<std::uint32_t> sizes;
    std::vector<std::uint32_t> indices;
    for (const auto& face : faces) {
      sizes.push_back(static_cast<std::uint32_t>(face.size()));
      indices.insert(indices.end(), face.begin(), face.end());
    }
    return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
  }
};

// Step 2: one copy of each vertex per fan; corners join across edges with exactly two faces.
// Returns whether any vertex was split.
bool split_fans(Soup& soup, const FaceVertexMesh& input, std::vector<bool>& split) {
  const FaceVertexMesh mesh = soup.to_mesh(input);
  const EdgeTable table = build_edge_table(mesh);
  std::vector<std::size_t> first_corner(mesh.face_count() + 1, 0);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) first_corner[f + 1] = first_corner[f] + mesh.face_sizes()[f];
  const auto corner_at = [&](std::uint32_t f, std::uint32_t v) {
    for (std::size_t c = first_corner[f]; c < first_corner[f + 1]; ++c) {
      if (mesh.face_indices()[c] == v) return static_cast<std::uint32_t>(c);
    }
    return 0xffffffffu;
  };
  UnionFind fans(mesh.face_indices().size());
  for (std::size_t e = 0; e < table.uses.size(); ++e) {
    const auto& uses = table.uses[e];
    if (uses.size() != 2) continue;
    for (std::uint32_t v : table.vertices[e]) fans.unite(corner_at(uses[0].face, v), corner_at(uses[1].face, v));
  }
  // The first fan of each vertex keeps the vertex; later fans get copies.
  std::unordered_map<std::uint32_t, std::uint32_t> vertex_of_fan;
  std::vector<bool> taken(soup.vertex_source.size(), false);
  bool any = false;
  std::size_t c = 0;
  for (auto& face : soup.faces) {
    for (std::uint32_t& v : face) {
      const std::uint32_t root = fans.find(static_cast<std::uint32_t>(c++));
      const auto it = vertex_of_fan.find(root);
      if (it != vertex_of_fan.end()) {
        v = it->second;
      } else if (!taken[v]) {
        taken[v] = true;
        vertex_of_fan.emplace(root, v);
      } else {
        const auto copy = static_cast<std::uint32_t>(soup.vertex_source.size());
        soup.vertex_source.push_back(soup.vertex_source[v]);
        split[soup.vertex_source[v]] = true;
        vertex_of_fan.emplace(root, copy);
        v = copy;
        any = true;
      }
    }
  }
  return any;
}

// Cuts edges still used by more than two faces: faces beyond the first two get own copies.
bool cut_crowded_edges(Soup& soup, const FaceVertexMesh& input, std::vector<bool>& split) {
  const EdgeTable table = build_edge_table(soup.to_mesh(input));
  bool any = false;
  for (std::size_t e = 0; e < table.uses.size(); ++e) {
    const auto& uses = table.uses[e];
    for (std::size_t k = 2; k < uses.size(); ++k) {
      for (std::uint32_t& v : soup.faces[uses[k].face]) {
        if (v != table.vertices[e][0] && v != table.vertices[e][1]) continue;
        const auto copy = static_cast<std::uint32_t>(soup.vertex_source.size());
        soup.vertex_source.push_back(soup.vertex_source[v]);
        split[soup.vertex_source[v]] = true;
        v = copy;
        any = true;
      }
    }
  }
  return any;
}

}  // namespace

RepairReport repair(const FaceVertexMesh& mesh) {
  RepairReport report{};
  Soup soup;
  soup.vertex_source.resize(mesh.vertex_count());
  std::iota(soup.vertex_source.begin(), soup.vertex_source.end(), 0u);
  std::vector<bool> split(mesh.vertex_count(), false);
  // 1. Merge consecutive repeats; remove what is left with < 3 corners; unpinch faces.
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    std::vector<std::uint32_t> corners;
    for (std::uint32_t v : mesh.face(f)) {
      if (corners.empty() || corners.back() != v) corners.push_back(v);
    }
    while (corners.size() > 1 && corners.front() == corners.back()) corners.pop_back();
    if (corners.size() != mesh.face(f).size()) report.merged_corner_faces.push_back(f);
    if (corners.size() < 3) {
      report.removed_faces.push_back(f);
      continue;
    }
    std::vector<std::uint32_t> seen;
    for (std::uint32_t& v : corners) {
      if (std::find(seen.begin(), seen.end(), v) != seen.end()) {
        const auto copy = static_cast<std::uint32_t>(soup.vertex_source.size());
        soup.vertex_source.push_back(v);
        split[v] = true;
        v = copy;
      } else {
        seen.push_back(v);
      }
    }
    soup.faces.push_back(std::move(corners));
    soup.face_source.push_back(f);
  }
  // 2. Split fans and crowded edges until nothing changes (each round only adds copies).
  for (int round = 0; round < 8; ++round) {
    const bool fans = split_fans(soup, mesh, split);
    const bool edges = cut_crowded_edges(soup, mesh, split);
    if (!fans && !edges) break;
  }
  // 3. Orientation.
  const Orientation orientation = orient(soup.to_mesh(mesh));
  report.mesh = orientation.mesh;
  report.source_vertex = soup.vertex_source;
  report.face_source = soup.face_source;
  for (FaceId f : orientation.flipped) report.flipped_faces.push_back(soup.face_source[f.index()]);
  report.orientable = std::all_of(orientation.component_orientable.begin(), orientation.component_orientable.end(),
                                  [](bool b) { return b; });
  report.non_orientable_cycles = orientation.non_orientable_cycles;
  for (std::uint32_t v = 0; v < split.size(); ++v) {
    if (split[v]) report.split_vertices.push_back(v);
  }
  return report;
}

std::string describe(const RepairReport& r) {
  std::ostringstream out;
  const auto list = [&out](const char* what, const std::vector<std::uint32_t>& items) {
    if (items.empty()) return;
    out << what << " (" << items.size() << "):";
    for (std::size_t k = 0; k < items.size() && k < 20; ++k) out << " " << items[k];
    if (items.size() > 20) out << " ...";
    out << "\n";
  };
  list("removed faces with fewer than 3 distinct corners", r.removed_faces);
  list("faces with repeated corners merged", r.merged_corner_faces);
  list("vertices split (non-manifold or pinched)", r.split_vertices);
  list("faces flipped for a consistent orientation", r.flipped_faces);
  if (!r.orientable) out << "not orientable: " << r.non_orientable_cycles.size() << " component(s) stay non-orientable\n";
  if (!r.changed()) out << "nothing to repair\n";
  return out.str();
}

}  // namespace patchwork
