#include "surfaces/surface_normal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"

namespace patchwork {
namespace {

// Highest order of N^(k) tried: enough for any collapse of a patch of degrees up to (n, m).
int max_normal_order(int n, int m) { return std::min(n + m, 12); }


// D^j applied to d^(a0,b0) F: sum_l C(j,l) du^l dv^(j-l) d^(a0+l, b0+j-l) F.
Vec3 directional(const PartialDerivatives<3>& F, int a0, int b0, int j, double du, double dv) {
  Vec3 sum = Vec3::Zero();
  for (int l = 0; l <= j; ++l) sum += binomial(j, l) * std::pow(du, l) * std::pow(dv, j - l) * F.at(a0 + l, b0 + j - l);
  return sum;
}

// The unit direction from (u, v) towards the centre (1/2, 1/2) of the square (the diagonal at
// the centre itself).
std::pair<double, double> towards_centre(double u, double v) {
  const double du = 0.5 - u;
  const double dv = 0.5 - v;
  const double length = std::hypot(du, dv);
  if (length < 1e-12) return {std::sqrt(0.5), std::sqrt(0.5)};
  return {du / length, dv / length};
}

}  // namespace

namespace detail {

DegeneracyThresholds degeneracy_thresholds(int n, int m, const Eigen::AlignedBox3d& box, bool rational,
                                           double weight_ratio) {
  const double scale = box.diagonal().norm();
  const double reach = box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).norm();
  const int d = std::max({n, m, 1});
  // A sum of 2 (d + 1) terms of weights |B_k'| summing to at most 2 d, each |P_k| <= R.
  const double noise = (rational ? 3.0 * weight_ratio : 1.0) * 4.0 * d * (d + 1) *
                       std::numeric_limits<double>::epsilon() * reach;
  // |F_u x F_v| takes each derivative's noise times the other derivative, |F_u| <= d s (times
  // the weight ratio for a rational patch).
  const double derivative = d * scale * (rational ? weight_ratio : 1.0);
  const double relative = 1e-12 * std::max(n * m, 1) * scale * scale;
  return {std::max(relative, 2.0 * noise * derivative), std::max(1e-12 * d * scale, noise), relative, noise};
}

bool first_normal_vanishes(const Vec3& du, const Vec3& dv, const DegeneracyThresholds& thresholds) {
  return du.cross(dv).norm() <= std::max(thresholds.relative, 2.0 * thresholds.noise * (du.norm() + dv.norm()));
}

DegeneracyThresholds degeneracy_thresholds(const BezierPatch3& patch) {
  Eigen::AlignedBox3d box(patch.control_points().front());
  for (const Vec3& p : patch.control_points()) box.extend(p);
  return degeneracy_thresholds(patch.degree_u(), patch.degree_v(), box);
}

DegeneracyThresholds degeneracy_thresholds(const RationalBezierPatch& patch) {
  const std::vector<Vec4>& H = patch.homogeneous().control_points();
  Eigen::AlignedBox3d box(H.front().head<3>() / H.front()[3]);
  double w_min = H.front()[3];
  double w_max = w_min;
  for (const Vec4& h : H) {
    box.extend(Vec3(h.head<3>() / h[3]));
    w_min = std::min(w_min, h[3]);
    w_max = std::max(w_max, h[3]);
  }
  return degeneracy_thresholds(patch.degree_u(), patch.degree_v(), box, true, w_max / w_min);
}

Vec3 limit_unit_normal(const PartialDerivatives<3>& F, double u, double v, const DegeneracyThresholds& thresholds,
                       int n, int m) {
  if (!first_normal_vanishes(F.at(1, 0), F.at(0, 1), thresholds)) return F.at(1, 0).cross(F.at(0, 1)).normalized();
  // For each further order the derivatives (and their rounding) grow by about max(n, m); N_k's
  // rounding is each factor's rounding times the other factor.
  const double degree = std::max({n, m, 1});
  const auto [du, dv] = towards_centre(u, v);
  for (int k = 1; k + 1 <= F.order(); ++k) {
    Vec3 Nk = Vec3::Zero();
    double rounding = 0.0;
    for (int j = 0; j <= k; ++j) {
      const Vec3 a = directional(F, 1, 0, j, du, dv);
      const Vec3 b = directional(F, 0, 1, k - j, du, dv);
      Nk += binomial(k, j) * a.cross(b);
      rounding += binomial(k, j) * (std::pow(degree, j) * b.norm() + std::pow(degree, k - j) * a.norm());
    }
    if (Nk.norm() > std::max(thresholds.relative * std::pow(degree, k), 2.0 * thresholds.noise * rounding)) {
      return Nk.normalized();
    }
  }
  throw NumericalError(message("unit_normal: the patch is degenerate around (", u, ", ", v, "): no normal"));
}

}  // namespace detail

