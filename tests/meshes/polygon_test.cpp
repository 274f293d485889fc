// Single polygons (seed Def 41-45): Newell's normal and area, planarity with a tolerance,
// simplicity, orientation with respect to a normal.

#include "meshes/polygon.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

using testing::Random;

std::vector<Vec3> reversed(std::vector<Vec3> polygon) {
  std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

// The regular k-gon of radius r in the plane z = 0, counter-clockwise seen from +z.
std::vector<Vec3> regular(int k, double r) {
  std::vector<Vec3> polygon;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * std::numbers::pi * i / k;
    polygon.emplace_back(r * std::cos(t), r * std::sin(t), 0);
  }
  return polygon;
}

// A uniformly random rotation: a point uniform in the 4-ball, normalised, is a unit quaternion
// uniform on the 3-sphere.
Eigen::Matrix3d random_rotation(Random& random) {
  while (true) {
    const Eigen::Vector4d q(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    if (q.norm() > 0.1 && q.norm() <= 1.0) return Eigen::Quaterniond(q.normalized()).toRotationMatrix();
  }
}

TEST(Polygon, NewellNormalOfTheUnitSquare) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_EQ(newell_normal(square), Vec3(0, 0, 1));
  EXPECT_EQ(newell_normal(reversed(square)), Vec3(0, 0, -1));
  EXPECT_EQ(polygon_area(square), 1.0);
}

TEST(Polygon, RegularPolygonAreaIsClosedForm) {
  // Area k/2 r^2 sin(2 pi / k); k terms of a few roundings each, relative error below 1e-14.
  for (int k = 3; k <= 12; ++k) {
    const double r = 1.5;
    const double area = 0.5 * k * r * r * std::sin(2 * std::numbers::pi / k);
    const Vec3 normal = newell_normal(regular(k, r));
    EXPECT_NEAR(normal.z(), area, 1e-14 * area) << k;
    EXPECT_NEAR(normal.x(), 0.0, 1e-14 * area) << k;
    EXPECT_NEAR(normal.y(), 0.0, 1e-14 * area) << k;
  }
}

TEST(Polygon, NewellNormalOfASkewQuadIsHalfTheCrossOfItsDiagonals) {
  // The square with corner 2 lifted by h: N = (p2 - p0) x (p3 - p1) / 2 = (-h, -h, 2) / 2.
  const double h = 0.5;
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, h}, {0, 1, 0}};
  EXPECT_EQ(newell_normal(quad), Vec3(-h / 2, -h / 2, 1));
}

TEST(Polygon, PlanarWithinTolerance) {
  // Corner 2 lifted by h: the corners lie at distance (h/4) / sqrt(1 + h^2/2) from the plane
  // through the centroid with Newell's normal (-h, -h, 2), alternately above and below.
  const double h = 0.01;
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, h}, {0, 1, 0}};
  const double distance = (h / 4) / std::sqrt(1 + h * h / 2);  // 0.00249993...
  EXPECT_FALSE(is_planar(quad, distance * (1 - 1e-9)));
  EXPECT_TRUE(is_planar(quad, distance * (1 + 1e-9)));
  EXPECT_TRUE(is_planar(regular(7, 3.0), 0.0));  // z = 0 exactly
  // Zero area: planar only if the points coincide within the tolerance (1 from their centroid).
  const std::vector<Vec3> collinear{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_FALSE(is_planar(collinear, 0.5));
  EXPECT_TRUE(is_planar(collinear, 1.0));
}

