#include "surfaces/patch_flatness.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <functional>

#include "core/errors.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

using testing::coordinate;

TEST(PatchFlatness, HyperbolicParaboloidAttainsTheBound) {
  // F = (u, v, uv): M_uu = M_vv = 0, M_uv = 1, bound (1/8) 2 h^2 = h^2 / 4, and on a cell's
  // diagonal uv - linear = h^2/4 at its midpoint: the bound is attained.
  const BezierPatch3 patch = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1));
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  EXPECT_EQ(M.uu, 0.0);
  EXPECT_EQ(M.vv, 0.0);
  EXPECT_EQ(M.uv, 1.0);
  for (int n : {1, 2, 5}) {
    const double h = 1.0 / n;
    EXPECT_DOUBLE_EQ(flatness_bound(M, h, h), h * h / 4.0);
    EXPECT_NEAR(testing::measured_distance(patch, n, n, 8), h * h / 4.0, 1e-15);
  }
}

TEST(PatchFlatness, SecondDifferencesOfAParabolicCylinder) {
  // z = u^2 in degree 2 has control values (0, 0, 1): second difference 1, M_uu = 2 = max |F_uu|.
  const BezierPatch3 patch =
      testing::product_patch({Vec3(0, 1, 0), Vec3(0.5, 1, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 1), Vec3(1, 1, 1)});
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  EXPECT_EQ(M.uu, 2.0);
  EXPECT_EQ(M.uv, 0.0);
  EXPECT_EQ(M.vv, 0.0);
  // A parabola deviates from its chord by exactly h^2 |z''| / 8 = h^2 / 4 at the midpoint.
  EXPECT_NEAR(testing::measured_distance(patch, 4, 1, 16), flatness_bound(M, 0.25, 1.0), 1e-15);
}

// max |F - L| over a `samples`-step barycentric lattice of the parameter triangle p, L the
// linear interpolant of F at its corners.
double sampled_triangle_distance(const BezierPatch3& patch, const std::array<Vec2, 3>& p, int samples) {
  std::array<Vec3, 3> corners;
  for (int k = 0; k < 3; ++k) corners[k] = patch.evaluate(p[k].x(), p[k].y());
  double distance = 0.0;
  for (int a = 0; a <= samples; ++a) {
    for (int b = 0; a + b <= samples; ++b) {
      const double x = static_cast<double>(a) / samples, y = static_cast<double>(b) / samples;
      const Vec2 uv = (1 - x - y) * p[0] + x * p[1] + y * p[2];
      const Vec3 linear = (1 - x - y) * corners[0] + x * corners[1] + y * corners[2];
      distance = std::max(distance, (patch.evaluate(uv.x(), uv.y()) - linear).norm());
    }
  }
  return distance;
}

// The biquadratic patch (x(u), y(v), z(u) + z(v)) from the Bernstein coefficients of the four
// quadratics.
BezierPatch3 quadratic_patch(const std::array<double, 3>& x_u, const std::array<double, 3>& y_v,
                             const std::array<double, 3>& z_u, const std::array<double, 3>& z_v) {
  std::vector<Vec3> points;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) points.emplace_back(x_u[i], y_v[j], z_u[i] + z_v[j]);
  }
  return BezierPatch3(2, 2, points);
}

TEST(PatchFlatness, DirectionalBoundIsExactWhereSecondDerivativesAreOrthogonal) {
  // F = (u^2, v^2, 0): F_uu = (2, 0, 0) and F_vv = (0, 2, 0) at right angles, F_uv = 0. On a grid
  // triangle |F - L| = h^2 sqrt((s(1-s))^2 + (t(1-t))^2), largest at the diagonal's midpoint:
  // sqrt(2) h^2 / 4, where the norms add to h^2 / 2.
  const BezierPatch3 patch = quadratic_patch({0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, 0});
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  ASSERT_TRUE(M.directions.has_value());
  for (int n : {1, 2, 4, 7}) {
    const double h = 1.0 / n;
    EXPECT_NEAR(flatness_bound(M, h, h), std::sqrt(2.0) * h * h / 4.0, 1e-15);
    EXPECT_NEAR(testing::measured_distance(patch, n, n, 8), std::sqrt(2.0) * h * h / 4.0, 1e-15);
  }
}

