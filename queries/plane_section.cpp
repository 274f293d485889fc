#include "queries/plane_section.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/assert.h"
#include "queries/query_arguments.h"
#include "queries/section_cells.h"

namespace patchwork {
namespace {

using detail::PatchSection;
using detail::SectionPiece;
using detail::SectionState;

// The line of an edge: (along_u, coordinate), as in section_cells.h.
std::pair<bool, double> line_of(PatchEdge edge) {
  switch (edge) {
    case PatchEdge::v0: return {true, 0.0};
    case PatchEdge::u1: return {false, 1.0};
    case PatchEdge::v1: return {true, 1.0};
    case PatchEdge::u0: return {false, 0.0};
  }
  return {true, 0.0};
}

// Union-find over the nodes.
struct NodeSets {
  std::vector<int> parent;
  explicit NodeSets(std::size_t count) : parent(count) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

// Which patches lie next to which: across each edge, the patch sharing it, or the other side of
// its T-junction (the long edge's patch, or its parts').
class Adjacency {
 public:
  explicit Adjacency(const PatchSet& set) : across_(set.count()) {
    const auto add = [&](const EdgeRef& a, const EdgeRef& b) {
      across_[a.patch][static_cast<std::size_t>(a.edge)].push_back(b.patch);
      across_[b.patch][static_cast<std::size_t>(b.edge)].push_back(a.patch);
    };
    for (const SharedEdge& s : set.shared_edges()) add(s.first, s.second);
    for (const TJunction& t : set.t_junctions())
      for (const EdgeRef& part : t.parts) add(t.edge, part);
  }

  // The patches a node lies on: its own, and those across the edges of its patch it is on.
  std::vector<std::uint32_t> patches_at(const SectionVertex& node) const {
    std::vector<std::uint32_t> result{node.patch};
    const std::array<bool, 4> on{node.uv.y() == 0.0, node.uv.x() == 1.0, node.uv.y() == 1.0, node.uv.x() == 0.0};
    for (std::size_t e = 0; e < 4; ++e)
      if (on[e]) result.insert(result.end(), across_[node.patch][e].begin(), across_[node.patch][e].end());
    return result;
  }

  // a and b are one patch or share an edge (whole or at a T-junction).
  bool next_to(std::uint32_t a, std::uint32_t b) const {
    return a == b || std::any_of(across_[a].begin(), across_[a].end(), [&](const std::vector<std::uint32_t>& patches) {
             return std::find(patches.begin(), patches.end(), b) != patches.end();
           });
  }

 private:
  std::vector<std::array<std::vector<std::uint32_t>, 4>> across_;
};

// Nodes at one point (within `distance`) are one node: a corner of several patches, a pole, the
// end of a side in the plane. Only where their patches are next to each other: patches that
// touch without sharing an edge around the point (the teapot's handle against its body) each keep
// their own crossings, so a curve ending on one's open edge does not join the other's curve there.
void unite_close_nodes(const std::vector<SectionVertex>& nodes, double distance, const Adjacency& adjacency,
                       NodeSets& sets) {
  std::vector<int> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return nodes[static_cast<std::size_t>(a)].point.x() < nodes[static_cast<std::size_t>(b)].point.x(); });
  const auto connected = [&](const SectionVertex& a, const SectionVertex& b) {
    const std::vector<std::uint32_t> at_a = adjacency.patches_at(a), at_b = adjacency.patches_at(b);
    return std::any_of(at_a.begin(), at_a.end(), [&](std::uint32_t p) {
      return std::any_of(at_b.begin(), at_b.end(), [&](std::uint32_t q) { return adjacency.next_to(p, q); });
    });
  };
  for (std::size_t i = 0; i < order.size(); ++i) {
    const SectionVertex& p = nodes[static_cast<std::size_t>(order[i])];
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const SectionVertex& q = nodes[static_cast<std::size_t>(order[j])];
      if (q.point.x() - p.point.x() > distance) break;
      if ((q.point - p.point).norm() <= distance && connected(p, q)) sets.unite(order[i], order[j]);
    }
  }
}

