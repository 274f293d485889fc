#pragma once
// orient() and analyze() computed the slow, obvious way, for any soup: ordered maps of edges,
// a breadth-first walk over faces, the faces around each vertex grouped by searching them. The
// meshes tests compare meshes/ against these on damaged surfaces and random soups, where every
// answer must agree (the proof cycles and the boundary loops at non-manifold vertices included,
// which depend on the conventions written out in meshes/orientation.h and meshes/topology.h).

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork::testing {

/// The undirected edges in order of first use (corner order), each with its walks.
inline std::vector<std::vector<Walk>> edges_by_first_use(const FaceVertexMesh& mesh) {
  std::map<std::uint64_t, std::size_t> number;
  std::vector<std::vector<Walk>> edges;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Walk walk{f, face[k], face[(k + 1) % face.size()]};
      const auto [it, inserted] = number.try_emplace(edge_key(walk.from, walk.to), edges.size());
      if (inserted) edges.emplace_back();
      edges[it->second].push_back(walk);
    }
  }
  return edges;
}

/// orient()'s answers (without the mesh): from each face not reached yet, in face order, a
/// breadth-first walk through edges of exactly two different faces, each face reached flipped
/// so that the two walk the edge in opposite directions; the first face found that would need
/// both flips gives the cycle (the walk's tree paths up to their common ancestor).
inline Orientation reference_orient(const FaceVertexMesh& mesh) {
  const std::vector<std::uint32_t> component = reference_components(mesh);
  const std::uint32_t components =
      component.empty() ? 0 : *std::max_element(component.begin(), component.end()) + 1;
  const auto walks = edge_walks(mesh);
  Orientation result{FaceVertexMesh(), {}, std::vector<bool>(components, true), {}};
  std::vector<bool> flip(mesh.face_count(), false), reached(mesh.face_count(), false);
  std::vector<std::uint32_t> parent(mesh.face_count());
  const auto path_up = [&parent](std::uint32_t f) {
    std::vector<std::uint32_t> path{f};
    while (parent[path.back()] != path.back()) path.push_back(parent[path.back()]);
    return path;
  };
  for (std::uint32_t root = 0; root < mesh.face_count(); ++root) {
    if (reached[root]) continue;
    reached[root] = true;
    parent[root] = root;
    std::deque<std::uint32_t> queue{root};
    bool found = false;
    while (!queue.empty()) {
      const std::uint32_t f = queue.front();
      queue.pop_front();
      const auto face = mesh.face(f);
      for (std::size_t k = 0; k < face.size(); ++k) {
        const auto& w = walks.at(edge_key(face[k], face[(k + 1) % face.size()]));
        if (w.size() != 2 || w[0].face == w[1].face) continue;
        const Walk& mine = w[0].face == f ? w[0] : w[1];
        const Walk& other = w[0].face == f ? w[1] : w[0];
        const bool wanted = (mine.from == other.from) != flip[f];  // the same way round: flip one
        if (!reached[other.face]) {
          reached[other.face] = true;
          parent[other.face] = f;
          flip[other.face] = wanted;
          queue.push_back(other.face);
        } else if (flip[other.face] != wanted && !found) {
          found = true;
          result.component_orientable[component[root]] = false;
          std::vector<std::uint32_t> up = path_up(f), down = path_up(other.face);
          while (up.size() > 1 && down.size() > 1 && up[up.size() - 2] == down[down.size() - 2]) {
            up.pop_back();
            down.pop_back();
          }
          std::vector<FaceId> cycle;
          for (std::uint32_t g : up) cycle.push_back(FaceId(g));
          for (auto it = down.rbegin() + 1; it != down.rend(); ++it) cycle.push_back(FaceId(*it));
          result.non_orientable_cycles.push_back(cycle);
        }
      }
    }
  }
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (flip[f]) result.flipped.push_back(FaceId(f));
  }
  return result;
}

/// The vertices whose corners fall into several fans: through each edge at v with two faces or
/// more, the corners at v of all its faces are joined (every corner of such a face at v, should
/// the face repeat v); a fan is a group of corners so joined.
inline std::vector<std::uint32_t> reference_several_fans(const FaceVertexMesh& mesh) {
  const auto walks = edge_walks(mesh);
  std::map<std::uint32_t, std::vector<std::uint32_t>> faces_at;  // vertex -> the face of each corner there
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    for (std::uint32_t v : mesh.face(f)) faces_at[v].push_back(f);
  }
  std::vector<std::uint32_t> several;
  for (const auto& [v, faces] : faces_at) {
    std::vector<std::size_t> fan(faces.size());  // a label per corner at v
    for (std::size_t i = 0; i < fan.size(); ++i) fan[i] = i;
    for (const auto& [key, w] : walks) {
      if (w.size() < 2 || (w[0].from != v && w[0].to != v)) continue;
      std::set<std::uint32_t> joined;
      for (const Walk& walk : w) joined.insert(walk.face);
      std::optional<std::size_t> label;
      for (std::size_t i = 0; i < faces.size(); ++i) {
        if (joined.count(faces[i]) == 0) continue;
        if (!label) {
          label = fan[i];
          continue;
        }
        const std::size_t old = fan[i];
        for (std::size_t& l : fan) l = l == old ? *label : l;
      }
    }
    if (std::any_of(fan.begin(), fan.end(), [&](std::size_t l) { return l != fan[0]; })) several.push_back(v);
  }
  return several;
}

