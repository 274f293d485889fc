// Derivatives of Bezier curves against an exact rational reference: the k-th derivative is the
// k-fold hodograph (seed Satz 21), n (n-1) ... (n-k+1) / (b-a)^k sum_i Delta^k P_i B_i^(n-k)(s),
// computed in mpq_class and evaluated exactly at the (exact) local parameter s.

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "tests/curves/exact_reference.h"

namespace patchwork {
namespace {

// Intervals [a, a + h] with h a power of two, and local parameters s with at most 40 bits: then
// t = a + h s and s = (t - a) / h are exact, 1/h^k is exact, and the reference sees the same s.
const std::vector<std::pair<double, double>> kIntervals = {{0.0, 1.0}, {-2.0, 2.0}, {1.0, 1.5}};

rc::Gen<double> local_parameter() {
  return rc::gen::oneOf(rc::gen::element(0.0, 0.5, 1.0),
                        rc::gen::map(rc::gen::inRange<std::int64_t>(0, (std::int64_t{1} << 40) + 1),
                                     [](std::int64_t k) { return std::ldexp(static_cast<double>(k), -40); }));
}

// A coordinate m 2^(e-30) with m a random integer in [-2^30, 2^30] (31 significant bits) and
// e in [-4, 4]: varied magnitudes and signs.
rc::Gen<double> coordinate() {
  return rc::gen::map(
      rc::gen::pair(rc::gen::inRange<std::int64_t>(-(std::int64_t{1} << 30), (std::int64_t{1} << 30) + 1),
                    rc::gen::inRange(-4, 5)),
      [](const std::pair<std::int64_t, int>& v) { return std::ldexp(static_cast<double>(v.first), v.second - 30); });
}

// n (n-1) ... (n-k+1), exactly.
mpz_class falling_factorial(int n, int k) {
  mpz_class result = 1;
  for (int j = 0; j < k; ++j) result *= n - j;
  return result;
}

// Exact d^k/dt^k of coordinate `c` of the curve at the local parameter s.
template <int Dim>
mpq_class exact_derivative(const BezierCurve<Dim>& curve, int c, double s, int k) {
  std::vector<mpq_class> q;
  for (const Point<Dim>& p : curve.control_points()) q.emplace_back(p[c]);
  if (k > curve.degree()) return 0;
  for (int j = 0; j < k; ++j) q = exact::derivative_coefficients(q);
  mpq_class h_power = 1;
  for (int j = 0; j < k; ++j) h_power *= mpq_class(curve.b() - curve.a());
  return exact::evaluate(q, mpq_class(s)) / h_power;
}

// Rounding-error bound for `derivatives` (s has at most 40 bits, so 1 - s is exact and each
// de Casteljau level rounds a product and a sum): de Casteljau down to degree k
// (gamma_{2(n-k)}), j forward differences (each at most doubles the magnitude; gamma_j), de
// Casteljau on them (gamma_{2(k-j)}), the factor n!/(n-k)!/h^k (gamma_{k+1}: the falling
// factorial exceeds 2^53 for large n): |error| <= n!/(n-k)! / h^k 2^k max_i |P_i| gamma_{2n+k+1}
// to first order; gamma_{2n+2k+2} leaves room.
mpq_class derivative_tolerance(int n, int k, double h, double max_coordinate) {
  if (k > n) return 0;
  mpq_class scale = mpq_class(falling_factorial(n, k)) * mpq_class(max_coordinate);
  for (int j = 0; j < k; ++j) scale *= 2 / mpq_class(h);
  return exact::gamma(2 * n + 2 * k + 2) * scale;
}

template <int Dim>
void check_all_orders(const BezierCurve<Dim>& curve, double s) {
  const int n = curve.degree();
  const double h = curve.b() - curve.a();
  const double t = curve.a() + h * s;
  RC_ASSERT(curve.local_parameter(t) == s);
  const int top = *rc::gen::inRange(0, n + 3);  // orders beyond n must give exactly zero
  const std::vector<Point<Dim>> all = derivatives(curve, t, top);
  RC_ASSERT(all.size() == static_cast<std::size_t>(top) + 1);
  for (int c = 0; c < Dim; ++c) {
    double max_coordinate = 0.0;
    for (const Point<Dim>& p : curve.control_points()) max_coordinate = std::max(max_coordinate, std::abs(p[c]));
    for (int k = 0; k <= top; ++k) {
      const mpq_class expected = exact_derivative(curve, c, s, k);
      const mpq_class error = abs(mpq_class(all[static_cast<std::size_t>(k)][c]) - expected);
      RC_ASSERT(error <= derivative_tolerance(n, k, h, max_coordinate));
      // The single-order entry point computes the same quantity.
      const mpq_class single_error = abs(mpq_class(derivative(curve, t, k)[c]) - expected);
      RC_ASSERT(single_error <= derivative_tolerance(n, k, h, max_coordinate));
    }
  }
}

RC_GTEST_PROP(BezierDerivative, MatchesExactHodographInOneDimension, ()) {
  const int n = *rc::gen::inRange(0, 41);
  const auto [a, b] = *rc::gen::elementOf(kIntervals);
  std::vector<Point<1>> points(static_cast<std::size_t>(n) + 1);
  for (Point<1>& p : points) p = Point<1>(*coordinate());
  check_all_orders(BezierCurve<1>(points, a, b), *local_parameter());
}

RC_GTEST_PROP(BezierDerivative, MatchesExactHodographInThreeDimensions, ()) {
  const int n = *rc::gen::inRange(0, 25);
  const auto [a, b] = *rc::gen::elementOf(kIntervals);
  std::vector<Point<3>> points(static_cast<std::size_t>(n) + 1);
  for (Point<3>& p : points) p = Point<3>(*coordinate(), *coordinate(), *coordinate());
  check_all_orders(BezierCurve<3>(points, a, b), *local_parameter());
}

RC_GTEST_PROP(BezierDerivative, HodographControlPointsAreExactUpToTwoRoundings, ()) {
  // derivative_curve: n/(b-a) is exact for these intervals; the difference and the product
  // round once each, so every coordinate is within gamma_2 |exact| of n (P_{i+1} - P_i)/(b-a).
  const int n = *rc::gen::inRange(0, 41);
  const auto [a, b] = *rc::gen::elementOf(kIntervals);
  std::vector<Point<3>> points(static_cast<std::size_t>(n) + 1);
  for (Point<3>& p : points) p = Point<3>(*coordinate(), *coordinate(), *coordinate());
  const BezierCurve<3> curve(points, a, b);
  const BezierCurve<3> hodograph = derivative_curve(curve);
  RC_ASSERT(hodograph.a() == a);
  RC_ASSERT(hodograph.b() == b);
  RC_ASSERT(hodograph.degree() == std::max(n - 1, 0));
  for (int c = 0; c < 3; ++c) {
    std::vector<mpq_class> q;
    for (const Point<3>& p : points) q.emplace_back(p[c]);
    const std::vector<mpq_class> d = exact::derivative_coefficients(q);
    for (std::size_t i = 0; i < d.size(); ++i) {
      const mpq_class expected = d[i] / mpq_class(b - a);
      RC_ASSERT(abs(mpq_class(hodograph.control_points()[i][c]) - expected) <= exact::gamma(2) * abs(expected));
    }
  }
}

TEST(BezierDerivative, CubicClosedForm) {
  // C(t) = t^3 on [0, 1] has control points 0, 0, 0, 1; C' = 3t^2, C'' = 6t, C''' = 6, C'''' = 0.
  // At t = 0.5 every value is exact in double.
  const BezierCurve<1> cubic({Point<1>(0.0), Point<1>(0.0), Point<1>(0.0), Point<1>(1.0)});
  const std::vector<Point<1>> d = derivatives(cubic, 0.5, 4);
  EXPECT_EQ(d[0][0], 0.125);
  EXPECT_EQ(d[1][0], 0.75);
  EXPECT_EQ(d[2][0], 3.0);
  EXPECT_EQ(d[3][0], 6.0);
  EXPECT_EQ(d[4][0], 0.0);
  // On [0, 2] the same points give C(t) = (t/2)^3: C'(1) = 3/8, C''(1) = 3/4, C'''(1) = 3/4.
  const BezierCurve<1> stretched = with_interval(cubic, 0.0, 2.0);
  EXPECT_EQ(derivative(stretched, 1.0, 1)[0], 0.375);
  EXPECT_EQ(derivative(stretched, 1.0, 2)[0], 0.75);
  EXPECT_EQ(derivative(stretched, 1.0, 3)[0], 0.75);
}

TEST(BezierDerivative, RejectsBadInput) {
  const BezierCurve<1> curve({Point<1>(0.0), Point<1>(1.0)});
  EXPECT_THROW(derivative(curve, 0.5, -1), InvalidInput);
  EXPECT_THROW(derivatives(curve, 0.5, -1), InvalidInput);
  EXPECT_THROW(derivative(curve, std::nan(""), 1), InvalidInput);
}

}  // namespace
}  // namespace patchwork
