#include "surfaces/surface_curvature.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "io/bpt.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/patch_transform.h"
#include "surfaces/surface_normal.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/rational_shapes.h"

namespace patchwork::surface_curvature_test {
namespace {

// Parameters spread over [a, b], both ends included.
std::vector<double> spread(double a, double b, int count) {
  std::vector<double> values;
  for (int k = 0; k < count; ++k) values.push_back(a + (b - a) * k / (count - 1));
  return values;
}

// |d . e| = 1: the unit vectors are parallel (up to sign).
double misalignment(const Vec3& d, const Vec3& e) { return 1.0 - std::abs(d.dot(e.normalized())); }

// A sphere of radius r about c with the outward normal (side = 1): k1 = k2 = H = -1/r,
// K = 1/r^2, umbilic, n = (x - c) / r; with the inward normal (side = -1) k1 = k2 = H = +1/r.
void expect_sphere(const SurfaceCurvature& k, const Vec3& x, const Vec3& c, double r, double tolerance,
                   double side = 1.0) {
  ASSERT_TRUE(k.defined);
  EXPECT_NEAR(k.gaussian, 1.0 / (r * r), tolerance / (r * r));
  EXPECT_NEAR(k.mean, -side / r, tolerance / r);
  EXPECT_NEAR(k.k1, -side / r, tolerance / r);
  EXPECT_NEAR(k.k2, -side / r, tolerance / r);
  EXPECT_TRUE(k.umbilic);
  EXPECT_LT((k.normal - side * (x - c) / r).norm(), tolerance);
  EXPECT_NEAR(k.d1.norm(), 1.0, 1e-15);
  EXPECT_LT(std::abs(k.d1.dot(k.normal)), 1e-15);
  EXPECT_LT((k.d1.cross(k.d2) - k.normal).norm(), 1e-15);
}

TEST(SurfaceCurvature, SphereOctantIsUmbilicWithMeanMinusOneOverR) {
  const Vec3 c(1.0, -2.0, 0.5);
  const double r = 3.0;
  const RationalBezierPatch octant = sphere_octant(c, r);
  const RationalBezierPatch transposed = testing::transposed(octant);
  for (const double u : spread(0.0, 1.0, 7)) {
    for (const double v : spread(0.0, 1.0, 7)) {
      const SurfaceCurvature k = curvature(octant, u, v);
      expect_sphere(k, octant.evaluate(u, v), c, r, 1e-13);
      // Row j = 2 is the pole (0, 0, r): computed there from the curves through it.
      EXPECT_EQ(k.at_pole, v == 1.0);
      if (v == 1.0) {
        EXPECT_LT(k.pole_residual, 1e-14 / r);
      }
      // u and v exchanged: the normal points inward, the curvatures change sign, and the pole
      // is the edge u = 1.
      const SurfaceCurvature inward = curvature(transposed, v, u);
      expect_sphere(inward, transposed.evaluate(v, u), c, r, 1e-13, -1.0);
      EXPECT_EQ(inward.at_pole, v == 1.0);
    }
  }
}

TEST(SurfaceCurvature, NurbsSphereIncludingItsPoles) {
  const Vec3 c(0.0, 0.5, -1.0);
  const double r = 0.75;
  const NurbsSurface sphere = nurbs_sphere(c, r);
  int poles = 0;
  for (const double u : spread(sphere.knots_u().a(), sphere.knots_u().b(), 9)) {
    for (const double v : spread(sphere.knots_v().a(), sphere.knots_v().b(), 9)) {
      const SurfaceCurvature k = curvature(sphere, u, v);
      expect_sphere(k, sphere.evaluate(u, v), c, r, 1e-12);
      poles += k.at_pole ? 1 : 0;
    }
  }
  EXPECT_EQ(poles, 2 * 9);  // both rows of poles
}

// The same sphere 10^6 away (not at integer coordinates): its poles' F_u is rounding of the
// coordinates' size, not 0, and must still count as vanishing (surface_normal.h's rule), so the
// poles take the pole fit; every curvature is the unmoved sphere's to that distance's rounding.
TEST(SurfaceCurvature, NurbsSphereFarFromTheOriginKeepsItsPoles) {
  const double r = 0.75;
  const NurbsSurface near = nurbs_sphere(Vec3(0.0, 0.5, -1.0), r);
  const NurbsSurface far = nurbs_sphere(Vec3(1e6 + 0.1, 7e5 + 0.3, -3e5 + 0.7), r);
  int poles = 0;
  for (const double u : spread(near.knots_u().a(), near.knots_u().b(), 9)) {
    for (const double v : spread(near.knots_v().a(), near.knots_v().b(), 9)) {
      const SurfaceCurvature expected = curvature(near, u, v);
      const SurfaceCurvature k = curvature(far, u, v);
      SCOPED_TRACE(::testing::Message() << "(" << u << ", " << v << ")");
      ASSERT_TRUE(k.defined);
      EXPECT_EQ(k.at_pole, expected.at_pole);
      EXPECT_NEAR(k.k1 * r, expected.k1 * r, 1e-6);
      EXPECT_NEAR(k.k2 * r, expected.k2 * r, 1e-6);
      EXPECT_LT((k.normal - expected.normal).norm(), 1e-6);
      poles += k.at_pole ? 1 : 0;
    }
  }
  EXPECT_EQ(poles, 2 * 9);
}

// The cylinder about z of radius r, outward normal: k1 = 0 along the axis, k2 = -1/r around it,
// K = 0, H = -1/(2r).
TEST(SurfaceCurvature, CylinderBendsAroundItsAxisOnly) {
  const double r = 1.5;
  const NurbsSurface cylinder = nurbs_cylinder(Vec3(0.5, 0.0, -1.0), r, 4.0);
  for (const double u : spread(cylinder.knots_u().a(), cylinder.knots_u().b(), 13)) {
    for (const double v : spread(cylinder.knots_v().a(), cylinder.knots_v().b(), 3)) {
      const SurfaceCurvature k = curvature(cylinder, u, v);
      ASSERT_TRUE(k.defined);
      const Vec3 x = cylinder.evaluate(u, v);
      const Vec3 radial = Vec3(x.x() - 0.5, x.y(), 0.0) / r;
      EXPECT_NEAR(k.gaussian, 0.0, 1e-13);
      EXPECT_NEAR(k.mean, -0.5 / r, 1e-13);
      EXPECT_NEAR(k.k1, 0.0, 1e-13);
      EXPECT_NEAR(k.k2, -1.0 / r, 1e-13);
      EXPECT_FALSE(k.umbilic);
      EXPECT_LT((k.normal - radial).norm(), 1e-13);
      EXPECT_LT(misalignment(k.d1, Vec3::UnitZ()), 1e-13);
      EXPECT_LT(misalignment(k.d2, Vec3::UnitZ().cross(radial)), 1e-13);
    }
  }
}

// The torus about z with major radius R and minor r: a point at tube angle phi (cos phi =
// (rho - R) / r, rho the distance from the axis) has, with the outward normal, the meridian
// curvature -1/r and the parallel's -cos(phi) / (R + r cos phi), so
//   K = cos(phi) / (r (R + r cos(phi))),   H = -(R + 2 r cos(phi)) / (2 r (R + r cos(phi))),
// k1 along the parallel (horizontal), k2 along the meridian.
TEST(SurfaceCurvature, TorusMatchesTheClosedForms) {
  const double R = 2.0, r = 0.5;
  const Vec3 c(0.0, 0.0, 1.0);
  const NurbsSurface torus = nurbs_torus(c, R, r);
  for (const double u : spread(torus.knots_u().a(), torus.knots_u().b(), 11)) {
    for (const double v : spread(torus.knots_v().a(), torus.knots_v().b(), 17)) {
      const SurfaceCurvature k = curvature(torus, u, v);
      ASSERT_TRUE(k.defined);
      const Vec3 x = torus.evaluate(u, v) - c;
      const double rho = std::hypot(x.x(), x.y());
      const double cos_phi = (rho - R) / r;
      const Vec3 radial(x.x() / rho, x.y() / rho, 0.0);
      const Vec3 parallel = Vec3::UnitZ().cross(radial);
      EXPECT_NEAR(k.gaussian, cos_phi / (r * (R + r * cos_phi)), 1e-12);
      EXPECT_NEAR(k.mean, -(R + 2 * r * cos_phi) / (2 * r * (R + r * cos_phi)), 1e-12);
      EXPECT_NEAR(k.k1, -cos_phi / (R + r * cos_phi), 1e-12);
      EXPECT_NEAR(k.k2, -1.0 / r, 1e-12);
      EXPECT_LT(misalignment(k.d1, parallel), 1e-12);
      EXPECT_LT(misalignment(k.d2, parallel.cross(k.normal)), 1e-12);
      EXPECT_LT((k.normal - (x - R * radial) / r).norm(), 1e-12);
    }
  }
}

TEST(SurfaceCurvature, PlaneIsFlatAndUmbilic) {
  const BezierPatch3 plane = testing::bilinear(Vec3(0, 0, 1), Vec3(2, 1, 1), Vec3(-1, 3, 1), Vec3(1.5, 4, 1));
  for (const double u : spread(0.0, 1.0, 5)) {
    for (const double v : spread(0.0, 1.0, 5)) {
      const SurfaceCurvature k = curvature(plane, u, v);
      ASSERT_TRUE(k.defined);
      EXPECT_EQ(k.gaussian, 0.0);
      EXPECT_EQ(k.mean, 0.0);
      EXPECT_TRUE(k.umbilic);
      EXPECT_LT((k.normal - Vec3::UnitZ()).norm(), 1e-15);
    }
  }
}

// z = x y over [-1, 2] x [-2, 1] is bilinear, so the bilinear patch through its corners is the
// saddle itself: F_u x F_v is along (-y, -x, 1), and with W = sqrt(1 + x^2 + y^2)
//   K = -1 / W^4,   H = -x y / W^3.
TEST(SurfaceCurvature, SaddleMatchesTheClosedForms) {
  const auto corner = [](double x, double y) { return Vec3(x, y, x * y); };
  const BezierPatch3 saddle = testing::bilinear(corner(-1, -2), corner(2, -2), corner(-1, 1), corner(2, 1));
  for (const double u : spread(0.0, 1.0, 9)) {
    for (const double v : spread(0.0, 1.0, 9)) {
      const SurfaceCurvature k = curvature(saddle, u, v);
      ASSERT_TRUE(k.defined);
      const double x = -1.0 + 3.0 * u, y = -2.0 + 3.0 * v;
      const double W = std::sqrt(1.0 + x * x + y * y);
      EXPECT_NEAR(k.gaussian, -1.0 / std::pow(W, 4), 1e-14);
      EXPECT_NEAR(k.mean, -x * y / std::pow(W, 3), 1e-14);
      EXPECT_NEAR(k.k1 * k.k2, k.gaussian, 1e-15);
      EXPECT_LT((k.normal - Vec3(-y, -x, 1.0) / W).norm(), 1e-14);
    }
  }
}

// A cone's apex is a pole whose curves leave it on a cone, not in a plane: no curvature there.
TEST(SurfaceCurvature, ConeApexIsNotDefined) {
  const NurbsSurface cone = nurbs_cone(Vec3::Zero(), 1.0, 2.0);
  const SurfaceCurvature apex = curvature(cone, cone.knots_u().a(), cone.knots_v().b());
  EXPECT_FALSE(apex.defined);
  EXPECT_TRUE(std::isnan(apex.gaussian));
  EXPECT_TRUE(std::isnan(apex.k1));
  // Away from it the cone is developable: K = 0.
  const SurfaceCurvature side = curvature(cone, cone.knots_u().a(), 0.5 * (cone.knots_v().a() + cone.knots_v().b()));
  ASSERT_TRUE(side.defined);
  EXPECT_NEAR(side.gaussian, 0.0, 1e-13);
}

// The teapot's lid and bottom are near-surfaces of revolution with poles (row v0 of patches 20-23
// and 28-31 collapsed). On a surface of revolution the pole is umbilic: K = k^2, H = -k (outward
// normal, the cap bending away from it) with k the curvature of the profile, the patch's column
// u0 through the pole. The teapot's circles are cubic approximations (the curves through the pole
// curve by k / |q|^2 with |q| up to 1.004 off the axis planes), so the surface is not exactly C^2
// at the pole: the fit's residual says how far (measured: 3.5e-4 on the lid, where k = 0.3125,
// and 2.0e-5 on the bottom, where k = 0.0246), and H, K are the revolution's within it
// (measured: |H + k| = 2.4e-4 and 1.3e-5).
TEST(SurfaceCurvature, TeapotPolesMatchTheProfileWithinTheResidual) {
  const std::vector<BezierPatch3> teapot = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  int poles = 0;
  for (const int p : {20, 21, 22, 23, 28, 29, 30, 31}) {
    const BezierPatch3& patch = teapot[static_cast<std::size_t>(p)];
    const double k = curvature(boundary_curve(patch, PatchEdge::u0), 0.0);
    for (const double u : spread(0.0, 1.0, 5)) {
      const SurfaceCurvature c = curvature(patch, u, 0.0);
      ASSERT_TRUE(c.defined) << "patch " << p;
      EXPECT_TRUE(c.at_pole);
      EXPECT_LT((c.normal - Vec3(0.0, 0.0, p < 28 ? 1.0 : -1.0)).norm(), 1e-15);  // lid up, bottom down
      EXPECT_GT(c.pole_residual, 1e-4 * k);  // not a surface of revolution to rounding
      EXPECT_LT(c.pole_residual, 2e-3 * k);
      EXPECT_LE(std::abs(c.mean + k), c.pole_residual) << "patch " << p;
      EXPECT_LE(std::abs(c.gaussian - k * k), 2.0 * k * c.pole_residual) << "patch " << p;
      ++poles;
    }
  }
  EXPECT_EQ(poles, 8 * 5);
}

// The largest principal curvature's size and the smallest angle's sine between F_u and F_v:
// where the patch is well-conditioned (sine >= 1/10), the curvature's rounding is a small
// multiple of eps times |F_uu| / |F_u|^2 (the size of every term of the shape operator).
struct Conditioning {
  double curvature_scale;
  double sine;
};

Conditioning conditioning(const BezierPatch3& patch, double u, double v) {
  const PartialDerivatives<3> F = partial_derivatives(patch, u, v, 2);
  const double first = std::min(F.at(1, 0).norm(), F.at(0, 1).norm());
  const double second = std::max({F.at(2, 0).norm(), F.at(1, 1).norm(), F.at(0, 2).norm()});
  const double sine = F.at(1, 0).cross(F.at(0, 1)).norm() / (F.at(1, 0).norm() * F.at(0, 1).norm());
  return {second / (first * first) + 1e-300, sine};
}

// Curvature is a property of the surface's shape: a rigid motion keeps K, H, k1, k2, turns the
// normal and the principal directions with it.
RC_GTEST_PROP(SurfaceCurvature, RigidMotionKeepsTheCurvature, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const double u = *testing::coordinate(0.0, 1.0), v = *testing::coordinate(0.0, 1.0);
  const Conditioning condition = conditioning(patch, u, v);
  RC_PRE(condition.sine >= 0.1);
  const Eigen::Isometry3d motion = *testing::random_rigid_motion();
  const SurfaceCurvature before = curvature(patch, u, v);
  const SurfaceCurvature after = curvature(transform(patch, Eigen::Affine3d(motion)), u, v);
  RC_ASSERT(before.defined && after.defined);
  const double bound = 1e-11 * condition.curvature_scale / (condition.sine * condition.sine);
  RC_ASSERT(std::abs(after.k1 - before.k1) <= bound);
  RC_ASSERT(std::abs(after.k2 - before.k2) <= bound);
  RC_ASSERT(std::abs(after.mean - before.mean) <= bound);
  RC_ASSERT(std::abs(after.gaussian - before.gaussian) <= bound * (std::abs(before.k1) + std::abs(before.k2) + bound));
  RC_ASSERT((after.normal - motion.linear() * before.normal).norm() <= 1e-12 / condition.sine);
  // The directions, where they are well apart (k1 - k2 not small against the rounding).
  if (before.k1 - before.k2 > 1e4 * bound) {
    RC_ASSERT(misalignment(after.d1, motion.linear() * before.d1) <= 1e-6);
  }
}

// Scaling by s divides every curvature by s (K by s^2); by a power of two, bit for bit, since
// every operation then scales exactly.
RC_GTEST_PROP(SurfaceCurvature, UniformScaleDividesTheCurvature, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const double u = *testing::coordinate(0.0, 1.0), v = *testing::coordinate(0.0, 1.0);
  const Conditioning condition = conditioning(patch, u, v);
  RC_PRE(condition.sine >= 0.1);
  const SurfaceCurvature before = curvature(patch, u, v);
  const double power = *rc::gen::element(0.25, 0.5, 2.0, 8.0);
  const SurfaceCurvature exact = curvature(transform(patch, Eigen::Affine3d(Eigen::Scaling(power))), u, v);
  RC_ASSERT(exact.k1 == before.k1 / power);
  RC_ASSERT(exact.k2 == before.k2 / power);
  RC_ASSERT(exact.mean == before.mean / power);
  RC_ASSERT(exact.gaussian == before.gaussian / (power * power));
  RC_ASSERT(exact.normal == before.normal);
  const double s = *testing::coordinate(0.1, 10.0);
  const SurfaceCurvature scaled = curvature(transform(patch, Eigen::Affine3d(Eigen::Scaling(s))), u, v);
  const double bound = 1e-11 * condition.curvature_scale / (condition.sine * condition.sine);
  RC_ASSERT(std::abs(scaled.k1 * s - before.k1) <= bound);
  RC_ASSERT(std::abs(scaled.k2 * s - before.k2) <= bound);
}

}  // namespace
}  // namespace patchwork::surface_curvature_test
