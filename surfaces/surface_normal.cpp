#include "surfaces/surface_normal.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace patchwork {
namespace {

// Highest order of N^(k) tried: enough for any collapse of a patch of degrees up to (n, m).
int max_normal_order(int n, int m) { return std::min(n + m, 12); }

template <int Dim>
double net_size(const std::vector<Point<Dim>>& points) {
  Eigen::AlignedBox<double, Dim> box(points.front());
  for (const auto& p : points) box.extend(p);
  return box.diagonal().norm();
}

// D^j applied to d^(a0,b0) F: sum_l C(j,l) du^l dv^(j-l) d^(a0+l, b0+j-l) F.
Vec3 directional(const PartialDerivatives<3>& F, int a0, int b0, int j, double du, double dv) {
  Vec3 sum = Vec3::Zero();
  for (int l = 0; l <= j; ++l) sum += binomial(j, l) * std::pow(du, l) * std::pow(dv, j - l) * F.at(a0 + l, b0 + j - l);
  return sum;
}

}  // namespace

namespace detail {

Vec3 limit_unit_normal(const PartialDerivatives<3>& F, double u, double v, double scale, int n, int m) {
  const Vec3 first = F.at(1, 0).cross(F.at(0, 1));
  // n ~ n m |P|^2 in size; below 1e-12 of that it is rounding noise, and for each further order
  // the derivatives grow by about max(n, m).
  const double degree = std::max({n, m, 1});
  const double threshold = 1e-12 * std::max(n * m, 1) * scale * scale;
  if (first.norm() > threshold) return first.normalized();
  double du = 0.5 - u;
  double dv = 0.5 - v;
  const double length = std::hypot(du, dv);
  if (length < 1e-12) {
    du = dv = std::sqrt(0.5);
  } else {
    du /= length;
    dv /= length;
  }
  for (int k = 1; k + 1 <= F.order(); ++k) {
    Vec3 Nk = Vec3::Zero();
    for (int j = 0; j <= k; ++j) {
      Nk += binomial(k, j) * directional(F, 1, 0, j, du, dv).cross(directional(F, 0, 1, k - j, du, dv));
    }
    if (Nk.norm() > threshold * std::pow(degree, k)) return Nk.normalized();
  }
  throw NumericalError(message("unit_normal: the patch is degenerate around (", u, ", ", v, "): no normal"));
}

}  // namespace detail

Vec3 normal(const BezierPatch3& patch, double u, double v) {
  return derivative(patch, u, v, 1, 0).cross(derivative(patch, u, v, 0, 1));
}

Vec3 normal(const RationalBezierPatch& patch, double u, double v) {
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  return F.at(1, 0).cross(F.at(0, 1));
}

Vec3 unit_normal(const BezierPatch3& patch, double u, double v) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const double scale = net_size(patch.control_points());
  const Vec3 first = normal(patch, u, v);
  if (first.norm() > 1e-12 * std::max(n * m, 1) * scale * scale) return first.normalized();
  return detail::limit_unit_normal(partial_derivatives(patch, u, v, max_normal_order(n, m) + 1), u, v, scale, n, m);
}

Vec3 unit_normal(const RationalBezierPatch& patch, double u, double v) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  std::vector<Vec3> points;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) points.push_back(patch.control_point(i, j));
  }
  const double scale = net_size(points);
  const Vec3 first = normal(patch, u, v);
  if (first.norm() > 1e-12 * std::max(n * m, 1) * scale * scale) return first.normalized();
  return detail::limit_unit_normal(partial_derivatives(patch, u, v, max_normal_order(n, m) + 1), u, v, scale, n, m);
}

}  // namespace patchwork