Vec3 normal(const BezierPatch3& patch, double u, double v) {
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  return F.at(1, 0).cross(F.at(0, 1));
}

Vec3 normal(const RationalBezierPatch& patch, double u, double v) {
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  return F.at(1, 0).cross(F.at(0, 1));
}

namespace {

// The limit normal where F_u x F_v vanishes. Nearly every such point (a pole) has it at the
// first order past the normal's own, from derivatives up to order 2: those are tried first (a
// sixth of the partials of the full order for bicubics), and the full order only where they do
// not decide. partial_derivatives' low orders do not depend on the order asked for, so the
// answer is the same bit for bit.
template <class Patch>
Vec3 staged_limit_normal(const Patch& patch, double u, double v, const detail::DegeneracyThresholds& thresholds) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const int full = max_normal_order(n, m) + 1;
  if (full > 2) {
    try {
      return detail::limit_unit_normal(partial_derivatives(patch, u, v, 2), u, v, thresholds, n, m);
    } catch (const NumericalError&) {
      // Degenerate to a higher order: the full table below.
    }
  }
  return detail::limit_unit_normal(partial_derivatives(patch, u, v, full), u, v, thresholds, n, m);
}

// de Casteljau of points[0..N] at s in place, partial_derivatives' arithmetic (r p_i + s p_i+1).
template <int N>
Vec3 de_casteljau_fixed(std::array<Vec3, 4>& points, double s) {
  const double r = 1.0 - s;
  for (int k = 1; k <= N; ++k) {
    for (int i = 0; i + k <= N; ++i) points[i] = r * points[i] + s * points[i + 1];
  }
  return points[0];
}

// F_u and F_v at (u, v) for degrees (N, M), both 1 to 3, by partial_derivatives' own arithmetic
// (the net differenced, its rows by de Casteljau, then across), bit for bit its at(1, 0) and
// at(0, 1), without F and without its table: the G1 test of every shared edge calls unit_normal
// at 13 points a side.
template <int N, int M>
void first_derivatives_fixed(const std::vector<Vec3>& P, double u, double v, Vec3& fu, Vec3& fv) {
  const auto at = [&](int i, int j) -> const Vec3& { return P[static_cast<std::size_t>(i + (N + 1) * j)]; };
  std::array<Vec3, 4> across;
  std::array<Vec3, 4> line;
  // F_v: rows of M (P_i,j+1 - P_ij), j < M, each at u (degree N), then across at v (degree M - 1).
  for (int j = 0; j < M; ++j) {
    for (int i = 0; i <= N; ++i) line[i] = static_cast<double>(M) * (at(i, j + 1) - at(i, j));
    across[j] = de_casteljau_fixed<N>(line, u);
  }
  fv = de_casteljau_fixed<M - 1>(across, v);
  // F_u: rows of N (P_i+1,j - P_ij), i < N, each at u (degree N - 1), then across (degree M).
  for (int j = 0; j <= M; ++j) {
    for (int i = 0; i < N; ++i) line[i] = static_cast<double>(N) * (at(i + 1, j) - at(i, j));
    across[j] = de_casteljau_fixed<N - 1>(line, u);
  }
  fu = de_casteljau_fixed<M>(across, v);
}

template <int N>
bool first_derivatives_fixed_u(int m, const std::vector<Vec3>& P, double u, double v, Vec3& fu, Vec3& fv) {
  if (m == 1) first_derivatives_fixed<N, 1>(P, u, v, fu, fv);
  if (m == 2) first_derivatives_fixed<N, 2>(P, u, v, fu, fv);
  if (m == 3) first_derivatives_fixed<N, 3>(P, u, v, fu, fv);
  return m >= 1 && m <= 3;
}

