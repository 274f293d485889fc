// Closest points against closed forms (circle, sphere, torus), dense sampling, the tessellated
// teapot's mesh distance within its error bound, and the orthogonality of the foot's residual.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "io/bpt.h"
#include "queries/closest_point.h"
#include "queries/patch_bvh.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/surface_normal.h"
#include "surfaces/tessellator.h"
#include "tests/queries/query_fixtures.h"

namespace closest_point_test {
namespace {

using namespace patchwork;

const auto& set_of = patchwork::testing::nurbs_patch_set;

const auto& teapot = patchwork::testing::teapot_set;

// The certified interval holds the true distance, and is as narrow as asked (or the search says
// how many pieces it took).
void expect_certified(double lower, double distance, double truth, double size) {
  EXPECT_LE(lower, truth + 1e-13 * size);
  EXPECT_GE(distance, truth - 1e-13 * size);
  EXPECT_LE(distance - truth, 1e-11 * size);
  EXPECT_LE(distance - lower, 2e-12 * size);
}

TEST(ClosestPointCurve, CircleClosedFormAndCentre) {
  const NurbsCurve<2> circle = join_rational_pieces(circle_arc(Vec2(1, 2), 3.0, 0.0, 2 * std::numbers::pi));
  for (const Vec2& q : {Vec2(10, 2), Vec2(1, 2.5), Vec2(-4, -7), Vec2(1 + 3 / std::sqrt(2.0), 2 + 3 / std::sqrt(2.0))}) {
    const auto result = closest_point(circle, q);
    const double truth = std::abs((q - Vec2(1, 2)).norm() - 3.0);
    expect_certified(result.lower_bound, result.distance, truth, 8.5);
    EXPECT_NEAR((result.point - Vec2(1, 2)).norm(), 3.0, 1e-14 * 8);
    EXPECT_NEAR((result.point - Vec2(1, 2)).normalized().dot((q - Vec2(1, 2)).normalized()), 1.0, 1e-12);
    EXPECT_FALSE(result.attained_more_than_once);
  }
  const auto centre = closest_point(circle, Vec2(1, 2));
  EXPECT_NEAR(centre.distance, 3.0, 1e-14 * 8);
  EXPECT_TRUE(centre.attained_more_than_once);
}

// The squared distance of a polynomial curve, sampled densely and refined by golden sections:
// an independent upper bound on the minimum that is tight to the sampling.
template <int Dim>
double sampled_minimum(const BezierCurve<Dim>& curve, const Point<Dim>& q) {
  const int samples = 400;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    double lo = std::max(0.0, (k - 1.0) / samples), hi = std::min(1.0, (k + 1.0) / samples);
    for (int it = 0; it < 60; ++it) {
      const double a = lo + (hi - lo) * 0.381966, b = lo + (hi - lo) * 0.618034;
      if ((curve.evaluate(a) - q).norm() < (curve.evaluate(b) - q).norm())
        hi = b;
      else
        lo = a;
    }
    best = std::min({best, (curve.evaluate(0.5 * (lo + hi)) - q).norm(), (curve.evaluate(k / double(samples)) - q).norm()});
  }
  return best;
}

RC_GTEST_PROP(ClosestPointCurve, GlobalMinimumOfRandomCubics, ()) {
  const int degree = *rc::gen::inRange(1, 7);
  std::vector<Vec2> points;
  for (int i = 0; i <= degree; ++i)
    points.emplace_back(*rc::gen::inRange(-1000, 1000) / 100.0, *rc::gen::inRange(-1000, 1000) / 100.0);
  const BezierCurve2 curve(points);
  const Vec2 q(*rc::gen::inRange(-1500, 1500) / 100.0, *rc::gen::inRange(-1500, 1500) / 100.0);
  const auto result = closest_point(curve, q);
  const double sampled = sampled_minimum(curve, q);
  // Global: never worse than the sampled minimum; certified: the interval is below it.
  RC_ASSERT(result.distance <= sampled + 1e-12 * 30);
  RC_ASSERT(result.lower_bound <= result.distance);
  RC_ASSERT(result.distance - result.lower_bound <= 1e-10);
  RC_ASSERT((curve.evaluate(result.t) - result.point).norm() == 0.0);
  // An interior foot's residual is orthogonal to the tangent.
  if (result.t > 1e-9 && result.t < 1 - 1e-9 && result.distance > 1e-9) {
    const Vec2 d = derivative(curve, result.t, 1);
    RC_ASSERT(std::abs(d.normalized().dot((result.point - q).normalized())) <= 1e-7);
  }
}

TEST(ClosestPointCurve, BSplinePieceAndEnds) {
  // A 3D B-spline: the foot of a point beyond its end is the end.
  const BSplineCurve<3> curve(KnotVector(2, {0, 0, 0, 1, 2, 2, 2}), {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 0, 1), Vec3(3, 0, 0)});
  const auto result = closest_point(curve, Vec3(10, 0, 0));
  EXPECT_EQ(result.t, 2.0);
  EXPECT_NEAR(result.distance, 7.0, 1e-14);
}

