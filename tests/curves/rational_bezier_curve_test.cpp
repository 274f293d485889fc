#include "curves/rational_bezier_curve.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// The unit quarter circle in the rational parametrisation t = tan(theta/2): homogeneous points
// (1,0,1), (1,1,1), (0,2,2) give X = 1 - s^2, Y = 2s, W = 1 + s^2 with s = (t-a)/(b-a), so
// x = (1-s^2)/(1+s^2), y = 2s/(1+s^2).
RationalBezierCurve2 quarter_circle(double a = 0.0, double b = 1.0) {
  return RationalBezierCurve2({Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {1.0, 1.0, 2.0}, a, b);
}

// d^k/ds^k f for f(s) = 1/(1+s^2), k = 0..3, by hand: f' = -2s/u^2, f'' = (6s^2-2)/u^3,
// f''' = 24s(1-s^2)/u^4 with u = 1+s^2.
mpq_class f_derivative(const mpq_class& s, int k) {
  const mpq_class u = 1 + s * s;
  if (k == 0) return 1 / u;
  if (k == 1) return -2 * s / (u * u);
  if (k == 2) return (6 * s * s - 2) / (u * u * u);
  return 24 * s * (1 - s * s) / (u * u * u * u);
}

// Exact d^k/ds^k of (x, y) = (2f - 1, 2sf); (sf)^(k) = s f^(k) + k f^(k-1) by Leibniz.
std::pair<mpq_class, mpq_class> quarter_circle_derivative(const mpq_class& s, int k) {
  if (k == 0) return {2 * f_derivative(s, 0) - 1, 2 * s * f_derivative(s, 0)};
  return {2 * f_derivative(s, k), 2 * (s * f_derivative(s, k) + k * f_derivative(s, k - 1))};
}

double random_coordinate() { return *rc::gen::inRange(-1000000, 1000001) / 1e6; }

template <int Dim>
Point<Dim> random_point() {
  Point<Dim> p;
  for (int d = 0; d < Dim; ++d) p[d] = random_coordinate();
  return p;
}

// Positive weights in [1/4, 4].
double random_weight() { return *rc::gen::inRange(250, 4001) / 1000.0; }

// Angles of a sampled arc: the signed increments between neighbouring samples add up to the
// sweep when the arc runs monotonically from start to end.
double swept_angle(const std::vector<RationalBezierCurve2>& arcs, const Vec2& center) {
  double total = 0.0;
  for (const auto& arc : arcs) {
    Vec2 previous = arc.evaluate(0.0) - center;
    for (int i = 1; i <= 64; ++i) {
      const Vec2 current = arc.evaluate(i / 64.0) - center;
      const double increment = std::atan2(previous[0] * current[1] - previous[1] * current[0], previous.dot(current));
      EXPECT_LT(std::abs(increment), 0.5 * pi);
      total += increment;
      previous = current;
    }
  }
  return total;
}

TEST(RationalBezierCurve, DerivativesMatchClosedFormOfQuarterCircle) {
  const RationalBezierCurve2 curve = quarter_circle();
  for (double s : {0.0, 0.125, 1.0 / 3.0, 0.5, 0.7, 1.0}) {
    for (int k = 0; k <= 3; ++k) {
      const auto [x, y] = quarter_circle_derivative(mpq_class(s), k);
      const Vec2 d = derivative(curve, s, k);
      // The homogeneous derivatives have rounding <= gamma_4 * 2^k n!/(n-k)! max|H_i| <= 64 eps
      // (0 for k = 3: H is quadratic); Leibniz divides by w >= 1 and mixes in lower orders
      // with binomials <= 3 and |w^(j)| <= 4: 256 eps bounds the chain (observed <= 24 eps).
      EXPECT_NEAR(d[0], x.get_d(), 256 * eps) << "s=" << s << " k=" << k;
      EXPECT_NEAR(d[1], y.get_d(), 256 * eps) << "s=" << s << " k=" << k;
    }
    // |C'(s)| = d theta/ds = 2/(1+s^2) for theta = 2 atan s.
    EXPECT_NEAR(derivative(curve, s, 1).norm(), 2.0 / (1.0 + s * s), 64 * eps);
  }
}

TEST(RationalBezierCurve, DerivativesFollowTheChainRuleOnAnInterval) {
  // On [2, 6] the local parameter is s = (t-2)/4, so d^k/dt^k = 4^-k d^k/ds^k (Satz 21).
  const RationalBezierCurve2 curve = quarter_circle(2.0, 6.0);
  for (double s : {0.0, 0.25, 0.625, 1.0}) {
    const double t = 2.0 + 4.0 * s;  // exact for these s
    for (int k = 0; k <= 3; ++k) {
      const auto [x, y] = quarter_circle_derivative(mpq_class(s), k);
      const double scale = std::pow(0.25, k);
      const Vec2 d = derivative(curve, t, k);
      // Same chain as above, every term scaled by 4^-k.
      EXPECT_NEAR(d[0], scale * x.get_d(), 256 * eps * scale) << "t=" << t << " k=" << k;
      EXPECT_NEAR(d[1], scale * y.get_d(), 256 * eps * scale) << "t=" << t << " k=" << k;
    }
  }
}

TEST(RationalBezierCurve, AccessorsReturnControlPointsAndWeights) {
  const RationalBezierCurve3 curve({Vec3(1, 2, 3), Vec3(-1, 0.5, 4), Vec3(0, 0, -2)}, {0.5, 2.0, 4.0}, -1.0, 3.0);
  EXPECT_EQ(curve.degree(), 2);
  EXPECT_EQ(curve.a(), -1.0);
  EXPECT_EQ(curve.b(), 3.0);
  // w_i P_i and its quotient by w_i are exact for these dyadic values.
  EXPECT_EQ(curve.control_point(1), Vec3(-1, 0.5, 4));
  EXPECT_EQ(curve.weight(2), 4.0);
  EXPECT_EQ(curve.homogeneous().control_points()[1], Vec4(-2, 1, 8, 2));
  // End points interpolate: C(a) = P_0, C(b) = P_n.
  EXPECT_EQ(curve.evaluate(-1.0), Vec3(1, 2, 3));
  EXPECT_EQ(curve.evaluate(3.0), Vec3(0, 0, -2));
}

TEST(RationalBezierCurve, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using Points = std::vector<Vec2>;
  EXPECT_THROW(RationalBezierCurve2(Points{}, {}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, 0.0}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, -2.0}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, nan}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, inf}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, nan), Vec2(1, 0)}, {1.0, 1.0}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(inf, 0)}, {1.0, 1.0}), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, 1.0}, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, 1.0}, 2.0, 1.0), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(Points{Vec2(0, 0), Vec2(1, 0)}, {1.0, 1.0}, 0.0, nan), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(BezierCurve3({Vec3(0, 0, 1), Vec3(1, 0, 0)})), InvalidInput);
  EXPECT_THROW(RationalBezierCurve2(BezierCurve3({Vec3(0, 0, 1), Vec3(1, 0, -1)})), InvalidInput);

  const RationalBezierCurve2 curve = quarter_circle();
  EXPECT_THROW(curve.evaluate(nan), InvalidInput);
  EXPECT_THROW(derivative(curve, 0.5, -1), InvalidInput);
  EXPECT_THROW(derivative(curve, inf, 1), InvalidInput);
  EXPECT_THROW(split(curve, 0.0), InvalidInput);
  EXPECT_THROW(split(curve, 1.0), InvalidInput);
  EXPECT_THROW(elevate_degree(curve, -1), InvalidInput);
  // A point curve has no tangent and no curvature.
  const RationalBezierCurve2 point({Vec2(1, 1), Vec2(1, 1)}, {1.0, 3.0});
  EXPECT_THROW(tangent(point, 0.5), NumericalError);
  EXPECT_THROW(curvature(point, 0.5), NumericalError);
}

