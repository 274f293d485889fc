// Self-intersections: a cubic's loop at its closed-form double point, a cusp (none), a curve that
// retraces itself (an overlap), space curves within a tolerance.

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "queries/self_intersection.h"

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