TEST(PatchFlatness, DirectionalBoundLetsASaddlesCurvaturesCancel) {
  // F = (u, v, u^2 - v^2): F_uu = (0, 0, 2) and F_vv = (0, 0, -2) cancel along the diagonal.
  // |F - L| = h^2 |s(1-s) - t(1-t)| on a grid triangle, at most h^2 / 4 (at t = 0, s = 1/2),
  // half the norm bound h^2 / 2.
  const BezierPatch3 patch = quadratic_patch({0, 0.5, 1}, {0, 0.5, 1}, {0, 0, 1}, {0, 0, -1});
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  for (int n : {1, 3, 8}) {
    const double h = 1.0 / n;
    EXPECT_NEAR(flatness_bound(M, h, h), h * h / 4.0, 1e-15);
    EXPECT_NEAR(testing::measured_distance(patch, n, n, 8), h * h / 4.0, 1e-15);
    // A triangle across the cell's other diagonal is not ordered alike in u and v: the mixed
    // moment may take either sign, and the bound still holds.
    EXPECT_GE(triangle_flatness_bound(M, Vec2(h, 0), Vec2(h, h), Vec2(0, h)), h * h / 4.0 - 1e-15);
  }
}

// Nets whose second differences are nearly constant vectors (a quadratic function of the indices,
// raised in degree, plus a little noise): where the directional bound, not the norm bound, is
// the smaller one. It must hold on grids and on any triangle.
RC_GTEST_PROP(PatchFlatness, DirectionalBoundHoldsOnNearlyQuadraticPatches, ()) {
  std::array<Vec3, 6> c;
  for (Vec3& v : c) v = Vec3(*coordinate(-3, 3), *coordinate(-3, 3), *coordinate(-3, 3));
  const double noise = *coordinate(0.0, 0.2);
  std::vector<Vec3> points;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) {
      const Vec3 jitter(*coordinate(-1, 1), *coordinate(-1, 1), *coordinate(-1, 1));
      points.push_back(c[0] + i * c[1] + j * c[2] + i * i * c[3] + i * j * c[4] + j * j * c[5] + noise * jitter);
    }
  }
  const BezierPatch3 patch =
      elevate_degree(BezierPatch3(2, 2, points), *rc::gen::inRange(0, 3), *rc::gen::inRange(0, 3));
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const int nu = *rc::gen::inRange(1, 7);
  const int nv = *rc::gen::inRange(1, 7);
  const double bound = flatness_bound(M, 1.0 / nu, 1.0 / nv);
  const double norms = (M.uu / (nu * nu) + 2.0 * M.uv / (nu * nv) + M.vv / (nv * nv)) / 8.0;
  RC_TAG(bound < 0.99 * norms ? "directional bound smaller" : "norm bound");
  const double slack = 1e-12 * testing::net_scale(patch);
  RC_ASSERT(testing::measured_distance(patch, nu, nv, 6) <= bound * (1.0 + 1e-12) + slack);
  // Any triangle, ordered alike in u and v or not.
  std::array<Vec2, 3> p;
  for (Vec2& q : p) q = Vec2(*coordinate(0, 1), *coordinate(0, 1));
  const double triangle = triangle_flatness_bound(M, p[0], p[1], p[2]);
  RC_ASSERT(sampled_triangle_distance(patch, p, 10) <= triangle * (1.0 + 1e-9) + slack);
}

RC_GTEST_PROP(PatchFlatness, MeasuredDistanceNeverExceedsTheBound, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 5);
  const int nu = *rc::gen::inRange(1, 9);
  const int nv = *rc::gen::inRange(1, 9);
  const double bound = flatness_bound(second_derivative_bounds(patch), 1.0 / nu, 1.0 / nv);
  RC_ASSERT(testing::measured_distance(patch, nu, nv, 6) <= bound * (1.0 + 1e-12) + 1e-12);
}

RC_GTEST_PROP(PatchFlatness, GridForToleranceIsTheSmallestThatMeetsTheBound, ()) {
  const BezierPatch3 patch = *testing::random_patch(2, 4);
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const double tolerance = *coordinate(0.05, 5.0);
  const std::int64_t least = *rc::gen::inRange(1, 4);
  const GridSize grid = grid_for_tolerance(M, tolerance, least);
  RC_ASSERT(flatness_bound(M, 1.0 / grid.segments_u, 1.0 / grid.segments_v) <= tolerance);
  RC_ASSERT(grid.segments_u >= least && grid.segments_v >= least);
  // Brute force: no grid with fewer cells (and at least `least` segments a side) meets the bound.
  const std::int64_t cells = grid.segments_u * grid.segments_v;
  for (std::int64_t nu = least; nu < cells; ++nu) {
    for (std::int64_t nv = least; nu * nv < cells; ++nv) {
      RC_ASSERT(flatness_bound(M, 1.0 / nu, 1.0 / nv) > tolerance);
    }
  }
}

