// Free-form records as surfaces: a record's NURBS surface, its range cut out by knot insertion,
// and the way back.

#include "io/freeform_surfaces.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "surfaces/nurbs_shapes.h"

namespace patchwork {
namespace {

// A bicubic B-spline record on knots with an interior double knot in u.
FreeformSurface wavy_record() {
  FreeformSurface record;
  record.basis = FreeformBasis::bspline;
  record.degree_u = 3;
  record.degree_v = 2;
  record.parameters_u = {0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3};
  record.parameters_v = {0, 0, 0, 0.5, 1, 1, 1};
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 7; ++i) record.points.emplace_back(i, j, std::sin(0.9 * i + 0.4 * j));
  }
  record.weights.assign(record.points.size(), 1.0);
  record.u0 = 0, record.u1 = 3, record.v0 = 0, record.v1 = 1;
  return record;
}

// The patch holding (u, v) of a piece list, evaluated in its parameters.
Vec3 evaluate_pieces(const NurbsBezierPatches& pieces, double u, double v) {
  std::size_t a = 0, b = 0;
  while (a + 2 < pieces.breaks_u.size() && u >= pieces.breaks_u[a + 1]) ++a;
  while (b + 2 < pieces.breaks_v.size() && v >= pieces.breaks_v[b + 1]) ++b;
  const double s = (u - pieces.breaks_u[a]) / (pieces.breaks_u[a + 1] - pieces.breaks_u[a]);
  const double t = (v - pieces.breaks_v[b]) / (pieces.breaks_v[b + 1] - pieces.breaks_v[b]);
  const AnyBezierPatch& patch = pieces.patches[a + static_cast<std::size_t>(pieces.spans_u) * b];
  if (const auto* p = std::get_if<BezierPatch3>(&patch)) return p->evaluate(s, t);
  return std::get<RationalBezierPatch>(patch).evaluate(s, t);
}

TEST(FreeformSurfaces, TheRangeIsCutOutOfTheSurface) {
  FreeformSurface record = wavy_record();
  const NurbsSurface surface = nurbs_surface(record);
  // [0.4, 2.5] x [0.2, 0.9]: cut inside spans, across the double knot at 2.
  record.u0 = 0.4, record.u1 = 2.5, record.v0 = 0.2, record.v1 = 0.9;
  const NurbsBezierPatches pieces = freeform_bezier_patches(record);
  EXPECT_EQ(pieces.breaks_u, (std::vector<double>{0.4, 1, 2, 2.5}));
  EXPECT_EQ(pieces.breaks_v, (std::vector<double>{0.2, 0.5, 0.9}));
  EXPECT_EQ(pieces.continuity_u, (std::vector<int>{2, 1}));
  EXPECT_EQ(pieces.continuity_v, (std::vector<int>{1}));
  for (double u : {0.4, 0.7, 1.0, 1.9, 2.0, 2.3, 2.5}) {
    for (double v : {0.2, 0.45, 0.5, 0.8, 0.9}) {
      EXPECT_LT((evaluate_pieces(pieces, u, v) - surface.evaluate(u, v)).norm(), 1e-13) << u << " " << v;
    }
  }
}

TEST(FreeformSurfaces, BezierBasisRecordsAndTheWayBack) {
  // A Bezier-basis record of two cubic segments in u: the same surface as the B-spline with
  // the breakpoint repeated 3 times.
  FreeformSurface record;
  record.basis = FreeformBasis::bezier;
  record.degree_u = 3;
  record.degree_v = 1;
  record.parameters_u = {0, 1, 3};
  record.parameters_v = {0, 1};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 7; ++i) record.points.emplace_back(i, j, i * i * 0.1 + j);
  }
  record.weights.assign(record.points.size(), 1.0);
  record.u0 = 0, record.u1 = 3, record.v0 = 0, record.v1 = 1;
  const NurbsSurface surface = nurbs_surface(record);
  EXPECT_EQ(surface.knots_u().knots(), (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 3, 3, 3, 3}));
  const NurbsBezierPatches two = freeform_bezier_patches(record);
  ASSERT_EQ(two.patches.size(), 2u);
  // Segment k on [breaks k, k+1] has the record's points 3k .. 3k + 3: the Bezier pieces themselves.
  for (double u : {0.0, 0.5, 1.0, 2.2, 3.0}) {
    for (double v : {0.0, 1.0}) EXPECT_LT((evaluate_pieces(two, u, v) - surface.evaluate(u, v)).norm(), 1e-13) << u;
  }
  EXPECT_EQ(std::get<BezierPatch3>(two.patches[1]).control_point(0, 1), record.points[3 + 7]);
  // A NURBS surface to a record and back: the same knots, points and weights.
  const NurbsSurface torus = nurbs_torus(Vec3(1, 2, 3), 2.0, 0.5);
  const NurbsSurface again = nurbs_surface(freeform_surface(torus, "torus"));
  EXPECT_EQ(again.knots_u(), torus.knots_u());
  EXPECT_EQ(again.knots_v(), torus.knots_v());
  for (int j = 0; j < torus.count_v(); ++j) {
    for (int i = 0; i < torus.count_u(); ++i) {
      EXPECT_LT((again.control_point(i, j) - torus.control_point(i, j)).norm(), 1e-15);
      EXPECT_NEAR(again.weight(i, j), torus.weight(i, j), 1e-16);
    }
  }
  // A Bezier patch as a record: one segment, the patch itself.
  const BezierPatch3 patch(2, 1,
                           {Vec3(0, 0, 0), Vec3(1, 0, 1), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1), Vec3(2, 1, 0)});
  const NurbsBezierPatches one = freeform_bezier_patches(freeform_surface(patch));
  ASSERT_EQ(one.patches.size(), 1u);
  EXPECT_EQ(std::get<BezierPatch3>(one.patches[0]).control_points(), patch.control_points());
  EXPECT_THROW((void)freeform_patches(FreeformDocument{}), InvalidInput);
}

}  // namespace
}  // namespace patchwork
