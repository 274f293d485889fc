#include "surfaces/patch_set.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <optional>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <variant>

#include "core/errors.h"
#include "core/parallel.h"
#include "core/union_find.h"
#include "curves/continuity.h"
#include "curves/degree.h"
#include "curves/subdivision.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_edge_geometry.h"

namespace patchwork {
namespace {

constexpr PatchEdge all_edges[4] = {PatchEdge::v0, PatchEdge::u1, PatchEdge::v1, PatchEdge::u0};

using detail::max_distance;
using detail::walks_forward;

// Points hashed into cubic cells; queries return the ids within the 27 neighbouring cells.
// A cell is keyed by its three whole coordinates, not folded into fewer bits: folded keys alias
// cells a fixed distance apart, which in a scene many times the cell size (a tolerance of 10^-9
// of the set) puts far-apart points into one bucket, and the cost grows faster than the scene.
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell > 0.0 ? cell : 1.0) {}
  void insert(const Vec3& p, std::size_t id) { cells_[key(p, 0, 0, 0)].push_back(id); }
  template <class Visit>
  void near(const Vec3& p, Visit visit) const {
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(p, dx, dy, dz));
          if (it == cells_.end()) continue;
          for (std::size_t id : it->second) visit(id);
        }
      }
    }
  }

 private:
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const noexcept {
      std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 31) ^ static_cast<std::uint64_t>(c[1])) * 0xC2B2AE3D27D4EB4Full;
      h = (h ^ (h >> 29) ^ static_cast<std::uint64_t>(c[2])) * 0x165667B19E3779F9ull;
      return static_cast<std::size_t>(h ^ (h >> 32));
    }
  };
  Cell key(const Vec3& p, int dx, int dy, int dz) const {
    // The cell index is clamped before the conversion (a quotient beyond 2^63 would be undefined
    // behaviour, found by fuzzing with a zero-size set): cells beyond 2^52 share a key.
    const auto c = [this](double x, int d) {
      return static_cast<std::int64_t>(std::clamp(std::floor(x / cell_), -0x1p52, 0x1p52)) + d;
    };
    return {c(p.x(), dx), c(p.y(), dy), c(p.z(), dz)};
  }
  double cell_;
  std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells_;
};

// Both point lists at one degree (the lower elevated), b read backwards when reversed; the
// largest distance between corresponding points.
double elevated_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool reversed) {
  if (a.size() == b.size()) return max_distance(a, b, reversed);
  const int degree = static_cast<int>(std::max(a.size(), b.size())) - 1;
  const auto up = [degree](const std::vector<Vec3>& p) {
    return elevate_degree(BezierCurve3(p), degree - static_cast<int>(p.size()) + 1).control_points();
  };
  return max_distance(up(a), up(b), reversed);
}

// The parameters t in (from, 1] where `curve` comes within `tolerance` of q, in increasing
// order: every local minimum of the distance over 64 samples, refined by Newton steps on
// (C(t) - q) . C'(t) = 0 kept inside the interval (an edge that passes near q twice gives both).
std::vector<double> near_parameters(const BezierCurve3& curve, double from, const Vec3& q, double tolerance) {
  constexpr int samples = 64;
  std::vector<double> ts(samples + 1);
  std::vector<double> distances(samples + 1);
  for (int k = 0; k <= samples; ++k) {
    ts[k] = k == samples ? 1.0 : from + (1.0 - from) * k / samples;
    distances[k] = (curve.evaluate(ts[k]) - q).norm();
  }
  std::vector<double> result;
  for (int k = 1; k <= samples; ++k) {
    if (distances[k] > distances[k - 1] || (k < samples && distances[k] > distances[k + 1])) continue;
    double t = ts[k];
    double best = distances[k];
    for (int iteration = 0; iteration < 20; ++iteration) {
      const std::vector<Vec3> d = derivatives(curve, t, 2);
      const double f = (d[0] - q).dot(d[1]);
      const double df = d[1].squaredNorm() + (d[0] - q).dot(d[2]);
      if (!(df > 0.0)) break;
      const double next = std::clamp(t - f / df, from, 1.0);
      const double distance = (curve.evaluate(next) - q).norm();
      if (next == t || !(distance <= best)) break;
      t = next;
      best = distance;
    }
    if (best <= tolerance) result.push_back(t);
  }
  return result;
}

