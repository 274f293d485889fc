#include "meshes/topology.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <numeric>
#include <ostream>
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

// Number of cycles in the boundary graph: closed walks that use every boundary edge once,
// continuing at each vertex with the first unused boundary edge there.
Count count_loops(const std::vector<std::array<std::uint32_t, 2>>& edges) {
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> at;
  for (std::uint32_t k = 0; k < edges.size(); ++k) {
    at[edges[k][0]].push_back(k);
    at[edges[k][1]].push_back(k);
  }
  std::vector<bool> used(edges.size(), false);
  Count loops = 0;
  for (std::uint32_t start = 0; start < edges.size(); ++start) {
    if (used[start]) continue;
    ++loops;
    used[start] = true;
    const std::uint32_t origin = edges[start][0];
    std::uint32_t vertex = edges[start][1];
    while (vertex != origin) {
      std::uint32_t next = 0xffffffffu;
      for (std::uint32_t k : at[vertex]) {
        if (!used[k]) {
          next = k;
          break;
        }
      }
      if (next == 0xffffffffu) break;  // only on odd-degree boundary vertices (non-manifold)
      used[next] = true;
      vertex = edges[next][0] == vertex ? edges[next][1] : edges[next][0];
    }
  }
  return loops;
}

}  // namespace

TopologyReport analyze(const FaceVertexMesh& mesh) {
  const EdgeTable table = build_edge_table(mesh);
  const std::vector<std::uint32_t> component = face_components(mesh);
  const Orientation orientation = orient(mesh);
  const auto components = static_cast<std::size_t>(orientation.component_orientable.size());

  TopologyReport report{};
  report.faces = static_cast<Count>(mesh.face_count());
  report.edges = static_cast<Count>(table.vertices.size());
  report.components = static_cast<Count>(components);
  report.non_orientable_cycles = orientation.non_orientable_cycles;

  // Vertices per component and in all; isolated vertices.
  std::vector<std::vector<std::uint32_t>> vertex_components(mesh.vertex_count());
  std::vector<std::size_t> first_corner(mesh.face_count() + 1, 0);
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    first_corner[f + 1] = first_corner[f] + mesh.face_sizes()[f];
    for (std::uint32_t v : mesh.face(f)) vertex_components[v].push_back(component[f]);
    std::vector<std::uint32_t> corners(mesh.face(f).begin(), mesh.face(f).end());
    std::sort(corners.begin(), corners.end());
    if (std::adjacent_find(corners.begin(), corners.end()) != corners.end()) report.faces_repeating_a_vertex.push_back(f);
  }
  report.per_component.assign(components, ComponentTopology{0, 0, 0, 0, 0, true, true, std::nullopt});
  for (auto& list : vertex_components) {
    if (list.empty()) {
      ++report.isolated_vertices;
      continue;
    }
    ++report.vertices;
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (std::uint32_t c : list) ++report.per_component[c].vertices;
  }
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) ++report.per_component[component[f]].faces;

  // Edges: per component counts, boundary edges, non-manifold edges.
  std::vector<std::vector<std::array<std::uint32_t, 2>>> boundary(components);
  for (std::size_t e = 0; e < table.vertices.size(); ++e) {
    const std::uint32_t c = component[table.uses[e][0].face];
    ++report.per_component[c].edges;
    if (table.uses[e].size() == 1) {
      ++report.boundary_edges;
      boundary[c].push_back(table.vertices[e]);
    } else if (table.uses[e].size() > 2) {
      report.non_manifold_edges.push_back(table.vertices[e]);
      report.per_component[c].manifold = false;
    }
  }
  for (std::uint32_t f : report.faces_repeating_a_vertex) report.per_component[component[f]].manifold = false;

  // Vertex fans: corners at the same vertex are joined through each edge both faces share there.
  UnionFind corners(mesh.face_indices().size());
  for (std::size_t e = 0; e < table.uses.size(); ++e) {
    const auto& uses = table.uses[e];
    if (uses.size() < 2) continue;
    for (std::uint32_t end : table.vertices[e]) {
      // The corners of each using face at vertex `end`.
      std::vector<std::size_t> at_end;
      for (const EdgeUse& use : uses) {
        for (std::size_t c = first_corner[use.face]; c < first_corner[use.face + 1]; ++c) {
          if (mesh.face_indices()[c] == end) at_end.push_back(c);
        }
      }
      for (std::size_t k = 1; k < at_end.size(); ++k) {
        corners.unite(static_cast<std::uint32_t>(at_end[0]), static_cast<std::uint32_t>(at_end[k]));
      }
    }
  }
  std::vector<std::uint32_t> fan_root(mesh.vertex_count(), 0xffffffffu);
  std::vector<bool> reported(mesh.vertex_count(), false);
  for (std::size_t c = 0; c < mesh.face_indices().size(); ++c) {
    const std::uint32_t v = mesh.face_indices()[c];
    const std::uint32_t root = corners.find(static_cast<std::uint32_t>(c));
    if (fan_root[v] == 0xffffffffu) {
      fan_root[v] = root;
    } else if (fan_root[v] != root && !reported[v]) {
      reported[v] = true;
      report.non_manifold_vertices.push_back(v);
    }
  }
  std::sort(report.non_manifold_vertices.begin(), report.non_manifold_vertices.end());
  for (std::uint32_t v : report.non_manifold_vertices) {
    for (std::uint32_t c : vertex_components[v]) report.per_component[c].manifold = false;
  }

  report.edge_manifold = report.non_manifold_edges.empty();
  report.vertex_manifold = report.non_manifold_vertices.empty() && report.faces_repeating_a_vertex.empty();
  report.manifold = report.edge_manifold && report.vertex_manifold;
  report.closed = report.boundary_edges == 0;
  report.euler = report.vertices - report.edges + report.faces;
  report.orientable = true;
  Count genus = 0;
  bool genus_defined = true;
  for (std::size_t c = 0; c < components; ++c) {
    ComponentTopology& part = report.per_component[c];
    part.euler = part.vertices - part.edges + part.faces;
    part.boundary_loops = count_loops(boundary[c]);
    part.orientable = orientation.component_orientable[c];
    report.boundary_loops += part.boundary_loops;
    report.orientable = report.orientable && part.orientable;
    if (part.orientable && part.manifold) {
      part.genus = (2 - part.euler - part.boundary_loops) / 2;
      genus += *part.genus;
    } else {
      genus_defined = false;
    }
  }
  if (genus_defined) report.genus = genus;
  return report;
}

