#include "surfaces/bezier_patch.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/errors.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

using testing::coordinate;
using testing::net_scale;
using testing::random_patch;

// F(u, v) in exact rational arithmetic: sum_ij B_i^n(u) B_j^m(v) P_ij for the double inputs.
Vec3 exact_evaluate(const BezierPatch3& patch, double u, double v) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const auto basis = [](int degree, int i, const mpq_class& t) {
    mpz_class c;
    mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(degree), static_cast<unsigned long>(i));
    mpq_class value = c;
    for (int k = 0; k < i; ++k) value *= t;
    for (int k = 0; k < degree - i; ++k) value *= (1 - t);
    return value;
  };
  Vec3 result;
  for (int c = 0; c < 3; ++c) {
    mpq_class sum = 0;
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) sum += basis(n, i, mpq_class(u)) * basis(m, j, mpq_class(v)) * mpq_class(patch.control_point(i, j)[c]);
    }
    result[c] = sum.get_d();
  }
  return result;
}

// The patch F(u, v) = (u, v, u^2 v^3): x = u in degree 2 is (0, 1/2, 1), y = v in degree 3 is
// (0, 1/3, 2/3, 1), u^2 is (0, 0, 1) and v^3 is (0, 0, 0, 1) (all exact in Bernstein form).
BezierPatch3 monomial_patch() {
  return testing::product_patch({Vec3(0, 1, 0), Vec3(0.5, 1, 0), Vec3(1, 1, 1)},
                                {Vec3(1, 0, 0), Vec3(1, 1.0 / 3.0, 0), Vec3(1, 2.0 / 3.0, 0), Vec3(1, 1, 1)});
}

// d^a/du^a d^b/dv^b of (u, v, u^2 v^3), in closed form.
Vec3 monomial_derivative(double u, double v, int a, int b) {
  const auto power_derivative = [](double t, int power, int order) {
    if (order > power) return 0.0;
    double factor = 1.0;
    for (int k = 0; k < order; ++k) factor *= power - k;
    return factor * std::pow(t, power - order);
  };
  return {b == 0 ? power_derivative(u, 1, a) : 0.0, a == 0 ? power_derivative(v, 1, b) : 0.0,
          power_derivative(u, 2, a) * power_derivative(v, 3, b)};
}

TEST(BezierPatch, ControlPointIndexIsFirstIndexFastest) {
  std::vector<Vec3> points;
  for (int k = 0; k < 6; ++k) points.emplace_back(k, 0, 0);
  const BezierPatch3 patch(2, 1, points);
  EXPECT_EQ(patch.control_point(2, 0).x(), 2.0);
  EXPECT_EQ(patch.control_point(0, 1).x(), 3.0);
  // Corners interpolate: F(1, 0) = P_n0 and F(0, 1) = P_0m.
  EXPECT_EQ(patch.evaluate(1.0, 0.0), patch.control_point(2, 0));
  EXPECT_EQ(patch.evaluate(0.0, 1.0), patch.control_point(0, 1));
}

TEST(BezierPatch, DerivativesMatchClosedForm) {
  const BezierPatch3 patch = monomial_patch();
  for (double u : {0.0, 0.3, 1.0}) {
    for (double v : {0.0, 0.7, 1.0}) {
      const PartialDerivatives<3> table = partial_derivatives(patch, u, v, 5);
      for (int a = 0; a <= 4; ++a) {
        for (int b = 0; b <= 5; ++b) {
          const Vec3 expected = monomial_derivative(u, v, a, b);
          // Differences of control points of size <= 1 times n!/(n-a)! m!/(m-b)! <= 12: 1e-13 absolute.
          EXPECT_LT((derivative(patch, u, v, a, b) - expected).norm(), 1e-13) << "a=" << a << " b=" << b;
          if (a + b <= 5) {
            EXPECT_LT((table.at(a, b) - expected).norm(), 1e-13) << "table a=" << a << " b=" << b;
          }
        }
      }
    }
  }
}

