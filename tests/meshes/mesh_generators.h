#pragma once
// Meshes whose topology is known from their construction, the operations that must not change
// any topological answer, and reference computations to check answers against, for the meshes
// tests and any later test that needs a surface of a given kind.
//
//   family            construction                                              chi      b  orientable
//   sphere            the surface of an nx x ny x nz box of unit quads           2        0  yes
//   genus g           boundary of a (2g+1) x 3 x 1 voxel plate, holes at         2 - 2g   0  yes
//                     x = 1, 3, .., 2g-1, y = 1 (each voxel split nx x ny x nz)
//   ... b holes cut   b pairwise vertex-disjoint faces removed                   2-2g-b   b  yes
//   disk              a rows x cols grid                                         1        1  yes
//   annulus           the grid glued column cols = column 0                      0        2  yes
//   torus             the grid glued in both directions                          0        0  yes
//   Moebius band      the grid glued column cols = column 0 reversed             0        1  no
//   Klein bottle      the torus grid with the column gluing reversed             0        0  no
//   projective plane  a Moebius band with a fan of triangles on its boundary     1        0  no
//   hemi-cube         the cube modulo p -> -p: V=4, E=6, F=3                     1        0  no
//   disjoint union    the sum of chi, b, components and genus                    sum      sum
//
// The grid's lattice points (i, j), row i in [0, rows], column j in [0, cols]; quad (i, j) is
//
//     (i+1, j) ---- (i+1, j+1)
//        |              |          corners (i, j), (i, j+1), (i+1, j+1), (i+1, j)
//     (i, j) ------ (i, j+1)
//
// Straight gluing identifies (i, cols) with (i, 0), twisted gluing with (rows - i, 0); gluing the
// rows identifies (rows, j) with (0, j) (or (0, cols - j) twisted).
//
// Randomness comes from a seed through splitmix64 (the same sequence on every platform), so a
// RapidCheck counterexample is reproduced from the values it prints.

#include <rapidcheck.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"
#include "tests/meshes/face_lists.h"

namespace patchwork::testing {

/// A face list with the topology its construction guarantees (never taken from analyze()).
struct KnownSurface {
  std::string name;
  FaceVertexMesh mesh;
  Count euler = 0;
  Count boundary_loops = 0;
  Count components = 1;
  bool orientable = true;
  /// Sum of the components' genera; nullopt when a component is non-orientable.
  std::optional<Count> genus;
  /// The enclosed volume, for closed surfaces built with outward normals (voxel surfaces).
  std::optional<double> volume;
  bool closed() const { return boundary_loops == 0; }
};

/// splitmix64: a portable random sequence (std distributions differ between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// A number in [0, n), n > 0 (the modulo bias is below 2^-32 for our n).
  std::uint32_t below(std::size_t n) { return static_cast<std::uint32_t>(next() % n); }
  bool coin() { return (next() >> 63) != 0; }
  /// A double in [lo, hi) with 53 random bits.
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1p-53; }

 private:
  std::uint64_t state_;
};

/// A uniformly random permutation of 0 .. n-1 (Fisher-Yates).
inline std::vector<std::uint32_t> random_permutation(std::size_t n, Random& random) {
  std::vector<std::uint32_t> p(n);
  for (std::uint32_t k = 0; k < n; ++k) p[k] = k;
  for (std::size_t k = n; k > 1; --k) std::swap(p[k - 1], p[random.below(k)]);
  return p;
}

// ---------------------------------------------------------------------------------------------
// Plain face lists

inline FaceList faces_of(const FaceVertexMesh& mesh) {
  FaceList faces;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) faces.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
  return faces;
}

inline std::vector<Vec3> points_of(const FaceVertexMesh& mesh) {
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) points.push_back(mesh.position(v));
  return points;
}

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// ---------------------------------------------------------------------------------------------
// Reference computations, written independently of meshes/ to check its answers

/// One face's walk along an undirected edge.
struct Walk {
  std::uint32_t face;
  std::uint32_t from;
  std::uint32_t to;
};

/// Every undirected edge with the walks of the faces along it.
inline std::map<std::uint64_t, std::vector<Walk>> edge_walks(const FaceVertexMesh& mesh) {
  std::map<std::uint64_t, std::vector<Walk>> walks;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::uint32_t a = face[k];
      const std::uint32_t b = face[(k + 1) % face.size()];
      walks[edge_key(a, b)].push_back({f, a, b});
    }
  }
  return walks;
}

/// V (vertices used by a face), E (distinct undirected edges), F, counted from scratch.
struct ElementCounts {
  Count vertices = 0;
  Count edges = 0;
  Count faces = 0;
  Count euler() const { return vertices - edges + faces; }
};

