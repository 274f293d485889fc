#include "meshes/topology.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <ostream>

#include "core/union_find.h"
#include "meshes/edge_table.h"
#include "meshes/orientation.h"

namespace patchwork {
namespace {

constexpr std::uint32_t unset = 0xffffffffu;

// The boundary loops of each component: closed walks that use every boundary edge once,
// continuing at each vertex with the first unused boundary edge there (in edge order).
// boundary: the boundary edges in edge order; result[c]: the loops of component c.
std::vector<Count> count_loops(const FaceVertexMesh& mesh, const detail::EdgeTable& table,
                               const std::vector<std::uint32_t>& boundary, const detail::FaceComponents& components) {
  if (boundary.empty()) return std::vector<Count>(components.count, 0);
  const std::vector<std::uint32_t>& component = components.of_face;
  const auto component_of = [&](std::uint32_t e) { return component[table.face_of(table.first_use(e))]; };
  // The boundary edges grouped by component, in edge order within each (a counting sort).
  std::vector<std::uint32_t> first(components.count + 1, 0);
  for (std::uint32_t e : boundary) ++first[component_of(e) + 1];
  for (std::size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];
  std::vector<std::uint32_t> edges(boundary.size());
  {
    std::vector<std::uint32_t> next = first;
    for (std::uint32_t e : boundary) edges[next[component_of(e)]++] = e;
  }
  // At each vertex, its boundary edges (positions k in `edges`), ascending: by component, then
  // by edge. Scanning for the first unused one passes the used ones of earlier components; one
  // of a later component means there is none left in this one.
  std::vector<std::uint32_t> at_start(mesh.vertex_count() + 2, 0);
  for (std::uint32_t e : edges) {
    for (std::uint32_t v : table.vertices(e)) ++at_start[v + 2];
  }
  for (std::size_t v = 2; v < at_start.size(); ++v) at_start[v] += at_start[v - 1];
  std::vector<std::uint32_t> at(2 * edges.size());
  for (std::uint32_t k = 0; k < edges.size(); ++k) {
    for (std::uint32_t v : table.vertices(edges[k])) at[at_start[v + 1]++] = k;
  }
  std::vector<bool> used(edges.size(), false);
  std::vector<Count> loops(components.count, 0);
  for (std::uint32_t c = 0; c < components.count; ++c) {
    for (std::uint32_t start = first[c]; start < first[c + 1]; ++start) {
      if (used[start]) continue;
      ++loops[c];
      used[start] = true;
      const std::uint32_t origin = table.vertices(edges[start])[0];
      std::uint32_t vertex = table.vertices(edges[start])[1];
      while (vertex != origin) {
        std::uint32_t next = unset;
        for (std::uint32_t i = at_start[vertex]; i < at_start[vertex + 1]; ++i) {
          if (!used[at[i]]) {
            next = at[i];
            break;
          }
        }
        if (next == unset || next >= first[c + 1]) break;  // only on odd-degree boundary vertices (non-manifold)
        used[next] = true;
        const auto ends = table.vertices(edges[next]);
        vertex = ends[0] == vertex ? ends[1] : ends[0];
      }
    }
  }
  return loops;
}

// The vertices whose faces form several fans, ascending: corners at a vertex are joined through
// each edge of two or more faces there (every corner of each such face at that end, should a
// face repeat the vertex). Where a vertex's edges have at most two faces and no face repeats it
// (nearly everywhere), a corner has at most two neighbours, and its fan is walked through twins;
// the other vertices are decided by a union-find over their corners.
std::vector<std::uint32_t> vertices_with_several_fans(const FaceVertexMesh& mesh, const detail::EdgeTable& table,
                                                      const std::vector<std::uint32_t>& repeating_faces,
                                                      const std::vector<std::uint32_t>& crowded_edges) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  std::vector<bool> general(mesh.vertex_count(), false);
  for (std::uint32_t f : repeating_faces) {
    const auto face = mesh.face(f);
    for (std::uint32_t v : face) general[v] = general[v] || std::count(face.begin(), face.end(), v) > 1;
  }
  for (std::uint32_t e : crowded_edges) {
    for (std::uint32_t v : table.vertices(e)) general[v] = true;
  }
  std::vector<std::uint32_t> several;
  // Walks: leaving corner z (at v) through the edge walked by `leave` (z for its outgoing edge,
  // the corner before z for its incoming one), the twin's face has its corner at v at the twin
  // or after it, and the walk goes on through that corner's other edge.
  std::vector<std::uint8_t> fans(mesh.vertex_count(), 0);
  std::vector<bool> visited(index.size(), false);
  for (std::uint32_t c = 0; c < index.size(); ++c) {
    const std::uint32_t v = index[c];
    if (general[v] || visited[c]) continue;
    visited[c] = true;
    if (fans[v] < 2 && ++fans[v] == 2) several.push_back(v);
    for (std::uint32_t leave : {c, table.prev_corner(c)}) {
      for (std::uint32_t twin = table.twin(leave); twin < detail::EdgeTable::crowded; twin = table.twin(leave)) {
        const std::uint32_t z = index[twin] == v ? twin : table.next_corner(twin);
        if (visited[z]) break;
        visited[z] = true;
        leave = z == twin ? table.prev_corner(z) : z;
      }
    }
  }
  if (std::find(general.begin(), general.end(), true) != general.end()) {
    UnionFind corners(index.size());
    for (std::uint32_t e = 0; e < table.edge_count(); ++e) {
      if (table.twin(table.first_use(e)) == detail::EdgeTable::none) continue;  // one face
      for (std::uint32_t end : table.vertices(e)) {
        if (!general[end]) continue;
        std::uint32_t first = unset;
        for (const detail::EdgeUse use : table.uses(e)) {
          detail::for_each_corner_at(mesh, use.face, end, [&](std::uint32_t c) {
            if (first == unset) {
              first = c;
            } else {
              corners.unite(first, c);
            }
          });
        }
      }
    }
    std::vector<std::uint32_t> fan_root(mesh.vertex_count(), unset);
    for (std::uint32_t c = 0; c < index.size(); ++c) {
      const std::uint32_t v = index[c];
      if (!general[v]) continue;
      const std::uint32_t root = corners.find(c);
      if (fan_root[v] == unset) {
        fan_root[v] = root;
      } else if (fan_root[v] != root && fans[v] < 2) {
        fans[v] = 2;
        several.push_back(v);
      }
    }
  }
  std::sort(several.begin(), several.end());
  return several;
}

}  // namespace

