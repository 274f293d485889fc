// Curve-surface intersections against closed forms (lines through spheres, vertical lines through
// height patches), exact root counts (a cubic against a plane patch, Sturm in GMP rationals), and
// hits on shared edges and corners of patch sets reported once.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "queries/curve_intersection.h"
#include "queries/curve_surface_intersection.h"
#include "surfaces/nurbs_shapes.h"
#include "tests/queries/exact_root_count.h"

namespace curve_surface_intersection_test {
namespace {

using namespace patchwork;

// The unit sphere about the origin as a patch set of 8 Bezier patches (NURBS extraction, with
// its known joins): poles at v = 0 and v = 1 rows, seams where the octants meet.
const PatchSet& unit_sphere() {
  static const PatchSet set = [] {
    const NurbsBezierPatches pieces = bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0));
    return PatchSet(pieces.patches, pieces.joins);
  }();
  return set;
}

// The line segment from p - 2d to p + 2d (|d| = 1) meets the unit sphere where
// |p + lambda d|^2 = 1: lambda = -p.d +- sqrt((p.d)^2 - |p|^2 + 1), at t = (lambda + 2) / 4.
std::vector<double> sphere_parameters(const Vec3& p, const Vec3& d) {
  const double b = p.dot(d), c = p.squaredNorm() - 1.0;
  const double root = std::sqrt(b * b - c);
  return {(-b - root + 2.0) / 4.0, (-b + root + 2.0) / 4.0};
}

void expect_two_sphere_hits(const Vec3& p, const Vec3& d) {
  const BezierCurve3 line({p - 2 * d, p + 2 * d});
  const CurveSurfaceHits result = intersect_curve_surface(line, unit_sphere());
  const std::vector<double> expected = sphere_parameters(p, d);
  ASSERT_EQ(result.hits.size(), 2u) << "line through " << p.transpose();
  for (int k = 0; k < 2; ++k) {
    const CurveSurfaceHit& hit = result.hits[k];
    EXPECT_LE(std::abs(hit.t - expected[k]), hit.t_bound + 1e-14);
    EXPECT_NEAR(hit.point.norm(), 1.0, 1e-14);
    EXPECT_LE(hit.distance, 8 * result.eps);
  }
}

TEST(CurveSurfaceIntersection, LineThroughSphereHitsTwiceAtTheClosedForm) {
  expect_two_sphere_hits(Vec3(0.1, 0.3, 0.2), Vec3(1, 0, 0));
  expect_two_sphere_hits(Vec3(-0.2, 0.1, 0.35), Vec3(0.48, 0.6, 0.64));
  for (const CurveSurfaceHit& hit : intersect_curve_surface(BezierCurve3({Vec3(-2, 0.3, 0.2), Vec3(2, 0.3, 0.2)}), unit_sphere()).hits) {
    EXPECT_FALSE(hit.tangential);
    EXPECT_LT(hit.t_bound, 1e-13);
  }
}

TEST(CurveSurfaceIntersection, HitOnASharedEdgeOrCornerIsReportedOnce) {
  // Through the equator (z = 0, the edge between the upper and lower patches).
  expect_two_sphere_hits(Vec3(0, 0.3, 0), Vec3(1, 0, 0));
  // Along the x axis: (+-1, 0, 0) are corners where four patches meet.
  expect_two_sphere_hits(Vec3(0, 0, 0), Vec3(1, 0, 0));
  // Along y: the seam u = 0 / u = 1 of the revolution and the equator.
  expect_two_sphere_hits(Vec3(0, 0, 0), Vec3(0, 1, 0));
}

TEST(CurveSurfaceIntersection, LineThroughThePolesHitsEachOnce) {
  // The poles are collapsed edges: F_u = 0 there, so no Krawczyk certificate; each is one contact.
  const BezierCurve3 axis({Vec3(0.0, 0.0, -2.0), Vec3(0.0, 0.0, 2.0)});
  const CurveSurfaceHits result = intersect_curve_surface(axis, unit_sphere());
  ASSERT_EQ(result.hits.size(), 2u);
  EXPECT_LE(std::abs(result.hits[0].t - 0.25), result.hits[0].t_bound + 1e-14);
  EXPECT_LE(std::abs(result.hits[1].t - 0.75), result.hits[1].t_bound + 1e-14);
  EXPECT_LT(result.hits[0].t_bound, 1e-6);
}

TEST(CurveSurfaceIntersection, TangentLineTouchesOnce) {
  // Tangent to the sphere at p = (0.48, 0.6, 0.64) along d = (0.8, 0, -0.6) (p.d = 0).
  const Vec3 p(0.48, 0.6, 0.64), d(0.8, 0, -0.6);
  const CurveSurfaceHits result = intersect_curve_surface(BezierCurve3({p - d, p + d}), unit_sphere());
  ASSERT_EQ(result.hits.size(), 1u);
  EXPECT_TRUE(result.hits[0].tangential);
  EXPECT_LT((result.hits[0].point - p).norm(), 1e-6);
  EXPECT_LE(std::abs(result.hits[0].t - 0.5), result.hits[0].t_bound);
  // Moved off the sphere by 1e-6 it misses.
  EXPECT_TRUE(intersect_curve_surface(BezierCurve3({1.000001 * p - d, 1.000001 * p + d}), unit_sphere()).hits.empty());
}

// A bicubic height patch over [-1, 1]^2 with x, y affine in (u, v): x = 2u - 1, y = 2v - 1.
BezierPatch3 height_patch(const std::vector<int>& heights) {
  std::vector<Vec3> points;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) points.emplace_back(-1.0 + 2.0 * i / 3.0, -1.0 + 2.0 * j / 3.0, heights[i + 4 * j] / 8.0);
  }
  return BezierPatch3(3, 3, points);
}