// Edge `a` tiled end to end by other unmatched edges (a T-junction), or nothing. From the
// long edge's start, each step takes an unmatched edge that begins there and whose far end lies
// on the rest of the long edge at some t, and whose control points are those of the long edge's
// piece up to t (de Casteljau, subcurve); it ends when a part reaches the long edge's end.
std::optional<TJunction> tile_edge(std::size_t a, const std::vector<EdgeRef>& edges,
                                   const std::vector<std::vector<Vec3>>& points, const std::vector<bool>& matched,
                                   const PointGrid& ends, double tolerance) {
  const BezierCurve3 curve(points[a]);
  TJunction tiling{edges[a], {}, {}, {}, true, 0.0};
  std::vector<std::size_t> used;
  double from = 0.0;
  // The next part starts within the tolerance of the long edge at `from`, or of the last part's
  // far end (the two may be up to twice the tolerance apart).
  Vec3 start = points[a].front();
  Vec3 last_end = start;
  const auto starts_here = [&](const Vec3& p) {
    return (p - start).norm() <= tolerance || (p - last_end).norm() <= tolerance;
  };
  // Parts shorter than 2^-20 of the edge are not looked for: each part advances the tiling.
  while (from < 1.0 && tiling.parts.size() < 64) {
    std::optional<std::size_t> found;
    double found_t = 0.0;
    bool found_reversed = false;
    double found_gap = 0.0;
    ends.near(start, [&](std::size_t b) {
      if (found || b == a || matched[b] || std::find(used.begin(), used.end(), b) != used.end()) return;
      const std::vector<Vec3>& pb = points[b];
      const bool reversed = !starts_here(pb.front());
      if (reversed && !starts_here(pb.back())) return;
      const Vec3& far = reversed ? pb.front() : pb.back();
      const bool last = (points[a].back() - far).norm() <= tolerance;
      for (const double t : near_parameters(curve, from, far, tolerance)) {
        if (t - from < 0x1p-20) continue;
        const double end = last && t > 1.0 - 0x1p-20 ? 1.0 : t;
        const double gap = elevated_distance(subcurve(curve, from, end).control_points(), pb, reversed);
        if (gap > tolerance) continue;
        found = b, found_t = end, found_reversed = reversed, found_gap = gap;
        return;
      }
    });
    if (!found) return std::nullopt;
    used.push_back(*found);
    tiling.parts.push_back(edges[*found]);
    tiling.breaks.push_back(found_t);
    tiling.reversed.push_back(found_reversed);
    tiling.gap = std::max(tiling.gap, found_gap);
    const bool opposite = walks_forward(edges[a].edge) != (walks_forward(edges[*found].edge) != found_reversed);
    tiling.consistently_oriented = tiling.consistently_oriented && opposite;
    from = found_t;
    start = curve.evaluate(from);
    last_end = found_reversed ? points[*found].front() : points[*found].back();
  }
  if (from < 1.0 || tiling.parts.size() < 2) return std::nullopt;
  return tiling;
}


}  // namespace

double PatchSet::control_box_diagonal(const std::vector<BezierPatch3>& nets) {
  Eigen::AlignedBox3d box(nets.front().control_points().front());
  for (const auto& patch : nets) {
    for (const auto& p : patch.control_points()) box.extend(p);
  }
  return box.diagonal().norm();
}

const char* edge_name(PatchEdge edge) {
  switch (edge) {
    case PatchEdge::v0: return "v0";
    case PatchEdge::u1: return "u1";
    case PatchEdge::v1: return "v1";
    case PatchEdge::u0: return "u0";
  }
  return "?";
}

// The nets and, where a patch is rational (weights not all equal), the rational patches.
PatchSet::Kinds PatchSet::split_kinds(std::span<const AnyBezierPatch> patches) {
  std::vector<BezierPatch3> nets;
  std::vector<std::optional<RationalBezierPatch>> rational(patches.size());
  nets.reserve(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (const auto* polynomial = std::get_if<BezierPatch3>(&patches[p])) {
      nets.push_back(*polynomial);
      continue;
    }
    const RationalBezierPatch& patch = std::get<RationalBezierPatch>(patches[p]);
    const std::vector<double> weights = patch.weights();
    nets.push_back(patch.control_net());
    if (std::any_of(weights.begin(), weights.end(), [&](double w) { return w != weights.front(); })) rational[p] = patch;
  }
  return {std::move(nets), std::move(rational)};
}

