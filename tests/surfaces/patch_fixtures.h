#pragma once
// Patches with known closed forms, and RapidCheck generators, for the surfaces tests.

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "surfaces/bezier_patch.h"
#include "surfaces/patch_flatness.h"

namespace patchwork::testing {

/// The bilinear patch with corners P00, P10, P01, P11.
inline BezierPatch3 bilinear(const Vec3& p00, const Vec3& p10, const Vec3& p01, const Vec3& p11) {
  return BezierPatch3(1, 1, {p00, p10, p01, p11});
}

/// The tensor product net x_ij = a_i * b_j for each coordinate: F = (sum a B)(sum b B) per
/// coordinate, so a product of two univariate polynomials given in Bernstein form.
inline BezierPatch3 product_patch(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  const int n = static_cast<int>(a.size()) - 1;
  const int m = static_cast<int>(b.size()) - 1;
  std::vector<Vec3> points;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) points.push_back(a[i].cwiseProduct(b[j]));
  }
  return BezierPatch3(n, m, std::move(points));
}

/// A value in [lo, hi] with 1e-6 resolution.
inline rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange(0, 1000001), [lo, hi](int k) { return lo + (hi - lo) * k / 1e6; });
}

/// A random patch with degrees in [0, max_degree] and coordinates in [-10, 10].
inline rc::Gen<BezierPatch3> random_patch(int min_degree = 0, int max_degree = 4) {
  return rc::gen::exec([=] {
    const int n = *rc::gen::inRange(min_degree, max_degree + 1);
    const int m = *rc::gen::inRange(min_degree, max_degree + 1);
    std::vector<Vec3> points;
    for (int k = 0; k < (n + 1) * (m + 1); ++k) {
      points.emplace_back(*coordinate(-10, 10), *coordinate(-10, 10), *coordinate(-10, 10));
    }
    return BezierPatch3(n, m, std::move(points));
  });
}

/// A random rotation (from a random unit quaternion) and translation.
inline rc::Gen<Eigen::Isometry3d> random_rigid_motion() {
  return rc::gen::exec([] {
    Eigen::Quaterniond q(*coordinate(-1, 1), *coordinate(-1, 1), *coordinate(-1, 1), *coordinate(-1, 1));
    if (q.norm() < 1e-3) q = Eigen::Quaterniond::Identity();
    q.normalize();
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    motion.linear() = q.toRotationMatrix();
    motion.translation() = Vec3(*coordinate(-5, 5), *coordinate(-5, 5), *coordinate(-5, 5));
    return motion;
  });
}

/// The patch with every control point mapped by an affine map.
inline BezierPatch3 transformed(const BezierPatch3& patch, const Eigen::Affine3d& map) {
  std::vector<Vec3> points;
  for (const Vec3& p : patch.control_points()) points.push_back(map * p);
  return BezierPatch3(patch.degree_u(), patch.degree_v(), std::move(points));
}

/// max |F(u,v) - L(u,v)| sampled over the triangulated nu x nv grid (patch_flatness.h).
inline double measured_distance(const BezierPatch3& patch, std::int64_t nu, std::int64_t nv, int samples) {
  return sampled_grid_distance(patch, nu, nv, samples);
}

/// Max norm of the control points (the scale for relative tolerances).
inline double net_scale(const BezierPatch3& patch) {
  double scale = 1.0;
  for (const Vec3& p : patch.control_points()) scale = std::max(scale, p.norm());
  return scale;
}

}  // namespace patchwork::testing