/// Boundary loops of one component, by topology.h's convention: from each unused boundary edge
/// (in edge order) walk on, at each vertex taking its first unused boundary edge in edge order,
/// until the walk is back at its start or stuck (an odd boundary vertex).
inline Count reference_loops(const std::vector<std::array<std::uint32_t, 2>>& edges) {
  std::map<std::uint32_t, std::vector<std::size_t>> at;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    at[edges[k][0]].push_back(k);
    at[edges[k][1]].push_back(k);
  }
  std::vector<bool> used(edges.size(), false);
  Count loops = 0;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (used[start]) continue;
    ++loops;
    used[start] = true;
    std::uint32_t vertex = edges[start][1];
    while (vertex != edges[start][0]) {
      const auto& list = at[vertex];
      const auto next = std::find_if(list.begin(), list.end(), [&](std::size_t k) { return !used[k]; });
      if (next == list.end()) break;
      used[*next] = true;
      vertex = edges[*next][0] == vertex ? edges[*next][1] : edges[*next][0];
    }
  }
  return loops;
}

/// analyze() by definition (meshes/topology.h), element by element.
inline TopologyReport reference_analyze(const FaceVertexMesh& mesh) {
  const std::vector<std::uint32_t> component = reference_components(mesh);
  const Orientation orientation = reference_orient(mesh);
  const std::size_t components = orientation.component_orientable.size();
  const auto edges = edges_by_first_use(mesh);
  TopologyReport r{};
  r.faces = static_cast<Count>(mesh.face_count());
  r.edges = static_cast<Count>(edges.size());
  r.components = static_cast<Count>(components);
  r.per_component.assign(components, ComponentTopology{0, 0, 0, 0, 0, true, true, std::nullopt});
  r.non_orientable_cycles = orientation.non_orientable_cycles;
  std::map<std::uint32_t, std::set<std::uint32_t>> components_at;  // vertex -> components
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    ++r.per_component[component[f]].faces;
    for (std::uint32_t v : mesh.face(f)) components_at[v].insert(component[f]);
    const std::set<std::uint32_t> distinct(mesh.face(f).begin(), mesh.face(f).end());
    if (distinct.size() != mesh.face(f).size()) {
      r.faces_repeating_a_vertex.push_back(f);
      r.per_component[component[f]].manifold = false;
    }
  }
  r.vertices = static_cast<Count>(components_at.size());
  r.isolated_vertices = static_cast<Count>(mesh.vertex_count()) - r.vertices;
  for (const auto& [v, set] : components_at) {
    for (std::uint32_t c : set) ++r.per_component[c].vertices;
  }
  std::vector<std::vector<std::array<std::uint32_t, 2>>> boundary(components);
  for (const auto& walks : edges) {
    const std::uint32_t c = component[walks[0].face];
    ++r.per_component[c].edges;
    if (walks.size() == 1) boundary[c].push_back({walks[0].from, walks[0].to});
    if (walks.size() > 2) {
      r.non_manifold_edges.push_back({walks[0].from, walks[0].to});
      r.per_component[c].manifold = false;
    }
  }
  r.non_manifold_vertices = reference_several_fans(mesh);
  for (std::uint32_t v : r.non_manifold_vertices) {
    for (std::uint32_t c : components_at[v]) r.per_component[c].manifold = false;
  }
  r.orientable = true;
  r.genus = 0;
  for (std::size_t c = 0; c < components; ++c) {
    ComponentTopology& part = r.per_component[c];
    part.euler = part.vertices - part.edges + part.faces;
    part.boundary_loops = reference_loops(boundary[c]);
    part.orientable = orientation.component_orientable[c];
    r.boundary_edges += static_cast<Count>(boundary[c].size());
    r.boundary_loops += part.boundary_loops;
    r.orientable = r.orientable && part.orientable;
    if (part.orientable && part.manifold) part.genus = (2 - part.euler - part.boundary_loops) / 2;
    r.genus = part.genus && r.genus ? std::optional<Count>(*r.genus + *part.genus) : std::nullopt;
  }
  r.euler = r.vertices - r.edges + r.faces;
  r.closed = r.boundary_edges == 0;
  r.edge_manifold = r.non_manifold_edges.empty();
  r.vertex_manifold = r.non_manifold_vertices.empty() && r.faces_repeating_a_vertex.empty();
  r.manifold = r.edge_manifold && r.vertex_manifold;
  return r;
}

}  // namespace patchwork::testing
