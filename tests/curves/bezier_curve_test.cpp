#include "curves/bezier_curve.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// Unit roundoff u = 2^-53 and gamma_k = k u / (1 - k u) (Higham's constant).

mpq_class exact_bernstein(int n, int i, const mpq_class& s) {
  mpq_class result = exact_binomial(n, i);
  for (int k = 0; k < i; ++k) result *= s;
  for (int k = 0; k < n - i; ++k) result *= 1 - s;
  return result;
}

// Forward differences Delta^k P_i, i = 0..n-k, in rational arithmetic.
template <int Dim>
std::vector<ExactPoint<Dim>> exact_differences(const std::vector<Point<Dim>>& P, int k) {
  std::vector<ExactPoint<Dim>> D(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    for (int c = 0; c < Dim; ++c) D[i][static_cast<std::size_t>(c)] = P[i][c];
  }
  for (int level = 0; level < k; ++level) {
    for (std::size_t i = 0; i + 1 < D.size(); ++i) {
      for (std::size_t c = 0; c < Dim; ++c) D[i][c] = D[i + 1][c] - D[i][c];
    }
    D.pop_back();
  }
  return D;
}

// Exact k-th derivative of the curve with control points P on [a, b] at the local parameter s:
// n!/(n-k)! / (b-a)^k sum_i Delta^k P_i B_i^{n-k}(s) (Satz 21 applied k times, chain rule).
template <int Dim>
ExactPoint<Dim> exact_derivative(const std::vector<Point<Dim>>& P, double a, double b, double s, int k) {
  const int n = static_cast<int>(P.size()) - 1;
  ExactPoint<Dim> result;
  if (k > n) return result;  // zero-initialised
  const std::vector<ExactPoint<Dim>> D = exact_differences<Dim>(P, k);
  const mpq_class h = mpq_class(b) - mpq_class(a);
  mpq_class factor = 1;
  for (int j = 0; j < k; ++j) factor *= mpq_class(n - j) / h;
  for (int i = 0; i <= n - k; ++i) {
    const mpq_class weight = factor * exact_bernstein(n - k, i, mpq_class(s));
    for (std::size_t c = 0; c < Dim; ++c) result[c] += weight * D[static_cast<std::size_t>(i)][c];
  }
  return result;
}

// Per coordinate p~(s) = sum_i |P_i| B_i^n(s), the scale of de Casteljau's rounding error.
template <int Dim>
ExactPoint<Dim> exact_absolute_sum(const std::vector<Point<Dim>>& P, double s) {
  const int n = static_cast<int>(P.size()) - 1;
  ExactPoint<Dim> result;
  for (int i = 0; i <= n; ++i) {
    const mpq_class weight = exact_bernstein(n, i, mpq_class(s));
    for (int c = 0; c < Dim; ++c)
      result[static_cast<std::size_t>(c)] += weight * std::abs(P[static_cast<std::size_t>(i)][c]);
  }
  return result;
}

// Largest absolute coordinate of the control points.

// Whether |x - exact| <= bound in every coordinate, compared exactly.
template <int Dim>
bool within(const Point<Dim>& x, const ExactPoint<Dim>& exact, const ExactPoint<Dim>& bound) {
  for (std::size_t c = 0; c < Dim; ++c) {
    if (abs(mpq_class(x[static_cast<int>(c)]) - exact[c]) > bound[c]) return false;
  }
  return true;
}

template <int Dim>
ExactPoint<Dim> scaled(const ExactPoint<Dim>& p, double factor) {
  ExactPoint<Dim> result;
  for (std::size_t c = 0; c < Dim; ++c) result[c] = p[c] * mpq_class(factor);
  return result;
}

template <int Dim>
ExactPoint<Dim> uniform(double value) {
  ExactPoint<Dim> result;
  for (auto& x : result) x = value;
  return result;
}

// Runs f and expects InvalidInput whose message contains `needle`.

// The parabola (t, t^2) on [0, 1] as a quadratic.
BezierCurve2 parabola(double a = 0.0, double b = 1.0) {
  return BezierCurve2({Vec2(0.0, 0.0), Vec2(0.5, 0.0), Vec2(1.0, 1.0)}, a, b);
}

