#include "tests/support/refined_maximum.h"
#include "curves/bounding_box.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "curves/bernstein.h"
#include "curves/rational_bezier_curve.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

constexpr double kEps = std::numeric_limits<double>::epsilon();

using testing::refined_max;

// Whether `inner` lies in `outer` enlarged by `slack` on every side.
template <int Dim>
bool inside(const Box<Dim>& inner, const Box<Dim>& outer, double slack) {
  return (inner.min().array() >= outer.min().array() - slack).all() &&
         (inner.max().array() <= outer.max().array() + slack).all();
}

// Coordinate c of the points as Bernstein coefficients of a scalar polynomial.
template <int Dim>
std::vector<double> coordinate(const std::vector<Point<Dim>>& points, int c) {
  std::vector<double> values;
  for (const auto& p : points) values.push_back(p[c]);
  return values;
}

// Each coordinate x_c(s)/w(s) (w = 1 for a polynomial curve), maximised and minimised by refined
// sampling through scalar de Casteljau, is within `slack` of the box's side: the box contains
// the curve and is tight.
template <int Dim>
void check_box_is_tight(const std::vector<Point<Dim>>& numerators, const std::vector<double>& weights,
                        const Box<Dim>& box, double slack) {
  for (int c = 0; c < Dim; ++c) {
    const std::vector<double> x = coordinate<Dim>(numerators, c);
    const auto value = [&](double s) { return bernstein_evaluate(x, s) / bernstein_evaluate(weights, s); };
    const double hi = refined_max(value);
    const double lo = -refined_max([&](double s) { return -value(s); });
    RC_ASSERT(std::abs(hi - box.max()[c]) <= slack);
    RC_ASSERT(std::abs(lo - box.min()[c]) <= slack);
  }
}

TEST(BoundingBox, CubicWithClosedFormExtremes) {
  // x = 3s, y = 9s(1-s)(1-2s): y' = 9(1 - 6s + 6s^2) vanishes at s = 1/2 -+ sqrt(3)/6, where
  // s(1-s) = 1/6 and 1-2s = +-sqrt(3)/3: y = +-sqrt(3)/2. The control polygon reaches +-3.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(1, 3), Vec2(2, -3), Vec2(3, 0)}, 1.0, 5.0);
  const Box<2> box = bounding_box(curve);
  // Flat at the extremes: only de Casteljau's rounding, gamma_6 times p~ <= 3.
  const double tolerance = 3 * gamma(6);
  EXPECT_EQ(box.min().x(), 0.0);
  EXPECT_EQ(box.max().x(), 3.0);
  EXPECT_NEAR(box.max().y(), std::sqrt(3.0) / 2, tolerance);
  EXPECT_NEAR(box.min().y(), -std::sqrt(3.0) / 2, tolerance);
  const Box<2> polygon = control_box(curve);
  EXPECT_EQ(polygon.min(), Vec2(0, -3));
  EXPECT_EQ(polygon.max(), Vec2(3, 3));
  EXPECT_TRUE(polygon.contains(box));
  EXPECT_LT(box.max().y(), polygon.max().y() - 2.0);  // strictly inside where the polygon overshoots
}

TEST(BoundingBox, ParabolaArchReachesThreeQuarters) {
  // y = 9s(1-s) (control ordinates 0, 3, 3, 0) peaks at s = 1/2 with 9/4 < 3.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(1, 3), Vec2(2, 3), Vec2(3, 0)});
  const Box<2> box = bounding_box(curve);
  EXPECT_NEAR(box.max().y(), 2.25, 3 * gamma(6));
  EXPECT_EQ(box.min().y(), 0.0);
  EXPECT_EQ(control_box(curve).max().y(), 3.0);
}

TEST(BoundingBox, PointAndSegment) {
  const Box<3> point = bounding_box(BezierCurve3({Vec3(1, -2, 3)}));
  EXPECT_EQ(point.min(), Vec3(1, -2, 3));
  EXPECT_EQ(point.max(), Vec3(1, -2, 3));
  const Box<3> segment = bounding_box(BezierCurve3({Vec3(1, -2, 3), Vec3(-1, 5, 3)}, -4.0, 4.0));
  EXPECT_EQ(segment.min(), Vec3(-1, -2, 3));
  EXPECT_EQ(segment.max(), Vec3(1, 5, 3));
  // A scalar polynomial: the box is its range, here of 4s(1-s) - 1 on [0, 1]: [-1, 0].
  const Box<1> range = bounding_box(BezierCurve1({Point<1>(-1.0), Point<1>(1.0), Point<1>(-1.0)}));
  EXPECT_EQ(range.min()[0], -1.0);
  EXPECT_EQ(range.max()[0], 0.0);
}

