#include "curves/bspline_curve.h"

#include <algorithm>
#include <cmath>

#include "core/assert.h"
#include "core/errors.h"
#include "curves/bspline_basis.h"
#include "curves/bspline_conversion.h"
#include "curves/curve_checks.h"
#include "curves/dimensions.h"
#include "curves/homogeneous.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {
namespace {

template <int Dim>
std::vector<Point<Dim>> checked_points(const char* function, const KnotVector& knots, std::vector<Point<Dim>> points) {
  detail::check_control_points(function, points);
  if (static_cast<int>(points.size()) != knots.control_point_count()) {
    throw InvalidInput(detail::message(function, ": ", points.size(), " control points but ", knots.size(),
                                       " knots of degree ", knots.degree(), " need ", knots.control_point_count(),
                                       " (knots = control points + p + 1)"));
  }
  return points;
}

// de Boor's algorithm on span s with the argument argument(r) at level r = 1..p: the blossom
// f(t_1, ..., t_p) of the piece on [u_s, u_{s+1}] (A3.1 generalised; Ramshaw's polar form).
// The denominators u_{s+j+1-r} - u_{s-p+j} span [u_s, u_{s+1}], so they are positive.
template <int Dim, class Argument>
Point<Dim> de_boor(const KnotVector& knots, const std::vector<Point<Dim>>& P, int s, Argument argument) {
  const int p = knots.degree();
  std::vector<Point<Dim>> d(P.begin() + (s - p), P.begin() + (s + 1));
  for (int r = 1; r <= p; ++r) {
    const double t = argument(r);
    for (int j = p; j >= r; --j) {
      const double lo = knots[s - p + j];
      const double alpha = (t - lo) / (knots[s + j + 1 - r] - lo);
      d[static_cast<std::size_t>(j)] =
          (1.0 - alpha) * d[static_cast<std::size_t>(j) - 1] + alpha * d[static_cast<std::size_t>(j)];
    }
  }
  return d[static_cast<std::size_t>(p)];
}

template <int Dim>
std::vector<Point<Dim>> wrapped(int degree, const std::vector<Point<Dim>>& polygon) {
  std::vector<Point<Dim>> points(polygon);
  for (int i = 0; i < degree; ++i) points.push_back(polygon[static_cast<std::size_t>(i) % polygon.size()]);
  return points;
}

}  // namespace

template <int Dim>
BSplineCurve<Dim>::BSplineCurve(KnotVector knots, std::vector<Point> control_points)
    : knots_(std::move(knots)), points_(checked_points<Dim>("BSplineCurve", knots_, std::move(control_points))) {}

template <int Dim>
typename BSplineCurve<Dim>::Point BSplineCurve<Dim>::evaluate(double u) const {
  const int s = knots_.span(u);
  return de_boor<Dim>(knots_, points_, s, [u](int) { return u; });
}

template <int Dim>
Point<Dim> blossom(const BSplineCurve<Dim>& curve, int span, std::span<const double> arguments) {
  const KnotVector& knots = curve.knot_vector();
  const int p = curve.degree();
  if (span < p || span >= knots.control_point_count() || !(knots[span] < knots[span + 1])) {
    throw InvalidInput(detail::message("blossom: ", span, " is not a non-empty span in [", p, ", ",
                                       knots.control_point_count() - 1, "]"));
  }
  if (static_cast<int>(arguments.size()) != p) {
    throw InvalidInput(detail::message("blossom: ", arguments.size(), " arguments for degree ", p));
  }
  for (double t : arguments) detail::check_parameter("blossom", t);
  return de_boor<Dim>(knots, curve.control_points(), span,
                      [arguments](int r) { return arguments[static_cast<std::size_t>(r) - 1]; });
}

template <int Dim>
std::vector<Point<Dim>> derivatives(const BSplineCurve<Dim>& curve, double u, int k) {
  if (k < 0) throw InvalidInput(detail::message("derivative: order ", k, " is negative"));
  const KnotVector& knots = curve.knot_vector();
  const int p = curve.degree();
  const int s = knots.span(u);
  const Eigen::MatrixXd N = basis_function_derivatives(knots, u, k);
  std::vector<Point<Dim>> d(static_cast<std::size_t>(k) + 1, Point<Dim>::Zero());
  for (int order = 0; order <= std::min(k, p); ++order) {
    for (int r = 0; r <= p; ++r) {
      d[static_cast<std::size_t>(order)] += N(order, r) * curve.control_points()[static_cast<std::size_t>(s - p + r)];
    }
  }
  return d;
}

template <int Dim>
Point<Dim> derivative(const BSplineCurve<Dim>& curve, double u, int k) {
  return derivatives(curve, u, k).back();
}

