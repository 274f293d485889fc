#include "curves/arc_length.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// Length of y = c x^2 from x = 0 to x = X: int sqrt(1 + 4 c^2 x^2) dx
//   = X/2 sqrt(1 + 4 c^2 X^2) + asinh(2 c X) / (4 c).
double parabola_length(double c, double X) {
  return 0.5 * X * std::sqrt(1.0 + 4.0 * c * c * X * X) + std::asinh(2.0 * c * X) / (4.0 * c);
}

// y = c x^2 for x in [0, X] as a quadratic with x linear in s: P = (0,0), (X/2, 0), (X, c X^2).
BezierCurve2 parabola(double c, double X) { return BezierCurve2({Vec2(0, 0), Vec2(0.5 * X, 0), Vec2(X, c * X * X)}); }

// The cuspidal cubic C(t) = (t^2, t^3) on [a, b] with a < 0 < b, control points from the blossoms
// (t1 t2 + t1 t3 + t2 t3)/3 and t1 t2 t3. |C'(t)| = |t| sqrt(4 + 9 t^2), whose antiderivative
// on t >= 0 is (4 + 9 t^2)^(3/2) / 27, so the length is that at |a| and at b, minus 2 * 8/27.
BezierCurve2 cusp_curve(double a, double b) {
  return BezierCurve2({Vec2(a * a, a * a * a), Vec2((a * a + 2 * a * b) / 3, a * a * b),
                       Vec2((2 * a * b + b * b) / 3, a * b * b), Vec2(b * b, b * b * b)},
                      a, b);
}

double cusp_length(double a, double b) {
  return (std::pow(4 + 9 * a * a, 1.5) - 8 + std::pow(4 + 9 * b * b, 1.5) - 8) / 27;
}

double max_norm(const BezierCurve2& curve) {
  double result = 0.0;
  for (const auto& p : curve.control_points()) result = std::max(result, p.norm());
  return result;
}

TEST(ArcLength, StraightLinesAreExact) {
  // Uniform and non-uniform speed along the line through (0,0) and (3,4): the speed is a
  // polynomial of degree <= 2, integrated exactly by the 10-point rule, so only rounding
  // remains: a sum of a few dozen terms of size <= 5, 64 eps * 5 bounds it.
  EXPECT_NEAR(arc_length(BezierCurve2({Vec2(0, 0), Vec2(3, 4)})).length, 5.0, 64 * eps * 5);
  // Positions 0, 0.5, 3, 5 along the unit direction (0.6, 0.8): increasing differences, monotone.
  const BezierCurve2 cubic({Vec2(0, 0), Vec2(0.3, 0.4), Vec2(1.8, 2.4), Vec2(3, 4)});
  EXPECT_NEAR(arc_length(cubic).length, 5.0, 64 * eps * 5);
  const BezierCurve3 line3({Vec3(1, 1, 1), Vec3(3, 4, 7)}, -2.0, 5.0);
  EXPECT_NEAR(arc_length(line3).length, 7.0, 64 * eps * 7);  // |(2, 3, 6)| = 7
  // A point has length 0, and so has an empty sub-range.
  EXPECT_EQ(arc_length(BezierCurve2({Vec2(2, 3)})).length, 0.0);
  EXPECT_EQ(arc_length(cubic, 0.5, 0.5, 1e-12).length, 0.0);
}

TEST(ArcLength, ParabolaMatchesClosedForm) {
  // y = x^2 on [0, 1]: (2 sqrt 5 + asinh 2) / 4.
  const double exact = (2.0 * std::sqrt(5.0) + std::asinh(2.0)) / 4.0;
  const ArcLength result = arc_length(parabola(1.0, 1.0), 1e-12);
  // Requested 1e-12, plus a few ulps for the closed form itself.
  EXPECT_NEAR(result.length, exact, 1e-12 + 8 * eps);
  EXPECT_LE(result.error_estimate, 1e-12);
  // A sub-range [t0, t1] is F(t1) - F(t0) with the antiderivative F (here x = t).
  const ArcLength piece = arc_length(parabola(1.0, 1.0), 0.2, 0.7, 1e-12);
  EXPECT_NEAR(piece.length, parabola_length(1.0, 0.7) - parabola_length(1.0, 0.2), 1e-12 + 8 * eps);
}

