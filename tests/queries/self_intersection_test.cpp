// Self-intersections: a cubic's loop at its closed-form double point, a cusp (none), a curve that
// retraces itself (an overlap), cubics folded back along a line (overlaps ending at the closed-form
// turning points; every partner of a point found, exactly), space curves within a tolerance.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "queries/self_intersection.h"
#include "tests/queries/exact_root_count.h"

namespace self_intersection_test {
namespace {

using namespace patchwork;

// Mirror-symmetric about x = 1/2: x(t) = 9t/2 - 21t^2/2 + 7t^3, y = 3t(1-t). The double point has
// x(t) = 1/2 with t != 1/2: 2x - 1 = (2t - 1)(7t^2 - 7t + 1), so t, s = (7 -+ sqrt(21)) / 14 and
// y = 3 t (1 - t) = 3/7.
const BezierCurve2 loop({Vec2(0, 0), Vec2(1.5, 1), Vec2(-0.5, 1), Vec2(1, 0)});

TEST(SelfIntersection, CubicLoopCrossesItselfOnceAtTheClosedForm) {
  const auto result = self_intersections(loop);
  ASSERT_EQ(result.points.size(), 1u);
  EXPECT_TRUE(result.overlaps.empty());
  const auto& x = result.points[0];
  EXPECT_FALSE(x.tangential);
  const double t = (7 - std::sqrt(21.0)) / 14, s = (7 + std::sqrt(21.0)) / 14;
  EXPECT_LE(std::abs(x.t - t), x.t_bound + 1e-15);
  EXPECT_LE(std::abs(x.s - s), x.s_bound + 1e-15);
  EXPECT_LT(x.t_bound, 1e-12);
  EXPECT_LT((x.point - Vec2(0.5, 3.0 / 7.0)).norm(), 1e-14);
}

TEST(SelfIntersection, CuspIsNotACrossing) {
  // C'(1/2) = 0: a cusp at (1/2, 3/4), where the branches meet only at the cusp point itself.
  const BezierCurve2 cusp({Vec2(0, 0), Vec2(1, 1), Vec2(0, 1), Vec2(1, 0)});
  const auto result = self_intersections(cusp);
  EXPECT_TRUE(result.points.empty());
  EXPECT_TRUE(result.overlaps.empty());
  // Pulled a little apart the control points make a small loop, which is found.
  const BezierCurve2 small_loop({Vec2(0, 0), Vec2(1.05, 1), Vec2(-0.05, 1), Vec2(1, 0)});
  const auto looped = self_intersections(small_loop);
  ASSERT_EQ(looped.points.size(), 1u);
  EXPECT_NEAR(looped.points[0].t + looped.points[0].s, 1.0, 1e-12);  // mirror-symmetric
  EXPECT_NEAR(looped.points[0].point.x(), 0.5, 1e-12);
}

// Cusps where the branches do not mirror each other. A cubic with a cusp has no other double point
// (a rational cubic has one singular point), so nothing is reported. Halved to depth 40 around the
// cusp, the pieces once met in points and tiny overlaps.
TEST(SelfIntersection, AsymmetricCuspsAreNotCrossings) {
  // C' = (-3, 0) (1 - t)^2 + (9/2, 3/2) t (1 - t) + (0, -9/4) t^2 vanishes at t = 2/5, which no
  // halving reaches: x' = 3/2 (1 - t)(5t - 2), y' = 3/4 t (2 - 5t).
  const BezierCurve2 at_two_fifths({Vec2(0.25, -0.25), Vec2(-0.75, -0.25), Vec2(0, 0), Vec2(0, -0.75)});
  // C' = (9/2, -9/4) (1 - t)^2 + (-15/2, 3) t (1 - t) + (3, -3/4) t^2 vanishes at t = 1/2:
  // x' = 3/2 (2t - 1)(5t - 3), y' = -3/4 (2t - 1)(4t - 3).
  const BezierCurve2 at_one_half({Vec2(-1, 0.75), Vec2(0.5, 0), Vec2(-0.75, 0.5), Vec2(0.25, 0.25)});
  // C' = (-3/4, -3/2) (1 - t)^2 + (3/2, 9/2) t (1 - t) + (-3/4, -3) t^2 vanishes at t = 1/2 too:
  // x' = -3/4 (2t - 1)^2, y' = -3/2 (2t - 1)(3t - 1), so x ~ (t - 1/2)^3, y ~ (t - 1/2)^2 there.
  const BezierCurve2 semicubical({Vec2(0, 0.25), Vec2(-0.25, -0.25), Vec2(0, 0.5), Vec2(-0.25, -0.5)});
  for (const auto& [cusp, t] :
       {std::pair{at_two_fifths, 0.4}, std::pair{at_one_half, 0.5}, std::pair{semicubical, 0.5}}) {
    EXPECT_LT(derivative(cusp, t, 1).norm(), 1e-15);
    const auto result = self_intersections(cusp);
    EXPECT_TRUE(result.points.empty()) << "cusp at " << t;
    EXPECT_TRUE(result.overlaps.empty()) << "cusp at " << t;
  }
}

TEST(SelfIntersection, PointCurveIsOnePiece) {
  // Every hodograph coefficient vanishes: one piece, nothing to report (it was split 2^40 ways).
  const auto result = self_intersections(BezierCurve2({Vec2(1, 1), Vec2(1, 1), Vec2(1, 1)}));
  EXPECT_TRUE(result.points.empty());
  EXPECT_TRUE(result.overlaps.empty());
}

TEST(SelfIntersection, RationalLoopKeepsItsSymmetry) {
  const RationalBezierCurve2 rational({Vec2(0, 0), Vec2(1.5, 1), Vec2(-0.5, 1), Vec2(1, 0)}, {1, 3, 3, 1});
  const auto result = self_intersections(rational);
  ASSERT_EQ(result.points.size(), 1u);
  EXPECT_NEAR(result.points[0].point.x(), 0.5, 1e-13);
  EXPECT_NEAR(result.points[0].t + result.points[0].s, 1.0, 1e-12);
}

TEST(SelfIntersection, RetracingCurveIsAnOverlap) {
  // x = 2t(1 - t): out to x = 1/2 and back over the same points, C(t) = C(1 - t).
  const BezierCurve2 retracing({Vec2(0, 0), Vec2(1, 0), Vec2(0, 0)});
  const auto result = self_intersections(retracing);
  EXPECT_TRUE(result.points.empty());
  ASSERT_EQ(result.overlaps.size(), 1u);
  EXPECT_NEAR(result.overlaps[0].t0, 0.0, 1e-9);
  EXPECT_NEAR(result.overlaps[0].t1, 0.5, 1e-9);
  EXPECT_NEAR(result.overlaps[0].s0, 1.0, 1e-9);
  EXPECT_NEAR(result.overlaps[0].s1, 0.5, 1e-9);
}

// A segment traversed back and forth, its end control point repeated: x(t) = 1/4 - 9/4 t (1 - t)^2
// on y = -1/4, x'(t) = -9/4 (1 - t)(1 - 3t). x falls from 1/4 to x(1/3) = -1/12 and comes back
// to 1/4 at t = 1 (where x' = 0 too, without turning): [0, 1/3] is retraced by [1/3, 1] backwards.
// x(t) = x(s) for t != s is s^2 + (t - 2) s + (1 - t)^2 = 0, so the partner of t in [0, 1/3] is
// s(t) = (2 - t - sqrt(t (4 - 3t))) / 2, from s(0) = 1 to s(1/3) = 1/3.
TEST(SelfIntersection, FoldedCubicRetracesItsFirstThird) {
  const BezierCurve2 folded({Vec2(0.25, -0.25), Vec2(-0.5, -0.25), Vec2(0.25, -0.25), Vec2(0.25, -0.25)});
  const auto partner = [](double t) { return (2 - t - std::sqrt(t * (4 - 3 * t))) / 2; };
  EXPECT_NEAR(partner(0.0), 1.0, 1e-15);
  EXPECT_NEAR(partner(1.0 / 3), 1.0 / 3, 1e-15);
  EXPECT_LT((folded.evaluate(0.2) - folded.evaluate(partner(0.2))).norm(), 1e-15);
  const auto result = self_intersections(folded);
  EXPECT_TRUE(result.points.empty());  // the fold is no crossing, nor are C(0) = C(1) or the stop at t = 1
  ASSERT_EQ(result.overlaps.size(), 1u);
  EXPECT_NEAR(result.overlaps[0].t0, 0.0, 1e-14);
  EXPECT_NEAR(result.overlaps[0].t1, 1.0 / 3, 1e-14);
  EXPECT_NEAR(result.overlaps[0].s0, 1.0, 1e-14);
  EXPECT_NEAR(result.overlaps[0].s1, 1.0 / 3, 1e-14);
}

// An S folded twice along the diagonal: C(t) = x(t) (1, 1), x(t) = 3/4 t (1 - t)(1 - 2t),
// x' = 3/4 (1 - 6t + 6t^2) = 0 at t1 = (3 - sqrt 3) / 6 and t2 = (3 + sqrt 3) / 6. x rises from 0
// to x(t1), falls through x(1/2) = 0 to x(t2) = -x(t1) and rises back to 0 at t = 1: the first run
// is retraced by the middle one from t = 1/2 back to t1, the last run retraces the middle one
// from t = 1/2 to t2, and C(0) = C(1) is the curve closing (the two outer runs share only that
// point).
TEST(SelfIntersection, CubicFoldedTwiceAlongADiagonalGivesTwoOverlaps) {
  const BezierCurve2 folded({Vec2(0, 0), Vec2(0.25, 0.25), Vec2(-0.25, -0.25), Vec2(0, 0)});
  const double t1 = (3 - std::sqrt(3.0)) / 6, t2 = (3 + std::sqrt(3.0)) / 6;
  const auto result = self_intersections(folded);
  EXPECT_TRUE(result.points.empty());
  ASSERT_EQ(result.overlaps.size(), 2u);
  const CurveOverlap& first = result.overlaps[0];
  EXPECT_NEAR(first.t0, 0.0, 1e-14);
  EXPECT_NEAR(first.t1, t1, 1e-14);
  EXPECT_NEAR(first.s0, 0.5, 1e-14);
  EXPECT_NEAR(first.s1, t1, 1e-14);
  const CurveOverlap& second = result.overlaps[1];
  EXPECT_NEAR(second.t0, 0.5, 1e-14);
  EXPECT_NEAR(second.t1, t2, 1e-14);
  EXPECT_NEAR(second.s0, 1.0, 1e-14);
  EXPECT_NEAR(second.s1, t2, 1e-14);
}

TEST(SelfIntersection, FoldedSpaceCubicRetracesItsFirstThird) {
  // The first fold on the line through (1/4, -1/4, 1/2) in direction (1, 2, 2), within 1e-6.
  const Vec3 origin(0.25, -0.25, 0.5), direction(1, 2, 2);
  std::vector<Vec3> points;
  for (const double x : {0.0, -0.75, 0.0, 0.0}) points.push_back(origin + x * direction);
  const auto result = self_intersections(BezierCurve3(points), 1e-6);
  EXPECT_TRUE(result.points.empty());
  ASSERT_EQ(result.overlaps.size(), 1u);
  EXPECT_NEAR(result.overlaps[0].t0, 0.0, 1e-14);
  EXPECT_NEAR(result.overlaps[0].t1, 1.0 / 3, 1e-14);
  EXPECT_NEAR(result.overlaps[0].s0, 1.0, 1e-14);
  EXPECT_NEAR(result.overlaps[0].s1, 1.0 / 3, 1e-14);
}

// Random cubics on a line, C(t) = origin + x(t) d with x's Bernstein coefficients k_i / 4: at
// rational t the partners s != t of t (the roots of x(s) - x(t), counted exactly by Sturm) are as
// many as the overlaps holding t inside their t or s interval, each overlap's ends match, and
// nothing else is reported.
RC_GTEST_PROP(SelfIntersection, FoldedLinesMissNoPartner, ()) {
  const auto k = *rc::gen::container<std::vector<int>>(4, rc::gen::inRange(-4, 5));
  const int dx = *rc::gen::inRange(-2, 3), dy = *rc::gen::inRange(-2, 3);
  RC_PRE(dx != 0 || dy != 0);
  RC_PRE(*std::min_element(k.begin(), k.end()) < *std::max_element(k.begin(), k.end()));
  const Vec2 origin(*rc::gen::inRange(-4, 5) / 4.0, *rc::gen::inRange(-4, 5) / 4.0), d(dx, dy);
  std::vector<Vec2> points;
  std::vector<mpq_class> x;
  for (const int k_i : k) points.push_back(origin + (k_i / 4.0) * d), x.push_back(mpq_class(k_i, 4));
  const BezierCurve2 curve(points);
  const auto result = self_intersections(curve);
  RC_ASSERT(result.points.empty());
  const auto along = [&](double t) { return (curve.evaluate(t) - origin).dot(d) / d.squaredNorm(); };
  for (const CurveOverlap& o : result.overlaps) {
    RC_ASSERT(o.t0 < o.t1);
    RC_ASSERT(o.s0 != o.s1);
    RC_ASSERT(std::abs(along(o.t0) - along(o.s0)) <= 1e-13);
    RC_ASSERT(std::abs(along(o.t1) - along(o.s1)) <= 1e-13);
  }
  const exact::Polynomial power = exact::bernstein_to_power(x);
  for (int m = 1; m < 29; ++m) {
    const mpq_class t(m, 29);
    const double t_value = m / 29.0;
    const bool near_an_end = std::any_of(result.overlaps.begin(), result.overlaps.end(), [&](const CurveOverlap& o) {
      return std::min({std::abs(t_value - o.t0), std::abs(t_value - o.t1), std::abs(t_value - o.s0),
                       std::abs(t_value - o.s1)}) < 1e-9;
    });
    if (near_an_end) continue;
    exact::Polynomial f = power;
    f[0] -= exact::value(power, t);
    if (exact::multiplicity(f, t) > 1) continue;  // a turning point
    const int partners = exact::distinct_roots(f, 0, 1) - 1;
    int covered = 0;
    for (const CurveOverlap& o : result.overlaps) {
      covered += o.t0 < t_value && t_value < o.t1;
      covered += std::min(o.s0, o.s1) < t_value && t_value < std::max(o.s0, o.s1);
    }
    RC_ASSERT(covered == partners);
  }
}

TEST(SelfIntersection, SpaceLoopWithinTheTolerance) {
  // The planar loop with z = h t^3: the branches pass h (s^3 - t^3) = 0.5454... h apart.
  const double h = 1e-3;
  const BezierCurve3 space({Vec3(0, 0, 0), Vec3(1.5, 1, 0), Vec3(-0.5, 1, 0), Vec3(1, 0, h)});
  EXPECT_TRUE(self_intersections(space, 1e-4).points.empty());
  const auto result = self_intersections(space, 1e-2);
  EXPECT_TRUE(result.overlaps.empty());  // pieces near the crossing lie within 1e-2, but are short
  ASSERT_EQ(result.points.size(), 1u);
  const double t = (7 - std::sqrt(21.0)) / 14, s = (7 + std::sqrt(21.0)) / 14;
  EXPECT_NEAR(result.points[0].distance, h * (s * s * s - t * t * t), 1e-6);
  EXPECT_LE(std::abs(result.points[0].t - t), result.points[0].t_bound);
  EXPECT_THROW(self_intersections(space, -1.0), InvalidInput);
}

}  // namespace
}  // namespace self_intersection_test