TEST(RationalBezierCurve, TangentIsTheLimitDirectionWhereTheDerivativeVanishes) {
  // P_0 = P_1 and P_2 = P_3: C' vanishes at both ends; near t = 0, C - P_0 ~ 3 t^2 w_2/w_0
  // (P_2 - P_0), and near t = 1 the curve arrives along P_3 - P_1. Both are (1,1)/sqrt 2.
  const RationalBezierCurve2 curve({Vec2(0, 0), Vec2(0, 0), Vec2(1, 1), Vec2(1, 1)}, {1.0, 2.0, 3.0, 1.0});
  EXPECT_EQ(derivative(curve, 0.0, 1), Vec2(0, 0));
  const Vec2 expected = Vec2(1, 1) / std::sqrt(2.0);
  // A unit vector from a normalised nonzero derivative: a few ulps per coordinate.
  EXPECT_LT((tangent(curve, 0.0) - expected).norm(), 8 * eps);
  EXPECT_LT((tangent(curve, 1.0) - expected).norm(), 8 * eps);
}

TEST(CircleArc, PointsLieOnTheCircleAndSweepTheRightAngle) {
  const Vec2 center(0.3, -1.7);
  const double radius = 2.5;
  for (double start : {0.0, 1.0, -2.0}) {
    for (double degrees : {30.0, 90.0, 180.0, 270.0, 360.0, -30.0, -90.0, -180.0, -270.0, -360.0}) {
      const double sweep = degrees * pi / 180.0;
      const auto arcs = circle_arc(center, radius, start, start + sweep);
      // Pieces of at most 90 degrees.
      EXPECT_EQ(static_cast<int>(arcs.size()), std::max(1, static_cast<int>(std::round(std::abs(degrees) / 90.0))));
      for (const auto& arc : arcs) {
        EXPECT_EQ(arc.degree(), 2);
        for (int i = 0; i <= 100; ++i) {
          const double t = i / 100.0;
          // de Casteljau on homogeneous points of size <= (|c| + r/cos 45deg) and one division:
          // a few ulps of that scale; 8 eps * (|c| + 2r) bounds it (observed 1.2).
          EXPECT_NEAR((arc.evaluate(t) - center).norm(), radius, 8 * eps * (center.norm() + 2 * radius))
              << "sweep " << degrees << " t=" << t;
        }
      }
      // Ends where the angles say; each piece starts where the previous one ended.
      const Vec2 first = center + radius * Vec2(std::cos(start), std::sin(start));
      const Vec2 last = center + radius * Vec2(std::cos(start + sweep), std::sin(start + sweep));
      EXPECT_LT((arcs.front().evaluate(0.0) - first).norm(), 8 * eps * (center.norm() + radius));
      EXPECT_LT((arcs.back().evaluate(1.0) - last).norm(), 8 * eps * (center.norm() + radius));
      for (std::size_t p = 1; p < arcs.size(); ++p) {
        EXPECT_LT((arcs[p].evaluate(0.0) - arcs[p - 1].evaluate(1.0)).norm(), 8 * eps * (center.norm() + radius));
      }
      // The arc turns monotonically through exactly the sweep (not the complement); atan2 of
      // exactly computed cross/dot products is accurate to a few ulps per step, 64 steps a piece.
      EXPECT_NEAR(swept_angle(arcs, center), sweep, 1e-12) << "sweep " << degrees;
    }
  }
}

