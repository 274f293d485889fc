#include "surfaces/rational_bezier_patch.h"

#include <gtest/gtest.h>
#include <array>
#include <iostream>
#include <limits>
#include <rapidcheck/gtest.h>

#include "core/errors.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/rational_bounds.h"
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

// The largest |F_uu|, |F_uv|, |F_vv| sampled on a (k+1) x (k+1) grid of [u0, u1] x [v0, v1].
std::array<double, 3> sampled_second_derivatives(const RationalBezierPatch& patch, double u0, double u1, double v0,
                                                 double v1, int k = 24) {
  std::array<double, 3> largest{0, 0, 0};
  for (int j = 0; j <= k; ++j) {
    for (int i = 0; i <= k; ++i) {
      const PartialDerivatives<3> d =
          partial_derivatives(patch, u0 + (u1 - u0) * i / k, v0 + (v1 - v0) * j / k, 2);
      largest[0] = std::max(largest[0], d.at(2, 0).norm());
      largest[1] = std::max(largest[1], d.at(1, 1).norm());
      largest[2] = std::max(largest[2], d.at(0, 2).norm());
    }
  }
  return largest;
}

rc::Gen<RationalBezierPatch> random_rational_patch() {
  return rc::gen::exec([] {
    const BezierPatch3 net = *testing::random_patch(1, 4);
    std::vector<double> weights;
    for (std::size_t k = 0; k < net.control_points().size(); ++k) weights.push_back(*testing::coordinate(0.2, 5.0));
    return RationalBezierPatch(net.degree_u(), net.degree_v(), net.control_points(), weights);
  });
}

// The quotient-rule bounds (surfaces/rational_bounds.h) hold at every sample of the true second
// derivatives, on the whole patch and on each of its 3 x 3 pieces.
RC_GTEST_PROP(RationalBounds, BoundTheSecondDerivatives, ()) {
  const RationalBezierPatch patch = *random_rational_patch();
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const std::array<double, 3> sampled = sampled_second_derivatives(patch, 0, 1, 0, 1);
  const double slack = 1 + 1e-9;
  RC_ASSERT(sampled[0] <= M.uu * slack + 1e-12);
  RC_ASSERT(sampled[1] <= M.uv * slack + 1e-12);
  RC_ASSERT(sampled[2] <= M.vv * slack + 1e-12);
  RC_ASSERT(!M.directions.has_value());
  const std::vector<SecondDerivativeBounds> pieces = piece_second_derivative_bounds(patch, 3);
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      const SecondDerivativeBounds& P = pieces[static_cast<std::size_t>(a + 3 * b)];
      const std::array<double, 3> here = sampled_second_derivatives(patch, a / 3.0, (a + 1) / 3.0, b / 3.0, (b + 1) / 3.0, 8);
      RC_ASSERT(here[0] <= P.uu * slack + 1e-12);
      RC_ASSERT(here[1] <= P.uv * slack + 1e-12);
      RC_ASSERT(here[2] <= P.vv * slack + 1e-12);
    }
  }
}

// With equal weights the patch is polynomial: the bounds are no looser than its norm bounds (the
// numerators are then w^3 times the nets of F_uu, F_uv, F_vv raised in degree, whose largest
// coefficient is at most the net's), and still hold (BoundTheSecondDerivatives).
RC_GTEST_PROP(RationalBounds, EqualWeightsAreNoLooserThanThePolynomialNormBounds, ()) {
  const BezierPatch3 net = *testing::random_patch(0, 4);
  const double w = *testing::coordinate(0.5, 3.0);
  const RationalBezierPatch patch(net.degree_u(), net.degree_v(), net.control_points(),
                                  std::vector<double>(net.control_points().size(), w));
  const SecondDerivativeBounds rational = second_derivative_bounds(patch);
  const SecondDerivativeBounds polynomial = second_derivative_bounds(net);
  const double scale = 1e-12 * (1 + testing::net_scale(net));
  RC_ASSERT(rational.uu <= polynomial.uu * (1 + 1e-12) + scale);
  RC_ASSERT(rational.uv <= polynomial.uv * (1 + 1e-12) + scale);
  RC_ASSERT(rational.vv <= polynomial.vv * (1 + 1e-12) + scale);
  // A bilinear net is its own elevation's extreme: there the two agree.
  if (net.degree_u() <= 1 && net.degree_v() <= 1) {
    RC_ASSERT(std::abs(rational.uv - polynomial.uv) <= scale * (1 + polynomial.uv));
  }
}

