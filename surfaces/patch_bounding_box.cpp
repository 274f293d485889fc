#include "surfaces/patch_bounding_box.h"

#include <cmath>
#include <limits>
#include <queue>

#include "core/errors.h"

namespace patchwork {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// The control points of a patch as they bound its surface (convex hull): the net itself, or a
// rational net's points (its weights are positive).
const std::vector<Vec3>& hull_points(const BezierPatch3& patch) { return patch.control_points(); }
std::vector<Vec3> hull_points(const RationalBezierPatch& patch) {
  std::vector<Vec3> points;
  for (const Vec4& h : patch.homogeneous().control_points()) points.push_back(h.head<3>() / h[3]);
  return points;
}

double max_over(const std::vector<Vec3>& points, const Vec3& direction) {
  double result = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) result = std::max(result, direction.dot(p));
  return result;
}

// The corners are surface points (of a rational patch too: F(0,0) = P_00).
template <class Patch>
double max_over_corners(const Patch& patch, const Vec3& direction) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  return std::max({direction.dot(patch.control_point(0, 0)), direction.dot(patch.control_point(n, 0)),
                   direction.dot(patch.control_point(0, m)), direction.dot(patch.control_point(n, m))});
}

template <class Patch>
struct Candidate {
  double upper;  // max of direction . P over the sub-patch's control points
  Patch patch;
  int depth;
  bool operator<(const Candidate& other) const { return upper < other.upper; }
};

// The least upper bound found for max over the surface of direction . F, or for the larger of
// that and lower_bound (a value the caller knows the maximum it wants reaches).
template <class Patch>
double extreme(const Patch& patch, const Vec3& direction, double tolerance, double lower_bound) {
  double lower = std::max(lower_bound, max_over_corners(patch, direction));
  std::priority_queue<Candidate<Patch>> queue;
  queue.push({max_over(hull_points(patch), direction), patch, 0});
  for (int steps = 0; steps < 100000; ++steps) {
    Candidate<Patch> best = queue.top();
    if (best.upper <= lower + tolerance) return best.upper;
    queue.pop();
    // Alternate the split direction with depth so both parameter ranges shrink.
    const auto [a, b] = best.depth % 2 == 0 ? split_u(best.patch, 0.5) : split_v(best.patch, 0.5);
    for (const Patch* piece : {&a, &b}) {
      lower = std::max(lower, max_over_corners(*piece, direction));
      queue.push({max_over(hull_points(*piece), direction), *piece, best.depth + 1});
    }
  }
  return queue.top().upper;  // still a valid upper bound, only less tight
}

template <class Patch>
Eigen::AlignedBox3d tight_box(const Patch& patch, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("bounding_box: tolerance ", tolerance, " is not positive"));
  }
  Eigen::AlignedBox3d box;
  for (int c = 0; c < 3; ++c) {
    const Vec3 direction = Vec3::Unit(c);
    box.max()[c] = extreme(patch, direction, tolerance, -inf);
    box.min()[c] = -extreme(patch, -direction, tolerance, -inf);
  }
  return box;
}

}  // namespace

Eigen::AlignedBox3d control_box(const BezierPatch3& patch) {
  Eigen::AlignedBox3d box(patch.control_points().front());
  for (const Vec3& p : patch.control_points()) box.extend(p);
  return box;
}

Eigen::AlignedBox3d bounding_box(const BezierPatch3& patch, double tolerance) { return tight_box(patch, tolerance); }

Eigen::AlignedBox3d bounding_box(const RationalBezierPatch& patch, double tolerance) { return tight_box(patch, tolerance); }

Eigen::AlignedBox3d bounding_box(std::span<const BezierPatch3> patches, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("bounding_box: tolerance ", tolerance, " is not positive"));
  }
  Eigen::AlignedBox3d box;
  if (patches.empty()) return box;
  for (int c = 0; c < 6; ++c) {
    const Vec3 direction = (c < 3 ? 1.0 : -1.0) * Vec3::Unit(c % 3);
    // The corners are surface points: their maximum is a lower bound on the set's. A patch
    // whose control points do not exceed it cannot raise the maximum (convex hull property).
    double lower = -inf;
    for (const BezierPatch3& patch : patches) lower = std::max(lower, max_over_corners(patch, direction));
    double face = lower;
    for (const BezierPatch3& patch : patches) {
      if (max_over(patch.control_points(), direction) > lower) face = std::max(face, extreme(patch, direction, tolerance, lower));
    }
    if (c < 3) {
      box.max()[c] = face;
    } else {
      box.min()[c % 3] = -face;
    }
  }
  return box;
}

}  // namespace patchwork
