#include "surfaces/surface_normal.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/errors.h"
#include "surfaces/rational_bezier_patch.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

using testing::coordinate;

// F(u, v) = (v(1-u), v u, v^2 (1 - 2u + 2u^2)): the paraboloid z = x^2 + y^2 over a triangle,
// with the edge v = 0 collapsed to the origin. In Bernstein form (degree 2 each way):
// 1-u -> (1, 1/2, 0), u -> (0, 1/2, 1), 1 - 2u + 2u^2 -> (1, 0, 1), v -> (0, 1/2, 1), v^2 -> (0, 0, 1).
// Near v = 0, F_u x F_v = v (-1, 1, 0) x (1-u, u, 0) + O(v^2) = v (0, 0, -1): the limit is -z.
BezierPatch3 collapsed_paraboloid() {
  return testing::product_patch({Vec3(1, 0, 1), Vec3(0.5, 0.5, 0), Vec3(0, 1, 1)},
                                {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(1, 1, 1)});
}

TEST(SurfaceNormal, PlaneHasConstantNormal) {
  const BezierPatch3 square = testing::bilinear(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(2, 3, 0));
  // de Casteljau on equal values may round in the last bit: 1e-14.
  EXPECT_LT((normal(square, 0.3, 0.6) - Vec3(0, 0, 6)).norm(), 1e-14);
  EXPECT_LT((unit_normal(square, 0.3, 0.6) - Vec3(0, 0, 1)).norm(), 1e-15);
}

TEST(SurfaceNormal, CollapsedEdgeGivesTheLimitNormal) {
  const BezierPatch3 patch = collapsed_paraboloid();
  for (double u : {0.0, 0.2, 0.5, 0.8, 1.0}) {
    EXPECT_EQ(normal(patch, u, 0.0).norm(), 0.0);
    const Vec3 n = unit_normal(patch, u, 0.0);
    EXPECT_TRUE(n.allFinite());
    EXPECT_LT((n - Vec3(0, 0, -1)).norm(), 1e-12) << "u=" << u;
    // Continuity: the ordinary normal just inside tends to the limit (O(v) away from it).
    EXPECT_LT((unit_normal(patch, u, 1e-7) - n).norm(), 1e-6);
  }
}

// The limit normal tried from derivatives up to order 2 first is the one from the full table,
// bit for bit: at a pole that order 2 decides (the collapsed paraboloid, the teapot's lid and
// bottom) and at one where it does not (two rows collapsed into the pole, so F_v vanishes there
// too and the normal appears at a higher order), polynomial and rational.
TEST(SurfaceNormal, StagedLimitNormalIsTheFullOrdersBitForBit) {
  const auto full = [](const auto& patch, double u, double v) {
    const int order = std::min(patch.degree_u() + patch.degree_v(), 12) + 1;
    return detail::limit_unit_normal(partial_derivatives(patch, u, v, order), u, v,
                                     detail::degeneracy_thresholds(patch), patch.degree_u(), patch.degree_v());
  };
  // A cubic-by-cubic dome over z = 1 - x^2 - y^2 whose rows j = 0 and j = 1 are the apex.
  std::vector<Vec3> dome;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) {
      const double angle = 0.5 * 3.14159265358979323846 * i / 3.0;
      const double r = j < 2 ? 0.0 : (j - 1) / 2.0;
      dome.emplace_back(r * std::cos(angle), r * std::sin(angle), 1.0 - r * r);
    }
  }
  const BezierPatch3 double_pole(3, 3, dome);
  const BezierPatch3 single_pole = collapsed_paraboloid();
  for (const BezierPatch3* patch : {&single_pole, &double_pole}) {
    const RationalBezierPatch rational = as_rational(*patch);
    for (const double u : {0.0, 0.25, 1.0 / 3.0, 0.5, 1.0}) {
      const Vec3 staged = unit_normal(*patch, u, 0.0);
      EXPECT_EQ(staged, full(*patch, u, 0.0)) << "u " << u;
      EXPECT_NEAR(staged.norm(), 1.0, 1e-15);
      EXPECT_EQ(unit_normal(rational, u, 0.0), full(rational, u, 0.0)) << "u " << u;
    }
  }
  // The double pole needs more than order 2: with only that much there is no normal.
  EXPECT_THROW(detail::limit_unit_normal(partial_derivatives(double_pole, 0.5, 0.0, 2), 0.5, 0.0,
                                         detail::degeneracy_thresholds(double_pole), 3, 3),
               NumericalError);
}

TEST(SurfaceNormal, DegeneratePatchThrows) {
  const BezierPatch3 point(1, 1, std::vector<Vec3>(4, Vec3(1, 2, 3)));
  EXPECT_THROW(unit_normal(point, 0.5, 0.5), NumericalError);
  const BezierPatch3 segment = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0));
  EXPECT_THROW(unit_normal(segment, 0.5, 0.5), NumericalError);
}

RC_GTEST_PROP(SurfaceNormal, OrthogonalToBothTangents, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const Vec3 du = derivative(patch, u, v, 1, 0);
  const Vec3 dv = derivative(patch, u, v, 0, 1);
  const Vec3 n = normal(patch, u, v);
  RC_PRE(n.norm() > 1e-6 * du.norm() * dv.norm());
  const Vec3 unit = unit_normal(patch, u, v);
  RC_ASSERT(std::abs(unit.norm() - 1.0) <= 4e-16);
  RC_ASSERT(std::abs(unit.dot(du)) <= 1e-13 * du.norm() * (du.norm() * dv.norm() / n.norm()));
  RC_ASSERT(std::abs(unit.dot(dv)) <= 1e-13 * dv.norm() * (du.norm() * dv.norm() / n.norm()));
  RC_ASSERT(unit.dot(n) > 0.0);
}

// unit_normal's unrolled first derivatives (degrees 1-3) are partial_derivatives' bit for bit:
// at regular points it is F_u x F_v of partial_derivatives(patch, u, v, 1), normalised, on and off
// the square, every degree pair (and degree 4, the general path).
RC_GTEST_PROP(SurfaceNormal, RegularNormalIsThePartialDerivativesOneBitForBit, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const double u = *coordinate(-0.25, 1.25);
  const double v = *coordinate(-0.25, 1.25);
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 1);
  const Vec3 n = F.at(1, 0).cross(F.at(0, 1));
  RC_PRE(n.norm() > 1e-6 * F.at(1, 0).norm() * F.at(0, 1).norm());
  RC_ASSERT(unit_normal(patch, u, v) == n.normalized());
}

RC_GTEST_PROP(SurfaceNormal, RotatesWithTheSurface, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 3);
  const Eigen::Isometry3d motion = *testing::random_rigid_motion();
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const Vec3 n = normal(patch, u, v);
  RC_PRE(n.norm() > 1e-3);
  const Vec3 moved = unit_normal(testing::transformed(patch, Eigen::Affine3d(motion)), u, v);
  RC_ASSERT((moved - motion.linear() * unit_normal(patch, u, v)).norm() <= 1e-9);
}

}  // namespace
}  // namespace patchwork