inline ElementCounts count_elements(const FaceVertexMesh& mesh) {
  std::set<std::uint32_t> used(mesh.face_indices().begin(), mesh.face_indices().end());
  return {static_cast<Count>(used.size()), static_cast<Count>(edge_walks(mesh).size()),
          static_cast<Count>(mesh.face_count())};
}

/// Def 47 directly: every edge of two faces is walked once in each direction.
inline bool consistently_oriented(const FaceVertexMesh& mesh) {
  for (const auto& [key, walks] : edge_walks(mesh)) {
    if (walks.size() == 2 && walks[0].from == walks[1].from) return false;
  }
  return true;
}

/// Faces joined through shared edges; component[f] numbered 0.. in order of smallest face.
inline std::vector<std::uint32_t> reference_components(const FaceVertexMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.face_count());
  for (std::uint32_t f = 0; f < parent.size(); ++f) parent[f] = f;
  const auto find = [&parent](std::uint32_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (const auto& [key, walks] : edge_walks(mesh)) {
    for (const Walk& w : walks) {
      const std::uint32_t a = find(walks[0].face), b = find(w.face);
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::uint32_t> component(mesh.face_count());
  std::map<std::uint32_t, std::uint32_t> number;
  for (std::uint32_t f = 0; f < component.size(); ++f) {
    component[f] = number.try_emplace(find(f), static_cast<std::uint32_t>(number.size())).first->second;
  }
  return component;
}

/// Whether `cycle` proves non-orientability: distinct faces, each sharing an edge of exactly two
/// faces with the next (the last with the first), such that carrying an orientation along the
/// chain (keep it across an edge walked both ways, flip it across one walked the same way) comes
/// back flipped. A 2-cycle must use two different edges.
inline bool proves_non_orientable(const FaceVertexMesh& mesh, const std::vector<FaceId>& cycle) {
  const std::size_t k = cycle.size();
  if (k < 2) return false;
  std::set<FaceId> distinct(cycle.begin(), cycle.end());
  if (distinct.size() != k) return false;
  const auto walks = edge_walks(mesh);
  // The relative orientations (+1 keep, -1 flip) that some shared edge allows between f and g.
  const auto relations = [&walks](FaceId f, FaceId g) {
    std::set<int> signs;
    for (const auto& [key, w] : walks) {
      if (w.size() != 2) continue;
      if ((w[0].face == f.value && w[1].face == g.value) || (w[0].face == g.value && w[1].face == f.value)) {
        signs.insert(w[0].from == w[1].from ? -1 : +1);
      }
    }
    return signs;
  };
  if (k == 2) return relations(cycle[0], cycle[1]).size() == 2;
  std::set<int> reachable{+1};
  for (std::size_t i = 0; i < k; ++i) {
    const std::set<int> signs = relations(cycle[i], cycle[(i + 1) % k]);
    if (signs.empty()) return false;
    std::set<int> next;
    for (int r : reachable) {
      for (int s : signs) next.insert(r * s);
    }
    reachable = next;
  }
  return reachable.count(-1) == 1;
}

/// Boundary loops counted by walking boundary edges on a manifold (each boundary vertex has two).
inline Count reference_boundary_loops(const FaceVertexMesh& mesh) {
  std::map<std::uint32_t, std::vector<std::uint32_t>> neighbours;
  for (const auto& [key, walks] : edge_walks(mesh)) {
    if (walks.size() != 1) continue;
    neighbours[walks[0].from].push_back(walks[0].to);
    neighbours[walks[0].to].push_back(walks[0].from);
  }
  std::set<std::uint32_t> seen;
  Count loops = 0;
  for (const auto& [start, list] : neighbours) {
    if (seen.count(start) != 0) continue;
    ++loops;
    std::vector<std::uint32_t> stack{start};
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      if (!seen.insert(v).second) continue;
      for (std::uint32_t w : neighbours[v]) stack.push_back(w);
    }
  }
  return loops;
}

// ---------------------------------------------------------------------------------------------
// Operations that keep every topological answer

/// Vertex v becomes vertex new_index[v]; positions move along.
inline FaceVertexMesh relabel_vertices(const FaceVertexMesh& mesh, const std::vector<std::uint32_t>& new_index) {
  std::vector<Vec3> points(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) points[new_index[v]] = mesh.position(v);
  FaceList faces = faces_of(mesh);
  for (auto& face : faces) {
    for (std::uint32_t& v : face) v = new_index[v];
  }
  return make_mesh(points, faces);
}

/// Face k of the result is face order[k] of the input.
inline FaceVertexMesh reorder_faces(const FaceVertexMesh& mesh, const std::vector<std::uint32_t>& order) {
  FaceList faces;
  for (std::uint32_t f : order) faces.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
  return make_mesh(points_of(mesh), faces);
}

/// Reverses face f where flip[f], keeping its first corner first (as orient() flips):
/// (a, b, c, d) -> (a, d, c, b), so flipping twice gives back the same list.
inline FaceVertexMesh flip_faces(const FaceVertexMesh& mesh, const std::vector<bool>& flip) {
  FaceList faces = faces_of(mesh);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (flip[f]) std::reverse(faces[f].begin() + 1, faces[f].end());
  }
  return make_mesh(points_of(mesh), faces);
}