RC_GTEST_PROP(CurveSurfaceIntersection, VerticalLineHitsAHeightPatchOnceAtItsHeight, ()) {
  const BezierPatch3 patch = height_patch(*rc::gen::container<std::vector<int>>(16, rc::gen::inRange(-16, 17)));
  const double u = *rc::gen::inRange(1, 64) / 64.0, v = *rc::gen::inRange(1, 64) / 64.0;
  const Vec3 foot(2 * u - 1, 2 * v - 1, 0.0);
  const BezierCurve3 line({foot - Vec3(0, 0, 4), foot + Vec3(0, 0, 4)});
  const CurveSurfaceHits result = intersect_curve_surface(line, patch);
  RC_ASSERT(result.hits.size() == 1u);
  const CurveSurfaceHit& hit = result.hits[0];
  RC_ASSERT(!hit.tangential);
  RC_ASSERT(std::abs(hit.u - u) <= hit.u_bound);
  RC_ASSERT(std::abs(hit.v - v) <= hit.v_bound);
  const double height = patch.evaluate(u, v).z();
  RC_ASSERT(std::abs(hit.t - (height + 4.0) / 8.0) <= hit.t_bound + 1e-15);
}

// A cubic against the plane patch z = 0 over [-4, 4]^2 (bicubic, affine in u, v): the hits are the
// distinct roots of z(t) in [0, 1], counted exactly.
RC_GTEST_PROP(CurveSurfaceIntersection, CubicAgainstPlaneMatchesExactRootCount, ()) {
  const std::vector<int> z = *rc::gen::container<std::vector<int>>(4, rc::gen::inRange(-8, 9));
  std::vector<Vec3> points;
  std::vector<mpq_class> coefficients;
  for (int i = 0; i < 4; ++i) {
    points.emplace_back(*rc::gen::inRange(-16, 17) / 8.0, *rc::gen::inRange(-16, 17) / 8.0, z[i] / 8.0);
    coefficients.emplace_back(z[i], 8);
  }
  const exact::Polynomial f = exact::bernstein_to_power(coefficients);
  RC_PRE(!exact::trimmed(f).empty());
  std::vector<Vec3> plane;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) plane.emplace_back(-4.0 + 8.0 * i / 3.0, -4.0 + 8.0 * j / 3.0, 0.0);
  }
  const CurveSurfaceHits result = intersect_curve_surface(BezierCurve3(points), BezierPatch3(3, 3, plane));
  int covered = 0;
  for (std::size_t k = 0; k < result.hits.size(); ++k) {
    const CurveSurfaceHit& hit = result.hits[k];
    if (k > 0) RC_ASSERT(result.hits[k - 1].t + result.hits[k - 1].t_bound < hit.t - hit.t_bound);
    const int roots = exact::distinct_roots(f, mpq_class(std::max(0.0, hit.t - hit.t_bound)), mpq_class(std::min(1.0, hit.t + hit.t_bound)));
    if (!hit.tangential) RC_ASSERT(roots == 1);
    covered += roots;
  }
  RC_ASSERT(covered == exact::distinct_roots(f, 0, 1));
}

TEST(CurveSurfaceIntersection, CubicTouchingThePlaneAtItsEndIsOneTangentialHit) {
  // z(t) = -(1 - t)^2 (1 + 2t): a double root at the end t = 1, where the curve arrives parallel
  // to the plane z = 0 (found by the property above; Gauss-Newton alone stalled at 2.2e-13).
  std::vector<Vec3> plane;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) plane.emplace_back(-4.0 + 8.0 * i / 3.0, -4.0 + 8.0 * j / 3.0, 0.0);
  }
  const BezierCurve3 cubic({Vec3(-2, -2, -1), Vec3(-2, -2, -1), Vec3(0.625, -1.875, 0), Vec3(-2, -2, 0)});
  const CurveSurfaceHits result = intersect_curve_surface(cubic, BezierPatch3(3, 3, plane));
  ASSERT_EQ(result.hits.size(), 1u);
  EXPECT_TRUE(result.hits[0].tangential);
  EXPECT_LE(1.0 - result.hits[0].t, result.hits[0].t_bound);
  EXPECT_LE(result.hits[0].distance, result.eps);
}

TEST(CurveSurfaceIntersection, RationalCurveOnRationalPatch) {
  // The circle of radius 0.6 about (0.5, 0.4, 0) in the plane y = 0.4 meets the unit sphere where
  // x^2 + z^2 = 0.84 and (x - 0.5)^2 + z^2 = 0.36: x = 0.73, z = sqrt(0.3071), at the angle
  // acos(0.23 / 0.6) = 1.178; in the octant x, y, z >= 0.
  const double pi = std::numbers::pi;
  const Vec3 centre(0.5, 0.4, 0), x_axis(1, 0, 0), z_axis(0, 0, 1);
  const RationalBezierPatch octant = sphere_octant(Vec3::Zero(), 1.0);
  const auto crossing = circle_arc(centre, x_axis, z_axis, 0.6, 0.05, pi / 2);
  ASSERT_EQ(crossing.size(), 1u);
  const CurveSurfaceHits result = intersect_curve_surface(crossing[0], octant);
  ASSERT_EQ(result.hits.size(), 1u);
  EXPECT_FALSE(result.hits[0].tangential);
  EXPECT_LT((result.hits[0].point - Vec3(0.73, 0.4, std::sqrt(0.3071))).norm(), 1e-13);
  // The arc up to the angle 1.0 stays outside the sphere.
  EXPECT_TRUE(intersect_curve_surface(circle_arc(centre, x_axis, z_axis, 0.6, 0.05, 1.0)[0], octant).hits.empty());
}

}  // namespace
}  // namespace curve_surface_intersection_test