// On the sphere's octant (weights 1/sqrt2 and 1/2 inside, a pole): the grid the bounds ask for at
// a tolerance meets it, measured as |F - L| at ten points of every triangle; finer pieces tighten
// the bound towards the sampled maximum of the true derivatives.
TEST(RationalBounds, SphereOctantGridMeetsItsTolerance) {
  const RationalBezierPatch octant = sphere_octant(Vec3(0.5, -1, 2), 3.0);
  const std::array<double, 3> sampled = sampled_second_derivatives(octant, 0, 1, 0, 1, 64);
  double previous = std::numeric_limits<double>::infinity();
  for (int pieces : {1, 2, 4, 8, 16}) {
    const SecondDerivativeBounds M = second_derivative_bounds(octant, pieces);
    EXPECT_GE(M.uu, sampled[0] * (1 - 1e-9));
    EXPECT_GE(M.uv, sampled[1] * (1 - 1e-9));
    EXPECT_GE(M.vv, sampled[2] * (1 - 1e-9));
    EXPECT_LE(M.uu + M.uv + M.vv, previous * (1 + 1e-12));
    previous = M.uu + M.uv + M.vv;
    std::cout << pieces << " pieces: M = (" << M.uu << ", " << M.uv << ", " << M.vv << "), sampled (" << sampled[0]
              << ", " << sampled[1] << ", " << sampled[2] << ")\n";
  }
  // Tight on small pieces: 16 x 16 pieces within 15% of the sampled maximum.
  const SecondDerivativeBounds M16 = second_derivative_bounds(octant, 16);
  EXPECT_LE(M16.uu, 1.15 * sampled[0]);
  EXPECT_LE(M16.uv, 1.15 * sampled[1]);
  EXPECT_LE(M16.vv, 1.15 * sampled[2]);
  for (const double tolerance : {1e-2, 1e-3, 1e-4}) {
    const GridSize grid = grid_for_tolerance(second_derivative_bounds(octant, 4), tolerance);
    const auto nu = grid.segments_u;
    const auto nv = grid.segments_v;
    double measured = 0.0;
    for (std::int64_t j = 0; j < nv; ++j) {
      for (std::int64_t i = 0; i < nu; ++i) {
        const Vec2 p00(static_cast<double>(i) / nu, static_cast<double>(j) / nv);
        const Vec2 p11(static_cast<double>(i + 1) / nu, static_cast<double>(j + 1) / nv);
        const Vec2 p10(p11.x(), p00.y());
        const Vec2 p01(p00.x(), p11.y());
        for (const auto& triangle : {std::array<Vec2, 3>{p00, p10, p11}, std::array<Vec2, 3>{p00, p11, p01}}) {
          std::array<Vec3, 3> corner;
          for (int c = 0; c < 3; ++c) corner[c] = octant.evaluate(triangle[c].x(), triangle[c].y());
          for (const auto& w : {std::array<double, 3>{1 / 3.0, 1 / 3.0, 1 / 3.0}, std::array<double, 3>{0.5, 0.5, 0},
                                std::array<double, 3>{0, 0.5, 0.5}, std::array<double, 3>{0.5, 0, 0.5}}) {
            const Vec2 uv = w[0] * triangle[0] + w[1] * triangle[1] + w[2] * triangle[2];
            const Vec3 linear = w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2];
            measured = std::max(measured, (octant.evaluate(uv.x(), uv.y()) - linear).norm());
          }
        }
      }
    }
    EXPECT_LE(measured, tolerance) << nu << " x " << nv;
    EXPECT_GT(measured, 0.3 * tolerance) << "the grid is not wastefully fine";
    std::cout << "tolerance " << tolerance << ": grid " << nu << " x " << nv << ", measured " << measured << "\n";
  }
}