TEST(BezierPatch, RejectsBadInput) {
  EXPECT_THROW(BezierPatch3(1, 1, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}), InvalidInput);
  EXPECT_THROW(BezierPatch3(-1, 1, {}), InvalidInput);
  EXPECT_THROW(BezierPatch3(0, 0, {Vec3(std::nan(""), 0, 0)}), InvalidInput);
  const BezierPatch3 patch = monomial_patch();
  EXPECT_THROW(patch.evaluate(std::nan(""), 0.5), InvalidInput);
  EXPECT_THROW(split_u(patch, 0.0), InvalidInput);
  EXPECT_THROW(split_v(patch, 1.5), InvalidInput);
  EXPECT_THROW(subpatch(patch, 0.5, 0.5, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(derivative(patch, 0.5, 0.5, -1, 0), InvalidInput);
  EXPECT_THROW(elevate_degree(patch, -1, 0), InvalidInput);
}

RC_GTEST_PROP(BezierPatch, EvaluationMatchesExactTensorSum, ()) {
  const BezierPatch3 patch = *random_patch(0, 5);
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  // Tensor de Casteljau: each coordinate a convex combination of values <= 10, n + m levels.
  const double bound = 2.0 * (patch.degree_u() + patch.degree_v() + 1) * 1.2e-16 * net_scale(patch) * 3.0;
  RC_ASSERT((patch.evaluate(u, v) - exact_evaluate(patch, u, v)).norm() <= bound);
}

RC_GTEST_PROP(BezierPatch, TensorPartitionOfUnity, ()) {
  const int n = *rc::gen::inRange(0, 8);
  const int m = *rc::gen::inRange(0, 8);
  const Vec3 c(*coordinate(-5, 5), *coordinate(-5, 5), *coordinate(-5, 5));
  const BezierPatch3 patch(n, m, std::vector<Vec3>(static_cast<std::size_t>((n + 1) * (m + 1)), c));
  RC_ASSERT((patch.evaluate(*coordinate(0, 1), *coordinate(0, 1)) - c).norm() <= 1e-14 * (n + m + 1) * 5.0);
}

RC_GTEST_PROP(BezierPatch, AffineInvariance, ()) {
  const BezierPatch3 patch = *random_patch();
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.linear() << *coordinate(-2, 2), *coordinate(-2, 2), *coordinate(-2, 2), *coordinate(-2, 2), *coordinate(-2, 2),
      *coordinate(-2, 2), *coordinate(-2, 2), *coordinate(-2, 2), *coordinate(-2, 2);
  map.translation() = Vec3(*coordinate(-5, 5), *coordinate(-5, 5), *coordinate(-5, 5));
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const Vec3 expected = map * patch.evaluate(u, v);
  RC_ASSERT((testing::transformed(patch, map).evaluate(u, v) - expected).norm() <= 1e-12 * 60.0);
}

RC_GTEST_PROP(BezierPatch, SplitThenEvaluateEqualsEvaluate, ()) {
  const BezierPatch3 patch = *random_patch();
  const double s = *coordinate(0.01, 0.99);
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const double tolerance = 1e-12 * net_scale(patch);
  const auto [left, right] = split_u(patch, s);
  const Vec3 from_split = u <= s ? left.evaluate(u / s, v) : right.evaluate((u - s) / (1.0 - s), v);
  RC_ASSERT((from_split - patch.evaluate(u, v)).norm() <= tolerance);
  const auto [lower, upper] = split_v(patch, s);
  const Vec3 from_split_v = v <= s ? lower.evaluate(u, v / s) : upper.evaluate(u, (v - s) / (1.0 - s));
  RC_ASSERT((from_split_v - patch.evaluate(u, v)).norm() <= tolerance);
}

RC_GTEST_PROP(BezierPatch, SubpatchReparametrises, ()) {
  const BezierPatch3 patch = *random_patch();
  const double u0 = *coordinate(0, 0.5);
  const double u1 = *coordinate(0.6, 1);
  const double v0 = *coordinate(0, 0.5);
  const double v1 = *coordinate(0.6, 1);
  const double s = *coordinate(0, 1);
  const double t = *coordinate(0, 1);
  const Vec3 expected = patch.evaluate(u0 + s * (u1 - u0), v0 + t * (v1 - v0));
  RC_ASSERT((subpatch(patch, u0, u1, v0, v1).evaluate(s, t) - expected).norm() <= 1e-11 * net_scale(patch));
}

RC_GTEST_PROP(BezierPatch, ElevationKeepsTheSurface, ()) {
  const BezierPatch3 patch = *random_patch();
  const int times_u = *rc::gen::inRange(0, 3);
  const int times_v = *rc::gen::inRange(0, 3);
  const BezierPatch3 elevated = elevate_degree(patch, times_u, times_v);
  RC_ASSERT(elevated.degree_u() == patch.degree_u() + times_u);
  RC_ASSERT(elevated.degree_v() == patch.degree_v() + times_v);
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  RC_ASSERT((elevated.evaluate(u, v) - patch.evaluate(u, v)).norm() <= 1e-12 * net_scale(patch));
}

RC_GTEST_PROP(BezierPatch, IsoAndBoundaryCurvesLieOnTheSurface, ()) {
  const BezierPatch3 patch = *random_patch();
  const double u = *coordinate(0, 1);
  const double v = *coordinate(0, 1);
  const double tolerance = 1e-12 * net_scale(patch);
  RC_ASSERT((iso_curve_u(patch, u).evaluate(v) - patch.evaluate(u, v)).norm() <= tolerance);
  RC_ASSERT((iso_curve_v(patch, v).evaluate(u) - patch.evaluate(u, v)).norm() <= tolerance);
  RC_ASSERT((boundary_curve(patch, PatchEdge::v0).evaluate(u) - patch.evaluate(u, 0.0)).norm() <= tolerance);
  RC_ASSERT((boundary_curve(patch, PatchEdge::v1).evaluate(u) - patch.evaluate(u, 1.0)).norm() <= tolerance);
  RC_ASSERT((boundary_curve(patch, PatchEdge::u0).evaluate(v) - patch.evaluate(0.0, v)).norm() <= tolerance);
  RC_ASSERT((boundary_curve(patch, PatchEdge::u1).evaluate(v) - patch.evaluate(1.0, v)).norm() <= tolerance);
  // The edge's control row is exactly the net's boundary row.
  RC_ASSERT(boundary_curve(patch, PatchEdge::u1).control_points().front() == patch.control_point(patch.degree_u(), 0));
}

}  // namespace
}  // namespace patchwork