TEST(CircleArc, TangentIsPerpendicularToTheRadiusAndCurvatureIsOneOverRadius) {
  const Vec2 center(-4.0, 1.5);
  const double radius = 0.75;
  for (double degrees : {30.0, 120.0, -200.0, 360.0}) {
    const auto arcs = circle_arc(center, radius, 0.5, 0.5 + degrees * pi / 180.0);
    for (const auto& arc : arcs) {
      for (int i = 0; i <= 20; ++i) {
        const double t = i / 20.0;
        const Vec2 radial = (arc.evaluate(t) - center) / radius;
        const Vec2 unit_tangent = tangent(arc, t);
        // Both unit vectors are accurate to a few ulps of |c|/r + 2 (absolute): their dot
        // product vanishes to that.
        EXPECT_NEAR(radial.dot(unit_tangent), 0.0, 64 * eps * (center.norm() / radius + 2));
        // Counter-clockwise for a positive sweep: radial x tangent = +1, clockwise -1.
        EXPECT_NEAR(radial[0] * unit_tangent[1] - radial[1] * unit_tangent[0], degrees > 0 ? 1.0 : -1.0,
                    64 * eps * (center.norm() / radius + 2));
        // Curvature loses digits in proportion to |c|/r (the homogeneous derivatives carry the
        // centre, C' and C'' are differences of them): 256 eps (1 + |c|/r) relative (observed
        // 23 eps).
        EXPECT_NEAR(curvature(arc, t), 1.0 / radius, 256 * eps * (1 + center.norm() / radius) / radius);
      }
    }
  }
}