// The pieces chained at their shared nodes: open chains from the nodes where an odd number of
// pieces end (the set's boundary), then closed ones.
std::vector<SectionPolyline> chain_pieces(const SectionState& state, NodeSets& sets) {
  const std::vector<SectionPiece>& pieces = state.pieces;
  std::vector<std::vector<std::pair<std::size_t, bool>>> at(state.nodes.size());  // (piece, starts here)
  std::vector<bool> used(pieces.size(), false);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const int a = sets.find(pieces[k].a), b = sets.find(pieces[k].b);
    if (a == b && pieces[k].inner.empty()) {  // one point
      used[k] = true;
      continue;
    }
    at[static_cast<std::size_t>(a)].emplace_back(k, true);
    at[static_cast<std::size_t>(b)].emplace_back(k, false);
  }
  std::vector<SectionPolyline> result;
  const auto walk = [&](std::size_t piece, bool forward) {
    SectionPolyline line{{}, false};
    const int start = sets.find(forward ? pieces[piece].a : pieces[piece].b);
    line.vertices.push_back(state.nodes[static_cast<std::size_t>(forward ? pieces[piece].a : pieces[piece].b)]);
    for (;;) {
      used[piece] = true;
      const SectionPiece& p = pieces[piece];
      if (forward) line.vertices.insert(line.vertices.end(), p.inner.begin(), p.inner.end());
      else line.vertices.insert(line.vertices.end(), p.inner.rbegin(), p.inner.rend());
      const int end = forward ? p.b : p.a;
      const int node = sets.find(end);
      if (node == start) {
        line.closed = true;
        break;
      }
      line.vertices.push_back(state.nodes[static_cast<std::size_t>(end)]);
      const auto& next = at[static_cast<std::size_t>(node)];
      const auto free = std::find_if(next.begin(), next.end(), [&](const auto& e) { return !used[e.first]; });
      if (free == next.end()) break;
      piece = free->first;
      forward = free->second;
    }
    result.push_back(std::move(line));
  };
  for (std::size_t node = 0; node < at.size(); ++node) {
    if (at[node].size() % 2 == 0) continue;
    for (const auto& [piece, forward] : at[node])
      if (!used[piece]) walk(piece, forward);
  }
  for (std::size_t piece = 0; piece < pieces.size(); ++piece)
    if (!used[piece]) walk(piece, true);
  PATCHWORK_ASSERT(std::all_of(used.begin(), used.end(), [](bool u) { return u; }), "every piece is in one polyline");
  return result;
}

}  // namespace