TEST(Polygon, SimpleOrNot) {
  EXPECT_TRUE(is_simple(regular(5, 1.0)));
  // A non-convex L shape.
  EXPECT_TRUE(is_simple(std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}));
  // Collinear neighbours meet only at their shared corner.
  EXPECT_TRUE(is_simple(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}));
  // A skew quad is simple in the plane of its Newell normal.
  EXPECT_TRUE(is_simple(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}}));
  // A bowtie: edges (0,0)-(1,1) and (1,0)-(0,1) cross.
  EXPECT_FALSE(is_simple(std::vector<Vec3>{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}));
  // The pentagram {5/2}.
  const std::vector<Vec3> pentagon = regular(5, 1.0);
  EXPECT_FALSE(is_simple(std::vector<Vec3>{pentagon[0], pentagon[2], pentagon[4], pentagon[1], pentagon[3]}));
  // A corner repeated, and a corner on a non-neighbouring edge.
  EXPECT_FALSE(is_simple(std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 0, 0}, {0, 2, 0}}));
  EXPECT_FALSE(is_simple(std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0, 0}}));
  // Zero area.
  EXPECT_FALSE(is_simple(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
}

TEST(Polygon, OrientationWithRespectToANormal) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_EQ(orientation(square, Vec3(0, 0, 1)), 1);  // counter-clockwise seen from +z (Def 45)
  EXPECT_EQ(orientation(square, Vec3(0, 0, -1)), -1);
  EXPECT_EQ(orientation(reversed(square), Vec3(0, 0, 1)), -1);
  EXPECT_EQ(orientation(square, Vec3(0.3, -2, 1e-9)), 1);  // any normal on the +z side
  EXPECT_EQ(orientation(square, Vec3(1, 0, 0)), 0);        // the normal lies in the polygon's plane
  EXPECT_EQ(orientation(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, Vec3(0, 0, 1)), 0);  // zero area
}

TEST(Polygon, RejectsFewerThanThreeCorners) {
  const std::vector<Vec3> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(newell_normal(two), InvalidInput);
  EXPECT_THROW(polygon_area(two), InvalidInput);
  EXPECT_THROW(is_planar(two, 1.0), InvalidInput);
  EXPECT_THROW(is_simple(two), InvalidInput);
  EXPECT_THROW(orientation(two, Vec3(0, 0, 1)), InvalidInput);
}

// A star-shaped polygon around the origin: k >= 4 corners at angles 2 pi (i + u_i) / k, u_i in
// [0, 0.9], so neighbouring corners are less than pi apart, radii in [0.5, 2]; then rotated by R
// and moved by t. Its area is sum r_i r_i+1 sin(theta_i+1 - theta_i) / 2 and its normal R e_z.
struct Star {
  std::vector<Vec3> points;
  double area;
  Vec3 normal;
  Vec3 centre;
};

Star random_star(Random& random, int k) {
  const Eigen::Matrix3d R = random_rotation(random);
  const Vec3 t(random.uniform(-10, 10), random.uniform(-10, 10), random.uniform(-10, 10));
  std::vector<double> theta(static_cast<std::size_t>(k)), r(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    theta[static_cast<std::size_t>(i)] = 2 * std::numbers::pi * (i + random.uniform(0, 0.9)) / k;
    r[static_cast<std::size_t>(i)] = random.uniform(0.5, 2.0);
  }
  Star star{{}, 0.0, R * Vec3::UnitZ(), t};
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const std::size_t j = (i + 1) % theta.size();
    const double gap = j == 0 ? theta[0] + 2 * std::numbers::pi - theta[i] : theta[j] - theta[i];
    star.area += 0.5 * r[i] * r[j] * std::sin(gap);
    star.points.push_back(R * Vec3(r[i] * std::cos(theta[i]), r[i] * std::sin(theta[i]), 0) + t);
  }
  return star;
}