TEST(ClosestPointCurve, BadPoint) {
  const BezierCurve2 curve({Vec2(0, 0), Vec2(1, 1)});
  EXPECT_THROW(closest_point(curve, Vec2(std::nan(""), 0)), InvalidInput);
}

TEST(ClosestPointSurface, SphereClosedFormInsideOutsideOnAndCentre) {
  const PatchSet sphere = set_of(nurbs_sphere(Vec3(0.5, -1, 2), 2.0));
  const PatchBvh bvh(sphere);
  const Vec3 centre(0.5, -1, 2);
  for (const Vec3& offset : {Vec3(5, 1, 2), Vec3(0.3, -0.2, 0.1), Vec3(0, 0, 7), Vec3(0, 0, -1.5)}) {
    const auto result = closest_point(bvh, centre + offset);
    const double truth = std::abs(offset.norm() - 2.0);
    expect_certified(result.lower_bound, result.distance, truth, bvh.size());
    EXPECT_NEAR((result.point - centre).norm(), 2.0, 1e-14 * 8);
    EXPECT_NEAR((result.point - centre).normalized().dot(offset.normalized()), 1.0, 1e-12);
    EXPECT_FALSE(result.attained_more_than_once);
  }
  // Near the centre nearly every point is nearly a foot: the search runs out of its budget of
  // pieces, and the interval it certifies is wider, but still holds the truth.
  const auto near_centre = closest_point(bvh, centre + Vec3(1e-3, 0, 0));
  EXPECT_LE(near_centre.lower_bound, 1.999);
  EXPECT_GE(near_centre.distance, 1.999 - 1e-14 * 8);
  EXPECT_FALSE(near_centre.attained_more_than_once);
  EXPECT_NEAR(near_centre.distance, 1.999, 1e-14 * 8);
  EXPECT_LE(near_centre.distance - near_centre.lower_bound, 1e-4);
  // A point on the surface: distance zero to rounding, and the interval starts at zero.
  const Vec3 on = centre + 2.0 * Vec3(1, 2, 2) / 3.0;
  const auto zero = closest_point(bvh, on);
  EXPECT_LE(zero.distance, 1e-15 * 8);
  EXPECT_EQ(zero.lower_bound, 0.0);
  // The centre: every point is a foot.
  const auto middle = closest_point(bvh, centre);
  EXPECT_NEAR(middle.distance, 2.0, 1e-14 * 8);
  EXPECT_TRUE(middle.attained_more_than_once);
}

TEST(ClosestPointSurface, TorusClosedForm) {
  const double major = 3.0, minor = 1.0;
  const PatchSet torus = set_of(nurbs_torus(Vec3::Zero(), major, minor));
  const PatchBvh bvh(torus);
  for (const Vec3& q : {Vec3(5, 1, 0.5), Vec3(3.2, 0.1, -0.3), Vec3(-1, 0.5, 2), Vec3(0.4, -4, 1.2)}) {
    const double ring = std::hypot(q.x(), q.y());
    const double truth = std::abs(std::hypot(ring - major, q.z()) - minor);
    const auto result = closest_point(bvh, q);
    expect_certified(result.lower_bound, result.distance, truth, bvh.size());
  }
  // On the axis every point of the inner equator's circle... is not the foot: the nearest points
  // form the circle of the tube nearest the axis, a medial point.
  const auto axis = closest_point(bvh, Vec3(0, 0, 0));
  EXPECT_NEAR(axis.distance, major - minor, 1e-13);
  EXPECT_TRUE(axis.attained_more_than_once);
}