TEST(CircleArc, ThreeDimensionalArcInATiltedPlane) {
  const Vec3 center(1.0, -2.0, 0.5);
  const Vec3 x_axis = Vec3(1, 2, 2) / 3.0;
  const Vec3 y_axis = Vec3(2, 1, -2) / 3.0;
  const Vec3 normal = Vec3(-2, 2, -1) / 3.0;  // x_axis x y_axis, by hand
  const double radius = 3.0;
  for (double degrees : {30.0, 90.0, 180.0, 270.0, 360.0, -45.0, -300.0}) {
    const double sweep = degrees * pi / 180.0;
    const auto arcs = circle_arc<3>(center, x_axis, y_axis, radius, 0.25, 0.25 + sweep);
    for (const auto& arc : arcs) {
      for (int i = 0; i <= 50; ++i) {
        const Vec3 offset = arc.evaluate(i / 50.0) - center;
        // As in 2D, plus the axes' own rounding of one ulp each.
        EXPECT_NEAR(offset.norm(), radius, 64 * eps * (center.norm() + 2 * radius));
        EXPECT_NEAR(offset.dot(normal), 0.0, 64 * eps * (center.norm() + 2 * radius));
        EXPECT_NEAR(curvature(arc, i / 50.0), 1.0 / radius, 256 * eps * (1 + center.norm() / radius) / radius);
      }
    }
    const Vec3 end = center + radius * (std::cos(0.25 + sweep) * x_axis + std::sin(0.25 + sweep) * y_axis);
    EXPECT_LT((arcs.back().evaluate(1.0) - end).norm(), 16 * eps * (center.norm() + radius));
  }
}