namespace {

// The homogeneous points (w P, w) of an edge: the rational patch's homogeneous row, or the
// net's row with weight 1.
std::vector<Vec4> homogeneous_row(const std::vector<Vec3>& row, const RationalBezierPatch* patch, PatchEdge edge) {
  if (patch != nullptr) return row_from_edge(patch->homogeneous(), edge, 0);
  std::vector<Vec4> result(row.size());
  for (std::size_t i = 0; i < row.size(); ++i) result[i] << row[i], 1.0;
  return result;
}

}  // namespace

PatchSet::PatchSet(std::vector<BezierPatch3> patches, double relative_tolerance)
    : PatchSet(Kinds(std::move(patches), {}), {}, relative_tolerance) {}

PatchSet::PatchSet(std::span<const AnyBezierPatch> patches, double relative_tolerance)
    : PatchSet(split_kinds(patches), {}, relative_tolerance) {}

PatchSet::PatchSet(std::span<const AnyBezierPatch> patches, std::span<const KnownJoin> joins, double relative_tolerance)
    : PatchSet(split_kinds(patches), joins, relative_tolerance) {}

const std::vector<BezierPatch3>& PatchSet::patches() const {
  if (rational_count_ > 0) {
    throw InvalidInput(detail::message("PatchSet::patches: ", rational_count_,
                                       " of the patches are rational; their control points are not the surface"));
  }
  return nets_;
}

namespace {
void check_patch_index(std::uint32_t p, std::size_t count) {
  if (p >= count) throw InvalidInput(detail::message("PatchSet: patch ", p, " of ", count, " does not exist"));
}
}  // namespace

AnyBezierPatch PatchSet::patch(std::uint32_t p) const {
  check_patch_index(p, count());
  if (is_rational(p)) return *rational_[p];
  return nets_[p];
}

RationalBezierPatch PatchSet::rational_patch(std::uint32_t p) const {
  check_patch_index(p, count());
  if (is_rational(p)) return *rational_[p];
  return as_rational(nets_[p]);
}