/// Face f starts at its corner shift[f] (modulo its size): the same polygon.
inline FaceVertexMesh rotate_corners(const FaceVertexMesh& mesh, const std::vector<std::uint32_t>& shift) {
  FaceList faces = faces_of(mesh);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::rotate(faces[f].begin(), faces[f].begin() + static_cast<std::ptrdiff_t>(shift[f] % faces[f].size()),
                faces[f].end());
  }
  return make_mesh(points_of(mesh), faces);
}

/// Random flags, one per face.
inline std::vector<bool> random_flags(std::size_t n, Random& random) {
  std::vector<bool> flags(n);
  for (std::size_t k = 0; k < n; ++k) flags[k] = random.coin();
  return flags;
}

/// Random relabelling, face order, corner rotation and per-face flips.
inline FaceVertexMesh scrambled(const FaceVertexMesh& mesh, Random& random) {
  FaceVertexMesh result = relabel_vertices(mesh, random_permutation(mesh.vertex_count(), random));
  result = reorder_faces(result, random_permutation(result.face_count(), random));
  std::vector<std::uint32_t> shift(result.face_count());
  for (std::uint32_t& s : shift) s = random.below(8);
  result = rotate_corners(result, shift);
  return flip_faces(result, random_flags(result.face_count(), random));
}

/// Inserts the midpoint of edge {a, b} (a new last vertex) into every face that walks the edge.
inline FaceVertexMesh split_edge(const FaceVertexMesh& mesh, std::uint32_t a, std::uint32_t b) {
  std::vector<Vec3> points = points_of(mesh);
  const auto middle = static_cast<std::uint32_t>(points.size());
  points.push_back(0.5 * (points[a] + points[b]));
  FaceList faces;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    std::vector<std::uint32_t> corners;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::uint32_t u = face[k];
      const std::uint32_t w = face[(k + 1) % face.size()];
      corners.push_back(u);
      if ((u == a && w == b) || (u == b && w == a)) corners.push_back(middle);
    }
    faces.push_back(std::move(corners));
  }
  return make_mesh(points, faces);
}

/// Face f (k corners) becomes k triangles (centre, v_i, v_i+1) around its centroid, a new last
/// vertex; the first triangle takes f's place, the others are appended.
inline FaceVertexMesh split_face_at_centre(const FaceVertexMesh& mesh, std::size_t f) {
  std::vector<Vec3> points = points_of(mesh);
  FaceList faces = faces_of(mesh);
  const std::vector<std::uint32_t> corners = faces[f];
  const auto centre = static_cast<std::uint32_t>(points.size());
  Vec3 sum = Vec3::Zero();
  for (std::uint32_t v : corners) sum += points[v];
  points.push_back(sum / static_cast<double>(corners.size()));
  for (std::size_t k = 0; k < corners.size(); ++k) {
    std::vector<std::uint32_t> triangle{centre, corners[k], corners[(k + 1) % corners.size()]};
    if (k == 0) {
      faces[f] = triangle;
    } else {
      faces.push_back(triangle);
    }
  }
  return make_mesh(points, faces);
}

/// Splits quad f (a, b, c, d) into (a, b, c), (a, c, d) (diagonal 0) or (a, b, d), (b, c, d)
/// (diagonal 1). nullopt if f is not a quad or the diagonal is an edge already.
inline std::optional<FaceVertexMesh> split_quad(const FaceVertexMesh& mesh, std::size_t f, int diagonal) {
  if (mesh.face(f).size() != 4) return std::nullopt;
  FaceList faces = faces_of(mesh);
  const auto q = faces[f];
  const auto walks = edge_walks(mesh);
  if (diagonal == 0) {
    if (walks.count(edge_key(q[0], q[2])) != 0) return std::nullopt;
    faces[f] = {q[0], q[1], q[2]};
    faces.push_back({q[0], q[2], q[3]});
  } else {
    if (walks.count(edge_key(q[1], q[3])) != 0) return std::nullopt;
    faces[f] = {q[0], q[1], q[3]};
    faces.push_back({q[1], q[2], q[3]});
  }
  return make_mesh(points_of(mesh), faces);
}