template <int Dim>
BSplineCurve<Dim> derivative_curve(const BSplineCurve<Dim>& curve) {
  const KnotVector& knots = curve.knot_vector();
  const int p = curve.degree();
  const auto& P = curve.control_points();
  if (p == 0) return BSplineCurve<Dim>(knots, std::vector<Point<Dim>>(P.size(), Point<Dim>::Zero()));
  const std::vector<double> breakpoints = knots.breakpoints();
  for (std::size_t i = 1; i + 1 < breakpoints.size(); ++i) {
    if (knots.multiplicity(breakpoints[i]) == p) {
      throw InvalidInput(detail::message("derivative_curve: knot ", breakpoints[i], " has multiplicity p = ", p,
                                         ", where the derivative is discontinuous"));
    }
  }
  std::vector<Point<Dim>> Q(P.size() - 1);
  for (std::size_t i = 0; i + 1 < P.size(); ++i) {
    const int j = static_cast<int>(i);
    const double gap = knots[j + p + 1] - knots[j + 1];
    // A zero gap means N_{i+1,p-1} = 0: the point does not matter, 0 keeps it finite.
    Q[i] = gap > 0.0 ? Point<Dim>(p * (P[i + 1] - P[i]) / gap) : Point<Dim>::Zero();
  }
  std::vector<double> inner(knots.knots().begin() + 1, knots.knots().end() - 1);
  return BSplineCurve<Dim>(KnotVector(p - 1, std::move(inner)), std::move(Q));
}

template <int Dim>
Point<Dim> tangent(const BSplineCurve<Dim>& curve, double u) {
  return tangent(bezier_piece(curve, curve.knot_vector().span(u)), u);
}

template <int Dim>
NurbsCurve<Dim>::NurbsCurve(KnotVector knots, std::vector<Point> control_points, std::vector<double> weights)
    : homogeneous_(std::move(knots), detail::homogeneous_points<Dim>("NurbsCurve", control_points, weights)) {}

template <int Dim>
NurbsCurve<Dim>::NurbsCurve(Homogeneous homogeneous) : homogeneous_(std::move(homogeneous)) {
  detail::check_homogeneous_weights<Dim>("NurbsCurve", homogeneous_.control_points());
}

template <int Dim>
typename NurbsCurve<Dim>::Point NurbsCurve<Dim>::control_point(int i) const {
  return detail::projected<Dim>(homogeneous_.control_points().at(static_cast<std::size_t>(i)));
}

template <int Dim>
typename NurbsCurve<Dim>::Point NurbsCurve<Dim>::evaluate(double u) const {
  return detail::projected<Dim>(homogeneous_.evaluate(u));
}

template <int Dim>
std::vector<Point<Dim>> derivatives(const NurbsCurve<Dim>& curve, double u, int k) {
  return detail::quotient_derivatives<Dim>(derivatives(curve.homogeneous(), u, k));
}

template <int Dim>
Point<Dim> derivative(const NurbsCurve<Dim>& curve, double u, int k) {
  return derivatives(curve, u, k).back();
}

template <int Dim>
Point<Dim> tangent(const NurbsCurve<Dim>& curve, double u) {
  return tangent(bezier_piece(curve, curve.knot_vector().span(u)), u);
}

template <int Dim>
BSplineCurve<Dim> periodic_curve(int degree, const std::vector<Point<Dim>>& polygon, double a, double b) {
  KnotVector knots = periodic_knots(degree, static_cast<int>(polygon.size()), a, b);
  return BSplineCurve<Dim>(std::move(knots), wrapped<Dim>(degree, polygon));
}

template <int Dim>
NurbsCurve<Dim> periodic_curve(int degree, const std::vector<Point<Dim>>& polygon, const std::vector<double>& weights,
                               double a, double b) {
  if (weights.size() != polygon.size()) {
    throw InvalidInput(detail::message("periodic_curve: ", polygon.size(), " points but ", weights.size(), " weights"));
  }
  KnotVector knots = periodic_knots(degree, static_cast<int>(polygon.size()), a, b);
  std::vector<double> wrapped_weights(weights);
  for (int i = 0; i < degree; ++i) wrapped_weights.push_back(weights[static_cast<std::size_t>(i) % weights.size()]);
  return NurbsCurve<Dim>(std::move(knots), wrapped<Dim>(degree, polygon), std::move(wrapped_weights));
}

#define PATCHWORK_INSTANTIATE(D)                                                   \
  template class BSplineCurve<D>;                                                  \
  template Point<D> blossom(const BSplineCurve<D>&, int, std::span<const double>); \
  template Point<D> derivative(const BSplineCurve<D>&, double, int);               \
  template std::vector<Point<D>> derivatives(const BSplineCurve<D>&, double, int); \
  template BSplineCurve<D> derivative_curve(const BSplineCurve<D>&);               \
  template Point<D> tangent(const BSplineCurve<D>&, double);                       \
  template BSplineCurve<D> periodic_curve(int, const std::vector<Point<D>>&, double, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

#define PATCHWORK_INSTANTIATE(D)                                                 \
  template class NurbsCurve<D>;                                                  \
  template Point<D> derivative(const NurbsCurve<D>&, double, int);               \
  template std::vector<Point<D>> derivatives(const NurbsCurve<D>&, double, int); \
  template Point<D> tangent(const NurbsCurve<D>&, double);                       \
  template NurbsCurve<D> periodic_curve(int, const std::vector<Point<D>>&, const std::vector<double>&, double, double);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
