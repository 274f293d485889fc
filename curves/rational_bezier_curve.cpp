#include "curves/rational_bezier_curve.h"

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "curves/curve_checks.h"
#include "curves/degree.h"
#include "curves/homogeneous.h"
#include "curves/limit_tangent.h"
#include "curves/subdivision.h"

namespace patchwork {
namespace {

template <int Dim>
BezierCurve<Dim + 1> homogenize(const char* function, const std::vector<Point<Dim>>& points,
                                const std::vector<double>& weights, double a, double b) {
  return BezierCurve<Dim + 1>(detail::homogeneous_points<Dim>(function, points, weights), a, b);
}

template <int Dim>
const BezierCurve<Dim + 1>& check_weights(const BezierCurve<Dim + 1>& homogeneous) {
  detail::check_homogeneous_weights<Dim>("RationalBezierCurve", homogeneous.control_points());
  return homogeneous;
}

}  // namespace

template <int Dim>
RationalBezierCurve<Dim>::RationalBezierCurve(std::vector<Point> control_points,
                                              std::vector<double> weights, double a, double b)
    : homogeneous_(homogenize<Dim>("RationalBezierCurve", control_points, weights, a, b)) {}

template <int Dim>
RationalBezierCurve<Dim>::RationalBezierCurve(Homogeneous homogeneous)
    : homogeneous_(check_weights<Dim>(homogeneous)) {}

template <int Dim>
typename RationalBezierCurve<Dim>::Point RationalBezierCurve<Dim>::control_point(int i) const {
  return detail::projected<Dim>(homogeneous_.control_points().at(static_cast<std::size_t>(i)));
}

template <int Dim>
typename RationalBezierCurve<Dim>::Point RationalBezierCurve<Dim>::evaluate(double t) const {
  return detail::projected<Dim>(homogeneous_.evaluate(t));
}

// C, C', ..., C^(k) at t by Leibniz's rule on C = H / w.
template <int Dim>
static std::vector<Point<Dim>> rational_derivatives(const RationalBezierCurve<Dim>& curve, double t, int k) {
  if (k < 0) throw InvalidInput(detail::message("derivative: order ", k, " is negative"));
  return detail::quotient_derivatives<Dim>(derivatives(curve.homogeneous(), t, k));
}

template <int Dim>
Point<Dim> derivative(const RationalBezierCurve<Dim>& curve, double t, int k) {
  return rational_derivatives(curve, t, k).back();
}

template <int Dim>
Point<Dim> tangent(const RationalBezierCurve<Dim>& curve, double t) {
  const int n = curve.degree();
  double magnitude = 0.0;
  for (int i = 0; i <= n; ++i) magnitude = std::max(magnitude, curve.control_point(i).norm());
  return detail::limit_tangent<Dim>(rational_derivatives(curve, t, std::max(n, 1)), n, curve.b() - curve.a(),
                                    magnitude, t >= curve.b(), t);
}

template <int Dim>
double curvature(const RationalBezierCurve<Dim>& curve, double t) {
  const std::vector<Point<Dim>> d = rational_derivatives(curve, t, 2);
  const double speed2 = d[1].squaredNorm();
  if (speed2 == 0.0) throw NumericalError(detail::message("curvature: C'(t) = 0 at t = ", t));
  double cross2;
  if constexpr (Dim == 2) {
    const double c = d[1][0] * d[2][1] - d[1][1] * d[2][0];
    cross2 = c * c;
  } else if constexpr (Dim == 3) {
    cross2 = d[1].cross(d[2]).squaredNorm();
  } else {
    cross2 = std::max(0.0, speed2 * d[2].squaredNorm() - d[1].dot(d[2]) * d[1].dot(d[2]));
  }
  return std::sqrt(cross2) / (speed2 * std::sqrt(speed2));
}

template <int Dim>
std::pair<RationalBezierCurve<Dim>, RationalBezierCurve<Dim>> split(const RationalBezierCurve<Dim>& curve,
                                                                    double t) {
  auto [left, right] = split(curve.homogeneous(), t);
  return {RationalBezierCurve<Dim>(std::move(left)), RationalBezierCurve<Dim>(std::move(right))};
}

template <int Dim>
RationalBezierCurve<Dim> elevate_degree(const RationalBezierCurve<Dim>& curve, int times) {
  return RationalBezierCurve<Dim>(elevate_degree(curve.homogeneous(), times));
}

template <int Dim>
std::vector<RationalBezierCurve<Dim>> circle_arc(const Point<Dim>& center, const Point<Dim>& x_axis,
                                                 const Point<Dim>& y_axis, double radius,
                                                 double start, double end) {
  if (!center.allFinite() || !std::isfinite(radius) || !(radius > 0.0)) {
    throw InvalidInput(detail::message("circle_arc: radius ", radius, " is not positive, or the centre is not finite"));
  }
  const double sweep = end - start;
  if (!std::isfinite(sweep) || sweep == 0.0 || std::abs(sweep) > 2.0 * std::numbers::pi * (1.0 + 1e-15)) {
    throw InvalidInput(detail::message("circle_arc: sweep ", sweep, " is zero, not finite or beyond 2 pi"));
  }
  if (!x_axis.allFinite() || !y_axis.allFinite() || std::abs(x_axis.norm() - 1.0) > 1e-12 ||
      std::abs(y_axis.norm() - 1.0) > 1e-12 || std::abs(x_axis.dot(y_axis)) > 1e-12) {
    throw InvalidInput("circle_arc: the axes are not orthonormal");
  }
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (0.5 * std::numbers::pi) - 1e-12)));
  const double phi = sweep / pieces;
  const double w = std::cos(0.5 * phi);
  const auto on_circle = [&](double angle, double r) {
    return Point<Dim>(center + r * (std::cos(angle) * x_axis + std::sin(angle) * y_axis));
  };
  std::vector<RationalBezierCurve<Dim>> arcs;
  arcs.reserve(static_cast<std::size_t>(pieces));
  for (int piece = 0; piece < pieces; ++piece) {
    const double a0 = start + piece * phi;
    const double a1 = (piece + 1 == pieces) ? end : start + (piece + 1) * phi;
    // The middle control point is where the end tangents meet: at radius r / cos(phi/2).
    arcs.emplace_back(std::vector<Point<Dim>>{on_circle(a0, radius), on_circle(0.5 * (a0 + a1), radius / w),
                                              on_circle(a1, radius)},
                      std::vector<double>{1.0, w, 1.0});
  }
  return arcs;
}

std::vector<RationalBezierCurve<2>> circle_arc(const Vec2& center, double radius, double start, double end) {
  return circle_arc<2>(center, Vec2::UnitX(), Vec2::UnitY(), radius, start, end);
}

#define PATCHWORK_INSTANTIATE(D)                                                                        \
  template class RationalBezierCurve<D>;                                                                \
  template Point<D> derivative(const RationalBezierCurve<D>&, double, int);                             \
  template Point<D> tangent(const RationalBezierCurve<D>&, double);                                     \
  template double curvature(const RationalBezierCurve<D>&, double);                                     \
  template std::pair<RationalBezierCurve<D>, RationalBezierCurve<D>> split(const RationalBezierCurve<D>&, \
                                                                           double);                     \
  template RationalBezierCurve<D> elevate_degree(const RationalBezierCurve<D>&, int);                   \
  template std::vector<RationalBezierCurve<D>> circle_arc(const Point<D>&, const Point<D>&,             \
                                                          const Point<D>&, double, double, double);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