/// Flips the edge {a, b} of triangles f = (a, b, c) and g = (b, a, d) (up to rotation) to {c, d}:
/// f becomes (a, d, c) and g (d, b, c), the quad a, d, b, c keeping its orientation. nullopt
/// unless f and g are triangles sharing exactly one edge, walked both ways, and {c, d} is new.
inline std::optional<FaceVertexMesh> flip_edge(const FaceVertexMesh& mesh, std::size_t f, std::size_t g) {
  if (f == g || mesh.face(f).size() != 3 || mesh.face(g).size() != 3) return std::nullopt;
  const auto walks = edge_walks(mesh);
  std::optional<std::array<std::uint32_t, 3>> found;  // a, b, c with f = (a, b, c) rotated
  int shared = 0;
  const auto tf = mesh.face(f);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t a = tf[k], b = tf[(k + 1) % 3], c = tf[(k + 2) % 3];
    const auto& w = walks.at(edge_key(a, b));
    for (const Walk& walk : w) {
      if (walk.face == g) {
        ++shared;
        if (walk.from == b && w.size() == 2) found = std::array<std::uint32_t, 3>{a, b, c};
      }
    }
  }
  if (shared != 1 || !found) return std::nullopt;
  const auto [a, b, c] = *found;
  std::uint32_t d = 0;
  for (std::uint32_t v : mesh.face(g)) {
    if (v != a && v != b) d = v;
  }
  if (c == d || walks.count(edge_key(c, d)) != 0) return std::nullopt;
  FaceList faces = faces_of(mesh);
  faces[f] = {a, d, c};
  faces[g] = {d, b, c};
  return make_mesh(points_of(mesh), faces);
}

/// One step of Catmull-Clark's topology: a face (v_0 .. v_k-1) becomes the k quads
/// (v_i, m(v_i, v_i+1), centre, m(v_i-1, v_i)) through its edge midpoints and centroid.
/// V' = V + E + F, E' = 2E + sum k, F' = sum k: chi is kept, and so is everything else.
inline FaceVertexMesh subdivided(const FaceVertexMesh& mesh) {
  std::vector<Vec3> points = points_of(mesh);
  std::map<std::uint64_t, std::uint32_t> midpoint;
  const auto middle = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, inserted] = midpoint.try_emplace(edge_key(a, b), static_cast<std::uint32_t>(points.size()));
    if (inserted) points.push_back(0.5 * (points[a] + points[b]));
    return it->second;
  };
  FaceList faces;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const std::size_t k = face.size();
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t v : face) sum += points[v];
    const auto centre = static_cast<std::uint32_t>(points.size());
    points.push_back(sum / static_cast<double>(k));
    for (std::size_t i = 0; i < k; ++i) {
      const std::uint32_t prev = face[(i + k - 1) % k], v = face[i], next = face[(i + 1) % k];
      faces.push_back({v, middle(v, next), centre, middle(prev, v)});
    }
  }
  return make_mesh(points, faces);
}

// ---------------------------------------------------------------------------------------------
// Surfaces of known topology

/// Sub-voxels per unit voxel along x, y, z.
struct Resolution {
  int x = 1;
  int y = 1;
  int z = 1;
};

/// The closed surface between filled and empty voxels (cell (i, j, k) is the unit cube at
/// (i, j, k)), each voxel split into res.x x res.y x res.z sub-voxels; one quad per sub-voxel
/// face between filled and empty, counter-clockwise seen from the empty side (outward normals).
/// Positions are the fine lattice points (integers, so volumes are exact): the solid's volume is
/// cells * res.x * res.y * res.z. \pre no two cells touch only along an edge or at a corner.
inline FaceVertexMesh voxel_surface(const std::vector<std::array<int, 3>>& cells, Resolution res) {
  const std::array<int, 3> n{res.x, res.y, res.z};
  std::set<std::array<int, 3>> filled;
  for (const auto& cell : cells) {
    for (int a = 0; a < n[0]; ++a) {
      for (int b = 0; b < n[1]; ++b) {
        for (int c = 0; c < n[2]; ++c) filled.insert({cell[0] * n[0] + a, cell[1] * n[1] + b, cell[2] * n[2] + c});
      }
    }
  }
  std::map<std::array<int, 3>, std::uint32_t> vertex_of;
  std::vector<Vec3> points;
  const auto vertex = [&](const std::array<int, 3>& p) {
    const auto [it, inserted] = vertex_of.try_emplace(p, static_cast<std::uint32_t>(points.size()));
    if (inserted) points.emplace_back(p[0], p[1], p[2]);
    return it->second;
  };
  FaceList faces;
  for (const auto& p : filled) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side : {-1, 1}) {
        std::array<int, 3> neighbour = p;
        neighbour[axis] += side;
        if (filled.count(neighbour) != 0) continue;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // e_u x e_v = e_axis
        std::array<int, 3> c0 = p;
        if (side > 0) ++c0[axis];
        std::array<int, 3> c1 = c0, c2 = c0, c3 = c0;
        ++c1[u];
        ++c2[u];
        ++c2[v];
        ++c3[v];
        if (side > 0) {
          faces.push_back({vertex(c0), vertex(c1), vertex(c2), vertex(c3)});
        } else {
          faces.push_back({vertex(c0), vertex(c3), vertex(c2), vertex(c1)});
        }
      }
    }
  }
  return make_mesh(points, faces);
}