// A memo kept across a sequence of tolerances (coming back, alternating, finer and coarser, with
// other least segments) answers every request with the grid the search without one finds, and
// holds the cell bounds it was told: exact entries are the bound, the others below it.
RC_GTEST_PROP(PatchFlatness, GridSearchMemoAnswersAsTheSearchWithoutIt, ()) {
  const BezierPatch3 patch = *testing::random_patch(2, 4);
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  GridSearchMemo memo;
  const auto tolerances = *rc::gen::container<std::vector<int>>(12, rc::gen::inRange(0, 6));
  const double ladder[6] = {0.05, 0.07, 0.3, 0.31, 1.0, 4.0};
  for (const int k : tolerances) {
    const double tolerance = ladder[k];
    const std::int64_t least = 1 + k % 2;
    const GridSize with = grid_for_tolerance(M, tolerance, least, memo);
    const GridSize without = grid_for_tolerance(M, tolerance, least);
    RC_ASSERT(with.segments_u == without.segments_u);
    RC_ASSERT(with.segments_v == without.segments_v);
  }
  RC_ASSERT(memo.answers.size() <= 2u);
  // flatness_bound through the memo, on every grid the searches tried (stopped ones included,
  // whose known value is only a lower one): the value without a memo, bit for bit.
  const std::vector<GridSearchMemo::CellBound> tried = memo.cell_bounds;
  for (const GridSearchMemo::CellBound& e : tried) {
    const double direct = flatness_bound(M, 1.0 / static_cast<double>(e.nu), 1.0 / static_cast<double>(e.nv), 0.0);
    RC_ASSERT(flatness_bound(M, e.nu, e.nv, 0.0, memo) == direct);
  }
  RC_ASSERT(memo.cell_bounds.size() <= GridSearchMemo::most_cell_bounds);
  for (const GridSearchMemo::CellBound& e : memo.cell_bounds) {
    const double bound = flatness_bound(M, 1.0 / static_cast<double>(e.nu), 1.0 / static_cast<double>(e.nv));
    // flatness_bound is the least of the quick and cell bounds: an exact entry is at least it.
    RC_ASSERT(e.value >= bound || !e.exact);
  }
}

TEST(PatchFlatness, ThirdAndFourthDifferencesOfABiquadratic) {
  // F = (u, v, u^2 v^2) in degree (2, 2): only P_22 has z = 1. F_uuv = 4v, F_uvv = 4u, F_uuvv = 4;
  // F_uuu, F_vvv and the other fourth derivatives vanish.
  std::vector<Vec3> points;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) points.emplace_back(i / 2.0, j / 2.0, i == 2 && j == 2 ? 1.0 : 0.0);
  }
  const DirectionalBounds d = *second_derivative_bounds(BezierPatch3(2, 2, points)).directions;
  EXPECT_EQ(d.third, (std::array<double, 4>{0.0, 4.0, 4.0, 0.0}));
  EXPECT_EQ(d.fourth, (std::array<double, 5>{0.0, 0.0, 4.0, 0.0, 0.0}));
}

// F = (u, v, u^3) in degree (3, 1).
BezierPatch3 cubic_ramp() {
  std::vector<Vec3> points;
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i <= 3; ++i) points.emplace_back(i / 3.0, j, i == 3 ? 1.0 : 0.0);
  }
  return BezierPatch3(3, 1, points);
}

