// The exact NURBS shapes (surfaces/nurbs_shapes.h) against closed forms.

#include "surfaces/nurbs_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "curves/rational_bezier_curve.h"
#include "surfaces/patch_set.h"
#include "surfaces/surface_integrals.h"

namespace patchwork {
namespace {

TEST(NurbsShapes, SphereIsExactWithItsPolesAndArea) {
  const Vec3 c(1, -2, 0.5);
  const double r = 3.0;
  const NurbsSurface sphere = nurbs_sphere(c, r);
  for (double u : {0.0, 0.1, 0.33, 0.5, 0.9, 1.0}) {
    for (double v : {0.0, 0.2, 0.5, 0.77, 1.0}) {
      const Vec3 p = sphere.evaluate(u, v);
      EXPECT_NEAR((p - c).norm(), r, 1e-14 * r);
      EXPECT_LT((unit_normal(sphere, u, v) - (p - c) / r).norm(), 1e-12) << u << " " << v;
    }
  }
  EXPECT_LT((sphere.evaluate(0.3, 0.0) - (c - r * Vec3::UnitZ())).norm(), 1e-14);
  EXPECT_LT((sphere.evaluate(0.3, 1.0) - (c + r * Vec3::UnitZ())).norm(), 1e-14);
  double total = 0.0;
  for (const AnyBezierPatch& patch : bezier_patches(sphere).patches)
    total += area(std::get<RationalBezierPatch>(patch), 1e-12).value;
  EXPECT_NEAR(total, 4 * std::numbers::pi * r * r, 1e-9);
}

TEST(NurbsShapes, AreasAgreeWithClosedForms) {
  const auto total_area = [](const NurbsSurface& surface) {
    double total = 0.0;
    for (const AnyBezierPatch& patch : bezier_patches(surface).patches) {
      total += area(std::get<RationalBezierPatch>(patch), 1e-12).value;
    }
    return total;
  };
  const double pi = std::numbers::pi;
  EXPECT_NEAR(total_area(nurbs_torus(Vec3(0, 0, 1), 2.0, 0.5)), 4 * pi * pi * 2.0 * 0.5, 1e-9);
  EXPECT_NEAR(total_area(nurbs_cylinder(Vec3(1, 1, 1), 0.75, 2.0)), 2 * pi * 0.75 * 2.0, 1e-9);
  EXPECT_NEAR(total_area(nurbs_cone(Vec3::Zero(), 1.0, 2.0)), pi * 1.0 * std::sqrt(5.0), 1e-9);
  // A revolution through a quarter turn of a line at distance 2 from the axis: a quarter of a
  // cylinder's side.
  const NurbsCurve<3> line(KnotVector(1, {0, 0, 1, 1}), {Vec3(2, 0, 0), Vec3(2, 0, 3)}, {1.0, 1.0});
  EXPECT_NEAR(total_area(revolve(line, Vec3::Zero(), Vec3::UnitZ(), pi / 2)), 0.25 * 2 * pi * 2 * 3, 1e-9);
}

TEST(NurbsShapes, ClosedShapesAreClosedPatchSets) {
  const PatchSet sphere(bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0)).patches);
  EXPECT_TRUE(report(sphere).closed);
  EXPECT_TRUE(report(sphere).consistently_oriented);
  const PatchSet torus(bezier_patches(nurbs_torus(Vec3::Zero(), 2.0, 0.5)).patches);
  EXPECT_TRUE(report(torus).closed);
  EXPECT_TRUE(report(torus).consistently_oriented);
  const PatchSet cylinder(bezier_patches(nurbs_cylinder(Vec3::Zero(), 1.0, 1.0)).patches);
  EXPECT_EQ(cylinder.boundary_loops().size(), 2u);
  const PatchSet cone(bezier_patches(nurbs_cone(Vec3::Zero(), 1.0, 1.0)).patches);
  EXPECT_EQ(cone.boundary_loops().size(), 1u);
  EXPECT_EQ(cone.collapsed_edges().size(), 4u);  // the apex, once per quarter
}

// The circle as one NURBS curve; pieces whose homogeneous points are scaled (a different first
// weight) join into the same curve.
TEST(NurbsShapes, CircleArcsJoinTheirPieces) {
  const NurbsCurve<3> circle =
      nurbs_circle_arc(Vec3(1, 2, 3), Vec3::UnitX(), Vec3::UnitY(), 2.0, 0.0, 2 * std::numbers::pi);
  for (int k = 0; k <= 40; ++k) EXPECT_NEAR((circle.evaluate(k / 40.0) - Vec3(1, 2, 3)).norm(), 2.0, 1e-14);
  std::vector<RationalBezierCurve<3>> pieces = circle_arc<3>(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1.0, 0.0, 2.0);
  ASSERT_GE(pieces.size(), 2u);
  std::vector<Vec4> scaled = pieces[1].homogeneous().control_points();
  for (Vec4& h : scaled) h *= 3.0;
  pieces[1] = RationalBezierCurve<3>(BezierCurve<4>(scaled));
  const NurbsCurve<3> joined = join_rational_pieces(pieces);
  for (int k = 0; k <= 40; ++k) EXPECT_NEAR(joined.evaluate(k / 40.0).norm(), 1.0, 1e-14);
  EXPECT_LT((joined.evaluate(1.0) - Vec3(std::cos(2.0), std::sin(2.0), 0)).norm(), 1e-14);
  pieces[1] = RationalBezierCurve<3>(BezierCurve<4>({Vec4(5, 5, 0, 1), Vec4(6, 5, 0, 1), Vec4(7, 5, 0, 1)}));
  EXPECT_THROW((void)join_rational_pieces(pieces), InvalidInput);
  EXPECT_THROW((void)join_rational_pieces(std::vector<RationalBezierCurve<3>>{}), InvalidInput);
}

TEST(NurbsShapes, ExtrusionAndThePolesAreExact) {
  // The extrusion of an arc: a quarter cylinder; its v = 1 row is the arc moved.
  const NurbsSurface wall =
      extrude(nurbs_circle_arc(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1.0, 0.0, 1.0), Vec3(0, 0, 2));
  for (double u : {0.0, 0.4, 1.0}) {
    EXPECT_NEAR(std::hypot(wall.evaluate(u, 1.0).x(), wall.evaluate(u, 1.0).y()), 1.0, 1e-15);
    EXPECT_EQ(wall.evaluate(u, 1.0).z(), 2.0);
  }
  // The sphere's pole rows are one point each (collapsed edges), not circles of radius 1e-16.
  const PatchSet sphere(bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0)).patches, 0.0);
  EXPECT_EQ(sphere.collapsed_edges().size(), 8u);
}

}  // namespace
}  // namespace patchwork