/// The cells of the (2g+1) x 3 x 1 plate with holes at x = 1, 3, .., 2g-1, y = 1.
inline std::vector<std::array<int, 3>> plate_cells(int genus) {
  std::vector<std::array<int, 3>> cells;
  for (int x = 0; x <= 2 * genus; ++x) {
    for (int y = 0; y < 3; ++y) {
      if (y == 1 && x % 2 == 1) continue;
      cells.push_back({x, y, 0});
    }
  }
  return cells;
}

/// A sphere: the surface of a res.x x res.y x res.z box of unit quads.
/// F = 2(xy + yz + zx), E = 2F, V = F + 2.
inline KnownSurface sphere(Resolution res) {
  return {"sphere", voxel_surface({{0, 0, 0}}, res), 2, 0, 1, true, 0, 1.0 * res.x * res.y * res.z};
}

/// The closed orientable surface of genus g (a torus for g = 1): the voxel plate of plate_cells.
inline KnownSurface genus_surface(int genus, Resolution res) {
  const auto cells = plate_cells(genus);
  return {"genus " + std::to_string(genus),
          voxel_surface(cells, res),
          2 - 2 * genus,
          0,
          1,
          true,
          genus,
          1.0 * static_cast<double>(cells.size()) * res.x * res.y * res.z};
}

/// Every quad split into two triangles along a random diagonal; other faces kept.
inline FaceVertexMesh triangulated(const FaceVertexMesh& mesh, Random& random) {
  FaceList faces;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto q = mesh.face(f);
    if (q.size() != 4) {
      faces.emplace_back(q.begin(), q.end());
    } else if (random.coin()) {
      faces.push_back({q[0], q[1], q[2]});
      faces.push_back({q[0], q[2], q[3]});
    } else {
      faces.push_back({q[0], q[1], q[3]});
      faces.push_back({q[1], q[2], q[3]});
    }
  }
  return make_mesh(points_of(mesh), faces);
}

inline KnownSurface triangulated(KnownSurface surface, Random& random) {
  surface.mesh = triangulated(surface.mesh, random);
  surface.name += ", triangulated";
  return surface;
}

/// Removes `holes` pairwise vertex-disjoint faces from a closed surface: each leaves a boundary
/// loop, chi drops by one per hole and the genus stays. \throws std::logic_error if no such
/// choice is found.
inline KnownSurface with_holes(KnownSurface surface, int holes, Random& random) {
  const FaceVertexMesh& mesh = surface.mesh;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    std::set<std::uint32_t> used;
    std::vector<bool> removed(mesh.face_count(), false);
    int count = 0;
    for (std::uint32_t f : random_permutation(mesh.face_count(), random)) {
      if (count == holes) break;
      const auto face = mesh.face(f);
      if (std::any_of(face.begin(), face.end(), [&used](std::uint32_t v) { return used.count(v) != 0; })) continue;
      used.insert(face.begin(), face.end());
      removed[f] = true;
      ++count;
    }
    if (count < holes) continue;
    FaceList faces;
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
      if (!removed[f]) faces.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
    }
    surface.mesh = make_mesh(points_of(mesh), faces);
    surface.name += " with " + std::to_string(holes) + " holes";
    surface.euler -= holes;
    surface.boundary_loops += holes;
    surface.volume.reset();
    return surface;
  }
  throw std::logic_error("with_holes: no " + std::to_string(holes) + " vertex-disjoint faces");
}

enum class Gluing { none, straight, twisted };

/// The rows x cols quad grid with columns (j = cols to j = 0) and rows (i = rows to i = 0) glued
/// as asked; a vertex per class of identified lattice points, placed at point(i, j) of the first
/// lattice point that a face uses.
template <class PointOf>
FaceVertexMesh glued_grid(int rows, int cols, Gluing columns, Gluing row_gluing, PointOf point) {
  const auto index = [cols](int i, int j) { return static_cast<std::size_t>(i * (cols + 1) + j); };
  std::vector<std::size_t> parent(static_cast<std::size_t>((rows + 1) * (cols + 1)));
  for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = k;
  const auto find = [&parent](std::size_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  const auto unite = [&](std::size_t a, std::size_t b) { parent[find(a)] = find(b); };
  for (int i = 0; i <= rows; ++i) {
    if (columns == Gluing::straight) unite(index(i, cols), index(i, 0));
    if (columns == Gluing::twisted) unite(index(i, cols), index(rows - i, 0));
  }
  for (int j = 0; j <= cols; ++j) {
    if (row_gluing == Gluing::straight) unite(index(rows, j), index(0, j));
    if (row_gluing == Gluing::twisted) unite(index(rows, j), index(0, cols - j));
  }
  std::map<std::size_t, std::uint32_t> vertex_of;
  std::vector<Vec3> points;
  const auto vertex = [&](int i, int j) {
    const auto [it, inserted] = vertex_of.try_emplace(find(index(i, j)), static_cast<std::uint32_t>(points.size()));
    if (inserted) points.push_back(point(i, j));
    return it->second;
  };
  FaceList faces;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j)
      faces.push_back({vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1), vertex(i + 1, j)});
  }
  return make_mesh(points, faces);
}