template <int Dim>
void check_evaluate_matches_exact(const BezierCurve<Dim>& curve, double t) {
  const auto& P = curve.control_points();
  const double s = curve.local_parameter(t);
  const Point<Dim> value = curve.evaluate(t);
  // de Casteljau for s in [0, 1]: |C - exact| <= gamma_{2n} p~(s) per coordinate when 1 - s is
  // exact; it is rounded for s < 1/2 (Sterbenz makes it exact above), which gives each level's
  // (1 - s) terms one more rounding: gamma_{3n} (a fresh seed found gamma_{2n} exceeded for a
  // line whose end points nearly cancel).
  const ExactPoint<Dim> bound = scaled<Dim>(exact_absolute_sum<Dim>(P, s), gamma(3 * curve.degree()));
  RC_ASSERT(within<Dim>(value, exact_derivative<Dim>(P, curve.a(), curve.b(), s, 0), bound));
}

TEST(BezierCurve, StoresControlPointsAndInterval) {
  const BezierCurve2 curve({Vec2(1, 2), Vec2(3, 4)}, -1.0, 2.0);
  EXPECT_EQ(curve.degree(), 1);
  EXPECT_EQ(curve.control_points()[1], Vec2(3, 4));
  EXPECT_EQ(curve.a(), -1.0);
  EXPECT_EQ(curve.b(), 2.0);
  EXPECT_EQ(curve.local_parameter(0.5), 0.5);
  const BezierCurve2 unit = with_interval(curve, 0.0, 1.0);
  EXPECT_EQ(unit.control_points(), curve.control_points());
  EXPECT_FALSE(unit == curve);  // the interval is part of the value
  EXPECT_TRUE(with_interval(unit, -1.0, 2.0) == curve);
}

TEST(BezierCurve, EvaluatesHighDegreeLikeExactBernsteinSum) {
  for (int n : {1, 2, 3, 5, 16, 17, 40}) {  // 3 is unrolled; > 15 leaves the stack scratch
    std::vector<Vec3> P;
    for (int i = 0; i <= n; ++i) P.emplace_back(std::cos(i), std::sin(3.0 * i) * 5.0, 1.0 / (i + 1));
    const BezierCurve3 curve(P, 2.0, 6.0);
    for (double t : {2.0, 2.1, 3.0, 4.0, 5.3, 6.0}) {
      const double s = curve.local_parameter(t);
      const ExactPoint<3> bound = scaled<3>(exact_absolute_sum<3>(P, s), gamma(2 * n));
      EXPECT_TRUE(within<3>(curve.evaluate(t), exact_derivative<3>(P, 2.0, 6.0, s, 0), bound))
          << "n=" << n << " t=" << t;
      EXPECT_EQ(curve(t), curve.evaluate(t));
    }
  }
}

TEST(BezierCurve, EvaluatesOnIntervalThroughLocalParameter) {
  // Def 57: C_[a,b](t) = C(s) with s = (t - a)/(b - a). On [1, 5], t = 2 is s = 1/4 exactly and
  // all de Casteljau values of (t, t^2) at s = 1/4 are short dyadic numbers: no rounding at all.
  const BezierCurve2 curve = parabola(1.0, 5.0);
  EXPECT_EQ(curve.evaluate(2.0), Vec2(0.25, 0.0625));
  EXPECT_EQ(curve.evaluate(3.0), Vec2(0.5, 0.25));
  EXPECT_EQ(curve.evaluate(5.0), Vec2(1.0, 1.0));
  // Outside [a, b] the polynomial is extrapolated: t = 7 is s = 1.5.
  EXPECT_EQ(curve.evaluate(7.0), Vec2(1.5, 2.25));
}

RC_GTEST_PROP(BezierCurve, EvaluateMatchesExactBernsteinSum, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  check_evaluate_matches_exact<3>(curve, *curve_gen::parameter(curve.a(), curve.b()));
  const auto planar = *curve_gen::bezier_curve<2>();
  check_evaluate_matches_exact<2>(planar, *curve_gen::parameter(0.0, 1.0));
}

RC_GTEST_PROP(BezierCurve, InterpolatesEndPointsExactly, ()) {
  // At s = 0 and s = 1 every de Casteljau step is 1*x + 0*y: no rounding.
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const auto& P = curve.control_points();
  RC_ASSERT(curve.evaluate(curve.a()) == P.front());
  RC_ASSERT(curve.evaluate(curve.b()) == P.back());
  const std::vector<double> ends{curve.a(), curve.b()};
  const std::vector<Vec3> batch = evaluate_many(curve, ends);
  RC_ASSERT(batch[0] == P.front());
  RC_ASSERT(batch[1] == P.back());
}

