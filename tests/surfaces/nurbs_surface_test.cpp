// NURBS surfaces: evaluation against the extracted Bezier patches, knot insertion, derivatives,
// continuity from the knots, the exact shapes against closed forms.

#include "surfaces/nurbs_surface.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/patch_set.h"
#include "surfaces/surface_integrals.h"
#include "surfaces/surface_normal.h"
#include "tests/curves/bspline_generators.h"
#include "tests/surfaces/nurbs_generators.h"

namespace patchwork {
namespace {

// The extracted patch holding (u, v), and (u, v) in its parameters.
struct Located {
  std::size_t patch;
  double s;
  double t;
  double du;
  double dv;
};

Located locate(const NurbsBezierPatches& pieces, double u, double v) {
  const auto find = [](const std::vector<double>& breaks, double x) {
    std::size_t k = 0;
    while (k + 2 < breaks.size() && x >= breaks[k + 1]) ++k;
    return k;
  };
  const std::size_t a = find(pieces.breaks_u, u), b = find(pieces.breaks_v, v);
  const double du = pieces.breaks_u[a + 1] - pieces.breaks_u[a], dv = pieces.breaks_v[b + 1] - pieces.breaks_v[b];
  return {a + static_cast<std::size_t>(pieces.spans_u) * b, (u - pieces.breaks_u[a]) / du, (v - pieces.breaks_v[b]) / dv,
          du, dv};
}

PartialDerivatives<3> patch_partials(const AnyBezierPatch& patch, double s, double t, int order) {
  if (const auto* polynomial = std::get_if<BezierPatch3>(&patch)) return partial_derivatives(*polynomial, s, t, order);
  return partial_derivatives(std::get<RationalBezierPatch>(patch), s, t, order);
}

RC_GTEST_PROP(NurbsSurface, ExtractedPatchesAreTheSurfaceWithItsDerivatives, ()) {
  const bool rational = *rc::gen::arbitrary<bool>();
  const NurbsSurface surface = *nurbs_gen::nurbs_surface(rational);
  const NurbsBezierPatches pieces = bezier_patches(surface);
  RC_ASSERT(pieces.spans_u + 1 == static_cast<int>(pieces.breaks_u.size()));
  RC_ASSERT(pieces.patches.size() == static_cast<std::size_t>(pieces.spans_u * pieces.spans_v));
  RC_ASSERT(pieces.continuity_u == surface.knots_u().breakpoint_continuity());
  for (int k = 0; k < 6; ++k) {
    const double u = *bspline_gen::parameter(surface.knots_u());
    const double v = *bspline_gen::parameter(surface.knots_v());
    const Located at = locate(pieces, u, v);
    const PartialDerivatives<3> F = partial_derivatives(surface, u, v, 2);
    const PartialDerivatives<3> G = patch_partials(pieces.patches[at.patch], at.s, at.t, 2);
    // Weights up to 16 times apart and points up to 10 amplify the rounding of the quotient.
    for (int a = 0; a <= 2; ++a) {
      for (int b = 0; a + b <= 2; ++b) {
        const Vec3 chain = G.at(a, b) / (std::pow(at.du, a) * std::pow(at.dv, b));
        RC_ASSERT((F.at(a, b) - chain).norm() <= 1e-9 * (1 + chain.norm()));
      }
    }
    RC_ASSERT((surface.evaluate(u, v) - F.at(0, 0)).norm() <= 1e-12 * (1 + F.at(0, 0).norm()));
  }
}

RC_GTEST_PROP(NurbsSurface, KnotInsertionKeepsTheSurface, ()) {
  const NurbsSurface surface = *nurbs_gen::nurbs_surface(true);
  const double u = *bspline_gen::parameter(surface.knots_u());
  const double v = *bspline_gen::parameter(surface.knots_v());
  const int times = *rc::gen::inRange(1, 3);
  // Insertion may not push a knot past multiplicity p; stay within it.
  const int room_u = surface.degree_u() - surface.knots_u().multiplicity(u);
  const int room_v = surface.degree_v() - surface.knots_v().multiplicity(v);
  RC_PRE(room_u >= times && room_v >= times);
  const NurbsSurface refined = insert_knot_v(insert_knot_u(surface, u, times), v, times);
  RC_ASSERT(refined.count_u() == surface.count_u() + times);
  RC_ASSERT(refined.count_v() == surface.count_v() + times);
  for (int k = 0; k < 6; ++k) {
    const double x = *bspline_gen::parameter(surface.knots_u());
    const double y = *bspline_gen::parameter(surface.knots_v());
    const Vec3 p = surface.evaluate(x, y);
    RC_ASSERT((refined.evaluate(x, y) - p).norm() <= 1e-11 * (1 + p.norm()));
  }
}

TEST(NurbsSurface, ContinuityAcrossPatchesIsThatOfTheKnots) {
  // Uniform spans (the patches' own parameters have equal speeds across each edge), bicubic,
  // interior knots of multiplicity 1 and 2 in u (C^2, C^1) and 3 in v (C^0).
  const KnotVector U(3, {0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3});
  const KnotVector V(3, {0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2});
  std::vector<Vec3> points;
  for (int j = 0; j < V.control_point_count(); ++j) {
    for (int i = 0; i < U.control_point_count(); ++i) points.emplace_back(i, j, std::sin(1.3 * i + 0.7 * j * j));
  }
  const NurbsSurface surface(U, V, points);
  EXPECT_FALSE(surface.rational());
  const NurbsBezierPatches pieces = bezier_patches(surface);
  ASSERT_EQ(pieces.spans_u, 3);
  ASSERT_EQ(pieces.spans_v, 2);
  EXPECT_EQ(pieces.continuity_u, (std::vector<int>{2, 1}));
  EXPECT_EQ(pieces.continuity_v, (std::vector<int>{0}));
  // The patch set finds the same joins from the points: C^2 and C^1 across u, C^0 across v.
  const PatchSet set(pieces.patches);
  EXPECT_EQ(set.shared_edges().size(), 7u);
  for (const SharedEdge& s : set.shared_edges()) {
    const std::uint32_t a = std::min(s.first.patch, s.second.patch), b = std::max(s.first.patch, s.second.patch);
    const int expected = b == a + 1 ? pieces.continuity_u[a % 3] : pieces.continuity_v[0];
    EXPECT_EQ(s.continuity.ck, expected) << a << " " << b;
    EXPECT_LT(s.continuity.gap, 1e-15);
  }
}

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
  for (const AnyBezierPatch& patch : bezier_patches(sphere).patches) total += area(std::get<RationalBezierPatch>(patch), 1e-12).value;
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

TEST(NurbsSurface, BadInputIsRefused) {
  const KnotVector U(1, {0, 0, 1, 1});
  EXPECT_THROW(NurbsSurface(U, U, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}), InvalidInput);
  const std::vector<Vec3> four(4, Vec3::Zero());
  EXPECT_THROW(NurbsSurface(U, U, four, {1, 1, 0, 1}), InvalidInput);
  EXPECT_THROW(NurbsSurface(U, U, four, {1, 1, std::nan(""), 1}), InvalidInput);
  EXPECT_THROW(NurbsSurface(U, U, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3(0, std::nan(""), 0)}), InvalidInput);
  const NurbsSurface flat(U, U, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)});
  EXPECT_THROW((void)flat.evaluate(1.5, 0.5), InvalidInput);
  EXPECT_THROW((void)flat.evaluate(0.5, std::nan("")), InvalidInput);
  EXPECT_THROW((void)partial_derivatives(flat, 0.5, 0.5, -1), InvalidInput);
  EXPECT_THROW((void)nurbs_torus(Vec3::Zero(), 1.0, 2.0), InvalidInput);
  EXPECT_THROW((void)revolve(NurbsCurve<3>(KnotVector(1, {0, 0, 1, 1}), {Vec3(1, 0, 0), Vec3(1, 0, 1)}, {1, 1}),
                             Vec3::Zero(), Vec3::Zero(), 1.0),
               InvalidInput);
}

}  // namespace
}  // namespace patchwork
