#include "curves/continuity.h"

#include <cmath>

#include "core/errors.h"
#include "curves/dimensions.h"
#include "curves/limit_tangent.h"

namespace patchwork {
namespace {

// Delta^j P_i = sum_l (-1)^(j-l) C(j,l) P_{i+l}.
template <int Dim>
Point<Dim> forward_difference(const std::vector<Point<Dim>>& P, int i, int j) {
  Point<Dim> sum = Point<Dim>::Zero();
  for (int l = 0; l <= j; ++l) sum += (((j - l) % 2) ? -1.0 : 1.0) * binomial(j, l) * P[i + l];
  return sum;
}

// C^(j) at the end (at_end) or the start of the curve, from the control points.
template <int Dim>
Point<Dim> end_derivative(const BezierCurve<Dim>& curve, int j, bool at_end) {
  const int n = curve.degree();
  if (j > n) return Point<Dim>::Zero();
  const double factor = falling_factorial(n, j) / std::pow(curve.b() - curve.a(), j);
  return factor * forward_difference(curve.control_points(), at_end ? n - j : 0, j);
}

template <int Dim>
double largest_control_point_norm(const BezierCurve<Dim>& curve) {
  double result = 0.0;
  for (const auto& p : curve.control_points()) result = std::max(result, p.norm());
  return result;
}

}  // namespace

template <int Dim>
Continuity continuity(const BezierCurve<Dim>& first, const BezierCurve<Dim>& second, int max_order,
                      double relative_tolerance) {
  if (max_order < 0) throw InvalidInput(detail::message("continuity: max_order ", max_order, " is negative"));
  if (!std::isfinite(relative_tolerance) || relative_tolerance < 0.0) {
    throw InvalidInput(detail::message("continuity: relative_tolerance ", relative_tolerance, " is not >= 0"));
  }
  // Each curve's rounding scale uses its own control points: a shared magnitude would let a large
  // second curve (a C^k continuation onto a much longer interval) inflate the tolerance of the
  // first curve's derivatives, whose 1/h1^j factor is then applied to the wrong size, and report
  // C^(k+1) for a generic join.
  const double magnitude1 = largest_control_point_norm(first);
  const double magnitude2 = largest_control_point_norm(second);
  const int n = first.degree();
  const int m = second.degree();
  const double h1 = first.b() - first.a();
  const double h2 = second.b() - second.a();
  const auto tolerance = [&](int j) {
    return relative_tolerance * std::max(detail::derivative_scale(n, j, h1, magnitude1),
                                         detail::derivative_scale(m, j, h2, magnitude2));
  };

  Continuity result{-1, false, (first.control_points().back() - second.control_points().front()).norm()};
  for (int j = 0; j <= max_order; ++j) {
    const Point<Dim> difference = end_derivative(first, j, true) - end_derivative(second, j, false);
    if (difference.norm() > tolerance(j)) break;
    result.ck = j;
  }
  if (result.ck >= 0) {
    // G^1: the limit unit tangents agree. Their rounding is that of C' relative to its length;
    // where C' vanishes on a side (a limit tangent from a higher order) a fixed 1e-9 is used.
    try {
      const Point<Dim> t1 = tangent(first, first.b());
      const Point<Dim> t2 = tangent(second, second.a());
      const double length = std::min(end_derivative(first, 1, true).norm(), end_derivative(second, 1, false).norm());
      const double angle_tolerance = length > tolerance(1) ? std::max(2.0 * tolerance(1) / length, 1e-15) : 1e-9;
      result.g1 = (t1 - t2).norm() <= angle_tolerance;
    } catch (const NumericalError&) {
      result.g1 = false;  // a point curve has no tangent
    }
  }
  return result;
}

template <int Dim>
std::vector<Point<Dim>> continue_ck(const BezierCurve<Dim>& curve, int k, int m, double length) {
  if (k < 0 || k > m) throw InvalidInput(detail::message("continue_ck: order k = ", k, " not in [0, m = ", m, "]"));
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw InvalidInput(detail::message("continue_ck: interval length ", length, " is not positive"));
  }
  std::vector<Point<Dim>> Q(static_cast<std::size_t>(k) + 1);
  for (int j = 0; j <= k; ++j) {
    // Delta^j Q_0 = target, and Delta^j Q_0 = Q_j + sum_{l<j} (-1)^(j-l) C(j,l) Q_l.
    const Point<Dim> target = std::pow(length, j) / falling_factorial(m, j) * end_derivative(curve, j, true);
    Point<Dim> q = target;
    for (int l = 0; l < j; ++l) q -= (((j - l) % 2) ? -1.0 : 1.0) * binomial(j, l) * Q[l];
    Q[j] = q;
  }
  return Q;
}

#define PATCHWORK_INSTANTIATE(D)                                                                 \
  template Continuity continuity(const BezierCurve<D>&, const BezierCurve<D>&, int, double);     \
  template std::vector<Point<D>> continue_ck(const BezierCurve<D>&, int, int, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