TEST(ArcLength, CuspConverges) {
  // (t^2, t^3) on [-1, 2]: exact control points; the cusp at t = 0 is at local s = 1/3, never
  // a bisection point, so |C'| has a real kink inside a sub-interval at every level.
  const BezierCurve2 curve({Vec2(1, -1), Vec2(-1, 2), Vec2(0, -4), Vec2(4, 8)}, -1.0, 2.0);
  const double exact = cusp_length(-1.0, 2.0);
  for (double tolerance : {1e-4, 1e-8, 1e-12}) {
    const ArcLength result = arc_length(curve, tolerance);
    // The requested accuracy plus rounding of the closed form and the sum (length ~ 9.3).
    EXPECT_NEAR(result.length, exact, tolerance + 64 * eps * exact) << "tolerance " << tolerance;
    EXPECT_LE(result.error_estimate, tolerance);
  }
}

TEST(ArcLength, CircleLengthsFromRationalArcs) {
  // Full unit circle (4 pieces): 2 pi; each piece gets 1e-13, rounding of 4 sums adds ulps.
  double total = 0.0;
  for (const auto& arc : circle_arc(Vec2(0.5, -0.25), 1.0, 0.0, 2.0 * pi)) total += arc_length(arc, 1e-13).length;
  EXPECT_NEAR(total, 2.0 * pi, 4e-13 + 64 * eps * 2.0 * pi);
  // 270 degrees of radius 3 clockwise: 3 * 3 pi / 2.
  total = 0.0;
  for (const auto& arc : circle_arc(Vec2(0, 0), 3.0, 1.0, 1.0 - 1.5 * pi)) total += arc_length(arc, 1e-13).length;
  EXPECT_NEAR(total, 4.5 * pi, 3e-13 + 64 * eps * 4.5 * pi);
  // The quarter circle with non-uniform speed 2/(1+t^2): (1,0),(1,1),(0,1), weights (1,1,2).
  const RationalBezierCurve2 quarter({Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {1.0, 1.0, 2.0});
  const ArcLength result = arc_length(quarter, 1e-12);
  EXPECT_NEAR(result.length, 0.5 * pi, 1e-12 + 64 * eps);
  EXPECT_LE(result.error_estimate, 1e-12);
}

TEST(IntegrateAdaptive, KinkAndReversedLimits) {
  // int_0^1 |t - 1/3| dt = (1/3)^2/2 + (2/3)^2/2 = 5/18; the kink is never a bisection point.
  const auto kink = [](double t) { return std::abs(t - 1.0 / 3.0); };
  for (double tolerance : {1e-6, 1e-12}) {
    const ArcLength forward = integrate_adaptive(kink, 0.0, 1.0, tolerance);
    EXPECT_NEAR(forward.length, 5.0 / 18.0, tolerance + 16 * eps);
    // int_1^0 = -int_0^1, to the same tolerance.
    const ArcLength backward = integrate_adaptive(kink, 1.0, 0.0, tolerance);
    EXPECT_NEAR(backward.length, -5.0 / 18.0, tolerance + 16 * eps) << "tolerance " << tolerance;
    EXPECT_LE(backward.error_estimate, tolerance);
  }
  // A smooth integrand: e - 1, the 10-point rule is exact to rounding at once.
  EXPECT_NEAR(integrate_adaptive([](double t) { return std::exp(t); }, 0.0, 1.0, 1e-14).length, std::exp(1.0) - 1.0,
              1e-14 + 16 * eps);
}

TEST(ArcLength, ToleranceBelowRoundingTerminates) {
  // 1000 times y = x^2 on [0, 1]: length ~1479, rounding of the sums ~1e-13. A tolerance of
  // 1e-14 cannot be reached; the result must still come back, accurate to the rounding level,
  // with an error estimate that says so.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(500, 0), Vec2(1000, 1000)});
  const double exact = 1000.0 * parabola_length(1.0, 1.0);
  const ArcLength result = arc_length(curve, 1e-14);
  // Rounding: a few ulps per rule value times the number of pieces (dozens at most).
  EXPECT_NEAR(result.length, exact, 1024 * eps * exact);
  EXPECT_LE(std::abs(result.length - exact), std::max(result.error_estimate, 1e-14) + 64 * eps * exact);
  // The same for a rational arc far from the origin, where |C'| ~ 1 is computed from homogeneous
  // points ~1e6 and carries noise ~1e6 eps: unit circle about (1e6, -2e6), length 2 pi.
  double total = 0.0;
  for (const auto& arc : circle_arc(Vec2(1e6, -2e6), 1.0, 0.0, 2.0 * pi)) total += arc_length(arc, 1e-12).length;
  // Each evaluation of |C'| errs by <= ~100 eps * 2e6 ~ 5e-8; the integral over [0, 1] likewise.
  EXPECT_NEAR(total, 2.0 * pi, 4 * 5e-8);
  // The generic integrator: int_0^1 1e6 e^t dt with tolerance 1e-20, far below its rounding.
  const ArcLength big = integrate_adaptive([](double t) { return 1e6 * std::exp(t); }, 0.0, 1.0, 1e-20);
  EXPECT_NEAR(big.length, 1e6 * (std::exp(1.0) - 1.0), 64 * eps * 1e6 * std::exp(1.0));
}

TEST(ArcLength, RejectsBadInput) {
  const BezierCurve2 curve = parabola(1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(arc_length(curve, 0.0), InvalidInput);
  EXPECT_THROW(arc_length(curve, -1e-6), InvalidInput);
  EXPECT_THROW(arc_length(curve, nan), InvalidInput);
  EXPECT_THROW(arc_length(curve, inf), InvalidInput);
  EXPECT_THROW(arc_length(curve, 0.7, 0.2, 1e-12), InvalidInput);
  EXPECT_THROW(arc_length(curve, -0.1, 0.5, 1e-12), InvalidInput);
  EXPECT_THROW(arc_length(curve, 0.5, 1.1, 1e-12), InvalidInput);
  EXPECT_THROW(arc_length(curve, nan, 0.5, 1e-12), InvalidInput);
  const RationalBezierCurve2 quarter({Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {1.0, 1.0, 2.0});
  EXPECT_THROW(arc_length(quarter, 0.0), InvalidInput);
  const auto one = [](double) { return 1.0; };
  EXPECT_THROW(integrate_adaptive(one, 0.0, inf, 1e-6), InvalidInput);
  EXPECT_THROW(integrate_adaptive(one, nan, 1.0, 1e-6), InvalidInput);
  EXPECT_THROW(integrate_adaptive(one, 0.0, 1.0, -1.0), InvalidInput);
}

RC_GTEST_PROP(ArcLength, ErrorEstimateIsHonestOnParabolas, ()) {
  const double c = 0.1 + 20.0 * random_unit();
  const double X = 0.1 + 3.0 * random_unit();
  const double tolerance = std::pow(10.0, -*rc::gen::inRange(2, 13));
  const ArcLength result = arc_length(parabola(c, X), tolerance);
  const double exact = parabola_length(c, X);
  // Rounding of the closed form and of the quadrature sum: a few ulps of the length (the
  // control point c X^2 is rounded too, changing the length by <= 2 n ulps of max|P|).
  const double rounding = 64 * eps * (exact + c * X * X);
  RC_ASSERT(std::abs(result.length - exact) <= std::max(result.error_estimate, tolerance) + rounding);
  RC_ASSERT(result.error_estimate <= tolerance);
}

RC_GTEST_PROP(ArcLength, ErrorEstimateIsHonestAtACusp, ()) {
  const double a = -(0.1 + 3.0 * random_unit());
  const double b = 0.1 + 3.0 * random_unit();
  const double tolerance = std::pow(10.0, -*rc::gen::inRange(2, 12));
  const BezierCurve2 curve = cusp_curve(a, b);
  const ArcLength result = arc_length(curve, tolerance);
  const double exact = cusp_length(a, b);
  // The rounded control points move the curve by delta with |delta'| integrating to at most
  // 2 n max|dP_i| <= 6 * 2 ulps of max|P_i|; plus rounding of the closed form and the sum.
  const double rounding = 64 * eps * (exact + max_norm(curve));
  RC_ASSERT(std::abs(result.length - exact) <= std::max(result.error_estimate, tolerance) + rounding);
}

RC_GTEST_PROP(ArcLength, IndependentOfTheParameterInterval, ()) {
  const int n = *rc::gen::inRange(1, 9);
  std::vector<Vec3> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = Vec3(random_unit(), random_unit(), random_unit()) * 2.0 - Vec3::Ones();
  const double a = 10.0 * random_unit() - 5.0;
  const double b = a + 0.01 + 10.0 * random_unit();
  const double tolerance = 1e-10;
  const ArcLength on_unit = arc_length(BezierCurve3(P), tolerance);
  const ArcLength on_ab = arc_length(BezierCurve3(P, a, b), tolerance);
  // Both within their tolerance of the same exact length, plus rounding of the sums and of
  // the chain-rule factor 1/(b-a) (a few ulps of the length).
  RC_ASSERT(std::abs(on_unit.length - on_ab.length) <= 2 * tolerance + 64 * eps * on_unit.length);
  // Additivity over a split parameter: L[a, t] + L[t, b] = L[a, b].
  const double t = a + (b - a) * random_unit();
  const double sum = arc_length(BezierCurve3(P, a, b), a, t, tolerance).length +
                     arc_length(BezierCurve3(P, a, b), t, b, tolerance).length;
  RC_ASSERT(std::abs(sum - on_ab.length) <= 3 * tolerance + 64 * eps * on_ab.length);
}

}  // namespace
}  // namespace patchwork