RC_GTEST_PROP(BoundingBox, ContainsCurveAndIsTight, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const Box<3> box = bounding_box(curve);
  const int n = curve.degree();
  // The box's sides are curve values (gamma_{2n} M each), compared with other curve values.
  const double slack =
      2 * gamma(2 * n) * max_abs<3>(curve.control_points()) + 4 * kUnit * max_abs<3>(curve.control_points());
  check_box_is_tight<3>(curve.control_points(), {1.0}, box, slack);
  RC_ASSERT(inside<3>(box, control_box(curve), slack));
}

RC_GTEST_PROP(BoundingBox, MonotoneControlPolygonGivesEndPointBox, ()) {
  // Sorted coordinates make every coordinate monotone: the box is that of P_0 and P_n, and at
  // s = 0 and 1 evaluation is exact.
  const int n = *curve_gen::degree(0, 12);
  std::vector<Vec2> P(static_cast<std::size_t>(n) + 1);
  for (int c = 0; c < 2; ++c) {
    // A coarse grid, so that equal neighbours (a zero derivative at an end) occur too.
    auto values = *rc::gen::container<std::vector<int>>(static_cast<std::size_t>(n) + 1, rc::gen::inRange(-6, 7));
    std::sort(values.begin(), values.end());
    if (c == 1) std::reverse(values.begin(), values.end());
    for (int i = 0; i <= n; ++i) P[static_cast<std::size_t>(i)][c] = values[static_cast<std::size_t>(i)];
  }
  const BezierCurve2 curve(P);
  Box<2> expected(P.front());
  expected.extend(P.back());
  const Box<2> box = bounding_box(curve);
  RC_ASSERT(box.min() == expected.min());
  RC_ASSERT(box.max() == expected.max());
}

TEST(BoundingBox, TightOnIntervalFarFromZero) {
  // On [1e9, 1e9 + 1e-6] neighbouring global parameters are ulp(1e9) = 1.2e-7 apart, an eighth
  // of the interval: the extremes must be evaluated at their local parameters, not at a rounded
  // t = a + s (b - a). The cubic of CubicWithClosedFormExtremes, y in [-sqrt(3)/2, sqrt(3)/2]
  // with extremes at s = 1/2 -+ sqrt(3)/6 (t would round to s = 1/4, y = 0.84375):
  const double a = 1e9;
  const double b = 1e9 + 1e-6;
  const BezierCurve2 curve({Vec2(0, 0), Vec2(1, 3), Vec2(2, -3), Vec2(3, 0)}, a, b);
  const Box<2> box = bounding_box(curve);
  EXPECT_NEAR(box.max().y(), std::sqrt(3.0) / 2, 3 * gamma(6));
  EXPECT_NEAR(box.min().y(), -std::sqrt(3.0) / 2, 3 * gamma(6));
  // A unit circle arc from -0.3 to 1.2 rad (one rational quadratic): x peaks at angle 0, away
  // from the middle of the parameter interval.
  const std::vector<RationalBezierCurve2> arc = circle_arc(Vec2(0, 0), 1.0, -0.3, 1.2);
  ASSERT_EQ(arc.size(), 1u);
  const RationalBezierCurve2 far(with_interval(arc[0].homogeneous(), a, b));
  // Circle points to a few ulps (weights and control points are rounded once or twice).
  EXPECT_NEAR(bounding_box(far).max().x(), 1.0, 8 * kEps);
  EXPECT_NEAR(bounding_box(arc[0]).max().x(), 1.0, 8 * kEps);
}

