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
  return {a + static_cast<std::size_t>(pieces.spans_u) * b, (u - pieces.breaks_u[a]) / du,
          (v - pieces.breaks_v[b]) / dv, du, dv};
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
  RC_ASSERT(pieces.continuity_v == surface.knots_v().breakpoint_continuity());
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
    // evaluate (the basis sum without derivatives) against the piece's de Casteljau point.
    RC_ASSERT((surface.evaluate(u, v) - G.at(0, 0)).norm() <= 1e-10 * (1 + G.at(0, 0).norm()));
    // The normal from the surface is the piece's (both the limit normal where S_u x S_v vanishes).
    const AnyBezierPatch& piece = pieces.patches[at.patch];
    try {
      const Vec3 n = unit_normal(surface, u, v);
      const Vec3 m = std::holds_alternative<BezierPatch3>(piece)
                         ? unit_normal(std::get<BezierPatch3>(piece), at.s, at.t)
                         : unit_normal(std::get<RationalBezierPatch>(piece), at.s, at.t);
      RC_ASSERT((n - m).norm() <= 1e-6);
    } catch (const NumericalError&) {
      // A random net can be degenerate around a point (no normal): both must say so.
      RC_ASSERT_THROWS_AS(std::holds_alternative<BezierPatch3>(piece)
                              ? unit_normal(std::get<BezierPatch3>(piece), at.s, at.t)
                              : unit_normal(std::get<RationalBezierPatch>(piece), at.s, at.t),
                          NumericalError);
    }
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

// The patch set of an extraction takes the neighbours' joins from the knots (their continuity in
// the surface's parameter, here with spans of unequal length, where the pieces' own parameters
// are only C^0), and finds the closed seam from the points.
TEST(NurbsSurface, PatchSetTakesTheJoinsFromTheKnots) {
  const NurbsSurface torus = nurbs_torus(Vec3::Zero(), 2.0, 0.5);
  const NurbsBezierPatches pieces = bezier_patches(torus);
  EXPECT_EQ(pieces.joins.size(), 24u);  // 4 x 4 patches: 3 x 4 joins each way
  const PatchSet known(pieces.patches, pieces.joins);
  const PatchSet found(pieces.patches);
  EXPECT_EQ(known.shared_edges().size(), 32u);
  EXPECT_EQ(found.shared_edges().size(), 32u);
  EXPECT_TRUE(report(known).closed);
  // Unequal spans: knots 0, 1, 3 in u (C^2 there, cubic); the pieces' own parameters do not
  // join C^1, the knots say C^2.
  const KnotVector U(3, {0, 0, 0, 0, 1, 3, 3, 3, 3});
  const KnotVector V(1, {0, 0, 1, 1});
  std::vector<Vec3> points;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 5; ++i) points.emplace_back(i, j, std::cos(1.1 * i) + 0.3 * j);
  }
  const NurbsBezierPatches uneven = bezier_patches(NurbsSurface(U, V, points));
  ASSERT_EQ(uneven.joins.size(), 1u);
  const PatchSet with_knots(uneven.patches, uneven.joins);
  const PatchSet from_points(uneven.patches);
  ASSERT_EQ(with_knots.shared_edges().size(), 1u);
  ASSERT_EQ(from_points.shared_edges().size(), 1u);
  EXPECT_EQ(with_knots.shared_edges()[0].continuity.ck, 2);
  EXPECT_EQ(from_points.shared_edges()[0].continuity.ck, 0);
  EXPECT_TRUE(with_knots.shared_edges()[0].continuity.g1);
  // A join that is not one is refused: patch 0's u0 edge is not patch 1's u1.
  const std::vector<KnownJoin> wrong = {{{0, PatchEdge::u0}, {1, PatchEdge::u1}, false, 2}};
  EXPECT_THROW(PatchSet(uneven.patches, wrong), InvalidInput);
  const std::vector<KnownJoin> twice = {uneven.joins[0], uneven.joins[0]};
  EXPECT_THROW(PatchSet(uneven.patches, twice), InvalidInput);
}

// Equal weights c != 1 are stored as 1: a cut by knot insertion (Boehm's affine combinations of
// c are not always c) keeps the surface polynomial.
TEST(NurbsSurface, EqualWeightsStayPolynomialThroughKnotInsertion) {
  const KnotVector U(1, {0, 0, 1, 1});
  const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1)};
  const NurbsSurface surface(U, U, square, std::vector<double>(4, std::sqrt(0.5)));
  EXPECT_FALSE(surface.rational());
  EXPECT_EQ(surface.weight(1, 1), 1.0);
  const NurbsBezierPatches pieces = bezier_patches(surface, 1.0 / 3, 1.0, 0.0, 1.0);
  ASSERT_EQ(pieces.patches.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<BezierPatch3>(pieces.patches[0]));
}

// A range ending at existing knots: at a single knot of a cubic (raised to multiplicity 3) and
// at a double one; every point of the range is the surface's.
TEST(NurbsSurface, RangesEndingAtKnots) {
  const KnotVector U(3, {0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3});
  const KnotVector V(1, {0, 0, 1, 1});
  std::vector<Vec3> points;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 7; ++i) points.emplace_back(i, j, std::sin(0.8 * i) + 0.2 * j);
  }
  const NurbsSurface surface(U, V, points);
  const NurbsBezierPatches pieces = bezier_patches(surface, 1.0, 2.0, 0.0, 1.0);
  ASSERT_EQ(pieces.breaks_u, (std::vector<double>{1.0, 2.0}));
  ASSERT_EQ(pieces.patches.size(), 1u);
  const BezierPatch3& patch = std::get<BezierPatch3>(pieces.patches[0]);
  for (double s : {0.0, 0.3, 0.7, 1.0}) {
    for (double t : {0.0, 0.5, 1.0}) EXPECT_LT((patch.evaluate(s, t) - surface.evaluate(1.0 + s, t)).norm(), 1e-13);
  }
  EXPECT_THROW((void)bezier_patches(surface, 2.0, 2.0, 0.0, 1.0), InvalidInput);
  EXPECT_THROW((void)bezier_patches(surface, -0.5, 2.0, 0.0, 1.0), InvalidInput);
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