TopologyReport analyze(const FaceVertexMesh& mesh) {
  const detail::EdgeTable table(mesh);
  detail::OrientationWalk orientation = detail::walk_orientation(mesh, table);
  const detail::FaceComponents& components = orientation.components;
  const std::vector<std::uint32_t>& component = components.of_face;

  TopologyReport report{};
  report.faces = static_cast<Count>(mesh.face_count());
  report.edges = static_cast<Count>(table.edge_count());
  report.components = static_cast<Count>(components.count);
  report.non_orientable_cycles = std::move(orientation.non_orientable_cycles);
  report.per_component.assign(components.count, ComponentTopology{0, 0, 0, 0, 0, true, true, std::nullopt});

  // Vertices per component and in all; isolated vertices. Nearly every vertex lies in one
  // component: first_component[v] holds it, and (v, c) pairs for any other are kept apart.
  std::vector<std::uint32_t> first_component(mesh.vertex_count(), unset);
  std::vector<std::uint64_t> more_components;  // v << 32 | c, sorted and unique below
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t c = component[f];
    for (std::uint32_t v : mesh.face(f)) {
      if (first_component[v] == unset) {
        first_component[v] = c;
      } else if (first_component[v] != c) {
        more_components.push_back(static_cast<std::uint64_t>(v) << 32 | c);
      }
    }
    ++report.per_component[c].faces;
    if (repeated_vertex(mesh.face(f))) report.faces_repeating_a_vertex.push_back(f);
  }
  std::sort(more_components.begin(), more_components.end());
  more_components.erase(std::unique(more_components.begin(), more_components.end()), more_components.end());
  for (std::uint32_t c : first_component) {
    if (c == unset) {
      ++report.isolated_vertices;
    } else {
      ++report.vertices;
      ++report.per_component[c].vertices;
    }
  }
  for (std::uint64_t pair : more_components) ++report.per_component[static_cast<std::uint32_t>(pair)].vertices;

  // Edges: per component counts, boundary edges, non-manifold edges.
  std::vector<std::uint32_t> boundary;
  std::vector<std::uint32_t> crowded_edges;
  for (std::uint32_t e = 0; e < table.edge_count(); ++e) {
    const std::uint32_t first = table.first_use(e);
    const std::uint32_t c = component[table.face_of(first)];
    ++report.per_component[c].edges;
    if (table.twin(first) == detail::EdgeTable::none) {
      ++report.boundary_edges;
      boundary.push_back(e);
    } else if (table.twin(first) == detail::EdgeTable::crowded) {
      report.non_manifold_edges.push_back(table.vertices(e));
      crowded_edges.push_back(e);
      report.per_component[c].manifold = false;
    }
  }
  for (std::uint32_t f : report.faces_repeating_a_vertex) report.per_component[component[f]].manifold = false;

  report.non_manifold_vertices =
      vertices_with_several_fans(mesh, table, report.faces_repeating_a_vertex, crowded_edges);
  for (std::uint32_t v : report.non_manifold_vertices) {
    report.per_component[first_component[v]].manifold = false;
    const auto from = std::lower_bound(more_components.begin(), more_components.end(), static_cast<std::uint64_t>(v) << 32);
    for (auto it = from; it != more_components.end() && (*it >> 32) == v; ++it) {
      report.per_component[static_cast<std::uint32_t>(*it)].manifold = false;
    }
  }

  report.edge_manifold = report.non_manifold_edges.empty();
  report.vertex_manifold = report.non_manifold_vertices.empty() && report.faces_repeating_a_vertex.empty();
  report.manifold = report.edge_manifold && report.vertex_manifold;
  report.closed = report.boundary_edges == 0;
  report.euler = report.vertices - report.edges + report.faces;
  report.orientable = true;
  const std::vector<Count> loops = count_loops(mesh, table, boundary, components);
  Count genus = 0;
  bool genus_defined = true;
  for (std::size_t c = 0; c < components.count; ++c) {
    ComponentTopology& part = report.per_component[c];
    part.euler = part.vertices - part.edges + part.faces;
    part.boundary_loops = loops[c];
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
