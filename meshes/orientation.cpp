#include "meshes/orientation.h"

#include <algorithm>
#include <numeric>

#include "core/union_find.h"
#include "meshes/edge_table.h"

namespace patchwork {
namespace {

// The path from f up to the root of the search tree.
std::vector<std::uint32_t> path_to_root(std::uint32_t f, const std::vector<std::uint32_t>& parent) {
  std::vector<std::uint32_t> path{f};
  while (parent[path.back()] != path.back()) path.push_back(parent[path.back()]);
  return path;
}

FaceVertexMesh with_flips(const FaceVertexMesh& mesh, const std::vector<bool>& flip) {
  std::vector<std::uint32_t> indices = mesh.face_indices();
  detail::flip_corners(mesh.face_sizes(), flip, indices);
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

namespace detail {

void flip_corners(std::span<const std::uint32_t> face_sizes, const std::vector<bool>& flip,
                  std::vector<std::uint32_t>& per_corner) {
  std::size_t offset = 0;
  for (std::size_t f = 0; f < face_sizes.size(); ++f) {
    const std::size_t size = face_sizes[f];
    // Reversing all but the first corner keeps the first corner first.
    if (flip[f]) {
      std::reverse(per_corner.begin() + static_cast<std::ptrdiff_t>(offset + 1),
                   per_corner.begin() + static_cast<std::ptrdiff_t>(offset + size));
    }
    offset += size;
  }
}

FaceComponents face_components(const FaceVertexMesh& mesh, const EdgeTable& table) {
  UnionFind sets(mesh.face_count());
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const std::uint32_t first = table.first_use(e), twin = table.twin(first);
    if (twin < EdgeTable::crowded) {
      sets.unite(table.face_of(first), table.face_of(twin));
    } else if (twin == EdgeTable::crowded) {
      for (const EdgeUse use : table.uses(e)) sets.unite(table.face_of(first), use.face);
    }
  }
  // A set's representative is its smallest face: numbering representatives as they come numbers
  // the components by smallest face.
  FaceComponents components{std::vector<std::uint32_t>(mesh.face_count()), 0};
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t root = sets.find(f);
    components.of_face[f] =
        root == f ? static_cast<std::uint32_t>(components.count++) : components.of_face[root];
  }
  return components;
}

namespace {

// Disjoint sets of faces with each face's flip relative to its set's representative (the
// smallest face, which keeps its orientation): orientation classes grown edge by edge.
// core/union_find.h keeps no parity, hence this variant.
class FlipUnionFind {
 public:
  explicit FlipUnionFind(std::size_t n) : parent_(n), flip_(n, 0) { std::iota(parent_.begin(), parent_.end(), 0u); }

  /// The representative of f's set; `flip`: whether f is flipped relative to it.
  std::uint32_t find(std::uint32_t f, bool& flip) noexcept {
    std::uint8_t parity = 0;
    while (parent_[f] != f) {
      const std::uint32_t up = parent_[f];
      flip_[f] ^= flip_[up];  // path halving: f skips to its grandparent (a root has flip 0)
      parent_[f] = parent_[up];
      parity ^= flip_[f];
      f = parent_[f];
    }
    flip = parity != 0;
    return f;
  }

  /// Requires f and g to differ in flip exactly when `differ`. Returns false if their sets
  /// already require the opposite (an orientation conflict).
  bool unite(std::uint32_t f, std::uint32_t g, bool differ) noexcept {
    bool flip_f = false, flip_g = false;
    const std::uint32_t a = find(f, flip_f), b = find(g, flip_g);
    if (a == b) return (flip_f != flip_g) == differ;
    const std::uint32_t child = std::max(a, b);
    parent_[child] = std::min(a, b);
    flip_[child] = static_cast<std::uint8_t>(flip_f != flip_g) ^ static_cast<std::uint8_t>(differ);
    return true;
  }

  /// The sets numbered 0.. by smallest face, with each face's flip relative to its set's
  /// smallest face; uses the union-find up. (A parent is a smaller face than its child, so one
  /// pass in face order finds every parent done, its number in place of its parent.)
  FaceComponents number(std::vector<bool>& flip) && {
    std::size_t count = 0;
    for (std::uint32_t f = 0; f < parent_.size(); ++f) {
      const std::uint32_t up = parent_[f];
      if (up == f) {
        parent_[f] = static_cast<std::uint32_t>(count++);
      } else {
        flip_[f] ^= flip_[up];
        parent_[f] = parent_[up];
      }
      flip[f] = flip_[f] != 0;
    }
    return {std::move(parent_), count};
  }