TEST(PatchFlatness, TheCellBoundsCubicTermVanishesWhereTheQuadraticOnePeaks) {
  // F = (u, v, u^3): max |F_uu| = 6 gives 6 h^2 / 8 = 0.75 h^2 to second order. The directional
  // bound's remainder adds |F_uuu| h^3 / 48 = h^3 / 8 on top; the cell bound takes the third
  // moment box by box, small where the second moment s(1-s) is near 1/4, and adds under h^3 / 40.
  // Along u, |F - L| = h^2 s(1-s)(3a + h(1+s)) on the cell [a, a+h]: the bound must cover it.
  const BezierPatch3 patch = cubic_ramp();
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  for (int n : {4, 8, 16}) {
    const double h = 1.0 / n;
    const double bound = flatness_bound(M, h, h);
    EXPECT_LE(bound, 0.75 * h * h + h * h * h / 40.0) << n;
    EXPECT_GE(bound, 0.75 * h * h) << n;
    double exact = 0.0;
    for (int k = 0; k <= 1000; ++k) {
      const double s = k / 1000.0;
      exact = std::max(exact, h * h * s * (1.0 - s) * (3.0 * (1.0 - h) + h * (1.0 + s)));
    }
    const double measured = testing::measured_distance(patch, n, n, 40);
    EXPECT_LE(measured, exact * (1.0 + 1e-12)) << n;
    EXPECT_GE(measured, exact * (1.0 - 1e-3)) << n;
    EXPECT_LE(exact, bound) << n;
  }
}

TEST(PatchFlatness, TheCellBoundPicksGridsTheQuickBoundsMiss) {
  // At a tolerance between the cell bound and the quick bounds of a grid, grid_for_tolerance
  // finds that grid or one with fewer cells.
  const BezierPatch3 patch = cubic_ramp();
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const double h = 0.25;
  const double tolerance = 0.75 * h * h + h * h * h / 30.0;  // the quick bounds need 0.75 h^2 + h^3 / 8
  const GridSize grid = grid_for_tolerance(M, tolerance, 1);
  EXPECT_LE(grid.segments_u * grid.segments_v, 4);
  EXPECT_LE(flatness_bound(M, 1.0 / grid.segments_u, 1.0 / grid.segments_v), tolerance);
}

// The cell bound's fourth-order remainder against brute force: at points of both halves of a
// cell, (1/24) sum_k lambda_k sum_a C(4,a) f_a |d_ku|^(4-a) |d_kv|^a (the most |D^4 F[d_k]^4| can
// be with |d^4 F / du^(4-a) dv^a| <= f_a) is at most c_1 m_1 + c_3 m_3, m the normalised second
// moments. Cells from flat to tall, each fourth derivative alone and all together.
RC_GTEST_PROP(PatchFlatness, FourthOrderRemainderCoversEveryPointOfACell, ()) {
  std::array<double, 5> f{};
  const int alone = *rc::gen::inRange(-1, 5);
  for (int a = 0; a < 5; ++a) f[a] = alone < 0 || alone == a ? *testing::coordinate(0.1, 10.0) : 0.0;
  const double du = std::pow(2.0, -*rc::gen::inRange(0, 8));
  const double dv = std::pow(2.0, -*rc::gen::inRange(0, 8));
  const auto [c1, c3] = detail::fourth_order_coefficients(f, du, dv);
  constexpr std::array<double, 5> binomial = {1, 4, 6, 4, 1};
  // Lower half (0,0), (1,0), (1,1) and upper half (0,0), (1,1), (0,1), in units of the steps.
  const std::array<std::array<Vec2, 3>, 2> halves = {std::array<Vec2, 3>{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)},
                                                     std::array<Vec2, 3>{Vec2(0, 0), Vec2(1, 1), Vec2(0, 1)}};
  const int samples = 12;
  for (const auto& corners : halves) {
    for (int i = 0; i <= samples; ++i) {
      for (int j = 0; i + j <= samples; ++j) {
        const std::array<double, 3> lambda = {1.0 - (i + j) / double(samples), i / double(samples),
                                              j / double(samples)};
        const Vec2 x = lambda[0] * corners[0] + lambda[1] * corners[1] + lambda[2] * corners[2];
        double remainder = 0.0, m1 = 0.0, m3 = 0.0;
        for (int k = 0; k < 3; ++k) {
          const Vec2 d = corners[k] - x;
          m1 += lambda[k] * d.x() * d.x();
          m3 += lambda[k] * d.y() * d.y();
          for (int a = 0; a < 5; ++a) {
            remainder += lambda[k] * binomial[a] * f[a] * std::pow(std::abs(d.x()) * du, 4 - a) *
                         std::pow(std::abs(d.y()) * dv, a) / 24.0;
          }
        }
        RC_ASSERT(remainder <= (c1 * m1 + c3 * m3) * (1.0 + 1e-12) + 1e-300);
      }
    }
  }
}