RC_GTEST_PROP(BoundingBox, DoesNotDependOnParameterInterval, ()) {
  // The same control points on [0, 1] and on an interval far from 0 trace the same set.
  const auto curve = *curve_gen::bezier_curve<2>(0, 12);
  const double offset = *rc::gen::element(1e3, 1e6, -3e7);
  const double length = *rc::gen::element(1e-3, 0.7, 5.0);
  const BezierCurve2 far = with_interval(curve, offset, offset + length);
  const Box<2> unit_box = bounding_box(curve);
  const Box<2> far_box = bounding_box(far);
  const int n = curve.degree();
  // Both boxes hold curve values at the same extremes: gamma_{2n} M each.
  const double slack =
      2 * gamma(2 * n) * max_abs<2>(curve.control_points()) + 4 * kUnit * max_abs<2>(curve.control_points());
  RC_ASSERT((unit_box.min() - far_box.min()).cwiseAbs().maxCoeff() <= slack);
  RC_ASSERT((unit_box.max() - far_box.max()).cwiseAbs().maxCoeff() <= slack);
}

TEST(BoundingBox, RationalCircularArc) {
  // The arc of the unit circle from -60 to 60 degrees: P_1 = (2, 0) where the end tangents
  // meet, weight cos 60 = 1/2. The box is [1/2, 1] x [-sqrt(3)/2, sqrt(3)/2] (x = 1 at angle
  // 0); the control polygon reaches x = 2.
  const double h = std::sqrt(3.0) / 2;
  const RationalBezierCurve2 arc({Vec2(0.5, -h), Vec2(2, 0), Vec2(0.5, h)}, {1.0, 0.5, 1.0}, 2.0, 3.0);
  const Box<2> box = bounding_box(arc);
  // Circle points to a few ulps (the weights are exact, sqrt(3)/2 is rounded once).
  EXPECT_NEAR(box.min().x(), 0.5, 4 * kEps);
  EXPECT_NEAR(box.max().x(), 1.0, 4 * kEps);
  EXPECT_NEAR(box.min().y(), -h, 4 * kEps);
  EXPECT_NEAR(box.max().y(), h, 4 * kEps);
  // A quarter circle (1, 0) -> (0, 1) spans exactly its end points' box.
  const RationalBezierCurve2 quarter({Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {1.0, std::sqrt(0.5), 1.0});
  const Box<2> quarter_box = bounding_box(quarter);
  EXPECT_NEAR((quarter_box.min() - Vec2(0, 0)).norm(), 0.0, 4 * kEps);
  EXPECT_NEAR((quarter_box.max() - Vec2(1, 1)).norm(), 0.0, 4 * kEps);
  // A half circle about the origin: x in [-1, 1], y in [0, 1], from two quadratic pieces.
  Box<2> half;
  for (const RationalBezierCurve2& piece : circle_arc(Vec2(0, 0), 1.0, 0.0, std::numbers::pi))
    half.extend(bounding_box(piece));
  EXPECT_NEAR(half.min().x(), -1.0, 4 * kEps);
  EXPECT_NEAR(half.max().x(), 1.0, 4 * kEps);
  EXPECT_NEAR(half.min().y(), 0.0, 4 * kEps);
  EXPECT_NEAR(half.max().y(), 1.0, 4 * kEps);
}

RC_GTEST_PROP(BoundingBox, RationalContainsCurveAndIsTight, ()) {
  const auto polynomial = *curve_gen::bezier_curve_on_interval<2>(1, 8);
  const int n = polynomial.degree();
  const auto weights =
      *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(n) + 1, curve_gen::coordinate(0.25, 4.0));
  const RationalBezierCurve2 curve(polynomial.control_points(), weights, polynomial.a(), polynomial.b());
  const Box<2> box = bounding_box(curve);
  std::vector<Vec2> numerators;
  for (int i = 0; i <= n; ++i)
    numerators.push_back(weights[static_cast<std::size_t>(i)] *
                         polynomial.control_points()[static_cast<std::size_t>(i)]);
  // Rational values: numerator and denominator each carry gamma_{2n+1} relative to their
  // absolute sums, amplified by max w / min w <= 16 in the quotient.
  const double slack = 2 * 16 * 2 * gamma(2 * n + 2) * max_abs<2>(polynomial.control_points());
  check_box_is_tight<2>(numerators, weights, box, slack);
}

}  // namespace
}  // namespace patchwork
