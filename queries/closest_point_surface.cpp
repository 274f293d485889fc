// Closest points of patches and patch sets: branch and bound over the PatchBvh's nodes and then
// quartered pieces (queries/closest_point.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "queries/closest_point.h"
#include "queries/patch_bvh.h"
#include "queries/patch_evaluation.h"
#include "queries/query_arguments.h"

namespace patchwork {
namespace {

constexpr double no_bound = std::numeric_limits<double>::infinity();

// A heap entry: a node of the hierarchy (node >= 0) or a piece of the pool.
struct Entry {
  double lower;
  std::int64_t node;
  std::size_t piece;
  // A piece as the hierarchy holds it (not yet halved).
  bool whole = false;
  bool operator>(const Entry& other) const { return lower > other.lower; }
};

struct Candidate {
  std::uint32_t patch;
  double u, v, distance;
};

SurfaceClosestPoint search(const PatchBvh& bvh, const Vec3& q, const ClosestPointOptions& options) {
  require_finite(q, "closest_point", "point");
  const PatchSet& set = bvh.set();
  Eigen::AlignedBox3d extent = bvh.nodes().front().box;
  extent.extend(q);
  const double size = std::max(extent.diagonal().norm(), std::numeric_limits<double>::min());
  const double gap = options.relative_gap * size;
  const double separation = options.relative_separation * size;
  const double newton_threshold = 1e-3 * size;

  Candidate best{0, 0.0, 0.0, no_bound};
  std::vector<Candidate> feet;
  auto offer_corners = [&](const detail::NetPiece& piece) {
    const int corner_i[4] = {0, piece.n, 0, piece.n};
    const int corner_j[4] = {0, 0, piece.m, piece.m};
    for (int c = 0; c < 4; ++c) {
      const double distance = (piece.point(corner_i[c], corner_j[c]) - q).norm();
      if (distance < best.distance)
        best = {piece.patch, c % 2 ? piece.u1 : piece.u0, c / 2 ? piece.v1 : piece.v0, distance};
    }
  };

  std::vector<detail::NetPiece> pool;
  std::vector<std::size_t> free_slots;
  auto store = [&](detail::NetPiece piece) {
    if (!free_slots.empty()) {
      const std::size_t slot = free_slots.back();
      free_slots.pop_back();
      pool[slot] = std::move(piece);
      return slot;
    }
    pool.push_back(std::move(piece));
    return pool.size() - 1;
  };

  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  heap.push({std::sqrt(bvh.nodes().front().box.squaredExteriorDistance(q)), 0, 0});
  double pruned_lower = no_bound;
  double lower = no_bound;
  std::int64_t examined = 0;
  while (!heap.empty()) {
    const Entry entry = heap.top();
    if (entry.lower >= best.distance - gap) {
      lower = entry.lower;
      break;
    }
    heap.pop();
    if (entry.node >= 0) {
      const PatchBvh::Node& node = bvh.nodes()[static_cast<std::size_t>(entry.node)];
      if (node.leaf()) {
        for (std::uint32_t k = 0; k < node.piece_count; ++k) {
          const detail::NetPiece& piece = bvh.pieces()[node.second_or_first_piece + k];
          offer_corners(piece);
          const double bound = detail::distance_lower_bound(piece, q);
          if (bound >= best.distance - gap)
            pruned_lower = std::min(pruned_lower, bound);
          else
            heap.push({bound, -1, store(piece), true});
        }
      } else {
        const std::size_t children[2] = {static_cast<std::size_t>(entry.node) + 1, node.second_or_first_piece};
        for (std::size_t child : children) {
          const double bound = std::sqrt(bvh.nodes()[child].box.squaredExteriorDistance(q));
          if (bound >= best.distance - gap)
            pruned_lower = std::min(pruned_lower, bound);
          else
            heap.push({bound, static_cast<std::int64_t>(child), 0});
        }
      }
      continue;
    }
    if (++examined > options.max_pieces) {
      lower = entry.lower;
      break;
    }
    detail::NetPiece piece = std::move(pool[entry.piece]);
    free_slots.push_back(entry.piece);
    // Newton from every piece of the hierarchy that is still in question, and from a halved piece
    // only where it could still be far better than the best so far (another basin).
    if (entry.whole || best.distance - entry.lower > newton_threshold) {
      const detail::PatchFoot foot =
          detail::newton_foot(set, piece.patch, 0.5 * (piece.u0 + piece.u1), 0.5 * (piece.v0 + piece.v1), q);
      const Candidate candidate{piece.patch, foot.u, foot.v, foot.distance};
      feet.push_back(candidate);
      if (candidate.distance < best.distance) best = candidate;
    }
    const int dir = detail::longer_direction(piece);
    const double low = dir == 0 ? piece.u0 : piece.v0, high = dir == 0 ? piece.u1 : piece.v1;
    if (!(low < 0.5 * (low + high) && 0.5 * (low + high) < high)) {
      pruned_lower = std::min(pruned_lower, entry.lower);  // cannot be halved further
      continue;
    }
    for (detail::NetPiece& child : detail::halves(piece, dir)) {
      offer_corners(child);
      const double bound = detail::distance_lower_bound(child, q);
      if (bound >= best.distance - gap)
        pruned_lower = std::min(pruned_lower, bound);
      else
        heap.push({bound, -1, store(std::move(child))});
    }
  }
  // A foot found as a piece's corner is polished by Newton (equal distance up to rounding, but
  // orthogonal).
  {
    const detail::PatchFoot polished = detail::newton_foot(set, best.patch, best.u, best.v, q);
    if (polished.distance <= best.distance + 8 * unit_roundoff * (best.distance + size))
      best = {best.patch, polished.u, polished.v, polished.distance};
  }
  SurfaceClosestPoint result;
  result.patch = best.patch;
  result.u = best.u;
  result.v = best.v;
  result.point = detail::patch_point(set, best.patch, best.u, best.v);
  result.distance = (result.point - q).norm();
  result.lower_bound = std::clamp(std::min({lower, pruned_lower, best.distance}), 0.0, result.distance);
  result.pieces = examined;
  const double within = best.distance + 4 * gap;
  for (const Candidate& foot : feet) {
    if (foot.distance <= within &&
        (detail::patch_point(set, foot.patch, foot.u, foot.v) - result.point).norm() > separation)
      result.attained_more_than_once = true;
  }
  return result;
}

template <class Patch>
SurfaceClosestPoint single_patch(const Patch& patch, const Vec3& q, const ClosestPointOptions& options) {
  require_finite(q, "closest_point", "point");
  const std::vector<AnyBezierPatch> patches{AnyBezierPatch(patch)};
  const PatchSet set(patches);
  const PatchBvh bvh(set, 1);
  return search(bvh, q, options);
}

}  // namespace

SurfaceClosestPoint closest_point(const BezierPatch3& patch, const Vec3& q, const ClosestPointOptions& options) {
  return single_patch(patch, q, options);
}

SurfaceClosestPoint closest_point(const RationalBezierPatch& patch, const Vec3& q, const ClosestPointOptions& options) {
  return single_patch(patch, q, options);
}

SurfaceClosestPoint closest_point(const PatchSet& set, const Vec3& q, const ClosestPointOptions& options) {
  require_finite(q, "closest_point", "point");
  return search(PatchBvh(set), q, options);
}

SurfaceClosestPoint closest_point(const PatchBvh& bvh, const Vec3& q, const ClosestPointOptions& options) {
  return search(bvh, q, options);
}

}  // namespace patchwork
