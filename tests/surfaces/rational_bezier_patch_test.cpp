#include "surfaces/rational_bezier_patch.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/errors.h"
#include "surfaces/surface_normal.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

using testing::coordinate;

TEST(RationalBezierPatch, SphereOctantLiesOnTheSphere) {
  const Vec3 center(1.0, -2.0, 0.5);
  const double radius = 2.5;
  const RationalBezierPatch octant = sphere_octant(center, radius);
  for (int a = 0; a <= 20; ++a) {
    for (int b = 0; b <= 20; ++b) {
      const Vec3 p = octant.evaluate(a / 20.0, b / 20.0) - center;
      // A few roundings in the homogeneous sums and one division: relative 1e-15.
      EXPECT_NEAR(p.norm(), radius, 1e-15 * 8.0 * radius);
      EXPECT_GE(p.minCoeff(), -1e-15 * radius);  // the positive octant
    }
  }
  EXPECT_LT((octant.evaluate(0.0, 0.0) - (center + Vec3(radius, 0, 0))).norm(), 1e-15 * radius);
  EXPECT_LT((octant.evaluate(1.0, 0.0) - (center + Vec3(0, radius, 0))).norm(), 1e-15 * radius);
  EXPECT_LT((octant.evaluate(0.3, 1.0) - (center + Vec3(0, 0, radius))).norm(), 1e-15 * radius);
}

TEST(RationalBezierPatch, SphereDerivativesAreTangentAndNormalIsRadial) {
  const RationalBezierPatch octant = sphere_octant(Vec3::Zero(), 1.0);
  for (double u : {0.1, 0.5, 0.9}) {
    for (double v : {0.0, 0.4, 0.8}) {
      const PartialDerivatives<3> F = partial_derivatives(octant, u, v, 2);
      // On the unit sphere F.F = 1, so F.F_u = 0, F.F_v = 0 and F.F_uu + F_u.F_u = 0.
      EXPECT_NEAR(F.at(0, 0).dot(F.at(1, 0)), 0.0, 1e-14);
      EXPECT_NEAR(F.at(0, 0).dot(F.at(0, 1)), 0.0, 1e-14);
      EXPECT_NEAR(F.at(0, 0).dot(F.at(2, 0)) + F.at(1, 0).squaredNorm(), 0.0, 1e-13);
      EXPECT_NEAR(F.at(0, 0).dot(F.at(1, 1)) + F.at(1, 0).dot(F.at(0, 1)), 0.0, 1e-13);
      EXPECT_NEAR(F.at(0, 0).dot(F.at(0, 2)) + F.at(0, 1).squaredNorm(), 0.0, 1e-13);
      // Outward: the unit normal is the position itself.
      EXPECT_LT((unit_normal(octant, u, v) - F.at(0, 0)).norm(), 1e-14);
    }
  }
}

TEST(RationalBezierPatch, PoleNormalIsTheLimit) {
  const RationalBezierPatch octant = sphere_octant(Vec3::Zero(), 1.0);
  // Row j = 2 collapses to the pole: F_u = 0 there, and the limit normal is +z for every u.
  for (double u : {0.0, 0.25, 0.5, 1.0}) {
    EXPECT_LT(normal(octant, u, 1.0).norm(), 1e-15);
    EXPECT_LT((unit_normal(octant, u, 1.0) - Vec3::UnitZ()).norm(), 1e-12) << "u=" << u;
  }
}

RC_GTEST_PROP(RationalBezierPatch, EqualWeightsGiveThePolynomialPatch, ()) {
  const BezierPatch3 patch = *testing::random_patch(0, 4);
  const double w = *coordinate(0.1, 10);
  const RationalBezierPatch rational(patch.degree_u(), patch.degree_v(), patch.control_points(),
                                     std::vector<double>(patch.control_points().size(), w));
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const PartialDerivatives<3> expected = partial_derivatives(patch, u, v, 3);
  const PartialDerivatives<3> got = partial_derivatives(rational, u, v, 3);
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; a + b <= 3; ++b) {
      // Derivatives up to 3 of a degree <= 4 net with coordinates <= 10: size <= 4^3 * 8 * 10.
      RC_ASSERT((got.at(a, b) - expected.at(a, b)).norm() <= 1e-12 * 5120.0);
    }
  }
}

TEST(RationalBezierPatch, RejectsBadWeights) {
  const std::vector<Vec3> points(4, Vec3::Zero());
  EXPECT_THROW(RationalBezierPatch(1, 1, points, {1, 1, 0, 1}), InvalidInput);
  EXPECT_THROW(RationalBezierPatch(1, 1, points, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(RationalBezierPatch(1, 1, points, {1, 1, std::nan(""), 1}), InvalidInput);
  EXPECT_THROW(sphere_octant(Vec3::Zero(), -1.0), InvalidInput);
}

}  // namespace
}  // namespace patchwork