PlaneSection plane_section(const PatchSet& set, const Vec3& point, const Vec3& normal, double tolerance) {
  require_finite(point, "plane_section", "point");
  require_direction(normal, "plane_section", "normal");
  require_positive(tolerance, "plane_section", "tolerance");
  const Vec3 scaled = normal / normal.cwiseAbs().maxCoeff();  // no underflow for tiny normals
  const Vec3 n = scaled / scaled.norm();

  SectionState state;
  state.tolerance = tolerance;
  PlaneSection result;
  const auto count = static_cast<std::uint32_t>(set.count());
  std::vector<PatchSection> patches;
  patches.reserve(count);
  std::vector<bool> in_plane(count, false);
  for (std::uint32_t p = 0; p < count; ++p) {
    PatchSection& patch = patches.emplace_back(p, set.patch(p));
    patch.f = detail::signed_distance_net(patch.patch, point, n);
    // c_ij = w_ij n.(P_ij - p) is computed with an error of a few units in the last place of
    // w_ij |P_ij - p|; coefficients below 64 of those are zero.
    const BezierPatch3& net = set.control_nets()[p];
    const std::vector<double> weights =
        set.is_rational(p) ? set.rational(p)->weights() : std::vector<double>(net.control_points().size(), 1.0);
    double scale = 0.0;
    for (std::size_t k = 0; k < weights.size(); ++k) scale = std::max(scale, weights[k] * (net.control_points()[k] - point).norm());
    patch.zero = 64.0 * std::numeric_limits<double>::epsilon() * scale;
    in_plane[p] = std::all_of(patch.f.c.begin(), patch.f.c.end(), [&](double c) { return std::abs(c) <= patch.zero; });
    if (in_plane[p]) result.patches_in_plane.push_back(p);
    for (int e = 0; e < 4; ++e) patch.edges[static_cast<std::size_t>(e)] = {false, false, p, static_cast<PatchEdge>(e), false};
  }
  for (const EdgeRef& e : set.collapsed_edges()) patches[e.patch].edges[static_cast<std::size_t>(e.edge)].collapsed = true;
  for (const SharedEdge& s : set.shared_edges()) {
    detail::EdgeInfo& second = patches[s.second.patch].edges[static_cast<std::size_t>(s.second.edge)];
    second.canonical_patch = s.first.patch;
    second.canonical_edge = s.first.edge;
    second.reversed = s.reversed;
    second.neighbour_in_plane = in_plane[s.first.patch];
    patches[s.first.patch].edges[static_cast<std::size_t>(s.first.edge)].neighbour_in_plane = in_plane[s.second.patch];
  }
  // The crossings along every edge, once per shared edge: the second patch takes the first's
  // points, at its own parameters (t or 1 - t).
  for (PatchSection& patch : patches) {
    for (int e = 0; e < 4; ++e) {
      const detail::EdgeInfo& info = patch.edges[static_cast<std::size_t>(e)];
      if (info.canonical_patch != patch.index) continue;
      const auto [along_u, at] = line_of(static_cast<PatchEdge>(e));
      patch.edge_roots[static_cast<std::size_t>(e)] = detail::line_roots(patch, along_u, at, state);
    }
  }
  for (PatchSection& patch : patches) {
    for (int e = 0; e < 4; ++e) {
      const detail::EdgeInfo& info = patch.edges[static_cast<std::size_t>(e)];
      if (info.canonical_patch == patch.index) continue;
      detail::LineRoots roots = patches[info.canonical_patch].edge_roots[static_cast<std::size_t>(info.canonical_edge)];
      if (info.reversed) {
        for (double& t : roots.t) t = 1.0 - t;
        std::reverse(roots.t.begin(), roots.t.end());
        std::reverse(roots.nodes.begin(), roots.nodes.end());
      }
      patch.edge_roots[static_cast<std::size_t>(e)] = std::move(roots);
    }
  }
  for (std::uint32_t p = 0; p < count; ++p)
    if (!in_plane[p]) detail::search_patch(patches[p], state);

  NodeSets sets(state.nodes.size());
  for (const auto& [a, b] : state.same_nodes) sets.unite(a, b);
  const double merge = std::max(set.tolerance(), 1e-12 * set.size());
  unite_close_nodes(state.nodes, merge, Adjacency(set), sets);
  result.polylines = chain_pieces(state, sets);
  for (const SectionPiece& piece : state.pieces) result.error_bound = std::max(result.error_bound, piece.bound);

  // A candidate is a tangent point unless the section passes through it; candidates at one point
  // (the cells around it, the patches at a pole) are one.
  for (const detail::TangentCandidate& candidate : state.tangent_candidates) {
    const Vec3& q = candidate.vertex.point;
    const bool crossed = std::any_of(result.polylines.begin(), result.polylines.end(), [&](const SectionPolyline& line) {
      return std::any_of(line.vertices.begin(), line.vertices.end(),
                         [&](const SectionVertex& v) { return (v.point - q).norm() <= merge + candidate.bound; });
    });
    if (crossed) continue;
    const bool known = std::any_of(result.tangent_points.begin(), result.tangent_points.end(), [&](const SectionVertex& v) {
      return (v.point - q).norm() <= merge + 2.0 * std::max(candidate.bound, result.error_bound);
    });
    result.error_bound = std::max(result.error_bound, candidate.bound);
    if (!known) result.tangent_points.push_back(candidate.vertex);
  }
  result.uncertified_pieces = state.uncertified;
  result.cells = state.cells;
  return result;
}

}  // namespace patchwork
