#include "surfaces/patch_bounding_box.h"

#include <cmath>
#include <queue>

#include "core/errors.h"

namespace patchwork {
namespace {

struct Candidate {
  double upper;  // max of direction . P over the sub-patch's control points
  BezierPatch3 patch;
  int depth;
  bool operator<(const Candidate& other) const { return upper < other.upper; }
};

double max_over(const std::vector<Vec3>& points, const Vec3& direction) {
  double result = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) result = std::max(result, direction.dot(p));
  return result;
}

double max_over_corners(const BezierPatch3& patch, const Vec3& direction) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  return std::max({direction.dot(patch.control_point(0, 0)), direction.dot(patch.control_point(n, 0)),
                   direction.dot(patch.control_point(0, m)), direction.dot(patch.control_point(n, m))});
}

// The least upper bound found for max over the surface of direction . F.
double extreme(const BezierPatch3& patch, const Vec3& direction, double tolerance) {
  double lower = max_over_corners(patch, direction);
  std::priority_queue<Candidate> queue;
  queue.push({max_over(patch.control_points(), direction), patch, 0});
  for (int steps = 0; steps < 100000; ++steps) {
    Candidate best = queue.top();
    if (best.upper <= lower + tolerance) return best.upper;
    queue.pop();
    // Alternate the split direction with depth so both parameter ranges shrink.
    const auto [a, b] = best.depth % 2 == 0 ? split_u(best.patch, 0.5) : split_v(best.patch, 0.5);
    for (const BezierPatch3* piece : {&a, &b}) {
      lower = std::max(lower, max_over_corners(*piece, direction));
      queue.push({max_over(piece->control_points(), direction), *piece, best.depth + 1});
    }
  }
  return queue.top().upper;  // still a valid upper bound, only less tight
}

}  // namespace

Eigen::AlignedBox3d control_box(const BezierPatch3& patch) {
  Eigen::AlignedBox3d box(patch.control_points().front());
  for (const Vec3& p : patch.control_points()) box.extend(p);
  return box;
}

Eigen::AlignedBox3d bounding_box(const BezierPatch3& patch, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("bounding_box: tolerance ", tolerance, " is not positive"));
  }
  Eigen::AlignedBox3d box;
  for (int c = 0; c < 3; ++c) {
    const Vec3 direction = Vec3::Unit(c);
    box.max()[c] = extreme(patch, direction, tolerance);
    box.min()[c] = -extreme(patch, -direction, tolerance);
  }
  return box;
}

}  // namespace patchwork