RC_GTEST_PROP(BezierCurve, EndTangentsFollowControlPolygon, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>(1, 12);
  const auto& P = curve.control_points();
  const int n = curve.degree();
  const Vec3 first = P[1] - P[0];
  const Vec3 last = P[n] - P[n - 1];
  const double M = max_abs<3>(P);
  RC_PRE(first.norm() > 1e-3 * M && last.norm() > 1e-3 * M);
  // Satz 21 at the ends: C'(a) = n (P_1 - P_0)/(b - a), C'(b) = n (P_n - P_{n-1})/(b - a).
  // The difference is rounded once (u), the factor n/(b-a) twice: 4 eps relative covers it.
  const double h = curve.b() - curve.a();
  const Vec3 start = derivative(curve, curve.a(), 1);
  const Vec3 end = derivative(curve, curve.b(), 1);
  const double eps = std::numeric_limits<double>::epsilon();
  RC_ASSERT((start - n / h * first).norm() <= 4 * eps * (n / h) * first.norm() + 4 * eps * (n / h) * M);
  RC_ASSERT((end - n / h * last).norm() <= 4 * eps * (n / h) * last.norm() + 4 * eps * (n / h) * M);
  // The unit tangents, with the rounding of P_1 - P_0 (u M) relative to its length.
  RC_ASSERT((tangent(curve, curve.a()) - first.normalized()).norm() <= 16 * eps * M / first.norm());
  RC_ASSERT((tangent(curve, curve.b()) - last.normalized()).norm() <= 16 * eps * M / last.norm());
}

TEST(BezierCurve, DerivativesOfParabolaOnInterval) {
  // (s, s^2) with s = (t - 1)/4 on [1, 5]: C' = (1, 2s)/4, C'' = (0, 2)/16, C''' = 0 (Satz 21 and
  // the chain rule). Every value is a short dyadic number, so the results are exact.
  const BezierCurve2 curve = parabola(1.0, 5.0);
  for (double t : {1.0, 2.0, 3.0, 4.5, 5.0}) {
    const double s = (t - 1.0) / 4.0;
    EXPECT_EQ(derivative(curve, t, 0), Vec2(s, s * s)) << t;
    EXPECT_EQ(derivative(curve, t, 1), Vec2(0.25, 0.5 * s)) << t;
    EXPECT_EQ(derivative(curve, t, 2), Vec2(0.0, 0.125)) << t;
    EXPECT_EQ(derivative(curve, t, 3), Vec2(0.0, 0.0)) << t;
    const std::vector<Vec2> all = derivatives(curve, t, 4);
    ASSERT_EQ(all.size(), 5u);
    EXPECT_EQ(all[0], Vec2(s, s * s));
    EXPECT_EQ(all[1], Vec2(0.25, 0.5 * s));
    EXPECT_EQ(all[2], Vec2(0.0, 0.125));
    EXPECT_EQ(all[3], Vec2::Zero());
    EXPECT_EQ(all[4], Vec2::Zero());
  }
}

TEST(BezierCurve, DerivativeAboveDegreeIsZeroForAnyOrder) {
  // d^k/dt^k of a polynomial of degree n vanishes for every k > n, however large k is.
  const BezierCurve2 curve = parabola(1.0, 5.0);
  EXPECT_EQ(derivative(curve, 2.0, 3), Vec2::Zero());
  EXPECT_EQ(derivative(curve, 2.0, 1000), Vec2::Zero());
  EXPECT_EQ(derivative(curve, 2.0, std::numeric_limits<int>::max()), Vec2::Zero());
  EXPECT_THROW(derivative(curve, std::numeric_limits<double>::quiet_NaN(), 1000), InvalidInput);
}

