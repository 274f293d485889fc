#include "surfaces/patch_bounding_box.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  // Tight: in each direction refine around the best sample (cells of 1/40, then 1/1600); the
  // value found can miss the true extreme by at most (1/8) M h^2 with M <= 4 * 3 * 40 (degree
  // <= 4, second differences <= 40) and h = 1/1600 * sqrt(2): < 2e-4.
  for (int c = 0; c < 3; ++c) {
    for (double sign : {1.0, -1.0}) {
      double best = -1e300, best_u = 0, best_v = 0;
      const auto search = [&](double u0, double v0, double step) {
        for (int a = 0; a <= 40; ++a) {
          for (int b = 0; b <= 40; ++b) {
            const double u = std::clamp(u0 + a * step, 0.0, 1.0), v = std::clamp(v0 + b * step, 0.0, 1.0);
            const double value = sign * patch.evaluate(u, v)[c];
            if (value > best) best = value, best_u = u, best_v = v;
          }
        }
      };
      search(0.0, 0.0, 1.0 / 40.0);
      search(best_u - 1.0 / 40.0, best_v - 1.0 / 40.0, 1.0 / 800.0);
      const double face = sign > 0 ? box.max()[c] : -box.min()[c];
      RC_ASSERT(face >= best - 1e-13);  // evaluated samples carry a few roundings of size 10
      RC_ASSERT(face <= best + 2e-4 + tolerance);
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