TEST(CircleArc, RejectsBadInput) {
  const Vec2 c(0, 0);
  EXPECT_THROW(circle_arc(c, 0.0, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(circle_arc(c, -1.0, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(circle_arc(c, std::nan(""), 0.0, 1.0), InvalidInput);
  EXPECT_THROW(circle_arc(c, 1.0, 0.5, 0.5), InvalidInput);
  EXPECT_THROW(circle_arc(c, 1.0, 0.0, 2.0 * pi + 1e-6), InvalidInput);
  EXPECT_THROW(circle_arc(c, 1.0, 0.0, -7.0), InvalidInput);
  EXPECT_THROW(circle_arc(c, 1.0, 0.0, std::numeric_limits<double>::infinity()), InvalidInput);
  EXPECT_THROW(circle_arc(Vec2(std::nan(""), 0), 1.0, 0.0, 1.0), InvalidInput);
  const Vec3 o(0, 0, 0);
  EXPECT_THROW(circle_arc<3>(o, Vec3(1, 0, 0), Vec3(1, 1, 0) / std::sqrt(2.0), 1.0, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(circle_arc<3>(o, Vec3(2, 0, 0), Vec3(0, 1, 0), 1.0, 0.0, 1.0), InvalidInput);
}

RC_GTEST_PROP(CircleArc, EveryPointIsAtTheRadius, ()) {
  const Vec2 center = 10.0 * random_point<2>();
  const double radius = *rc::gen::inRange(1, 10001) / 1000.0;
  const double start = *rc::gen::inRange(-6283, 6284) / 1000.0;
  const int sweep_mrad = *rc::gen::suchThat(rc::gen::inRange(-6283, 6284), [](int k) { return k != 0; });
  const double sweep = sweep_mrad / 1000.0;
  const auto arcs = circle_arc(center, radius, start, start + sweep);
  for (const auto& arc : arcs) {
    for (int i = 0; i <= 16; ++i) {
      // As in the fixed cases: a few ulps of |c| + 2r.
      RC_ASSERT(std::abs((arc.evaluate(i / 16.0) - center).norm() - radius) <= 8 * eps * (center.norm() + 2 * radius));
    }
  }
}

RC_GTEST_PROP(RationalBezierCurve, EqualWeightsGiveThePolynomialCurve, ()) {
  const int n = *rc::gen::inRange(0, 11);
  std::vector<Vec3> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = random_point<3>();
  const double w = random_weight();
  const double a = random_coordinate();
  const double h = 0.25 + std::abs(random_coordinate()) * 4.0;
  const RationalBezierCurve3 rational(P, std::vector<double>(P.size(), w), a, a + h);
  const BezierCurve3 polynomial(P, a, a + h);
  double magnitude = 0.0;
  for (const auto& p : P) magnitude = std::max(magnitude, p.norm());
  const double t = a + h * (*rc::gen::inRange(0, 1001) / 1000.0);
  for (int k = 0; k <= n + 1; ++k) {
    // Both errors are de Casteljau roundings, <= gamma_{2n} times 2^k n!/(n-k)!/h^k max|P_i|
    // (weighted points and the common weight add 2 ulps): (8n + 8) eps times that scale.
    double scale = magnitude;
    for (int j = 0; j < k; ++j) scale *= 2.0 * std::max(n - j, 0) / h;
    const Vec3 difference = derivative(rational, t, k) - derivative(polynomial, t, k);
    RC_ASSERT(difference.norm() <= (8.0 * n + 8.0) * eps * scale);
  }
}

RC_GTEST_PROP(RationalBezierCurve, SplitAndElevationKeepThePoints, ()) {
  const int n = *rc::gen::inRange(1, 9);
  std::vector<Vec2> P(static_cast<std::size_t>(n) + 1);
  std::vector<double> w(P.size());
  double magnitude = 0.0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    P[i] = random_point<2>();
    w[i] = random_weight();
    magnitude = std::max(magnitude, P[i].norm());
  }
  const RationalBezierCurve2 curve(P, w, -1.0, 2.0);
  const double t_split = -1.0 + 3.0 * (*rc::gen::inRange(1, 1000) / 1000.0);
  const auto [left, right] = split(curve, t_split);
  const RationalBezierCurve2 elevated = elevate_degree(curve, *rc::gen::inRange(0, 4));
  RC_ASSERT(left.a() == -1.0 && left.b() == t_split && right.a() == t_split && right.b() == 2.0);
  // A rational point is a convex combination of the P_i with weights w_i B_i / W; its rounding
  // is gamma_{2n} sum |w_i P_i| B_i / W <= 2n eps (max w / min w) max|P|, for each of the two
  // evaluations and the split itself: 64 n eps * 16 * max|P| bounds it with room.
  const double tolerance = 64.0 * n * eps * 16.0 * magnitude;
  for (int i = 0; i <= 10; ++i) {
    const double t = -1.0 + 0.3 * i;
    const RationalBezierCurve2& piece = t <= t_split ? left : right;
    RC_ASSERT((piece.evaluate(t) - curve.evaluate(t)).norm() <= tolerance);
    RC_ASSERT((elevated.evaluate(t) - curve.evaluate(t)).norm() <= tolerance);
  }
  RC_ASSERT((left.evaluate(t_split) - right.evaluate(t_split)).norm() <= tolerance);
}

}  // namespace
}  // namespace patchwork