TEST(BezierCurve, DerivativeCurveIsSatz21Hodograph) {
  // n (P_{i+1} - P_i)/(b - a) with integer points and b - a = 2: exact.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(2, 4), Vec2(6, 4), Vec2(8, -2)}, 1.0, 3.0);
  const BezierCurve2 hodograph = derivative_curve(curve);
  EXPECT_EQ(hodograph.degree(), 2);
  EXPECT_EQ(hodograph.a(), 1.0);
  EXPECT_EQ(hodograph.b(), 3.0);
  EXPECT_EQ(hodograph.control_points()[0], Vec2(3, 6));
  EXPECT_EQ(hodograph.control_points()[1], Vec2(6, 0));
  EXPECT_EQ(hodograph.control_points()[2], Vec2(3, -9));
  const BezierCurve2 point({Vec2(7, 8)}, 0.0, 2.0);
  const BezierCurve2 zero = derivative_curve(point);
  EXPECT_EQ(zero.degree(), 0);
  EXPECT_EQ(zero.control_points()[0], Vec2::Zero());
  EXPECT_EQ(zero.a(), 0.0);
  EXPECT_EQ(zero.b(), 2.0);
}

template <int Dim>
void check_derivatives_match_exact(const BezierCurve<Dim>& curve, double t) {
  const auto& P = curve.control_points();
  const int n = curve.degree();
  const double s = curve.local_parameter(t);
  const double h = curve.b() - curve.a();
  const double M = max_abs<Dim>(P);
  const std::vector<Point<Dim>> all = derivatives(curve, t, n + 1);
  RC_ASSERT(all.size() == static_cast<std::size_t>(n) + 2);
  for (int k = 0; k <= n + 1; ++k) {
    const ExactPoint<Dim> exact = exact_derivative<Dim>(P, curve.a(), curve.b(), s, k);
    // Rounding: the level-k points are differences of de Casteljau values of size <= 2^k M,
    // each step adding u of that scale (n de Casteljau steps, k differences, the factor and
    // h^k): (4n + 4k + 8) u n!/(n-k)! 2^k M / h^k bounds the error of C^(k).
    const double scale = reference_falling_factorial(n, k) * std::pow(2.0, k) * M / std::pow(h, k);
    const ExactPoint<Dim> bound = uniform<Dim>((4 * n + 4 * k + 8) * kUnit * scale);
    RC_ASSERT(within<Dim>(all[static_cast<std::size_t>(k)], exact, bound));
    RC_ASSERT(within<Dim>(derivative(curve, t, k), exact, bound));
  }
  RC_ASSERT(all[static_cast<std::size_t>(n) + 1] == Point<Dim>::Zero());
}

RC_GTEST_PROP(BezierCurve, DerivativesMatchExactHodograph, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  check_derivatives_match_exact<3>(curve, *curve_gen::parameter(curve.a(), curve.b()));
  const auto scalar = *curve_gen::bezier_curve_on_interval<1>();
  check_derivatives_match_exact<1>(scalar, *curve_gen::parameter(scalar.a(), scalar.b()));
}

RC_GTEST_PROP(BezierCurve, DerivativeCurveEvaluatesToDerivative, ()) {
  // Satz 21 by two routes: the hodograph's control points, evaluated, against derivative().
  const auto curve = *curve_gen::bezier_curve_on_interval<2>(1, 12);
  const double t = *curve_gen::parameter(curve.a(), curve.b());
  const int n = curve.degree();
  const double h = curve.b() - curve.a();
  const double M = max_abs<2>(curve.control_points());
  BezierCurve2 hodograph = curve;
  for (int k = 1; k <= n; ++k) {
    hodograph = derivative_curve(hodograph);
    RC_ASSERT(hodograph.degree() == n - k);
    // Both values carry the rounding bound of check_derivatives_match_exact.
    const double scale = reference_falling_factorial(n, k) * std::pow(2.0, k) * M / std::pow(h, k);
    const double tolerance = 2 * (4 * n + 4 * k + 8) * kUnit * scale;
    RC_ASSERT((hodograph.evaluate(t) - derivative(curve, t, k)).cwiseAbs().maxCoeff() <= tolerance);
  }
}

