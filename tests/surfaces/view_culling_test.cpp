#include "surfaces/view_culling.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "core/errors.h"
#include "io/bpt.h"
#include "surfaces/surface_normal.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

// The tensor Bernstein sum of coefficients of degrees (N, M) at (u, v).
double bernstein_sum(const std::vector<double>& c, int N, int M, double u, double v) {
  double sum = 0.0;
  for (int j = 0; j <= M; ++j) {
    for (int i = 0; i <= N; ++i) sum += c[static_cast<std::size_t>(i + (N + 1) * j)] * bernstein(N, i, u) * bernstein(M, j, v);
  }
  return sum;
}

// The coefficients represent g(u, v) = (F - eye) . (F_u x F_v) exactly (up to rounding).
RC_GTEST_PROP(ViewCulling, FacingCoefficientsRepresentTheTangentPlaneFunction, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const Vec3 eye(*testing::coordinate(-20, 20), *testing::coordinate(-20, 20), *testing::coordinate(-20, 20));
  const std::vector<double> c = facing_coefficients(patch, eye);
  const int n = patch.degree_u(), m = patch.degree_v();
  RC_ASSERT(c.size() == static_cast<std::size_t>((3 * n) * (3 * m)));
  double scale = 0.0;
  for (double x : c) scale = std::max(scale, std::abs(x));
  for (int k = 0; k < 5; ++k) {
    const double u = *testing::coordinate(0, 1), v = *testing::coordinate(0, 1);
    const double direct = (patch.evaluate(u, v) - eye).dot(normal(patch, u, v));
    RC_ASSERT(std::abs(bernstein_sum(c, 3 * n - 1, 3 * m - 1, u, v) - direct) <= 1e-10 * scale);
  }
}

TEST(ViewCulling, APlaneFacesTheSideItsNormalPointsTo) {
  // Normal F_u x F_v = +z.
  const BezierPatch3 square = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
  EXPECT_FALSE(back_facing(square, Vec3(0.5, 0.5, 3)));
  EXPECT_TRUE(back_facing(square, Vec3(0.5, 0.5, -3)));
  // Edge-on: not culled.
  EXPECT_FALSE(back_facing(square, Vec3(5, 0.5, 0)));
}

TEST(ViewCulling, FrustumAndToleranceFollowTheCamera) {
  const BezierPatch3 square = testing::bilinear(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(-1, 1, 0), Vec3(1, 1, 0));
  Camera camera;
  camera.eye = Vec3(0, -10, 0);
  camera.target = Vec3(0, 0, 0);
  camera.fov_degrees = 90;
  camera.width = camera.height = 1000;
  EXPECT_FALSE(outside_frustum(square, camera));
  EXPECT_DOUBLE_EQ(focal_length_pixels(camera), 500.0);
  EXPECT_DOUBLE_EQ(nearest_depth(square, camera), 9.0);
  camera.target = Vec3(0, -20, 0);  // looking away: the square is behind the eye
  EXPECT_TRUE(outside_frustum(square, camera));
  camera.target = Vec3(100, -10, 0);  // looking along +x: the square is far to the right... of -y
  EXPECT_TRUE(outside_frustum(square, camera));
  Camera bad = camera;
  bad.target = bad.eye;
  EXPECT_THROW(validate(bad), InvalidInput);
  bad = camera;
  bad.fov_degrees = 180;
  EXPECT_THROW(validate(bad), InvalidInput);
  bad = camera;
  bad.up = bad.target - bad.eye;
  EXPECT_THROW(validate(bad), InvalidInput);
}

// Cameras around the teapot: a culled patch never has a front-facing triangle inside the view,
// in a fine tessellation of the whole pot; and culling saves work.
TEST(ViewCulling, NoCulledPatchHasAVisibleFrontFacingTriangle) {
  const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  TessellationOptions fine;
  fine.relative_tolerance = 1e-3;
  fine.optimize = false;
  fine.measure = false;
  const Tessellation all = tessellate(set, fine);
  std::size_t culled_total = 0;
  for (int k = 0; k < 12; ++k) {
    const double angle = 2 * std::numbers::pi * k / 12;
    Camera camera;
    camera.eye = Vec3(8 * std::cos(angle), 8 * std::sin(angle), k % 3 == 0 ? 6.0 : (k % 3 == 1 ? -2.0 : 1.5));
    camera.target = Vec3(k % 2 ? 1.0 : 0.0, 0, 1.5);
    camera.fov_degrees = k % 4 == 0 ? 20 : 45;
    camera.width = 800;
    camera.height = 600;
    std::vector<bool> culled(set.patches().size());
    for (std::size_t p = 0; p < culled.size(); ++p) {
      culled[p] = outside_frustum(set.patches()[p], camera) || back_facing(set.patches()[p], camera.eye);
    }
    const Vec3 forward = (camera.target - camera.eye).normalized();
    const Vec3 right = forward.cross(camera.up).normalized();
    const Vec3 up = right.cross(forward);
    const double tan_v = std::tan(camera.fov_degrees * std::numbers::pi / 360), tan_h = tan_v * 800 / 600;
    const auto inside = [&](const Vec3& p) {
      const Vec3 q = p - camera.eye;
      const double z = q.dot(forward);
      return z > 0 && std::abs(q.dot(right)) <= z * tan_h && std::abs(q.dot(up)) <= z * tan_v;
    };
    for (std::size_t t = 0; t < all.mesh.triangle_count(); ++t) {
      if (!culled[all.triangle_patches[t]]) continue;
      const Vec3& a = all.mesh.positions[all.mesh.indices[3 * t]];
      const Vec3& b = all.mesh.positions[all.mesh.indices[3 * t + 1]];
      const Vec3& c = all.mesh.positions[all.mesh.indices[3 * t + 2]];
      const bool front = (a - camera.eye).dot((b - a).cross(c - a)) < 0;
      ASSERT_FALSE(front && (inside(a) || inside(b) || inside(c)))
          << "camera " << k << ": patch " << all.triangle_patches[t] << " culled with a visible front triangle " << t;
    }
    TessellationOptions view;
    view.camera = camera;
    view.pixel_tolerance = 0.5;
    // The teapot is open, so automatic culling leaves its back faces in; the predicate is
    // under test here, as a caller who asks for it gets it.
    view.back_face_culling = BackFaceCulling::always;
    view.measure = false;  // the culling is under test here, not the error (tested elsewhere)
    view.optimize = false;
    const Tessellation seen = tessellate(set, view);
    const auto expected = static_cast<std::size_t>(std::count(culled.begin(), culled.end(), true));
    EXPECT_EQ(seen.culled_patches, expected);
    for (std::uint32_t p : seen.triangle_patches) EXPECT_FALSE(culled[p]);
    culled_total += expected;
  }
  // The whole-patch test is conservative, yet every view culls some patches (34 of 384 here).
  EXPECT_GE(culled_total, 12u);
  std::cout << "culled " << culled_total << " of " << 12 * set.patches().size() << " patches over 12 views\n";
}

}  // namespace
}  // namespace patchwork
