#include "meshes/orientation.h"

#include <algorithm>
#include <deque>
#include <numeric>

#include "meshes/edge_table.h"

namespace patchwork {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller face is the root
  }
};

std::vector<std::uint32_t> components_of(const FaceVertexMesh& mesh, const EdgeTable& table) {
  UnionFind sets(mesh.face_count());
  for (const auto& uses : table.uses) {
    for (std::size_t k = 1; k < uses.size(); ++k) sets.unite(uses[0].face, uses[k].face);
  }
  std::vector<std::uint32_t> component(mesh.face_count());
  std::vector<std::uint32_t> number(mesh.face_count(), 0xffffffffu);
  std::uint32_t next = 0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t root = sets.find(f);
    if (number[root] == 0xffffffffu) number[root] = next++;
    component[f] = number[root];
  }
  return component;
}

// The path from f up to the root of the search tree.
std::vector<std::uint32_t> path_to_root(std::uint32_t f, const std::vector<std::uint32_t>& parent) {
  std::vector<std::uint32_t> path{f};
  while (parent[path.back()] != path.back()) path.push_back(parent[path.back()]);
  return path;
}

FaceVertexMesh with_flips(const FaceVertexMesh& mesh, const std::vector<bool>& flip) {
  std::vector<std::uint32_t> indices = mesh.face_indices();
  std::size_t offset = 0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::size_t size = mesh.face_sizes()[f];
    // Reversing all but the first corner keeps the first corner first.
    if (flip[f]) std::reverse(indices.begin() + static_cast<std::ptrdiff_t>(offset + 1), indices.begin() + static_cast<std::ptrdiff_t>(offset + size));
    offset += size;
  }
  return FaceVertexMesh(mesh.positions(), mesh.face_sizes(), std::move(indices));
}

// 6 times the signed volume of the cone from the origin over face f (fanned from corner 0).
double face_volume6(const FaceVertexMesh& mesh, std::uint32_t f) {
  const auto face = mesh.face(f);
  const Vec3 p0 = mesh.position(face[0]);
  double sum = 0.0;
  for (std::size_t k = 1; k + 1 < face.size(); ++k) sum += p0.dot(mesh.position(face[k]).cross(mesh.position(face[k + 1])));
  return sum;
}

}  // namespace

std::vector<std::uint32_t> face_components(const FaceVertexMesh& mesh) {
  return components_of(mesh, build_edge_table(mesh));
}

Orientation orient(const FaceVertexMesh& mesh) {
  const EdgeTable table = build_edge_table(mesh);
  const std::vector<std::uint32_t> component = components_of(mesh, table);
  const std::uint32_t components = mesh.face_count() == 0 ? 0 : *std::max_element(component.begin(), component.end()) + 1;
  // Faces' edges, to walk from a face to its neighbours.
  std::vector<std::size_t> first_corner(mesh.face_count() + 1, 0);
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) first_corner[f + 1] = first_corner[f] + mesh.face_sizes()[f];

  std::vector<bool> flip(mesh.face_count(), false);
  std::vector<bool> seen(mesh.face_count(), false);
  std::vector<std::uint32_t> parent(mesh.face_count());
  Orientation result{mesh, {}, std::vector<bool>(components, true), {}};
  for (std::uint32_t root = 0; root < mesh.face_count(); ++root) {
    if (seen[root]) continue;
    seen[root] = true;
    parent[root] = root;
    std::deque<std::uint32_t> queue{root};
    bool conflict_found = false;
    while (!queue.empty()) {
      const std::uint32_t f = queue.front();
      queue.pop_front();
      for (std::size_t c = first_corner[f]; c < first_corner[f + 1]; ++c) {
        const std::uint32_t e = table.corner_edge[c];
        const auto& uses = table.uses[e];
        if (uses.size() != 2) continue;
        const EdgeUse& mine = uses[0].face == f ? uses[0] : uses[1];
        const EdgeUse& other = uses[0].face == f ? uses[1] : uses[0];
        if (other.face == f) continue;  // a face meeting itself (a repeated vertex): no constraint between faces
        // Consistent when the two walk the edge in opposite directions after the flips.
        const bool needs_flip = (mine.forward != flip[f]) == other.forward;
        if (!seen[other.face]) {
          seen[other.face] = true;
          parent[other.face] = f;
          flip[other.face] = needs_flip;
          queue.push_back(other.face);
        } else if (flip[other.face] != needs_flip && !conflict_found) {
          conflict_found = true;
          result.component_orientable[component[root]] = false;
          // The cycle: f up to the common ancestor, then down to other.face.
          std::vector<std::uint32_t> up = path_to_root(f, parent);
          std::vector<std::uint32_t> down = path_to_root(other.face, parent);
          while (up.size() > 1 && down.size() > 1 && up[up.size() - 2] == down[down.size() - 2]) {
            up.pop_back();
            down.pop_back();
          }
          std::vector<FaceId> cycle;
          for (std::uint32_t g : up) cycle.push_back(FaceId(g));
          for (std::size_t k = down.size() - 1; k-- > 0;) cycle.push_back(FaceId(down[k]));
          result.non_orientable_cycles.push_back(std::move(cycle));
        }
      }
    }
  }
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (flip[f]) result.flipped.push_back(FaceId(f));
  }
  result.mesh = with_flips(mesh, flip);
  return result;
}

double signed_volume(const FaceVertexMesh& mesh) {
  double volume = 0.0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) volume += face_volume6(mesh, f);
  return volume / 6.0;
}

Orientation orient_outward(const FaceVertexMesh& mesh) {
  Orientation result = orient(mesh);
  const EdgeTable table = build_edge_table(result.mesh);
  const std::vector<std::uint32_t> component = components_of(result.mesh, table);
  const std::size_t components = result.component_orientable.size();
  std::vector<bool> closed(components, true);
  for (const auto& uses : table.uses) {
    if (uses.size() == 1) closed[component[uses[0].face]] = false;
  }
  // Signed volume per component, from the oriented faces.
  std::vector<double> volume(components, 0.0);
  for (std::uint32_t f = 0; f < result.mesh.face_count(); ++f) volume[component[f]] += face_volume6(result.mesh, f);
  std::vector<bool> flip(result.mesh.face_count(), false);
  bool any = false;
  for (std::uint32_t f = 0; f < result.mesh.face_count(); ++f) {
    const std::uint32_t c = component[f];
    flip[f] = closed[c] && result.component_orientable[c] && volume[c] < 0.0;
    any = any || flip[f];
  }
  if (!any) return result;
  result.mesh = with_flips(result.mesh, flip);
  // A face flipped twice is back where it started: report the net flips against the input.
  std::vector<bool> net(mesh.face_count(), false);
  for (FaceId f : result.flipped) net[f.index()] = true;
  result.flipped.clear();
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (net[f] != flip[f]) result.flipped.push_back(FaceId(f));
  }
  return result;
}

}  // namespace patchwork