RC_GTEST_PROP(Polygon, StarShapedPolygonsInAnyPlane, ()) {
  Random random(*testing::seed());
  const int k = *rc::gen::inRange(4, 40);
  const Star star = random_star(random, k);
  // Corners of size <= 12 (translation up to 10 plus radius 2): Newell's sum of (p - q) x (p + q)
  // loses about |p + q| / |p - q| digits against the area; 1e-12 relative leaves a wide margin.
  const Vec3 normal = newell_normal(star.points);
  RC_ASSERT(std::abs(normal.norm() - star.area) <= 1e-12 * star.area * k);
  RC_ASSERT((normal / normal.norm() - star.normal).norm() <= 1e-12 * k);
  RC_ASSERT(std::abs(polygon_area(star.points) - star.area) <= 1e-12 * star.area * k);
  RC_ASSERT(orientation(star.points, star.normal) == 1);
  RC_ASSERT(orientation(star.points, -star.normal) == -1);
  RC_ASSERT(orientation(reversed(star.points), star.normal) == -1);
  RC_ASSERT(is_simple(star.points));
  RC_ASSERT(is_simple(reversed(star.points)));
  // Planar up to rounding of coordinates of size 12 (1e-9 is a million ulps).
  RC_ASSERT(is_planar(star.points, 1e-9));
}

RC_GTEST_PROP(Polygon, CrownIsPlanarExactlyWithinItsHeight, ()) {
  // A regular 2m-gon with corners lifted alternately by +h and -h along its normal: the lifts
  // cancel in the centroid and in Newell's sum (sum_j s_j+1 (q_j + q_j+1) x n = 0 for s
  // alternating), so every corner lies exactly h from the plane that is_planar() measures.
  Random random(*testing::seed());
  const int k = 2 * *rc::gen::inRange(2, 20);
  const double h = random.uniform(1e-3, 1.0);
  const Eigen::Matrix3d R = random_rotation(random);
  const Vec3 t(random.uniform(-10, 10), random.uniform(-10, 10), random.uniform(-10, 10));
  std::vector<Vec3> crown;
  for (int i = 0; i < k; ++i) {
    const double angle = 2 * std::numbers::pi * i / k;
    crown.push_back(R * Vec3(std::cos(angle), std::sin(angle), i % 2 == 0 ? h : -h) + t);
  }
  // Coordinates of size <= 12 carry errors near 1e-14; the margin h * 1e-6 >= 1e-9 is far above.
  RC_ASSERT(!is_planar(crown, h * (1 - 1e-6)));
  RC_ASSERT(is_planar(crown, h * (1 + 1e-6)));
  RC_ASSERT(orientation(crown, R * Vec3::UnitZ()) == 1);
}

RC_GTEST_PROP(Polygon, SwappingTwoNeighboursOfAConvexPolygonMakesItCross, ()) {
  Random random(*testing::seed());
  const int k = *rc::gen::inRange(4, 30);
  // Corners on a circle (convex position) at jittered angles, in a random plane.
  const Eigen::Matrix3d R = random_rotation(random);
  std::vector<Vec3> polygon;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * std::numbers::pi * (i + random.uniform(0.1, 0.9)) / k;
    polygon.push_back(R * Vec3(std::cos(t), std::sin(t), 0));
  }
  RC_ASSERT(is_simple(polygon));
  // Swapping corners i and i+1: edges (i-1, i+1) and (i, i+2) are the diagonals of the convex
  // quadrilateral i-1, i, i+1, i+2 and cross.
  const std::size_t i = random.below(polygon.size());
  std::swap(polygon[i], polygon[(i + 1) % polygon.size()]);
  RC_ASSERT(!is_simple(polygon));
}

RC_GTEST_PROP(Polygon, NewellNormalIgnoresTranslationAndStartCorner, ()) {
  Random random(*testing::seed());
  const Star star = random_star(random, *rc::gen::inRange(4, 20));
  std::vector<Vec3> moved = star.points;
  for (Vec3& p : moved) p -= star.centre;
  std::rotate(moved.begin(), moved.begin() + random.below(moved.size()), moved.end());
  // Coordinates of size 12 against 2: a few ulps of 12 per term.
  RC_ASSERT((newell_normal(moved) - newell_normal(star.points)).norm() <= 1e-12 * star.area * 40);
}

}  // namespace
}  // namespace patchwork