RC_GTEST_PROP(BezierCurve, ChainRuleOnInterval, ()) {
  // Satz 21: d^k/dt^k C_[a,b](t) = (b - a)^-k C^(k)(s).
  const auto curve = *curve_gen::bezier_curve_on_interval<3>(0, 10);
  const auto unit = with_interval(curve, 0.0, 1.0);
  const double t = *curve_gen::parameter(curve.a(), curve.b());
  const double s = curve.local_parameter(t);
  const int n = curve.degree();
  const double h = curve.b() - curve.a();
  const double M = max_abs<3>(curve.control_points());
  for (int k = 0; k <= n; ++k) {
    const Vec3 expected = derivative(unit, s, k) / std::pow(h, k);
    const double scale = reference_falling_factorial(n, k) * std::pow(2.0, k) * M / std::pow(h, k);
    RC_ASSERT((derivative(curve, t, k) - expected).cwiseAbs().maxCoeff() <= 2 * (4 * n + 4 * k + 8) * kUnit * scale);
  }
}

TEST(BezierCurve, TangentAtDegenerateEndIsLimitDirection) {
  // P_0 = P_1: C'(a) = 0, the limit direction from the right is that of C''(a) ~ P_2 - P_0.
  const BezierCurve2 start({Vec2(1, 1), Vec2(1, 1), Vec2(4, 5), Vec2(9, 0)}, 0.0, 2.0);
  EXPECT_EQ(derivative(start, 0.0, 1), Vec2::Zero());
  const Vec2 expected_start = Vec2(3, 4) / 5.0;
  EXPECT_NEAR((tangent(start, 0.0) - expected_start).norm(), 0.0, 4 * std::numeric_limits<double>::epsilon());
  // P_{n-1} = P_n: from the left, the direction is P_n - P_{n-2} (C''(b) points the other way).
  const BezierCurve2 end({Vec2(0, 0), Vec2(-3, 7), Vec2(2, 2), Vec2(2, 2)}, 1.0, 3.0);
  EXPECT_EQ(derivative(end, 3.0, 1), Vec2::Zero());
  const Vec2 expected_end = Vec2(5, -5) / std::sqrt(50.0);
  EXPECT_NEAR((tangent(end, 3.0) - expected_end).norm(), 0.0, 4 * std::numeric_limits<double>::epsilon());
  // A segment traversed as P_0, P_1 = P_2 = P_3: C' and C'' vanish at b, C''' ~ P_3 - P_0.
  const BezierCurve2 segment({Vec2(0, 0), Vec2(1, 2), Vec2(1, 2), Vec2(1, 2)});
  const Vec2 direction = Vec2(1, 2) / std::sqrt(5.0);
  EXPECT_NEAR((tangent(segment, 1.0) - direction).norm(), 0.0, 4 * std::numeric_limits<double>::epsilon());
  EXPECT_NEAR((tangent(segment, 0.0) - direction).norm(), 0.0, 4 * std::numeric_limits<double>::epsilon());
}

TEST(BezierCurve, TangentAtCuspIsDirectionOfSecondDerivative) {
  // C'(1/2) = 3 [(1,1) + 2 (-1,0) + (1,-1)]/4 = 0 and C''(1/2) = (0, -6): from the right the
  // curve leaves the cusp along (0, -1). Curvature is undefined there.
  const BezierCurve2 cusp({Vec2(0, 0), Vec2(1, 1), Vec2(0, 1), Vec2(1, 0)});
  EXPECT_EQ(derivative(cusp, 0.5, 1), Vec2::Zero());
  EXPECT_EQ(derivative(cusp, 0.5, 2), Vec2(0, -6));
  EXPECT_EQ(tangent(cusp, 0.5), Vec2(0, -1));
  EXPECT_THROW(curvature(cusp, 0.5), NumericalError);
}

TEST(BezierCurve, TangentOfPointCurveThrows) {
  EXPECT_THROW(tangent(BezierCurve2({Vec2(1, 2)}), 0.5), NumericalError);
  EXPECT_THROW(tangent(BezierCurve2({Vec2(1, 2), Vec2(1, 2), Vec2(1, 2)}), 0.0), NumericalError);
  EXPECT_THROW(curvature(BezierCurve2({Vec2(1, 2), Vec2(1, 2)}), 0.3), NumericalError);
}