PatchSet::PatchSet(Kinds kinds, std::span<const KnownJoin> joins, double relative_tolerance)
    : nets_(std::move(kinds.first)), rational_(std::move(kinds.second)) {
  if (nets_.empty()) throw InvalidInput("PatchSet: no patches");
  if (nets_.size() >= 0xffffffffu) throw InvalidInput(detail::message("PatchSet: ", nets_.size(), " patches (limit 2^32 - 1)"));
  if (!std::isfinite(relative_tolerance) || relative_tolerance < 0.0) {
    throw InvalidInput(detail::message("PatchSet: relative tolerance ", relative_tolerance, " is not >= 0"));
  }
  rational_count_ = static_cast<std::size_t>(
      std::count_if(rational_.begin(), rational_.end(), [](const auto& r) { return r.has_value(); }));
  if (rational_count_ == 0) rational_.clear();
  size_ = control_box_diagonal(nets_);
  tolerance_ = relative_tolerance * size_;

  // Every edge: collapsed (a rational edge too: its points are convex combinations of the
  // control points), or a candidate for sharing.
  std::vector<EdgeRef> edges;
  std::vector<std::vector<Vec3>> points;
  for (std::uint32_t p = 0; p < nets_.size(); ++p) {
    for (PatchEdge e : all_edges) {
      std::vector<Vec3> row = row_from_edge(nets_[p], e, 0);
      const bool collapsed = std::all_of(row.begin(), row.end(), [&](const Vec3& q) { return (q - row.front()).norm() <= tolerance_; });
      if (collapsed) {
        collapsed_.push_back({p, e});
        continue;
      }
      edges.push_back({p, e});
      points.push_back(std::move(row));
    }
  }
  PointGrid ends(std::max(2.0 * tolerance_, 1e-300));
  for (std::size_t k = 0; k < edges.size(); ++k) {
    ends.insert(points[k].front(), k);
    ends.insert(points[k].back(), k);
  }
  const auto rational_edge = [&](std::size_t k) { return is_rational(edges[k].patch); };
  // A rational pair: the homogeneous rows at one degree, points within the tolerance and
  // weights proportional within the relative tolerance.
  const auto rational_match = [&](std::size_t a, std::size_t b, bool reversed) {
    std::vector<Vec4> ha = homogeneous_row(points[a], rational(edges[a].patch), edges[a].edge);
    std::vector<Vec4> hb = homogeneous_row(points[b], rational(edges[b].patch), edges[b].edge);
    const int degree = static_cast<int>(std::max(ha.size(), hb.size())) - 1;
    ha = elevate_degree(BezierCurve<4>(ha), degree - static_cast<int>(ha.size()) + 1).control_points();
    hb = elevate_degree(BezierCurve<4>(hb), degree - static_cast<int>(hb.size()) + 1).control_points();
    const detail::EdgeAgreement agreement = detail::edge_agreement(ha, hb, reversed);
    return agreement.points <= tolerance_ && agreement.weights <= relative_tolerance;
  };
  std::vector<bool> matched(edges.size(), false);
  std::vector<bool> known(edges.size(), false);  // joined by a known join: not matched again
  const auto shared_edge = [&](std::size_t a, std::size_t b, bool reversed) {
    const EdgeRef ea = edges[a];
    const EdgeRef eb = edges[b];
    const bool rational_pair = rational_edge(a) || rational_edge(b);
    return SharedEdge{ea, eb, reversed, walks_forward(ea.edge) != (walks_forward(eb.edge) != reversed),
                      rational_pair ? edge_continuity(patch(ea.patch), ea.edge, patch(eb.patch), eb.edge, reversed)
                                    : edge_continuity(nets_[ea.patch], ea.edge, nets_[eb.patch], eb.edge, reversed)};
  };
  // The known joins first: taken as given, once their points are checked.
  if (!joins.empty()) {
    std::unordered_map<std::uint64_t, std::size_t> edge_index;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      edge_index[(std::uint64_t{edges[k].patch} << 2) | static_cast<std::uint64_t>(edges[k].edge)] = k;
    }
    const auto find = [&](const EdgeRef& e, std::size_t j) {
      if (e.patch >= nets_.size()) throw InvalidInput(detail::message("PatchSet: known join ", j, " names patch ", e.patch, " of ", nets_.size()));
      const auto it = edge_index.find((std::uint64_t{e.patch} << 2) | static_cast<std::uint64_t>(e.edge));
      if (it == edge_index.end()) return std::optional<std::size_t>();  // collapsed
      if (known[it->second]) {
        throw InvalidInput(detail::message("PatchSet: known join ", j, ": patch ", e.patch, " ", edge_name(e.edge), " is joined twice"));
      }
      return std::optional<std::size_t>(it->second);
    };
    for (std::size_t j = 0; j < joins.size(); ++j) {
      const std::optional<std::size_t> first = find(joins[j].first, j);
      const std::optional<std::size_t> second = find(joins[j].second, j);
      if (!first || !second) continue;
      const std::size_t a = *first, b = *second;
      matched[a] = known[a] = true;
      matched[b] = known[b] = true;
      SharedEdge shared = shared_edge(a, b, joins[j].reversed);
      if (!(shared.continuity.gap <= 2 * tolerance_)) {
        throw InvalidInput(detail::message("PatchSet: known join ", j, " (patch ", joins[j].first.patch, " ",
                                           edge_name(joins[j].first.edge), ", patch ", joins[j].second.patch, " ",
                                           edge_name(joins[j].second.edge), "): the edges are ", shared.continuity.gap,
                                           " apart"));
      }
      shared.continuity.ck = joins[j].ck;
      shared.continuity.g1 = shared.continuity.max_normal_angle <= 1e-7;
      shared_.push_back(shared);
    }
  }
  struct Found {
    std::size_t a;
    std::size_t b;
    bool reversed;
  };
  std::vector<Found> found;
  for (std::size_t a = 0; a < edges.size(); ++a) {
    if (known[a]) continue;
    std::vector<std::size_t> candidates;
    ends.near(points[a].front(), [&](std::size_t b) {
      if (b > a) candidates.push_back(b);
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (std::size_t b : candidates) {
      if (known[b]) continue;
      const bool rational_pair = rational_edge(a) || rational_edge(b);
      std::vector<Vec3> pa = points[a];
      std::vector<Vec3> pb = points[b];
      if (pa.size() != pb.size() && !rational_pair) {
        const int degree = static_cast<int>(std::max(pa.size(), pb.size())) - 1;
        pa = elevate_degree(BezierCurve3(pa), degree - static_cast<int>(pa.size()) + 1).control_points();
        pb = elevate_degree(BezierCurve3(pb), degree - static_cast<int>(pb.size()) + 1).control_points();
      }
      for (bool reversed : {false, true}) {
        if (rational_pair ? !rational_match(a, b, reversed) : max_distance(pa, pb, reversed) > tolerance_) continue;
        found.push_back({a, b, reversed});
        matched[a] = matched[b] = true;
        break;
      }
    }
  }
  // The matched edges' continuity (a normal-angle search along each edge: most of the set's
  // construction), in parallel, each into its own slot; an exception is rethrown as the lowest
  // edge's, whatever the threads.
  {
    const std::size_t first = shared_.size();
    shared_.resize(first + found.size());
    std::vector<std::exception_ptr> errors(found.size());
    parallel_for(found.size(), 0, [&](std::size_t k) {
      try {
        shared_[first + k] = shared_edge(found[k].a, found[k].b, found[k].reversed);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    });
    for (const std::exception_ptr& error : errors) {
      if (error) std::rethrow_exception(error);
    }
  }
  // T-junctions among the edges left: each long edge tiled by parts (longest first, so that a
  // part is never taken for a long edge itself).
  // Rational edges are left out (tile_edge compares polynomial pieces).
  std::vector<std::size_t> unmatched;
  std::vector<bool> excluded = matched;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    if (rational_edge(k)) excluded[k] = true;
    if (!excluded[k]) unmatched.push_back(k);
  }
  if (unmatched.size() >= 3) {
    std::vector<double> chord(edges.size(), 0.0);
    for (std::size_t k : unmatched) chord[k] = (points[k].back() - points[k].front()).norm();
    std::stable_sort(unmatched.begin(), unmatched.end(), [&](std::size_t x, std::size_t y) { return chord[x] > chord[y]; });
    std::unordered_map<std::uint64_t, std::size_t> index_of;
    for (std::size_t k = 0; k < edges.size(); ++k) index_of[(std::uint64_t{edges[k].patch} << 2) | static_cast<std::uint64_t>(edges[k].edge)] = k;
    for (std::size_t a : unmatched) {
      if (excluded[a]) continue;
      std::optional<TJunction> tiling = tile_edge(a, edges, points, excluded, ends, tolerance_);
      if (!tiling) continue;
      matched[a] = excluded[a] = true;
      for (const EdgeRef& part : tiling->parts) {
        const std::size_t k = index_of.at((std::uint64_t{part.patch} << 2) | static_cast<std::uint64_t>(part.edge));
        matched[k] = excluded[k] = true;
      }
      t_junctions_.push_back(std::move(*tiling));
    }
  }
  for (std::size_t k = 0; k < edges.size(); ++k) {
    if (!matched[k]) open_.push_back(edges[k]);
  }

  // Boundary loops: chain open edges head to tail in walking order, through corners joined as the
  // tessellator welds them (by shared and collapsed edges and T-junctions, not by position: a
  // patch whose edge is a closed curve, or patches touching at a point, keep their corners apart).
  // Edge k of a patch runs, along boundary_curve, from corner edge_start[k] to edge_end[k]
  // (c0 = (0,0), c1 = (1,0), c2 = (1,1), c3 = (0,1)).
  const auto corner = [](EdgeRef e, bool at_start) {
    constexpr int edge_start[4] = {0, 1, 3, 0};
    constexpr int edge_end[4] = {1, 2, 2, 3};
    const int k = static_cast<int>(e.edge);
    return static_cast<std::uint32_t>(4 * e.patch + (at_start ? edge_start[k] : edge_end[k]));
  };
  UnionFind welded(static_cast<std::uint32_t>(4 * nets_.size()));
  for (const SharedEdge& s : shared_) {
    welded.unite(corner(s.first, true), corner(s.second, !s.reversed));
    welded.unite(corner(s.first, false), corner(s.second, s.reversed));
  }
  for (const EdgeRef& e : collapsed_) welded.unite(corner(e, true), corner(e, false));
  for (const TJunction& t : t_junctions_) {
    for (std::size_t b = 0; b < t.parts.size(); ++b) {
      const bool reversed = t.reversed[b];
      if (b == 0) welded.unite(corner(t.edge, true), corner(t.parts[b], !reversed));
      if (b + 1 == t.parts.size()) welded.unite(corner(t.edge, false), corner(t.parts[b], reversed));
      if (b + 1 < t.parts.size()) welded.unite(corner(t.parts[b], reversed), corner(t.parts[b + 1], !t.reversed[b + 1]));
    }
  }
  const auto walk_start = [&](EdgeRef e) { return welded.find(corner(e, walks_forward(e.edge))); };
  const auto walk_end = [&](EdgeRef e) { return welded.find(corner(e, !walks_forward(e.edge))); };
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> starts;
  for (std::size_t k = 0; k < open_.size(); ++k) starts[walk_start(open_[k])].push_back(k);
  std::vector<bool> used(open_.size(), false);
  for (std::size_t first = 0; first < open_.size(); ++first) {
    if (used[first]) continue;
    BoundaryLoop loop{{open_[first]}, false};
    used[first] = true;
    const std::uint32_t origin = walk_start(open_[first]);
    std::size_t current = first;
    while (true) {
      const std::uint32_t end = walk_end(open_[current]);
      if (end == origin) {
        loop.closed = true;
        break;
      }
      std::optional<std::size_t> next;
      const auto here = starts.find(end);
      if (here != starts.end()) {
        for (std::size_t k : here->second) {
          if (!used[k]) {
            next = k;
            break;
          }
        }
      }
      if (!next) break;
      used[*next] = true;
      loop.edges.push_back(open_[*next]);
      current = *next;
    }
    loops_.push_back(std::move(loop));
  }

  // Touching points: corners grouped by position; patches there joined by shared edges that end
  // at the point (or by a collapsed edge, which is the point itself).
  struct Corner {
    Vec3 point;
    std::uint32_t patch;
  };
  std::vector<Corner> corners;
  for (std::uint32_t p = 0; p < nets_.size(); ++p) {
    const auto& patch = nets_[p];
    const int n = patch.degree_u();
    const int m = patch.degree_v();
    for (const Vec3& q : {patch.control_point(0, 0), patch.control_point(n, 0), patch.control_point(n, m), patch.control_point(0, m)}) {
      corners.push_back({q, p});
    }
  }
  PointGrid corner_grid(std::max(2.0 * tolerance_, 1e-300));
  for (std::size_t k = 0; k < corners.size(); ++k) corner_grid.insert(corners[k].point, k);
  // The shared edges (by their first patch) and T-junctions of each patch: a point looks only at
  // those of the patches there.
  std::vector<std::vector<std::uint32_t>> shared_of(nets_.size());
  for (std::uint32_t i = 0; i < shared_.size(); ++i) shared_of[shared_[i].first.patch].push_back(i);
  std::vector<std::vector<std::uint32_t>> junctions_of(nets_.size());
  for (std::uint32_t i = 0; i < t_junctions_.size(); ++i) {
    junctions_of[t_junctions_[i].edge.patch].push_back(i);
    for (const EdgeRef& part : t_junctions_[i].parts) junctions_of[part.patch].push_back(i);
  }
  std::vector<bool> visited(corners.size(), false);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    if (visited[k]) continue;
    std::vector<std::uint32_t> here;
    corner_grid.near(corners[k].point, [&](std::size_t c) {
      if ((corners[c].point - corners[k].point).norm() <= tolerance_) {
        visited[c] = true;
        here.push_back(corners[c].patch);
      }
    });
    std::sort(here.begin(), here.end());
    here.erase(std::unique(here.begin(), here.end()), here.end());
    if (here.size() < 2) continue;
    const auto touches = [&](EdgeRef e) {
      const auto row = row_from_edge(nets_[e.patch], e.edge, 0);
      return (row.front() - corners[k].point).norm() <= tolerance_ || (row.back() - corners[k].point).norm() <= tolerance_;
    };
    const auto index_of = [&](std::uint32_t patch) {
      return static_cast<std::size_t>(std::lower_bound(here.begin(), here.end(), patch) - here.begin());
    };
    UnionFind groups(here.size());
    std::vector<std::uint32_t> junctions;
    for (const std::uint32_t patch : here) {
      for (const std::uint32_t i : shared_of[patch]) {
        const SharedEdge& s = shared_[i];
        if (!std::binary_search(here.begin(), here.end(), s.second.patch) || !touches(s.first)) continue;
        groups.unite(static_cast<std::uint32_t>(index_of(s.first.patch)), static_cast<std::uint32_t>(index_of(s.second.patch)));
      }
      junctions.insert(junctions.end(), junctions_of[patch].begin(), junctions_of[patch].end());
    }
    std::sort(junctions.begin(), junctions.end());
    junctions.erase(std::unique(junctions.begin(), junctions.end()), junctions.end());
    // The patches of a T-junction here meet along its long edge, which runs through the point
    // (a junction) or ends at it.
    for (const std::uint32_t i : junctions) {
      const TJunction& t = t_junctions_[i];
      std::optional<std::uint32_t> first;
      const auto join = [&](const EdgeRef& e) {
        if (!std::binary_search(here.begin(), here.end(), e.patch) || !touches(e)) return;
        const auto i = static_cast<std::uint32_t>(index_of(e.patch));
        if (first) groups.unite(*first, i); else first = i;
      };
      join(t.edge);
      for (const EdgeRef& part : t.parts) join(part);
    }
    std::unordered_map<std::size_t, std::vector<std::uint32_t>> by_root;
    for (std::uint32_t i = 0; i < here.size(); ++i) by_root[groups.find(i)].push_back(here[i]);
    if (by_root.size() < 2) continue;
    TouchingPoint point{corners[k].point, {}};
    for (auto& [root, members] : by_root) point.groups.push_back(std::move(members));
    std::sort(point.groups.begin(), point.groups.end());
    touching_.push_back(std::move(point));
  }
}

