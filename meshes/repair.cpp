#include "meshes/repair.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "core/union_find.h"
#include "meshes/edge_table.h"
#include "meshes/orientation.h"

namespace patchwork {
namespace {

constexpr std::uint32_t none = 0xffffffffu;

// A mutable soup: a face list whose vertices are copies of input vertices (vertex_source).
struct Soup {
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> face_source;
  std::vector<std::uint32_t> vertex_source;

  FaceVertexMesh to_mesh(const FaceVertexMesh& input) const {
    return FaceVertexMesh(input.positions()(vertex_source, Eigen::all), sizes, indices);
  }

  // A new copy of soup vertex v; split[its input vertex] is set.
  std::uint32_t copy_of(std::uint32_t v, std::vector<bool>& split) {
    const auto copy = static_cast<std::uint32_t>(vertex_source.size());
    vertex_source.push_back(vertex_source[v]);
    split[vertex_source[v]] = true;
    return copy;
  }
};

// Step 2: one copy of each vertex per fan; corners join across edges with exactly two faces.
// Returns whether any vertex was split.
bool split_fans(Soup& soup, const FaceVertexMesh& input, std::vector<bool>& split) {
  const FaceVertexMesh mesh = soup.to_mesh(input);
  const detail::EdgeTable table(mesh);
  UnionFind fans(mesh.face_indices().size());
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    if (!table.has_two_uses(e)) continue;
    const auto uses = table.first_two_uses(e);
    for (std::uint32_t v : table.vertices(e)) {
      fans.unite(detail::corner_at(mesh, uses[0].face, v), detail::corner_at(mesh, uses[1].face, v));
    }
  }
  // The first fan of each vertex keeps the vertex; later fans get copies.
  std::vector<std::uint32_t> vertex_of_fan(soup.indices.size(), none);  // by the fan's root corner
  std::vector<bool> taken(soup.vertex_source.size(), false);
  bool any = false;
  for (std::uint32_t c = 0; c < soup.indices.size(); ++c) {
    std::uint32_t& v = soup.indices[c];
    std::uint32_t& fan_vertex = vertex_of_fan[fans.find(c)];
    if (fan_vertex != none) {
      v = fan_vertex;
    } else if (!taken[v]) {
      taken[v] = true;
      fan_vertex = v;
    } else {
      v = fan_vertex = soup.copy_of(v, split);
      any = true;
    }
  }
  return any;
}

// Cuts edges still used by more than two faces: faces beyond the first two get own copies.
bool cut_crowded_edges(Soup& soup, const FaceVertexMesh& input, std::vector<bool>& split) {
  const FaceVertexMesh mesh = soup.to_mesh(input);
  const detail::EdgeTable table(mesh);
  bool any = false;
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const auto [a, b] = table.vertices(e);
    std::size_t k = 0;
    for (const detail::EdgeUse use : table.uses(e)) {
      if (k++ < 2) continue;
      for (std::size_t c = mesh.first_corner(use.face); c < mesh.first_corner(use.face + 1); ++c) {
        std::uint32_t& v = soup.indices[c];
        if (v != a && v != b) continue;
        v = soup.copy_of(v, split);
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
  std::vector<std::uint32_t> corners;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    corners.clear();
    for (std::uint32_t v : mesh.face(f)) {
      if (corners.empty() || corners.back() != v) corners.push_back(v);
    }
    while (corners.size() > 1 && corners.front() == corners.back()) corners.pop_back();
    if (corners.size() != mesh.face(f).size()) report.merged_corner_faces.push_back(f);
    if (corners.size() < 3) {
      report.removed_faces.push_back(f);
      continue;
    }
    for (std::size_t k = 1; k < corners.size(); ++k) {
      if (std::find(corners.begin(), corners.begin() + static_cast<std::ptrdiff_t>(k), corners[k]) !=
          corners.begin() + static_cast<std::ptrdiff_t>(k)) {
        corners[k] = soup.copy_of(corners[k], split);
      }
    }
    soup.sizes.push_back(static_cast<std::uint32_t>(corners.size()));
    soup.indices.insert(soup.indices.end(), corners.begin(), corners.end());
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