// F_u and F_v of a polynomial patch: partial_derivatives(patch, u, v, 1)'s, unrolled for the
// usual degrees.
void first_derivatives(const BezierPatch3& patch, double u, double v, Vec3& fu, Vec3& fv) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const std::vector<Vec3>& P = patch.control_points();
  if ((n == 1 && first_derivatives_fixed_u<1>(m, P, u, v, fu, fv)) ||
      (n == 2 && first_derivatives_fixed_u<2>(m, P, u, v, fu, fv)) ||
      (n == 3 && first_derivatives_fixed_u<3>(m, P, u, v, fu, fv))) {
    return;
  }
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  fu = F.at(1, 0);
  fv = F.at(0, 1);
}

}  // namespace

Vec3 unit_normal(const BezierPatch3& patch, double u, double v) {
  return detail::unit_normal(patch, u, v, detail::degeneracy_thresholds(patch));
}

Vec3 detail::unit_normal(const BezierPatch3& patch, double u, double v, const DegeneracyThresholds& thresholds) {
  if (!std::isfinite(u) || !std::isfinite(v)) (void)partial_derivatives(patch, u, v, 1);  // throws InvalidInput
  Vec3 fu, fv;
  first_derivatives(patch, u, v, fu, fv);
  if (!detail::first_normal_vanishes(fu, fv, thresholds)) return fu.cross(fv).normalized();
  return staged_limit_normal(patch, u, v, thresholds);
}

namespace {

// unit_derivative_direction for either kind of patch (both have partial_derivatives).
template <class Patch>
Vec3 derivative_direction(const Patch& patch, double u, double v, bool along_u) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const double degree = std::max({n, m, 1});
  const double threshold = detail::degeneracy_thresholds(patch).derivative;
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, std::min(n + m, 12) + 1);
  const int a0 = along_u ? 1 : 0;
  const int b0 = along_u ? 0 : 1;
  if (F.at(a0, b0).norm() > threshold) return F.at(a0, b0).normalized();
  const auto [du, dv] = towards_centre(u, v);
  // d/ds^k of the derivative along the inward direction; the first that does not vanish.
  for (int k = 1; k + 1 <= F.order(); ++k) {
    const Vec3 Dk = directional(F, a0, b0, k, du, dv);
    if (Dk.norm() > threshold * std::pow(degree, k)) return Dk.normalized();
  }
  throw NumericalError(detail::message("unit_derivative_direction: the patch is degenerate around (", u, ", ", v, ")"));
}

template <class Patch>
Vec4 tangent_of(const Patch& patch, double u, double v, const Vec3& unit_normal) {
  const Vec3 along_u = derivative_direction(patch, u, v, true);
  Vec3 tangent = along_u - along_u.dot(unit_normal) * unit_normal;
  if (tangent.norm() < 1e-9) {
    // F_u along the normal can only happen at a singular point; any tangent direction serves.
    tangent = unit_normal.unitOrthogonal();
  }
  tangent.normalize();
  const Vec3 along_v = derivative_direction(patch, u, v, false);
  const double w = unit_normal.cross(tangent).dot(along_v) < 0.0 ? -1.0 : 1.0;
  return {tangent.x(), tangent.y(), tangent.z(), w};
}

}  // namespace

Vec3 unit_derivative_direction(const BezierPatch3& patch, double u, double v, bool along_u) {
  return derivative_direction(patch, u, v, along_u);
}

Vec3 unit_derivative_direction(const RationalBezierPatch& patch, double u, double v, bool along_u) {
  return derivative_direction(patch, u, v, along_u);
}

Vec4 unit_tangent(const BezierPatch3& patch, double u, double v, const Vec3& unit_normal) {
  return tangent_of(patch, u, v, unit_normal);
}

Vec4 unit_tangent(const RationalBezierPatch& patch, double u, double v, const Vec3& unit_normal) {
  return tangent_of(patch, u, v, unit_normal);
}

Vec3 unit_normal(const RationalBezierPatch& patch, double u, double v) {
  const detail::DegeneracyThresholds thresholds = detail::degeneracy_thresholds(patch);
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  if (!detail::first_normal_vanishes(F.at(1, 0), F.at(0, 1), thresholds)) {
    return F.at(1, 0).cross(F.at(0, 1)).normalized();
  }
  return staged_limit_normal(patch, u, v, thresholds);
}

namespace detail {

Vec3 degenerate_unit_normal(const BezierPatch3& patch, double u, double v) {
  return staged_limit_normal(patch, u, v, degeneracy_thresholds(patch));
}

Vec3 degenerate_unit_normal(const RationalBezierPatch& patch, double u, double v) {
  return staged_limit_normal(patch, u, v, degeneracy_thresholds(patch));
}

}  // namespace detail

}  // namespace patchwork