std::optional<EdgeRef> PatchSet::neighbour(EdgeRef edge) const {
  for (const SharedEdge& s : shared_) {
    if (s.first == edge) return s.second;
    if (s.second == edge) return s.first;
  }
  return std::nullopt;
}

std::vector<Shell> shells(const PatchSet& set) {
  const auto count = static_cast<std::uint32_t>(set.count());
  UnionFind joined(count);
  for (const SharedEdge& s : set.shared_edges()) joined.unite(s.first.patch, s.second.patch);
  for (const TJunction& t : set.t_junctions()) {
    for (const EdgeRef& part : t.parts) joined.unite(t.edge.patch, part.patch);
  }
  std::vector<std::int64_t> index(count, -1);
  std::vector<Shell> result;
  for (std::uint32_t p = 0; p < count; ++p) {
    std::int64_t& i = index[joined.find(p)];
    if (i < 0) {
      i = static_cast<std::int64_t>(result.size());
      result.push_back({{}, true, true});
    }
    result[static_cast<std::size_t>(i)].patches.push_back(p);
  }
  const auto shell_of = [&](std::uint32_t p) -> Shell& { return result[static_cast<std::size_t>(index[joined.find(p)])]; };
  for (const EdgeRef& e : set.open_edges()) shell_of(e.patch).closed = false;
  for (const SharedEdge& s : set.shared_edges()) {
    if (!s.consistently_oriented) shell_of(s.first.patch).consistently_oriented = false;
  }
  for (const TJunction& t : set.t_junctions()) {
    if (!t.consistently_oriented) shell_of(t.edge.patch).consistently_oriented = false;
  }
  return result;
}

Eigen::AlignedBox3d bounding_box(const PatchSet& set, double tolerance) {
  if (set.rational_count() == 0) return bounding_box(std::span<const BezierPatch3>(set.patches()), tolerance);
  Eigen::AlignedBox3d box;
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    const RationalBezierPatch* rational = set.rational(p);
    box.extend(rational != nullptr ? bounding_box(*rational, tolerance) : bounding_box(set.control_nets()[p], tolerance));
  }
  return box;
}

}  // namespace patchwork
