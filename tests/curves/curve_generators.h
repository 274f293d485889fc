#pragma once
// RapidCheck generators shared by the curve tests: coordinates, points, parameter intervals,
// parameters inside an interval, and Bezier curves of a random degree.
//
//   lo ----- a ======= t ======= b ----- hi      interval(lo, hi) gives a < b inside [lo, hi],
//                                                parameter(a, b) a t in [a, b] (a and b included)
//
// Values are drawn from a grid of 2^30 steps across their range, independent of RapidCheck's
// size (so the first cases already spread over the whole range), and shrink towards the lower
// end. Degrees do grow with the size: early cases have low degree, later ones up to the maximum.
// Curves print their degree, interval and control points when a property fails.

#include <rapidcheck.h>

#include <algorithm>
#include <cstdint>
#include <ostream>
#include <utility>
#include <vector>

#include "curves/bezier_curve.h"

namespace patchwork {

/// Prints a curve in a RapidCheck counterexample: "degree 2 on [0, 1]: (x y) (x y) (x y)".
template <int Dim>
void showValue(const BezierCurve<Dim>& curve, std::ostream& os) {
  const auto precision = os.precision(17);
  os << "degree " << curve.degree() << " on [" << curve.a() << ", " << curve.b() << "]:";
  for (const auto& p : curve.control_points()) os << " (" << p.transpose() << ")";
  os.precision(precision);
}

namespace curve_gen {

/// A parameter interval a < b.
struct Interval {
  double a;
  double b;
};

/// Prints an interval in a RapidCheck counterexample.
inline void showValue(const Interval& interval, std::ostream& os) {
  const auto precision = os.precision(17);
  os << "[" << interval.a << ", " << interval.b << "]";
  os.precision(precision);
}

/// Number of grid steps across a range.
inline constexpr std::int64_t kSteps = std::int64_t{1} << 30;

/// lo + (hi - lo) k / 2^30, clamped into [lo, hi] against rounding.
inline double grid_value(double lo, double hi, std::int64_t k) {
  const double x = lo + (hi - lo) * (static_cast<double>(k) / static_cast<double>(kSteps));
  return std::clamp(x, lo, hi);
}

/// A number in [lo, hi] (both ends possible).
inline rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<std::int64_t>(0, kSteps + 1)),
                      [lo, hi](std::int64_t k) { return grid_value(lo, hi, k); });
}

/// A point with every coordinate in [lo, hi].
template <int Dim>
rc::Gen<Point<Dim>> point(double lo = -10.0, double hi = 10.0) {
  return rc::gen::map(rc::gen::container<std::vector<double>>(Dim, coordinate(lo, hi)),
                      [](const std::vector<double>& x) {
                        Point<Dim> p;
                        for (int c = 0; c < Dim; ++c) p[c] = x[static_cast<std::size_t>(c)];
                        return p;
                      });
}

/// A point on the unit sphere in R^Dim (a direction), from a non-degenerate random vector.
template <int Dim>
rc::Gen<Point<Dim>> direction() {
  return rc::gen::map(rc::gen::suchThat(point<Dim>(-1.0, 1.0), [](const Point<Dim>& p) { return p.norm() > 1e-3; }),
                      [](const Point<Dim>& p) { return Point<Dim>(p / p.norm()); });
}

/// An interval lo <= a < b <= hi whose length is at least (hi - lo) / 1000.
inline rc::Gen<Interval> interval(double lo = -5.0, double hi = 5.0) {
  constexpr std::int64_t kMinLength = kSteps / 1000;
  const auto starts = rc::gen::resize(100, rc::gen::inRange<std::int64_t>(0, kSteps - kMinLength + 1));
  return rc::gen::mapcat(starts, [lo, hi](std::int64_t k0) {
    const auto lengths = rc::gen::resize(100, rc::gen::inRange<std::int64_t>(kMinLength, kSteps - k0 + 1));
    return rc::gen::map(lengths, [lo, hi, k0](std::int64_t length) {
      return Interval{grid_value(lo, hi, k0), grid_value(lo, hi, k0 + length)};
    });
  });
}

/// A parameter t in [a, b]: a or b exactly in one case of ten each, otherwise spread over [a, b].
inline rc::Gen<double> parameter(double a, double b) {
  return rc::gen::weightedOneOf<double>({{1, rc::gen::just(a)}, {1, rc::gen::just(b)}, {8, coordinate(a, b)}});
}

/// A parameter strictly inside (a, b) (for splitting); needs an interval wider than a few ulps.
inline rc::Gen<double> interior_parameter(double a, double b) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<std::int64_t>(1, kSteps)), [a, b](std::int64_t k) {
    const double t = grid_value(a, b, k);
    return (a < t && t < b) ? t : 0.5 * (a + b);
  });
}

/// A degree in [min_degree, max_degree], growing with RapidCheck's size.
inline rc::Gen<int> degree(int min_degree, int max_degree) { return rc::gen::inRange(min_degree, max_degree + 1); }

/// Control points P_0..P_n for a degree n, every coordinate in [lo, hi].
template <int Dim>
rc::Gen<std::vector<Point<Dim>>> control_points(int n, double lo = -10.0, double hi = 10.0) {
  return rc::gen::container<std::vector<Point<Dim>>>(static_cast<std::size_t>(n) + 1, point<Dim>(lo, hi));
}

/// A Bezier curve on [0, 1] of degree min_degree..max_degree, coordinates in [lo, hi].
template <int Dim>
rc::Gen<BezierCurve<Dim>> bezier_curve(int min_degree = 0, int max_degree = 12, double lo = -10.0, double hi = 10.0) {
  return rc::gen::mapcat(degree(min_degree, max_degree), [lo, hi](int n) {
    return rc::gen::map(control_points<Dim>(n, lo, hi),
                        [](std::vector<Point<Dim>> P) { return BezierCurve<Dim>(std::move(P)); });
  });
}

/// A Bezier curve as bezier_curve, on a random interval [a, b] inside [-5, 5].
template <int Dim>
rc::Gen<BezierCurve<Dim>> bezier_curve_on_interval(int min_degree = 0, int max_degree = 12, double lo = -10.0,
                                                   double hi = 10.0) {
  return rc::gen::apply(
      [](const BezierCurve<Dim>& curve, const Interval& ab) { return with_interval(curve, ab.a, ab.b); },
      bezier_curve<Dim>(min_degree, max_degree, lo, hi), interval());
}

}  // namespace curve_gen
}  // namespace patchwork
