// B-spline and NURBS curves through their Bezier pieces: intersections at breakpoints reported
// once, a curve against its knot-inserted self (one overlap), a bow-tie's one crossing, a NURBS
// circle through a sphere's equator.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "curves/bspline_conversion.h"
#include "curves/knot_insertion.h"
#include "queries/spline_intersection.h"
#include "surfaces/nurbs_shapes.h"

namespace spline_intersection_test {
namespace {

using namespace patchwork;

constexpr double pi = std::numbers::pi;

TEST(SplineIntersection, CirclesMeetingAtBreakpointsMeetOnceEach) {
  // The unit circle about (0, 0) from -pi/2 to pi (breakpoints at angles 0 and pi/2) and the unit
  // circle about (1, 1) from 0 to 2 pi (breakpoints at pi/2, pi, 3 pi/2) meet at (1, 0) and (0, 1),
  // both breakpoints of both curves, at right angles.
  const NurbsCurve2 first = join_rational_pieces(circle_arc(Vec2(0, 0), 1.0, -pi / 2, pi));
  const NurbsCurve2 second = join_rational_pieces(circle_arc(Vec2(1, 1), 1.0, 0.0, 2 * pi));
  const auto result = intersect_curves(first, second);
  ASSERT_EQ(result.points.size(), 2u);
  EXPECT_LT((result.points[0].point - Vec2(1, 0)).norm(), 1e-14);
  EXPECT_LT((result.points[1].point - Vec2(0, 1)).norm(), 1e-14);
  EXPECT_NEAR(result.points[0].t, 1.0 / 3.0, result.points[0].t_bound + 1e-15);  // piece 1 of 3 ends there
  EXPECT_NEAR(result.points[1].s, 0.5, result.points[1].s_bound + 1e-15);         // angle pi, piece 2 of 4
  for (const auto& x : result.points) EXPECT_FALSE(x.tangential);
}

TEST(SplineIntersection, CurveAgainstItsKnotInsertedSelfIsOneOverlap) {
  const BSplineCurve2 curve(clamped_uniform_knots(3, 6), {Vec2(0, 0), Vec2(1, 2), Vec2(2, -1), Vec2(3, 2), Vec2(4, 0), Vec2(5, 1)});
  const BSplineCurve2 refined = insert_knot(insert_knot(curve, 0.3), 0.8);
  const auto result = intersect_curves(curve, refined);
  EXPECT_TRUE(result.points.empty());
  ASSERT_EQ(result.overlaps.size(), 1u);
  EXPECT_NEAR(result.overlaps[0].t0, 0.0, 1e-9);
  EXPECT_NEAR(result.overlaps[0].t1, 1.0, 1e-9);
  EXPECT_NEAR(result.overlaps[0].s0, 0.0, 1e-9);
  EXPECT_NEAR(result.overlaps[0].s1, 1.0, 1e-9);
}

TEST(SplineIntersection, BowTieCrossesItselfOnceAtItsCentre) {
  // Q_{k+2} = -Q_k: the closed curve is symmetric about the origin, C(t + 1/2) = -C(t), so its one
  // crossing is the origin. Where it closes (t = 0, s = 1) is no crossing.
  const BSplineCurve2 bow_tie = periodic_curve(3, std::vector<Vec2>{Vec2(-2, -1), Vec2(-2, 1), Vec2(2, -1), Vec2(2, 1)});
  const auto result = self_intersections(bow_tie);
  ASSERT_EQ(result.points.size(), 1u);
  EXPECT_LT(result.points[0].point.norm(), 1e-14);
  EXPECT_NEAR(result.points[0].s - result.points[0].t, 0.5, 1e-12);
  EXPECT_FALSE(result.points[0].tangential);
  // The same polygon in the plane y = 3z / 4 in space, within a tolerance of 1e-9.
  std::vector<Vec3> lifted;
  for (const Vec2& q : {Vec2(-2, -1), Vec2(-2, 1), Vec2(2, -1), Vec2(2, 1)}) lifted.emplace_back(q.x(), 0.75 * q.y(), q.y());
  const auto space = self_intersections(periodic_curve(3, lifted), 1e-9);
  ASSERT_EQ(space.points.size(), 1u);
  EXPECT_LT(space.points[0].point.norm(), 1e-14);
}

TEST(SplineIntersection, NurbsCircleThroughTheSphereEquatorHitsTwice) {
  // The circle of radius 1 about (1, 0, 0) in the plane z = 0 meets the unit sphere where
  // 2 + 2 cos a = 1: (1/2, +-sqrt(3)/2, 0), on the equator, an edge between two patches.
  const NurbsBezierPatches sphere = bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0));
  const PatchSet set(sphere.patches, sphere.joins);
  const NurbsCurve3 circle = nurbs_circle_arc(Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1.0, 0.0, 2 * pi);
  const CurveSurfaceHits result = intersect_curve_surface(circle, set);
  ASSERT_EQ(result.hits.size(), 2u);
  EXPECT_LT((result.hits[0].point - Vec3(0.5, std::sqrt(3.0) / 2, 0)).norm(), 1e-13);
  EXPECT_LT((result.hits[1].point - Vec3(0.5, -std::sqrt(3.0) / 2, 0)).norm(), 1e-13);
}

}  // namespace
}  // namespace spline_intersection_test
