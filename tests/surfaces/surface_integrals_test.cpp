#include "surfaces/surface_integrals.h"

#include <gtest/gtest.h>

#include <numbers>

#include "core/errors.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {

// The unit cube [0,1]^3 as six bilinear patches with F_u x F_v pointing out.
std::vector<BezierPatch3> unit_cube(const Vec3& offset) {
  const auto face = [&](Vec3 origin, Vec3 a, Vec3 b) {
    return testing::bilinear(offset + origin, offset + origin + a, offset + origin + b, offset + origin + a + b);
  };
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ(), o = Vec3::Zero();
  return {face(o, y, x), face(z, x, y), face(o, x, z), face(y, z, x), face(o, z, y), face(x, y, z)};
}

TEST(SurfaceArea, BilinearRectangle) {
  const BezierPatch3 rectangle = testing::bilinear(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(2, 3, 0));
  EXPECT_NEAR(area(rectangle).value, 6.0, 1e-13);
}

TEST(SurfaceArea, PlanarPatchWithNonUniformSpacing) {
  // x(u) with control values 0, 0.1, 2.5, 3 (monotone) and y(v) with 0, 1.7, 1.9, 2: the same
  // rectangle [0,3] x [0,2], parametrised unevenly; the area does not depend on that: 6.
  const BezierPatch3 patch = testing::product_patch({Vec3(0, 1, 0), Vec3(0.1, 1, 0), Vec3(2.5, 1, 0), Vec3(3, 1, 0)},
                                                    {Vec3(1, 0, 0), Vec3(1, 1.7, 0), Vec3(1, 1.9, 0), Vec3(1, 2, 0)});
  const SurfaceIntegral result = area(patch, 1e-12);
  EXPECT_NEAR(result.value, 6.0, 1e-11);
  EXPECT_LE(std::abs(result.value - 6.0), std::max(result.error_estimate, 1e-12) + 1e-13);
}

TEST(SurfaceArea, SphereOctantIsPiOverTwo) {
  // Seed Beispiel 4: the unit sphere has area 4 pi, an octant pi/2.
  const SurfaceIntegral octant = area(sphere_octant(Vec3::Zero(), 1.0), 1e-12);
  EXPECT_NEAR(octant.value, std::numbers::pi / 2.0, 1e-10);
  const SurfaceIntegral scaled = area(sphere_octant(Vec3(3, 4, 5), 2.0), 1e-12);
  EXPECT_NEAR(scaled.value, 2.0 * std::numbers::pi, 4e-10);
}

TEST(SurfaceVolume, UnitCubeAnywhere) {
  for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(10, -20, 30)}) {
    const std::vector<BezierPatch3> cube = unit_cube(offset);
    // Each contribution is exact for bilinear patches; the sum of six terms of size ~|offset|^3.
    EXPECT_NEAR(enclosed_volume(cube), 1.0, 1e-15 * 6.0 * std::pow(1.0 + offset.norm(), 3));
  }
}

TEST(SurfaceVolume, CurvedCubeFacesKeepTheVolume) {
  // Elevate the faces to degree (3, 2) and move the inner control points within each face's
  // plane: the edges stay, the faces stay planar, so the enclosed volume stays 1 exactly.
  std::vector<BezierPatch3> cube = unit_cube(Vec3::Zero());
  for (BezierPatch3& face : cube) {
    const BezierPatch3 elevated = elevate_degree(face, 2, 1);
    const Vec3 a = face.control_point(1, 0) - face.control_point(0, 0);
    const Vec3 b = face.control_point(0, 1) - face.control_point(0, 0);
    std::vector<Vec3> points = elevated.control_points();
    points[1 + 4 * 1] += 0.3 * a - 0.2 * b;
    points[2 + 4 * 1] += -0.1 * a + 0.25 * b;
    face = BezierPatch3(3, 2, points);
  }
  EXPECT_NEAR(enclosed_volume(cube), 1.0, 1e-14);
}

TEST(SurfaceVolume, InwardOrientationIsNegative) {
  std::vector<BezierPatch3> cube = unit_cube(Vec3::Zero());
  for (BezierPatch3& face : cube) {
    // Swapping u and v flips F_u x F_v.
    face = BezierPatch3(1, 1, {face.control_point(0, 0), face.control_point(0, 1), face.control_point(1, 0), face.control_point(1, 1)});
  }
  EXPECT_NEAR(enclosed_volume(cube), -1.0, 1e-15);
}

TEST(SurfaceVolume, SphereFromEightOctants) {
  // Rotations by 90 degrees about z and a mirror in z give the eight octants; the mirror flips
  // the orientation, so those octants are flipped back by swapping u and v.
  double volume = 0.0;
  double total_area = 0.0;
  for (int quarter = 0; quarter < 4; ++quarter) {
    for (int side : {1, -1}) {
      const RationalBezierPatch base = sphere_octant(Vec3::Zero(), 1.0);
      const Eigen::Matrix3d rotation = Eigen::AngleAxisd(quarter * std::numbers::pi / 2.0, Vec3::UnitZ()).toRotationMatrix();
      const Eigen::Matrix3d mirror = Eigen::Vector3d(1.0, 1.0, side).asDiagonal();
      std::vector<Vec4> points;
      for (int j = 0; j <= 2; ++j) {
        for (int i = 0; i <= 2; ++i) {
          const int si = side == 1 ? i : j;
          const int sj = side == 1 ? j : i;
          const Vec4& h = base.homogeneous().control_point(si, sj);
          Vec4 moved;
          moved << mirror * rotation * h.head<3>(), h[3];
          points.push_back(moved);
        }
      }
      const RationalBezierPatch octant{BezierPatch4(2, 2, points)};
      volume += volume_contribution(octant, 1e-12).value;
      total_area += area(octant, 1e-12).value;
    }
  }
  EXPECT_NEAR(total_area, 4.0 * std::numbers::pi, 1e-9);
  EXPECT_NEAR(volume, 4.0 * std::numbers::pi / 3.0, 1e-9);
}

TEST(SurfaceIntegral, RejectsBadTolerance) {
  EXPECT_THROW(integrate_over_square([](double, double) { return 1.0; }, 0.0), InvalidInput);
  EXPECT_THROW(integrate_over_square([](double, double) { return 1.0; }, std::nan("")), InvalidInput);
}

}  // namespace
}  // namespace patchwork
