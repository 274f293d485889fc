#pragma once
// RapidCheck generators for the B-spline tests: knot vectors of degree 0..5 that are clamped,
// unclamped (distinct outer knots) or clamped at one end only, with interior knots of random
// multiplicity 1..p, on dyadic knot values (sums of gaps k/8, exact in double); control points
// and positive weights on top.
//
//   clamped     a a a | u_1 u_1 u_2 ... | b b b          (p + 1 equal end knots)
//   unclamped   . . . a | u_1 ... | b . . .              (p distinct knots beyond each end)

#include <rapidcheck.h>

#include <ostream>
#include <vector>

#include "curves/bspline_curve.h"
#include "tests/curves/curve_generators.h"

namespace patchwork {

/// Prints a knot vector in a RapidCheck counterexample: "degree 2: {0 0 0 0.5 1 1 1}".
inline void showValue(const KnotVector& knots, std::ostream& os) {
  const auto precision = os.precision(17);
  os << "degree " << knots.degree() << ": {";
  for (double u : knots.knots()) os << " " << u;
  os << " }";
  os.precision(precision);
}

/// Prints a B-spline curve in a RapidCheck counterexample.
template <int Dim>
void showValue(const BSplineCurve<Dim>& curve, std::ostream& os) {
  showValue(curve.knot_vector(), os);
  const auto precision = os.precision(17);
  for (const auto& p : curve.control_points()) os << " (" << p.transpose() << ")";
  os.precision(precision);
}

/// Prints a NURBS curve in a RapidCheck counterexample (homogeneous points).
template <int Dim>
void showValue(const NurbsCurve<Dim>& curve, std::ostream& os) {
  showValue(curve.homogeneous(), os);
}

namespace bspline_gen {

/// Which ends are clamped.
enum class Ends { clamped, unclamped, clamped_start };

/// A knot vector of degree min_degree..max_degree with min_groups..max_groups interior
/// breakpoints (none for degree 0), clamped at both ends or (unless clamped_only) not.
inline rc::Gen<KnotVector> knot_vector(int min_degree = 1, int max_degree = 5, int max_groups = 5, int min_groups = 0,
                                       bool clamped_only = false) {
  return rc::gen::exec([=] {
    const int p = *rc::gen::inRange(min_degree, max_degree + 1);
    const Ends ends =
        clamped_only ? Ends::clamped : *rc::gen::element(Ends::clamped, Ends::unclamped, Ends::clamped_start);
    const int groups = p == 0 ? 0 : *rc::gen::inRange(min_groups, max_groups + 1);
    double value = *rc::gen::inRange(-16, 17) / 8.0;
    const auto next = [&value] { return value += *rc::gen::inRange(1, 9) / 8.0; };
    std::vector<double> knots;
    if (ends == Ends::unclamped) {
      for (int i = 0; i < p; ++i) knots.push_back(next());
      knots.push_back(next());
    } else {
      knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, next());
    }
    for (int g = 0; g < groups; ++g) {
      const int multiplicity = *rc::gen::inRange(1, p + 1);
      knots.insert(knots.end(), static_cast<std::size_t>(multiplicity), next());
    }
    if (ends == Ends::clamped) {
      knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, next());
    } else {
      for (int i = 0; i <= p; ++i) knots.push_back(next());
    }
    return KnotVector(p, std::move(knots));
  });
}

/// A B-spline curve on a random knot vector, coordinates in [-10, 10].
template <int Dim>
rc::Gen<BSplineCurve<Dim>> bspline_curve(int min_degree = 1, int max_degree = 5, int max_groups = 5,
                                         int min_groups = 0) {
  return rc::gen::mapcat(knot_vector(min_degree, max_degree, max_groups, min_groups), [](const KnotVector& knots) {
    return rc::gen::map(curve_gen::control_points<Dim>(knots.control_point_count() - 1),
                        [knots](std::vector<Point<Dim>> P) { return BSplineCurve<Dim>(knots, std::move(P)); });
  });
}

/// A NURBS curve on a random knot vector, weights in [1/4, 4].
template <int Dim>
rc::Gen<NurbsCurve<Dim>> nurbs_curve(int min_degree = 1, int max_degree = 5, int max_groups = 5, int min_groups = 0) {
  return rc::gen::mapcat(
      bspline_curve<Dim>(min_degree, max_degree, max_groups, min_groups), [](const BSplineCurve<Dim>& curve) {
        const auto count = curve.control_points().size();
        return rc::gen::map(rc::gen::container<std::vector<double>>(count, curve_gen::coordinate(0.25, 4.0)),
                            [curve](std::vector<double> w) {
                              return NurbsCurve<Dim>(curve.knot_vector(), curve.control_points(), std::move(w));
                            });
      });
}

/// A parameter in the valid range [a, b] of a curve: a, b or an interior knot in one case of
/// four, otherwise spread over [a, b].
inline rc::Gen<double> parameter(const KnotVector& knots) {
  const std::vector<double> breakpoints = knots.breakpoints();
  return rc::gen::weightedOneOf<double>(
      {{1, rc::gen::elementOf(breakpoints)}, {3, curve_gen::coordinate(knots.a(), knots.b())}});
}

}  // namespace bspline_gen
}  // namespace patchwork