TEST(PatchFlatness, RejectsBadInput) {
  const SecondDerivativeBounds M{1.0, 1.0, 1.0};
  EXPECT_THROW(flatness_bound(M, 0.0, 0.5), InvalidInput);
  EXPECT_THROW(grid_for_tolerance(M, 0.0), InvalidInput);
  EXPECT_THROW(grid_for_tolerance(M, -1.0), InvalidInput);
  EXPECT_THROW(grid_for_tolerance(M, std::nan("")), InvalidInput);
  EXPECT_THROW(grid_for_tolerance(M, 1e-300), InvalidInput);  // would need more than 2^20 segments
  EXPECT_THROW(grid_for_tolerance(M, 1.0, 0), InvalidInput);
  EXPECT_THROW(grid_for_tolerance(M, 1.0, (1 << 20) + 1), InvalidInput);
}

}  // namespace
}  // namespace patchwork

namespace patchwork {
namespace {

TEST(TriangleFlatnessBound, AGridTriangleGetsTheGridBound) {
  const SecondDerivativeBounds M{3.0, 1.5, 0.7};
  const double du = 0.25, dv = 0.1;
  EXPECT_NEAR(triangle_flatness_bound(M, Vec2(0, 0), Vec2(du, 0), Vec2(du, dv), dv / du), flatness_bound(M, du, dv),
              1e-15);
}

TEST(RefinedTriangleFlatnessBound, TendsToTheTrueMaximum) {
  // F = (u, v, u^3) on the triangle (0,0), (1,0), (0,1): L = (u, v, u), so |F - L| = u - u^3, at
  // most 2 / (3 sqrt 3) at u = 1/sqrt 3. The a-priori bound is |F_uu| / 8 = 0.75, nearly twice that.
  const BezierPatch3 patch = cubic_ramp();
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const std::function<Vec3(const Vec2&)> surface = [&](const Vec2& p) { return patch.evaluate(p.x(), p.y()); };
  const Vec2 a(0, 0), b(1, 0), c(0, 1);
  const double exact = 2.0 / (3.0 * std::sqrt(3.0));
  const double quick = triangle_flatness_bound(M, a, b, c);
  EXPECT_NEAR(quick, 0.75, 1e-12);
  // Each level of splitting leaves a quarter of the a-priori part: 6 levels come within 1%.
  const double refined = refined_triangle_flatness_bound(M, surface, a, b, c, 1.0, 1.01 * exact, 6);
  EXPECT_LE(refined, 1.01 * exact);
  EXPECT_GE(refined, exact * (1.0 - 1e-12));
  // A target below the true maximum cannot be met: the a-priori bound stands.
  EXPECT_EQ(refined_triangle_flatness_bound(M, surface, a, b, c, 1.0, 0.99 * exact, 6), quick);
  // A target the a-priori bound meets needs no split.
  EXPECT_EQ(refined_triangle_flatness_bound(M, surface, a, b, c, 1.0, quick, 6), quick);
}

// The refined bound still bounds the sampled distance, and is never above the a-priori one.
RC_GTEST_PROP(RefinedTriangleFlatnessBound, BoundsTheSampledDistanceAndNeverExceedsTheAPrioriBound, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 5);
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  const std::function<Vec3(const Vec2&)> surface = [&](const Vec2& p) { return patch.evaluate(p.x(), p.y()); };
  std::array<Vec2, 3> p;
  for (Vec2& q : p) q = Vec2(*testing::coordinate(0, 1), *testing::coordinate(0, 1));
  const double quick = triangle_flatness_bound(M, p[0], p[1], p[2]);
  const double target = quick * *testing::coordinate(0.3, 1.1);
  const double refined =
      refined_triangle_flatness_bound(M, surface, p[0], p[1], p[2], 1.0, target, *rc::gen::inRange(0, 5));
  RC_TAG(refined <= target && refined < quick ? "refined below the target" : "a-priori bound");
  RC_ASSERT(refined <= quick);
  RC_ASSERT(sampled_triangle_distance(patch, p, 16) <= refined * (1 + 1e-9) + 1e-12 * testing::net_scale(patch));
}

// The bound holds for any triangle (not just grid cells): sampled |F - L| never exceeds it.
RC_GTEST_PROP(TriangleFlatnessBound, BoundsTheSampledDistanceOnAnyTriangle, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const SecondDerivativeBounds M = second_derivative_bounds(patch);
  std::array<Vec2, 3> p;
  for (Vec2& q : p) q = Vec2(*testing::coordinate(0, 1), *testing::coordinate(0, 1));
  const double aspect = *testing::coordinate(0.1, 10);
  const double bound = triangle_flatness_bound(M, p[0], p[1], p[2], aspect);
  RC_ASSERT(sampled_triangle_distance(patch, p, 12) <= bound * (1 + 1e-9) + 1e-12 * testing::net_scale(patch));
}

}  // namespace
}  // namespace patchwork