// Split, sub-patch, degree elevation, iso and boundary curves of the homogeneous net describe
// the same rational surface: equal points at random parameters.
RC_GTEST_PROP(RationalBezierPatch, OperationsKeepTheSurface, ()) {
  const RationalBezierPatch patch = *random_rational_patch();
  const double u = *testing::coordinate(0.05, 0.95);
  const double v = *testing::coordinate(0.05, 0.95);
  const double s = *testing::coordinate(0, 1);
  const double t = *testing::coordinate(0, 1);
  double scale = 1.0;
  for (int j = 0; j <= patch.degree_v(); ++j) {
    for (int i = 0; i <= patch.degree_u(); ++i) scale = std::max(scale, patch.control_point(i, j).norm());
  }
  // Weights in [0.2, 5]: the quotient loses up to their ratio's worth of digits.
  const double tolerance = 1e-11 * scale;
  const auto near = [&](const Vec3& a, const Vec3& b) { return (a - b).norm() <= tolerance; };
  const auto [left, right] = split_u(patch, u);
  RC_ASSERT(near(left.evaluate(s, t), patch.evaluate(s * u, t)));
  RC_ASSERT(near(right.evaluate(s, t), patch.evaluate(u + s * (1 - u), t)));
  const auto [low, high] = split_v(patch, v);
  RC_ASSERT(near(low.evaluate(s, t), patch.evaluate(s, t * v)));
  RC_ASSERT(near(high.evaluate(s, t), patch.evaluate(s, v + t * (1 - v))));
  const RationalBezierPatch piece = subpatch(patch, 0.5 * u, u, v, 0.5 + 0.5 * v);
  RC_ASSERT(near(piece.evaluate(s, t), patch.evaluate(0.5 * u + s * 0.5 * u, v + t * (0.5 - 0.5 * v))));
  const RationalBezierPatch raised = elevate_degree(patch, 2, 1);
  RC_ASSERT(raised.degree_u() == patch.degree_u() + 2 && raised.degree_v() == patch.degree_v() + 1);
  RC_ASSERT(near(raised.evaluate(s, t), patch.evaluate(s, t)));
  RC_ASSERT(near(iso_curve_u(patch, u).evaluate(t), patch.evaluate(u, t)));
  RC_ASSERT(near(iso_curve_v(patch, v).evaluate(s), patch.evaluate(s, v)));
  RC_ASSERT(near(boundary_curve(patch, PatchEdge::v1).evaluate(s), patch.evaluate(s, 1)));
  RC_ASSERT(near(boundary_curve(patch, PatchEdge::u0).evaluate(t), patch.evaluate(0, t)));
}

// The tight box of the sphere's octant is [c, c + r]^3 to within the tolerance, and a box of a
// random rational patch holds every sampled point, each face within the tolerance of a sample.
TEST(RationalBezierPatch, TightBoxOfTheSphereOctant) {
  const Vec3 centre(0.5, -1, 2);
  const double r = 3.0;
  const double tolerance = 1e-9;
  const Eigen::AlignedBox3d box = bounding_box(sphere_octant(centre, r), tolerance);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(box.max()[c], centre[c] + r - 1e-15 * r);
    EXPECT_LE(box.max()[c], centre[c] + r + tolerance);
    EXPECT_LE(box.min()[c], centre[c] + 1e-15 * r);
    EXPECT_GE(box.min()[c], centre[c] - tolerance);
  }
}

RC_GTEST_PROP(RationalBezierPatch, TightBoxHoldsTheSurface, ()) {
  const RationalBezierPatch patch = *random_rational_patch();
  const double tolerance = 1e-6;
  const Eigen::AlignedBox3d box = bounding_box(patch, tolerance);
  Eigen::AlignedBox3d sampled;
  for (int j = 0; j <= 40; ++j) {
    for (int i = 0; i <= 40; ++i) sampled.extend(patch.evaluate(i / 40.0, j / 40.0));
  }
  for (int c = 0; c < 3; ++c) {
    RC_ASSERT(box.max()[c] >= sampled.max()[c] - 1e-12);
    RC_ASSERT(box.min()[c] <= sampled.min()[c] + 1e-12);
  }
  // Tight: each face within the tolerance of the true extreme, which the samples approach
  // (within the sampling gap of a 40 x 40 grid, far below the box of the control points).
  const Vec3 slack = 0.05 * (box.max() - box.min()) + Vec3::Constant(tolerance);
  for (int c = 0; c < 3; ++c) {
    RC_ASSERT(box.max()[c] <= sampled.max()[c] + slack[c]);
    RC_ASSERT(box.min()[c] >= sampled.min()[c] - slack[c]);
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