/// A disk: the rows x cols grid of unit squares in z = 0, normals +z. V = (r+1)(c+1),
/// E = r(c+1) + c(r+1), F = rc, chi = 1.
inline KnownSurface disk(int rows, int cols) {
  return {"disk", glued_grid(rows, cols, Gluing::none, Gluing::none, [](int i, int j) { return Vec3(j, i, 0); }),
          1,      1,
          1,      true,
          0,      std::nullopt};
}

/// An annulus (open cylinder of height rows around cols >= 3 columns).
inline KnownSurface annulus(int rows, int cols) {
  const auto point = [cols](int i, int j) {
    const double phi = 2 * std::numbers::pi * j / cols;
    return Vec3(std::cos(phi), std::sin(phi), i);
  };
  return {"annulus", glued_grid(rows, cols, Gluing::straight, Gluing::none, point), 0, 2, 1, true, 0, std::nullopt};
}

/// A torus (rows, cols >= 3) embedded with radii 2 and 1.
inline KnownSurface torus(int rows, int cols) {
  const auto point = [rows, cols](int i, int j) {
    const double theta = 2 * std::numbers::pi * i / rows, phi = 2 * std::numbers::pi * j / cols;
    return Vec3((2 + std::cos(theta)) * std::cos(phi), (2 + std::cos(theta)) * std::sin(phi), std::sin(theta));
  };
  return {"torus", glued_grid(rows, cols, Gluing::straight, Gluing::straight, point), 0, 0, 1, true, 1, std::nullopt};
}

/// The Moebius band embedded in R^3 (width rows >= 1, length cols >= 3).
inline Vec3 mobius_point(int rows, int cols, int i, int j) {
  const double phi = 2 * std::numbers::pi * j / cols, w = static_cast<double>(i) / rows - 0.5;
  return Vec3((1 + w * std::cos(phi / 2)) * std::cos(phi), (1 + w * std::cos(phi / 2)) * std::sin(phi),
              w * std::sin(phi / 2));
}

inline KnownSurface mobius_band(int rows, int cols) {
  const auto point = [rows, cols](int i, int j) { return mobius_point(rows, cols, i, j); };
  return {"Moebius band", glued_grid(rows, cols, Gluing::twisted, Gluing::none, point), 0, 1, 1, false, std::nullopt,
          std::nullopt};
}

/// The Klein bottle (rows, cols >= 3); its positions are only for finiteness (it has no embedding).
inline KnownSurface klein_bottle(int rows, int cols) {
  const auto point = [](int i, int j) { return Vec3(j, i, 0.25 * i * j); };
  return {
      "Klein bottle", glued_grid(rows, cols, Gluing::twisted, Gluing::straight, point), 0, 0, 1, false, std::nullopt,
      std::nullopt};
}

/// The projective plane: a Moebius band (rows >= 1, cols >= 3) whose boundary loop (0,0), (0,1),
/// .., (0,cols) = (rows,0), (rows,1), .., (rows,cols) = (0,0) of 2 cols edges is closed by a fan
/// of triangles around a new vertex: chi = 0 + 1.
inline KnownSurface projective_plane(int rows, int cols) {
  const FaceVertexMesh band = mobius_band(rows, cols).mesh;
  // The band's vertices on lattice row 0 and row `rows`, found by position (they are distinct).
  std::vector<Vec3> points = points_of(band);
  const auto vertex_at = [&](int i, int j) {
    const Vec3 p = mobius_point(rows, cols, i, j);
    for (std::uint32_t v = 0; v < points.size(); ++v) {
      if ((points[v] - p).norm() < 1e-9) return v;
    }
    throw std::logic_error("projective_plane: lattice point not found");
  };
  std::vector<std::uint32_t> loop;
  for (int j = 0; j < cols; ++j) loop.push_back(vertex_at(0, j));
  for (int j = 0; j < cols; ++j) loop.push_back(vertex_at(rows, j));
  const auto centre = static_cast<std::uint32_t>(points.size());
  points.emplace_back(0, 0, 3);
  FaceList faces = faces_of(band);
  for (std::size_t k = 0; k < loop.size(); ++k) faces.push_back({centre, loop[k], loop[(k + 1) % loop.size()]});
  return {"projective plane", make_mesh(points, faces), 1, 0, 1, false, std::nullopt, std::nullopt};
}