namespace patchwork {
namespace {

// The bounds from p x p pieces (segment matrices) equal those of the de Casteljau sub-patches,
// and never exceed the whole net's: sub-net differences are convex combinations of the net's,
// times 1/p^2 per order, which the factor p^2 undoes.
RC_GTEST_PROP(PatchFlatness, PieceBoundsAreTheSubpatchesAndNoLargerThanTheNets, ()) {
  const int n = *rc::gen::inRange(0, 6);
  const int m = *rc::gen::inRange(0, 6);
  const int pieces = *rc::gen::inRange(1, 6);
  std::vector<Vec3> points;
  for (int k = 0; k < (n + 1) * (m + 1); ++k) {
    points.emplace_back(*rc::gen::inRange(-100, 101) / 10.0, *rc::gen::inRange(-100, 101) / 10.0,
                        *rc::gen::inRange(-100, 101) / 10.0);
  }
  const BezierPatch3 patch(n, m, points);
  const SecondDerivativeBounds fast = second_derivative_bounds(patch, pieces);
  SecondDerivativeBounds reference{0, 0, 0};
  SecondDerivativeBounds directions{0, 0, 0};
  for (int b = 0; b < pieces; ++b) {
    for (int a = 0; a < pieces; ++a) {
      const double p = pieces;
      const SecondDerivativeBounds s =
          second_derivative_bounds(subpatch(patch, a / p, (a + 1) / p, b / p, (b + 1) / p));
      reference = {std::max(reference.uu, p * p * s.uu), std::max(reference.uv, p * p * s.uv),
                   std::max(reference.vv, p * p * s.vv)};
      // The directional bounds, merged piece by piece after the chain rule.
      const SecondDerivativeBounds in_patch = scaled_bounds(s, p);
      directions = a + b == 0 ? in_patch : merged_bounds(directions, in_patch);
    }
  }
  const SecondDerivativeBounds whole = second_derivative_bounds(patch);
  const double slack = 1e-9 * (1.0 + whole.uu + whole.uv + whole.vv);
  RC_ASSERT(std::abs(fast.uu - reference.uu) <= slack);
  RC_ASSERT(std::abs(fast.uv - reference.uv) <= slack);
  RC_ASSERT(std::abs(fast.vv - reference.vv) <= slack);
  RC_ASSERT(fast.uu <= whole.uu + slack);
  RC_ASSERT(fast.uv <= whole.uv + slack);
  RC_ASSERT(fast.vv <= whole.vv + slack);
  RC_ASSERT(fast.directions.has_value() && directions.directions.has_value());
  const DirectionalBounds& d = *fast.directions;
  const DirectionalBounds& r = *directions.directions;
  const double gram_slack = slack * (1.0 + whole.uu + whole.uv + whole.vv);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      RC_ASSERT(std::abs(d.gram_max[i][j] - r.gram_max[i][j]) <= gram_slack);
      RC_ASSERT(std::abs(d.gram_min[i][j] - r.gram_min[i][j]) <= gram_slack);
      RC_ASSERT(d.gram_max[i][j] >= d.gram_min[i][j]);
    }
    // The diagonal bounds the squared norms: no larger than the norm bounds squared.
    const double norm = i == 0 ? fast.uu : i == 1 ? fast.uv : fast.vv;
    RC_ASSERT(d.gram_max[i][i] <= norm * norm + gram_slack);
  }
  for (int k = 0; k < 4; ++k) RC_ASSERT(std::abs(d.third[k] - r.third[k]) <= slack * (1.0 + r.third[k]));
  for (int k = 0; k < 5; ++k) RC_ASSERT(std::abs(d.fourth[k] - r.fourth[k]) <= slack * (1.0 + r.fourth[k]));
}

}  // namespace
}  // namespace patchwork
