// The NURBS section's meter and ideal counts on closed forms (the section itself is checked in
// report_quick_test.cpp).

#include "report/nurbs_section.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace patchwork::performance {
namespace {

const ExactShape& shape(const std::string& name) {
  static const std::vector<ExactShape> shapes = exact_shapes();
  for (const ExactShape& s : shapes) {
    if (s.name == name) return s;
  }
  throw std::logic_error("no shape " + name);
}

// The octahedron inscribed in the unit sphere: its corners lie on the sphere and its faces come
// closest to the centre at their centroids, at 1 / sqrt 3. The lattice of order 3 holds the
// centroid; those of order 4 and 64 do not, and come within (edge / 64)^2 of it from below.
TEST(NurbsSection, InscribedOctahedronIsOneMinusOneOverSqrtThreeFromTheSphere) {
  const std::vector<Vec3> corners{Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                  Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  std::vector<std::uint32_t> indices;
  for (const std::uint32_t x : {0u, 1u}) {
    for (const std::uint32_t y : {2u, 3u}) {
      for (const std::uint32_t z : {4u, 5u}) indices.insert(indices.end(), {x, y, z});
    }
  }
  const double exact = 1 - 1 / std::sqrt(3.0);
  EXPECT_NEAR(mesh_to_surface_distance(shape("sphere"), corners, indices, 3, 0), exact, 1e-15);
  const double sampled = mesh_to_surface_distance(shape("sphere"), corners, indices, 4, 8);
  EXPECT_LE(sampled, exact + 1e-15);
  EXPECT_GE(sampled, exact - 2.0 / (64 * 64));
  EXPECT_LT(mesh_to_surface_distance(shape("sphere"), corners, indices, 4, 0), sampled);
}

// Points off the torus (radii 2 and 1/2 about z): the centre is 2 - 1/2 from it, a point above
// the core circle 0.3 above the tube, one on the outer equator on it.
TEST(NurbsSection, TorusDistanceIsTheClosedForm) {
  const ExactShape& torus = shape("torus");
  EXPECT_NEAR(torus.distance(Vec3(0, 0, 0)), 1.5, 1e-15);
  EXPECT_NEAR(torus.distance(Vec3(0, 2, 0.8)), 0.3, 1e-15);
  EXPECT_NEAR(torus.distance(Vec3(-2.5 / std::sqrt(2.0), 2.5 / std::sqrt(2.0), 0)), 0.0, 1e-15);
  // One collapsed triangle at the centre: its distance from the lattice.
  EXPECT_NEAR(mesh_to_surface_distance(torus, {Vec3::Zero()}, {0, 0, 0}, 2, 1), 1.5, 1e-15);
}

// N_ideal = area kappa_max / (3 sqrt 3 / 2 e): the sphere's 4 pi R / (2.598 e); the torus's
// kappa_max is the tube's 1 / r = 2 (larger than the inner equator's 1 / (R - r) = 2/3).
TEST(NurbsSection, IdealUniformCountsAreTheClosedForms) {
  const double pi = std::numbers::pi;
  const double factor = 3 * std::sqrt(3.0) / 2;
  EXPECT_NEAR(ideal_uniform_triangles(shape("sphere"), 1e-3), 4 * pi / (factor * 1e-3), 1e-9);
  EXPECT_NEAR(ideal_uniform_triangles(shape("torus"), 1e-3), 4 * pi * pi * 2 * 0.5 * 2 / (factor * 1e-3), 1e-9);
}

TEST(NurbsSection, BadMeshesThrow) {
  const std::vector<Vec3> one{Vec3::Zero()};
  EXPECT_THROW(mesh_to_surface_distance(shape("sphere"), one, {0, 0, 1}, 4, 0), InvalidInput);
  EXPECT_THROW(mesh_to_surface_distance(shape("sphere"), one, {0, 0, 0}, 0, 0), InvalidInput);
}

}  // namespace
}  // namespace patchwork::performance