TEST(BezierCurve, CurvatureOfParabolaMatchesClosedForm) {
  // y = x^2 has curvature 2 / (1 + 4x^2)^(3/2); 2 at the vertex. Curvature is geometric: the
  // same on [1, 5], in a plane of R^3 and R^4 (the Gram-determinant branch).
  const double eps = std::numeric_limits<double>::epsilon();
  EXPECT_EQ(curvature(parabola(), 0.0), 2.0);
  EXPECT_EQ(curvature(parabola(1.0, 5.0), 1.0), 2.0);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.2, Vec3::UnitZ())).toRotationMatrix();
  std::vector<Vec3> P3;
  std::vector<Vec4> P4;
  const BezierCurve2 planar = parabola();
  for (const Vec2& p : planar.control_points()) {
    P3.push_back(rotation * Vec3(p.x(), p.y(), 0.0) + Vec3(1, -2, 3));
    P4.emplace_back(p.y(), 0.5, p.x(), -1.0);
  }
  const BezierCurve3 tilted(P3, -1.0, 1.0);
  const BezierCurve4 embedded(P4);
  for (double x : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0}) {
    const double expected = 2.0 / std::pow(1.0 + 4.0 * x * x, 1.5);
    // A few roundings in C', C'' and the formula: 16 eps relative.
    EXPECT_NEAR(curvature(parabola(), x), expected, 16 * eps * expected) << x;
    EXPECT_NEAR(curvature(parabola(1.0, 5.0), 1.0 + 4.0 * x), expected, 16 * eps * expected) << x;
    // The rotation rounds the control points by ~u: 64 eps relative.
    EXPECT_NEAR(curvature(tilted, 2.0 * x - 1.0), expected, 64 * eps * expected) << x;
    EXPECT_NEAR(curvature(embedded, x), expected, 64 * eps * expected) << x;
  }
}

TEST(BezierCurve, StraightLineHasZeroCurvature) {
  // Collinear control points, unevenly spaced (non-uniform speed, C'' != 0 along the line).
  const Vec2 origin(1, -2);
  const Vec2 along(3, 4);
  std::vector<Vec2> P2;
  std::vector<Vec3> P3;
  std::vector<double> P1;
  for (double lambda : {0.0, 2.0, 3.0, 7.0}) {  // C'' ~ (4s - 1) along, C' never 0
    P2.push_back(origin + lambda * along);
    P3.push_back(Vec3(2, 0, 1) + lambda * Vec3(1, -2, 2));
  }
  const BezierCurve2 line2(P2);
  const BezierCurve3 line3(P3, -2.0, 2.0);
  const BezierCurve1 line1({Point<1>(0.0), Point<1>(5.0), Point<1>(-1.0)});
  for (double s : {0.0, 0.125, 0.5, 0.75, 1.0}) {
    ASSERT_NE(derivative(line2, s, 2).norm(), 0.0);
    // Integer control points and dyadic s: every product in the cross product is exact.
    EXPECT_EQ(curvature(line2, s), 0.0) << s;
    EXPECT_EQ(curvature(line3, 4.0 * s - 2.0), 0.0) << s;
    EXPECT_EQ(curvature(line1, s), 0.0) << s;
  }
}

template <int Dim>
void check_start_curvature(const BezierCurve<Dim>& curve) {
  // kappa(a) = (n-1)/n |D0 x D1| / |D0|^3 with D0 = P_1 - P_0, D1 = P_2 - P_1; the squared
  // area |D0|^2 |D1|^2 - (D0.D1)^2 and the rest computed exactly.
  const auto& P = curve.control_points();
  const int n = curve.degree();
  const Point<Dim> d0 = P[1] - P[0];
  const Point<Dim> d2 = P[2] - 2 * P[1] + P[0];
  const double M = max_abs<Dim>(P);
  RC_PRE(d0.norm() > 0.05 * M && d2.norm() > 0.05 * M);
  const double sine = std::sqrt(std::max(0.0, 1.0 - std::pow(d0.dot(d2) / (d0.norm() * d2.norm()), 2)));
  RC_PRE(sine > 0.05);
  const std::vector<ExactPoint<Dim>> D = exact_differences<Dim>(P, 1);
  mpq_class d00 = 0, d11 = 0, d01 = 0;
  for (std::size_t c = 0; c < Dim; ++c) {
    d00 += D[0][c] * D[0][c];
    d11 += D[1][c] * D[1][c];
    d01 += D[0][c] * D[1][c];
  }
  const mpq_class squared = mpq_class(n - 1, n) * mpq_class(n - 1, n) * (d00 * d11 - d01 * d01) / (d00 * d00 * d00);
  const double expected = std::sqrt(squared.get_d());
  // C' and C'' at s = 0 carry an error of a few u M (differences of exact control points),
  // i.e. relative 8u M/|d| each; the area |C' x C''| or its Gram form loses 1/sin^2 of the angle
  // between C' and C''. 64 u (M/|d0| + M/|d2|) / sin^2 + 16 u bounds the relative error.
  const double tolerance = (64 * kUnit * (M / d0.norm() + M / d2.norm()) / (sine * sine) + 16 * kUnit) * expected;
  RC_ASSERT(std::abs(curvature(curve, curve.a()) - expected) <= tolerance);
}

