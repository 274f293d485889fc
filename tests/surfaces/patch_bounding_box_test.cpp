#include "surfaces/patch_bounding_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>
#include <rapidcheck/gtest.h>

#include "core/errors.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

TEST(PatchBoundingBox, BumpHasItsTrueMaximum) {
  // z = 16 u(1-u) v(1-v): u(1-u) in degree 2 is (0, 1/2, 0), so the middle control point has
  // z = 4 while the surface peaks at z = 1 in (1/2, 1/2).
  const BezierPatch3 bump = testing::product_patch({Vec3(0, 1, 0), Vec3(0.5, 1, 2), Vec3(1, 1, 0)},
                                                   {Vec3(1, 0, 0), Vec3(1, 0.5, 2), Vec3(1, 1, 0)});
  EXPECT_EQ(control_box(bump).max().z(), 4.0);
  const Eigen::AlignedBox3d box = bounding_box(bump, 1e-12);
  EXPECT_GE(box.max().z(), 1.0);
  EXPECT_LE(box.max().z(), 1.0 + 1e-12);
  EXPECT_EQ(box.min().z(), 0.0);
  EXPECT_EQ(box.min().x(), 0.0);
  EXPECT_EQ(box.max().y(), 1.0);
}

RC_GTEST_PROP(PatchBoundingBox, ContainsSamplesAndIsTight, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const double tolerance = 1e-9;
  const Eigen::AlignedBox3d box = bounding_box(patch, tolerance);
  RC_ASSERT(control_box(patch).contains(box));
  Eigen::AlignedBox3d sampled(patch.evaluate(0, 0));
  for (int a = 0; a <= 40; ++a) {
    for (int b = 0; b <= 40; ++b) sampled.extend(patch.evaluate(a / 40.0, b / 40.0));
  }
  RC_ASSERT(box.contains(Eigen::AlignedBox3d(sampled.min() + Vec3::Constant(1e-13), sampled.max() - Vec3::Constant(1e-13))));
  // Tight: each face is within target + tolerance of the true extreme, which a branch and bound
  // over parameter cells brackets independently of the code under test. On a cell of side h the
  // surface exceeds the bilinear interpolant of its corner values by at most
  // h^2 / 8 (max |f_uu| + max |f_vv|), and |f_uu| <= n (n - 1) max |second u-differences| of the
  // control points (likewise in v); a cell whose best corner plus that bound stays below
  // best + target cannot hold a value above best + target, so when no cell is left the extreme
  // is at most best + target.
  const double target = 1e-5;
  for (int c = 0; c < 3; ++c) {
    const int n = patch.degree_u(), m = patch.degree_v();
    double second_u = 0, second_v = 0;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= m; ++j) {
        const auto at = [&](int a, int b) { return patch.control_point(a, b)[c]; };
        if (i + 2 <= n) second_u = std::max(second_u, std::abs(at(i + 2, j) - 2 * at(i + 1, j) + at(i, j)));
        if (j + 2 <= m) second_v = std::max(second_v, std::abs(at(i, j + 2) - 2 * at(i, j + 1) + at(i, j)));
      }
    }
    const double curvature = n * (n - 1) * second_u + m * (m - 1) * second_v;
    for (double sign : {1.0, -1.0}) {
      const auto value = [&](double u, double v) { return sign * patch.evaluate(u, v)[c]; };
      struct Cell { double u, v, h; };
      std::vector<Cell> open{{0.0, 0.0, 1.0}};
      double best = value(0, 0);
      while (!open.empty()) {
        const Cell cell = open.back();
        open.pop_back();
        const double corners = std::max({value(cell.u, cell.v), value(cell.u + cell.h, cell.v),
                                         value(cell.u, cell.v + cell.h), value(cell.u + cell.h, cell.v + cell.h)});
        best = std::max(best, corners);
        if (corners + cell.h * cell.h / 8 * curvature <= best + target) continue;
        const double half = cell.h / 2;
        for (const Cell child : {Cell{cell.u, cell.v, half}, Cell{cell.u + half, cell.v, half},
                                 Cell{cell.u, cell.v + half, half}, Cell{cell.u + half, cell.v + half, half}}) {
          open.push_back(child);
        }
      }
      const double face = sign > 0 ? box.max()[c] : -box.min()[c];
      RC_ASSERT(face >= best - 1e-13);  // evaluated samples carry a few roundings of size 10
      RC_ASSERT(face <= best + target + tolerance + 1e-13);
    }
  }
}

RC_GTEST_PROP(PatchBoundingBox, OfASetIsTheUnionUpToTheTolerance, ()) {
  // Both boxes are upper bounds within the tolerance of the set's true extremes, so their faces
  // are within the tolerance of each other; the set's box holds every sample of every patch.
  const int count = *rc::gen::inRange(1, 5);
  std::vector<BezierPatch3> patches;
  for (int k = 0; k < count; ++k) patches.push_back(*testing::random_patch(1, 4));
  const double tolerance = 1e-7;
  Eigen::AlignedBox3d joined;
  for (const BezierPatch3& patch : patches) joined.extend(bounding_box(patch, tolerance));
  const Eigen::AlignedBox3d box = bounding_box(std::span<const BezierPatch3>(patches), tolerance);
  for (int c = 0; c < 3; ++c) {
    RC_ASSERT(std::abs(box.max()[c] - joined.max()[c]) <= tolerance);
    RC_ASSERT(std::abs(box.min()[c] - joined.min()[c]) <= tolerance);
  }
  for (const BezierPatch3& patch : patches) {
    for (int a = 0; a <= 20; ++a) {
      for (int b = 0; b <= 20; ++b) {
        const Vec3 p = patch.evaluate(a / 20.0, b / 20.0);
        RC_ASSERT(((box.min() - Vec3::Constant(1e-13)).array() <= p.array()).all());
        RC_ASSERT((p.array() <= (box.max() + Vec3::Constant(1e-13)).array()).all());
      }
    }
  }
  RC_ASSERT(bounding_box(std::span<const BezierPatch3>(), tolerance).isEmpty());
}

TEST(PatchBoundingBox, RejectsBadTolerance) {
  const BezierPatch3 patch = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
  EXPECT_THROW(bounding_box(patch, 0.0), InvalidInput);
  const std::vector<BezierPatch3> set = {patch};
  EXPECT_THROW(bounding_box(std::span<const BezierPatch3>(set), -1.0), InvalidInput);
}

}  // namespace
}  // namespace patchwork