std::ostream& operator<<(std::ostream& out, const TopologyReport& r) {
  const auto yes = [](bool b) { return b ? "yes" : "no"; };
  out << "vertices: " << r.vertices << " (isolated, not counted: " << r.isolated_vertices << ")\n"
      << "edges: " << r.edges << "\nfaces: " << r.faces << "\ncomponents: " << r.components
      << "\nboundary edges: " << r.boundary_edges << "\nboundary loops: " << r.boundary_loops
      << "\nclosed: " << yes(r.closed) << "\norientable: " << yes(r.orientable) << "\nmanifold: " << yes(r.manifold)
      << " (edges: " << yes(r.edge_manifold) << ", vertices: " << yes(r.vertex_manifold) << ")\neuler characteristic: " << r.euler
      << "\ngenus: ";
  if (r.genus) {
    out << *r.genus;
  } else {
    out << "undefined (a component is non-orientable or non-manifold)";
  }
  out << "\n";
  for (const auto& e : r.non_manifold_edges) out << "non-manifold edge (" << e[0] << "," << e[1] << ")\n";
  for (std::uint32_t v : r.non_manifold_vertices) out << "non-manifold vertex " << v << "\n";
  for (std::uint32_t f : r.faces_repeating_a_vertex) out << "face repeating a vertex " << f << "\n";
  for (const auto& cycle : r.non_orientable_cycles) {
    out << "non-orientable along faces";
    for (FaceId f : cycle) out << " " << f.value;
    out << "\n";
  }
  return out;
}

std::string to_json(const TopologyReport& r) {
  using nlohmann::json;
  json components = json::array();
  for (const ComponentTopology& c : r.per_component) {
    components.push_back({{"vertices", c.vertices}, {"edges", c.edges}, {"faces", c.faces}, {"euler", c.euler},
                          {"boundary_loops", c.boundary_loops}, {"orientable", c.orientable}, {"manifold", c.manifold},
                          {"genus", c.genus ? json(*c.genus) : json(nullptr)}});
  }
  json cycles = json::array();
  for (const auto& cycle : r.non_orientable_cycles) {
    json faces = json::array();
    for (FaceId f : cycle) faces.push_back(f.value);
    cycles.push_back(faces);
  }
  const json document = {{"vertices", r.vertices},
                         {"edges", r.edges},
                         {"faces", r.faces},
                         {"components", r.components},
                         {"boundary_loops", r.boundary_loops},
                         {"closed", r.closed},
                         {"orientable", r.orientable},
                         {"manifold", r.manifold},
                         {"euler", r.euler},
                         {"genus", r.genus ? json(*r.genus) : json(nullptr)},
                         {"isolated_vertices", r.isolated_vertices},
                         {"boundary_edges", r.boundary_edges},
                         {"non_manifold_edges", r.non_manifold_edges},
                         {"non_manifold_vertices", r.non_manifold_vertices},
                         {"faces_repeating_a_vertex", r.faces_repeating_a_vertex},
                         {"non_orientable_cycles", cycles},
                         {"per_component", components}};
  return document.dump(2);
}

}  // namespace patchwork
