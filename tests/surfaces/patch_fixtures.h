#pragma once
// Patches with known closed forms, and RapidCheck generators, for the surfaces tests.

#include <rapidcheck.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
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

/// A curved bicubic patch over [0,1]^2 (a wavy height field), for cutting into pieces.
inline BezierPatch3 wavy_bicubic() {
  std::vector<Vec3> points;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i)
      points.emplace_back(i / 3.0, j / 3.0, 0.3 * std::sin(1.7 * i + 0.9 * j) - 0.1 * i * j / 9.0);
  }
  return BezierPatch3(3, 3, std::move(points));
}

/// Two biquadratic height fields side by side, [0,1] x [0,1] and [1,2] x [0,1]: the right one
/// continues the left across x = 1, its u0 column on the left's u1 column, then each point j of
/// that column moved by move(j) (a gap that a PatchSet of enough tolerance still joins).
inline std::array<BezierPatch3, 2> height_fields_side_by_side(const std::function<Vec3(int)>& move) {
  const double heights[3][3] = {{0.0, 0.3, 0.1}, {0.4, -0.2, 0.2}, {0.1, 0.3, 0.0}};
  std::vector<Vec3> left;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) left.emplace_back(0.5 * i, 0.5 * j, heights[j][i]);
  }
  std::vector<Vec3> right;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) right.push_back(i == 0 ? left[2 + 3 * j] + move(j) : left[i + 3 * j] + Vec3(1, 0, 0));
  }
  return {BezierPatch3(2, 2, left), BezierPatch3(2, 2, right)};
}

/// The same surface with its parameter square turned by 180 degrees ((u, v) -> (1 - u, 1 - v)):
/// the orientation stays, every edge is another and runs the other way.
inline BezierPatch3 turned_half(const BezierPatch3& patch) {
  std::vector<Vec3> points;
  for (int j = patch.degree_v(); j >= 0; --j) {
    for (int i = patch.degree_u(); i >= 0; --i) points.push_back(patch.control_point(i, j));
  }
  return BezierPatch3(patch.degree_u(), patch.degree_v(), std::move(points));
}

/// Pieces of `surface` with T-junctions: the bottom half [0,1] x [0,1/2] whole, the top half cut
/// at u = cuts[0] < cuts[1] < ... into pieces [c_k, c_{k+1}] x [1/2, 1]; the bottom's v1 edge meets
/// the pieces' v0 edges.
inline std::vector<BezierPatch3> t_junction_pieces(const BezierPatch3& surface, const std::vector<double>& cuts) {
  std::vector<BezierPatch3> patches = {subpatch(surface, 0.0, 1.0, 0.0, 0.5)};
  double from = 0.0;
  for (std::size_t k = 0; k <= cuts.size(); ++k) {
    const double to = k < cuts.size() ? cuts[k] : 1.0;
    patches.push_back(subpatch(surface, from, to, 0.5, 1.0));
    from = to;
  }
  return patches;
}

}  // namespace patchwork::testing