TEST(ClosestPointSurface, PointMovedAlongTheNormalHasThatDistance) {
  const PatchSet& set = teapot();
  const PatchBvh bvh(set);
  int checked = 0;
  for (std::uint32_t p = 0; p < set.count(); p += 3) {
    for (const auto& [u, v] : {std::pair{0.3, 0.6}, std::pair{0.71, 0.2}}) {
      const Vec3 point = set.control_nets()[p].evaluate(u, v);
      const Vec3 n = unit_normal(set.control_nets()[p], u, v);
      const double d = 1e-3;  // below the local radius of curvature everywhere on the teapot
      for (double sign : {1.0, -1.0}) {
        const auto result = closest_point(bvh, point + sign * d * n);
        expect_certified(result.lower_bound, result.distance, d, bvh.size());
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 40);
}

// The distance from q to a triangle mesh, by brute force (Ericson's closest point on a triangle).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

TEST(ClosestPointSurface, TeapotAgainstTheTessellatedMeshWithinItsBound) {
  const PatchSet& set = teapot();
  const PatchBvh bvh(set);
  TessellationOptions options;
  options.relative_tolerance = 1e-3;
  const Tessellation mesh = tessellate(set, options);
  const double bound = mesh.error_bound;
  for (const Vec3& q : {Vec3(0, 0, 0), Vec3(4, 1, 2), Vec3(-3.5, 0.2, 1.0), Vec3(0, 0, 4), Vec3(0.1, -2.5, 0.7),
                        Vec3(2.9, 0, 2.3), Vec3(0, 0, -1)}) {
    double mesh_distance = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.mesh.triangle_count(); ++t) {
      const Vec3& a = mesh.mesh.positions[mesh.mesh.indices[3 * t]];
      const Vec3& b = mesh.mesh.positions[mesh.mesh.indices[3 * t + 1]];
      const Vec3& c = mesh.mesh.positions[mesh.mesh.indices[3 * t + 2]];
      mesh_distance = std::min(mesh_distance, (closest_on_triangle(q, a, b, c) - q).norm());
    }
    const auto result = closest_point(bvh, q);
    // The surface is within `bound` of the mesh both ways, so the true distance is within
    // `bound` of the mesh distance; the certified interval must meet that range.
    EXPECT_LE(result.lower_bound, mesh_distance + bound) << q.transpose();
    EXPECT_GE(result.distance, mesh_distance - bound) << q.transpose();
    EXPECT_LE(result.distance - result.lower_bound, 1e-11 * bvh.size());
    EXPECT_EQ(result.point, set.control_nets()[result.patch].evaluate(result.u, result.v));
  }
}

RC_GTEST_PROP(ClosestPointSurface, TeapotFootResidualIsOrthogonalAndGlobal, ()) {
  static const PatchBvh bvh(teapot());
  const Vec3 q(*rc::gen::inRange(-600, 600) / 100.0, *rc::gen::inRange(-400, 400) / 100.0, *rc::gen::inRange(-200, 500) / 100.0);
  const auto result = closest_point(bvh, q);
  RC_ASSERT(result.lower_bound <= result.distance);
  RC_ASSERT(result.distance - result.lower_bound <= 1e-11 * bvh.size());
  // Global: no sample of any patch is nearer.
  for (std::uint32_t p = 0; p < teapot().count(); ++p)
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) RC_ASSERT((teapot().control_nets()[p].evaluate(i / 8.0, j / 8.0) - q).norm() >= result.lower_bound);
  // Inside a patch and off the surface, the residual is orthogonal to both tangents.
  if (result.u > 1e-6 && result.u < 1 - 1e-6 && result.v > 1e-6 && result.v < 1 - 1e-6 && result.distance > 1e-6) {
    const BezierPatch3& patch = teapot().control_nets()[result.patch];
    const Vec3 r = (result.point - q).normalized();
    const Vec3 fu = derivative(patch, result.u, result.v, 1, 0), fv = derivative(patch, result.u, result.v, 0, 1);
    if (fu.norm() > 1e-3 && fv.norm() > 1e-3) {
      RC_ASSERT(std::abs(fu.normalized().dot(r)) <= 1e-7);
      RC_ASSERT(std::abs(fv.normalized().dot(r)) <= 1e-7);
    }
  }
}

TEST(ClosestPointSurface, TeapotPoleAndSinglePatches) {
  const PatchSet& set = teapot();
  // Straight above the lid's knob: the foot is the pole, on the axis.
  const auto above = closest_point(set, Vec3(0, 0, 5));
  EXPECT_NEAR(above.point.x(), 0.0, 1e-12);
  EXPECT_NEAR(above.point.y(), 0.0, 1e-12);
  EXPECT_NEAR(above.distance, 5.0 - above.point.z(), 1e-12);
  // One patch alone agrees with the set's answer restricted to it when the foot is on it.
  const auto on_set = closest_point(set, Vec3(3.6, 0.3, 1.2));
  const auto on_patch = closest_point(set.control_nets()[on_set.patch], Vec3(3.6, 0.3, 1.2));
  EXPECT_NEAR(on_patch.distance, on_set.distance, 1e-12);
}

TEST(ClosestPointSurface, BadPoint) {
  const PatchSet& set = teapot();
  try {
    closest_point(set, Vec3(0, std::numeric_limits<double>::infinity(), 0));
    FAIL() << "no exception";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()), "closest_point: argument 'point' is not finite (0, inf, 0)");
  }
}

}  // namespace
}  // namespace closest_point_test