RC_GTEST_PROP(BezierCurve, CurvatureAtStartMatchesClosedForm, ()) {
  check_start_curvature<2>(*curve_gen::bezier_curve_on_interval<2>(2, 12));
  check_start_curvature<3>(*curve_gen::bezier_curve_on_interval<3>(2, 12));
  check_start_curvature<4>(*curve_gen::bezier_curve_on_interval<4>(2, 12));
}

RC_GTEST_PROP(BezierCurve, IsAffineInvariant, ()) {
  // The curve of the images A P_i + v is the image A C(t) + v of the curve.
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const double t = *curve_gen::parameter(curve.a(), curve.b());
  const auto entries = *rc::gen::container<std::vector<double>>(9, curve_gen::coordinate(-2.0, 2.0));
  const Eigen::Matrix3d A = Eigen::Map<const Eigen::Matrix3d>(entries.data());
  const Vec3 v = *curve_gen::point<3>();
  std::vector<Vec3> image;
  for (const Vec3& p : curve.control_points()) image.push_back(A * p + v);
  const BezierCurve3 mapped(image, curve.a(), curve.b());
  const Vec3 expected = A * curve.evaluate(t) + v;
  // Both sides are within (2n + 6) u of A C(t) + v on the scale |A|_inf M + |v|_inf (de
  // Casteljau's gamma_{2n} on both, three roundings in each A p + v).
  const int n = curve.degree();
  const double scale =
      A.cwiseAbs().rowwise().sum().maxCoeff() * max_abs<3>(curve.control_points()) + v.cwiseAbs().maxCoeff();
  RC_ASSERT((mapped.evaluate(t) - expected).cwiseAbs().maxCoeff() <= 2 * (2 * n + 6) * kUnit * scale);
}

RC_GTEST_PROP(BezierCurve, LiesInConvexHullOfControlPoints, ()) {
  // For every direction d: min_i d.P_i <= d.C(t) <= max_i d.P_i (the convex hull property).
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const double t = *curve_gen::parameter(curve.a(), curve.b());
  const Vec3 point = curve.evaluate(t);
  const int n = curve.degree();
  const double M = max_abs<3>(curve.control_points());
  for (int trial = 0; trial < 8; ++trial) {
    const Vec3 d = *curve_gen::direction<3>();
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Vec3& p : curve.control_points()) {
      lo = std::min(lo, d.dot(p));
      hi = std::max(hi, d.dot(p));
    }
    // gamma_{2n} M per coordinate in C(t), and 3 roundings in each dot product, times |d|_1.
    const double tolerance = (gamma(2 * n) + 6 * kUnit) * M * d.cwiseAbs().sum();
    RC_ASSERT(d.dot(point) >= lo - tolerance);
    RC_ASSERT(d.dot(point) <= hi + tolerance);
  }
}

RC_GTEST_PROP(BezierCurve, EvaluateManyMatchesDeCasteljau, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>(0, 40);
  const auto ts = *rc::gen::container<std::vector<double>>(5, curve_gen::parameter(curve.a(), curve.b()));
  const std::vector<Vec3> batch = evaluate_many(curve, ts);
  RC_ASSERT(batch.size() == ts.size());
  const int n = curve.degree();
  for (std::size_t j = 0; j < ts.size(); ++j) {
    const double s = curve.local_parameter(ts[j]);
    const ExactPoint<3> p_tilde = exact_absolute_sum<3>(curve.control_points(), s);
    const ExactPoint<3> exact = exact_derivative<3>(curve.control_points(), curve.a(), curve.b(), s, 0);
    const Vec3 single = curve.evaluate(ts[j]);
    // Weights by Satz 20 carry gamma_{2n} relative error, their sum n+1 more roundings:
    // |batch - exact| <= gamma_{3n+2} p~(s); de Casteljau's own gamma_{2n} p~(s) on top for
    // the difference of the two.
    RC_ASSERT(within<3>(batch[j], exact, scaled<3>(p_tilde, gamma(3 * n + 2))));
    const ExactPoint<3> de_casteljau{mpq_class(single[0]), mpq_class(single[1]), mpq_class(single[2])};
    RC_ASSERT(within<3>(batch[j], de_casteljau, scaled<3>(p_tilde, gamma(3 * n + 2) + gamma(2 * n))));
  }
}