/// The hemi-cube: the cube's vertices modulo p -> -p, A = (1,1,1), B = (1,1,-1), C = (1,-1,1),
/// D = (-1,1,1), and its faces x = 1 (A C D B), y = 1 (A B C D), z = 1 (A D B C). Every pair
/// of vertices is an edge used by two faces: V = 4, E = 6, F = 3, chi = 1.
inline KnownSurface hemi_cube() {
  const std::vector<Vec3> points{{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
  return {"hemi-cube", make_mesh(points, {{0, 2, 3, 1}, {0, 1, 2, 3}, {0, 3, 1, 2}}), 1, 0, 1, false, std::nullopt,
          std::nullopt};
}

/// Both surfaces side by side (b's vertices after a's, b shifted by `offset` in space).
inline KnownSurface disjoint_union(const KnownSurface& a, const KnownSurface& b, const Vec3& offset = Vec3(100, 0, 0)) {
  std::vector<Vec3> points = points_of(a.mesh);
  const auto shift = static_cast<std::uint32_t>(points.size());
  for (const Vec3& p : points_of(b.mesh)) points.push_back(p + offset);
  FaceList faces = faces_of(a.mesh);
  for (auto face : faces_of(b.mesh)) {
    for (std::uint32_t& v : face) v += shift;
    faces.push_back(std::move(face));
  }
  std::optional<Count> genus;
  if (a.genus && b.genus) genus = *a.genus + *b.genus;
  std::optional<double> volume;
  if (a.volume && b.volume) volume = *a.volume + *b.volume;
  return {a.name + " + " + b.name,
          make_mesh(points, faces),
          a.euler + b.euler,
          a.boundary_loops + b.boundary_loops,
          a.components + b.components,
          a.orientable && b.orientable,
          genus,
          volume};
}

// ---------------------------------------------------------------------------------------------
// RapidCheck generators (each case draws its parameters and a seed for the random choices)

/// A random number in [lo, hi].
inline int random_int(Random& random, int lo, int hi) {
  return lo + static_cast<int>(random.below(static_cast<std::size_t>(hi - lo + 1)));
}

/// Random per-axis resolution in [lo, hi]^3.
inline Resolution random_resolution(Random& random, int lo, int hi) {
  return {random_int(random, lo, hi), random_int(random, lo, hi), random_int(random, lo, hi)};
}

/// A closed orientable surface with outward normals: a sphere or a genus g <= 5 plate, maybe
/// triangulated; at most 2 * 104 * max_resolution^2 faces. A sphere of resolution 1 (a cube)
/// has only two vertex-disjoint faces: ask for min_resolution 2 to cut up to 3 holes.
inline KnownSurface closed_orientable_surface(Random& random, int max_resolution, int min_resolution = 1) {
  const int genus = random_int(random, 0, 5);
  KnownSurface surface = genus == 0 && random.coin()
                             ? sphere(random_resolution(random, min_resolution, max_resolution + 1))
                             : genus_surface(genus, random_resolution(random, 1, max_resolution));
  return random.coin() ? triangulated(std::move(surface), random) : surface;
}

/// An orientable surface of any kind above: closed of genus g <= 5, with up to 3 holes (pairs
/// of pants among them), a disk, an annulus, a grid torus, maybe triangulated.
inline KnownSurface orientable_surface(Random& random, int max_resolution) {
  const int rows = random_int(random, 3, 6), cols = random_int(random, 3, 6);
  KnownSurface surface;
  switch (random.below(6)) {
    case 0:
      surface = disk(random_int(random, 1, 6), random_int(random, 1, 6));
      break;
    case 1:
      surface = annulus(random_int(random, 1, 5), cols);
      break;
    case 2:
      surface = torus(rows, cols);
      break;
    case 3:
      surface = with_holes(sphere(random_resolution(random, 2, 3)), 3, random);
      break;  // pair of pants
    case 4:
      surface = with_holes(closed_orientable_surface(random, max_resolution, 2), random_int(random, 1, 3), random);
      break;
    default:
      surface = closed_orientable_surface(random, max_resolution);
  }
  if (random.coin() && surface.mesh.face_sizes()[0] == 4) surface = triangulated(std::move(surface), random);
  return surface;
}

/// A non-orientable surface: Moebius band, Klein bottle, projective plane, hemi-cube, maybe
/// triangulated (not the hemi-cube, whose triangles would share all three corners).
inline KnownSurface non_orientable_surface(Random& random) {
  const int rows = random_int(random, 3, 6), cols = random_int(random, 3, 6);
  KnownSurface surface;
  switch (random.below(4)) {
    case 0:
      surface = mobius_band(random_int(random, 1, 4), cols);
      break;
    case 1:
      surface = klein_bottle(rows, cols);
      break;
    case 2:
      surface = projective_plane(random_int(random, 1, 4), cols);
      break;
    default:
      return hemi_cube();
  }
  return random.coin() ? triangulated(std::move(surface), random) : surface;
}

/// Any surface above, or a disjoint union of two of them.
inline KnownSurface any_surface(Random& random, int max_resolution) {
  const auto one = [&]() {
    return random.below(3) == 0 ? non_orientable_surface(random) : orientable_surface(random, max_resolution);
  };
  if (random.below(4) == 0) {
    const KnownSurface a = one();
    return disjoint_union(a, one());
  }
  return one();
}

// ---------------------------------------------------------------------------------------------
// Soups that are not surfaces

// Damage a surface of known topology the way files from the wild are damaged: glue vertices
// together, duplicate faces, add fins on edges, add degenerate faces; then shuffle everything.
inline FaceVertexMesh damaged(const FaceVertexMesh& mesh, Random& random) {
  std::vector<Vec3> points = points_of(mesh);
  FaceList faces = faces_of(mesh);
  for (int step = random_int(random, 1, 6); step > 0; --step) {
    const auto some_vertex = [&]() { return faces[random.below(faces.size())][0]; };
    switch (random.below(4)) {
      case 0: {  // glue two vertices (pinches, and degenerate corners where they were neighbours)
        const std::uint32_t keep = some_vertex(), gone = some_vertex();
        for (auto& face : faces) std::replace(face.begin(), face.end(), gone, keep);
        break;
      }
      case 1: {  // a duplicate face, maybe reversed: its edges get three or more faces
        std::vector<std::uint32_t> copy = faces[random.below(faces.size())];
        if (random.coin()) std::reverse(copy.begin(), copy.end());
        faces.push_back(copy);
        break;
      }
      case 2: {  // a fin: a new triangle on an existing edge
        const auto& face = faces[random.below(faces.size())];
        const std::size_t k = random.below(face.size());
        points.push_back(points[face[k]] + Vec3(0.1, 0.2, 0.3));
        faces.push_back({face[k], face[(k + 1) % face.size()], static_cast<std::uint32_t>(points.size() - 1)});
        break;
      }
      default: {  // a degenerate face
        const std::uint32_t a = some_vertex(), b = some_vertex();
        const FaceList degenerate{{a, a, b}, {a, b, a}, {a, a, a}, {b, a, a, b}};
        faces.push_back(degenerate[random.below(degenerate.size())]);
      }
    }
  }
  return scrambled(make_mesh(points, faces), random);
}

/// A random soup: 3 to 10 vertices at random points and up to 12 faces of 3 to 6 random corners
/// each (repeats, crowded edges, any orientation).
inline FaceVertexMesh random_soup(Random& random) {
  const int vertices = random_int(random, 3, 10);
  std::vector<Vec3> points;
  for (int v = 0; v < vertices; ++v) {
    points.emplace_back(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
  }
  FaceList faces(static_cast<std::size_t>(random_int(random, 0, 12)));
  for (auto& face : faces) {
    for (int k = random_int(random, 3, 6); k > 0; --k) face.push_back(random.below(points.size()));
  }
  return make_mesh(points, faces);
}

/// Glues up to three pairs of vertices that share no face and no neighbour: each glued vertex
/// has two fans (two closed ones on a closed surface), while every edge keeps its faces and no
/// face repeats a vertex.
inline FaceVertexMesh pinched(const FaceVertexMesh& mesh, Random& random) {
  FaceList faces = faces_of(mesh);
  std::vector<std::set<std::uint32_t>> near(mesh.vertex_count());  // vertices sharing a face
  for (const auto& face : faces) {
    for (std::uint32_t v : face) near[v].insert(face.begin(), face.end());
  }
  int glued = 0;
  for (int attempt = 0; attempt < 50 && glued < 3 && !faces.empty(); ++attempt) {
    const std::uint32_t a = faces[random.below(faces.size())][0], b = faces[random.below(faces.size())][0];
    if (a == b || near[a].count(b) != 0) continue;
    if (std::any_of(near[b].begin(), near[b].end(), [&](std::uint32_t w) { return near[a].count(w) != 0; })) continue;
    for (auto& face : faces) std::replace(face.begin(), face.end(), b, a);
    near[a].insert(near[b].begin(), near[b].end());
    near[b].clear();
    ++glued;
  }
  return make_mesh(points_of(mesh), faces);
}

/// A damaged surface (pinched vertices, crowded edges, degenerate faces), a random soup, or a
/// surface with pinched vertices only.
inline FaceVertexMesh any_soup(Random& random) {
  switch (random.below(3)) {
    case 0: return damaged(any_surface(random, 1).mesh, random);
    case 1: return random_soup(random);
    default: return pinched(scrambled(any_surface(random, 1).mesh, random), random);
  }
}

/// RapidCheck: a seed for Random (printed with a counterexample, so it reproduces).
inline rc::Gen<std::uint64_t> seed() { return rc::gen::arbitrary<std::uint64_t>(); }

}  // namespace patchwork::testing