 private:
  std::vector<std::uint32_t> parent_;  // always a smaller face, or the face itself
  std::vector<std::uint8_t> flip_;
};

// The breadth-first walk from `root` over its orientation class (faces joined through edges of
// exactly two faces), flipping faces to agree with the face they are reached from; the first
// conflict found makes the component non-orientable, with the cycle that proves it.
void walk_from(std::uint32_t root, const FaceVertexMesh& mesh, const EdgeTable& table, std::vector<bool>& seen,
               std::vector<std::uint32_t>& parent, std::vector<std::uint32_t>& queue, OrientationWalk& result) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  std::vector<bool>& flip = result.flip;
  seen[root] = true;
  parent[root] = root;
  queue.clear();
  queue.push_back(root);
  bool conflict_found = false;
  for (std::size_t head = 0; head < queue.size();) {
    const std::uint32_t f = queue[head++];
    for (auto c = static_cast<std::uint32_t>(mesh.first_corner(f)); c < mesh.first_corner(f + 1); ++c) {
      const std::uint32_t twin = table.twin(c);
      if (twin >= EdgeTable::crowded) continue;  // no other face, or more than one
      const EdgeUse mine{f, c};
      const EdgeUse other{table.face_of(twin), twin};
      if (other.face == f) continue;  // a face meeting itself (a repeated vertex): no constraint between faces
      // Consistent when the two walk the edge in opposite directions after the flips.
      const bool needs_flip = (index[mine.corner] == index[other.corner]) != flip[f];
      if (!seen[other.face]) {
        seen[other.face] = true;
        parent[other.face] = f;
        flip[other.face] = needs_flip;
        queue.push_back(other.face);
      } else if (flip[other.face] != needs_flip && !conflict_found) {
        conflict_found = true;
        result.component_orientable[result.components.of_face[root]] = false;
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

}  // namespace

OrientationWalk walk_orientation(const FaceVertexMesh& mesh, const EdgeTable& table) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  const auto faces = static_cast<std::uint32_t>(mesh.face_count());
  OrientationWalk result{{}, std::vector<bool>(faces, false), {}, {}};
  // Orientation classes: faces joined through edges of exactly two faces. An orientable class has
  // one consistent flip per face relative to its smallest face, whatever the order of the walk:
  // the union-find finds them (and the classes that have none) in edge order, with far better
  // locality than a breadth-first walk over a large mesh.
  FlipUnionFind classes(faces);
  std::vector<std::uint32_t> conflicts;  // a face of each class with a conflict
  bool crowded = false;
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const std::uint32_t twin = table.twin(table.first_use(e));
    crowded = crowded || twin == EdgeTable::crowded;
    if (twin >= EdgeTable::crowded) continue;
    const auto [first, second] = table.first_two_uses(e);
    if (first.face == second.face) continue;  // a face meeting itself: no constraint
    // Two faces walking the edge the same way must differ in flip.
    if (!classes.unite(first.face, second.face, index[first.corner] == index[second.corner])) {
      conflicts.push_back(first.face);
    }
  }
  std::vector<std::uint32_t> roots;  // the smallest face of each class with a conflict
  for (std::uint32_t f : conflicts) {
    bool flip = false;
    roots.push_back(classes.find(f, flip));
  }
  // Without crowded edges (more than two faces), the classes are the edge-connected components.
  FaceComponents& components = result.components;
  components = std::move(classes).number(result.flip);
  if (crowded) components = face_components(mesh, table);
  result.component_orientable.assign(components.count, true);
  if (roots.empty()) return result;
  // A non-orientable class has no consistent flips: its flips and the proving cycle are those of
  // the breadth-first walk from its smallest face, class by class in that order.
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  std::vector<bool> seen(faces, false);
  std::vector<std::uint32_t> parent(faces);
  std::vector<std::uint32_t> queue;
  for (std::uint32_t root : roots) walk_from(root, mesh, table, seen, parent, queue, result);
  return result;
}

}  // namespace detail

std::vector<std::uint32_t> face_components(const FaceVertexMesh& mesh) {
  return detail::face_components(mesh, detail::EdgeTable(mesh)).of_face;
}

namespace {

Orientation oriented(const FaceVertexMesh& mesh, detail::OrientationWalk walk) {
  Orientation result{with_flips(mesh, walk.flip), {}, std::move(walk.component_orientable),
                     std::move(walk.non_orientable_cycles)};
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (walk.flip[f]) result.flipped.push_back(FaceId(f));
  }
  return result;
}

}  // namespace

Orientation orient(const FaceVertexMesh& mesh) {
  const detail::EdgeTable table(mesh);
  return oriented(mesh, detail::walk_orientation(mesh, table));
}

double signed_volume(const FaceVertexMesh& mesh) {
  double volume = 0.0;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) volume += face_volume6(mesh, f);
  return volume / 6.0;
}

Orientation orient_outward(const FaceVertexMesh& mesh) {
  // Flips change no edge's faces: one table serves the walk, the components and closedness.
  const detail::EdgeTable table(mesh);
  detail::OrientationWalk walk = detail::walk_orientation(mesh, table);
  const detail::FaceComponents components = std::move(walk.components);
  Orientation result = oriented(mesh, std::move(walk));
  const std::vector<std::uint32_t>& component = components.of_face;
  std::vector<bool> closed(components.count, true);
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    const std::uint32_t first = table.first_use(e);
    if (table.twin(first) == detail::EdgeTable::none) closed[component[table.face_of(first)]] = false;
  }
  // Signed volume per component, from the oriented faces.
  std::vector<double> volume(components.count, 0.0);
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