TEST(BezierCurve, EvaluateWithTableUsesLocalParameters) {
  // Table rows are local parameters s = k/16 (exact), whatever the curve's interval.
  std::vector<Vec2> P;
  for (int i = 0; i <= 7; ++i) P.emplace_back(i * i - 3.5, std::sin(i));
  const BezierCurve2 curve(P, 10.0, 30.0);
  const BernsteinTable table = BernsteinTable::uniform(7, 17);
  const std::vector<Vec2> values = evaluate(curve, table);
  ASSERT_EQ(values.size(), 17u);
  double worst_ulps = 0.0;
  for (int k = 0; k <= 16; ++k) {
    const double s = k / 16.0;
    const ExactPoint<2> exact = exact_derivative<2>(P, 0.0, 1.0, s, 0);
    const ExactPoint<2> p_tilde = exact_absolute_sum<2>(P, s);
    EXPECT_TRUE(within<2>(values[static_cast<std::size_t>(k)], exact, scaled<2>(p_tilde, gamma(3 * 7 + 2)))) << k;
    for (int c = 0; c < 2; ++c) {
      if (p_tilde[static_cast<std::size_t>(c)] == 0) continue;  // P_0.y = 0 at s = 0: exact
      const double error = std::abs(values[static_cast<std::size_t>(k)][c] - curve.evaluate(10.0 + 20.0 * s)[c]);
      worst_ulps = std::max(
          worst_ulps, error / (std::numeric_limits<double>::epsilon() * p_tilde[static_cast<std::size_t>(c)].get_d()));
    }
  }
  // Table and de Casteljau agree to a few ulps of the scale p~(s): (gamma_23 + gamma_14) p~(s)
  // is 37 u = 18.5 eps.
  EXPECT_LE(worst_ulps, 18.5);
  RecordProperty("table_vs_de_casteljau_ulps", std::to_string(worst_ulps));
}

TEST(BezierCurve, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid_input([] { BezierCurve2(std::vector<Vec2>{}); }, "no control points");
  expect_invalid_input([&] { BezierCurve2({Vec2(0, 0), Vec2(nan, 1)}); }, "control point 1");
  expect_invalid_input([&] { BezierCurve3({Vec3(0, 0, inf)}); }, "control point 0");
  expect_invalid_input([] { BezierCurve2({Vec2(0, 0)}, 1.0, 1.0); }, "interval");
  expect_invalid_input([] { BezierCurve2({Vec2(0, 0)}, 2.0, 1.0); }, "interval");
  expect_invalid_input([&] { BezierCurve2({Vec2(0, 0)}, nan, 1.0); }, "interval");
  expect_invalid_input([&] { BezierCurve2({Vec2(0, 0)}, 0.0, inf); }, "interval");
  const BezierCurve2 curve = parabola();
  expect_invalid_input([&] { with_interval(curve, 3.0, -3.0); }, "interval");
  expect_invalid_input([&] { curve.evaluate(nan); }, "evaluate");
  expect_invalid_input([&] { curve(inf); }, "evaluate");
  expect_invalid_input([&] { derivative(curve, 0.5, -1); }, "order -1");
  expect_invalid_input([&] { derivative(curve, nan, 1); }, "not finite");
  expect_invalid_input([&] { derivatives(curve, 0.5, -2); }, "order -2");
  expect_invalid_input([&] { tangent(curve, nan); }, "not finite");
  expect_invalid_input([&] { curvature(curve, inf); }, "not finite");
  const std::vector<double> ts{0.5, nan};
  expect_invalid_input([&] { evaluate_many(curve, ts); }, "evaluate_many");
  const BernsteinTable cubic_table = BernsteinTable::uniform(3, 4);
  expect_invalid_input([&] { evaluate(curve, cubic_table); }, "degree 3");
}

}  // namespace
}  // namespace patchwork
