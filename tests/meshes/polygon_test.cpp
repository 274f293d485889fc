// Single polygons (seed Def 41-45): Newell's normal and area, planarity with a tolerance,
// simplicity, orientation with respect to a normal.

#include "meshes/polygon.h"

#include <gtest/gtest.h>
#include <gmpxx.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
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

// ---------------------------------------------------------------------------------------------
// Triangulation (ear clipping in the projection along the Newell normal's axis)

// Twice the signed area of the 2D triangle (a, b, c), exact for small integers.
double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Twice the shoelace area of a 2D polygon, exact for small integers.
double twice_shoelace(const std::vector<Vec2>& polygon) {
  double sum = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& p = polygon[i];
    const Vec2& q = polygon[(i + 1) % polygon.size()];
    sum += p.x() * q.y() - p.y() * q.x();
  }
  return sum;
}

// The 2D polygon placed in 3D by an axis permutation with signs (exact): (x, y) -> a frame whose
// third axis is `normal`, so the polygon's Newell normal is the 2D area times `normal`.
std::vector<Vec3> embedded(const std::vector<Vec2>& polygon, int frame) {
  static const int axes[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}};
  const int* a = axes[frame % 6];
  const bool odd = frame % 6 >= 3;  // the odd permutations reverse the handedness: flip x
  std::vector<Vec3> out;
  for (const Vec2& p : polygon) {
    Vec3 q = Vec3::Zero();
    q[a[0]] = odd ? -p.x() : p.x();
    q[a[1]] = p.y();
    q[a[2]] = 7;  // off the coordinate plane
    out.push_back(q);
  }
  return out;
}

// The properties every triangulation of the simple 2D polygon `polygon` (counter-clockwise) must
// have, checked exactly on integer coordinates, through the 3D embedding `frame`.
void check_triangulation(const std::vector<Vec2>& polygon, int frame) {
  const std::vector<Vec3> corners = embedded(polygon, frame);
  const Vec3 normal = newell_normal(corners);
  const auto triangles = triangulate_polygon(corners);
  RC_ASSERT(triangles.size() == polygon.size() - 2);
  Vec3 sum = Vec3::Zero();
  for (const auto& t : triangles) {
    RC_ASSERT(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    RC_ASSERT(std::max({t[0], t[1], t[2]}) < polygon.size());
    const std::vector<Vec3> triangle = {corners[t[0]], corners[t[1]], corners[t[2]]};
    const Vec3 n = newell_normal(triangle);
    RC_ASSERT(n.dot(normal) > 0);  // counter-clockwise with respect to the polygon, not degenerate
    sum += n;
    const Vec2 &a = polygon[t[0]], &b = polygon[t[1]], &c = polygon[t[2]];
    RC_ASSERT(twice_area(a, b, c) > 0);
    for (const Vec2& r : polygon) {  // no corner strictly inside
      RC_ASSERT(!(twice_area(a, b, r) > 0 && twice_area(b, c, r) > 0 && twice_area(c, a, r) > 0));
    }
  }
  RC_ASSERT(sum == normal);  // the areas add up to the polygon's, exactly (integers)
  RC_ASSERT(std::abs(normal.norm()) == std::abs(twice_shoelace(polygon)) / 2);
}

// Thin slivers far from the origin, where the Newell normal in floating point gets the sign or
// zero wrong (found by a review with exact fractions): every triangle turns the polygon's way and
// their areas add up to the polygon's, all in exact rational arithmetic.
TEST(Triangulate, ThinSliversAreOrientedExactly) {
  const auto exact_twice_area = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const mpq_class ax(a.x()), ay(a.y()), bx(b.x()), by(b.y()), cx(c.x()), cy(c.y());
    return mpq_class((bx - ax) * (cy - ay) - (by - ay) * (cx - ax));
  };
  const std::vector<std::vector<Vec2>> slivers = {
      {{370000, 370000}, {370001, 370000.0000000002}, {370000.32532246766, 370000.00000000006},
       {370000.30927916605, 370000.00000000006}},
      {{77.7, 77.7}, {78.7, 77.70000000000002}, {78.64702227791433, 77.70000000000002},
       {78.35912186302335, 77.70000000000002}}};
  for (const std::vector<Vec2>& sliver : slivers) {
    std::vector<Vec3> corners;
    for (const Vec2& p : sliver) corners.emplace_back(p.x(), p.y(), 0.0);
    mpq_class polygon = 0;
    for (std::size_t i = 1; i + 1 < sliver.size(); ++i) polygon += exact_twice_area(sliver[0], sliver[i], sliver[i + 1]);
    ASSERT_NE(sgn(polygon), 0);
    std::vector<std::array<std::uint32_t, 3>> triangles;
    ASSERT_NO_THROW(triangles = triangulate_polygon(corners));
    ASSERT_EQ(triangles.size(), 2u);
    mpq_class sum = 0;
    for (const auto& t : triangles) {
      const mpq_class area = exact_twice_area(sliver[t[0]], sliver[t[1]], sliver[t[2]]);
      EXPECT_EQ(sgn(area), sgn(polygon)) << "triangle (" << t[0] << ", " << t[1] << ", " << t[2] << ")";
      sum += area;
    }
    EXPECT_EQ(sum, polygon);
  }
}

TEST(Triangulate, LShapedHexagonGivesFourTrianglesOfAreaThree) {
  // Counter-clockwise from (2, 1), beside the reflex corner (1, 1): the fan from corner 0 would
  // have the clockwise triangle (2, 1) (1, 1) (1, 2) over the notch, total area 4.
  const std::vector<Vec3> l_shape{{2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}};
  const auto triangles = triangulate_polygon(l_shape);
  ASSERT_EQ(triangles.size(), 4u);
  double area = 0;
  for (const auto& t : triangles) {
    const Vec3 n = newell_normal(std::vector<Vec3>{l_shape[t[0]], l_shape[t[1]], l_shape[t[2]]});
    EXPECT_EQ(n.x(), 0);
    EXPECT_EQ(n.y(), 0);
    EXPECT_GT(n.z(), 0) << "counter-clockwise seen from +z, as the polygon";
    area += std::abs(n.z());
  }
  EXPECT_EQ(area, 3.0);
  // Reversed, the triangles turn with it.
  for (const auto& t : triangulate_polygon(reversed(l_shape))) {
    const std::vector<Vec3> r = reversed(l_shape);
    EXPECT_LT(newell_normal(std::vector<Vec3>{r[t[0]], r[t[1]], r[t[2]]}).z(), 0);
  }
}

TEST(Triangulate, ConvexPolygonsKeepTheirArea) {
  for (int k = 3; k <= 12; ++k) {
    const std::vector<Vec3> polygon = regular(k, 1.5);
    const auto triangles = triangulate_polygon(polygon);
    ASSERT_EQ(triangles.size(), static_cast<std::size_t>(k - 2));
    double area = 0;
    for (const auto& t : triangles) area += newell_normal(std::vector<Vec3>{polygon[t[0]], polygon[t[1]], polygon[t[2]]}).z();
    EXPECT_NEAR(area, polygon_area(polygon), 1e-14 * k) << k;
    // Exactly the fan from corner 0, as the CLI wrote convex faces before.
    for (std::uint32_t j = 0; j + 2 < static_cast<std::uint32_t>(k); ++j) {
      EXPECT_EQ(triangles[j], (std::array<std::uint32_t, 3>{0, j + 1, j + 2})) << k;
    }
  }
  // A triangle is itself, even a degenerate one.
  const std::vector<Vec3> flat{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_EQ(triangulate_polygon(flat), (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}}));
}

TEST(Triangulate, CollinearCornersGiveNoDegenerateTriangle) {
  // A square with extra corners along two of its sides.
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 3}, {3, 4}, {0, 4}, {0, 2}};
  for (int frame = 0; frame < 6; ++frame) check_triangulation(square, frame);
}

TEST(Triangulate, NonPlanarPolygonsAreTriangulatedInTheirProjection) {
  // The L-hexagon with its corners lifted alternately by 0.3: Newell's normal is still mostly +z,
  // the projection onto xy is the planar L, and the triangles' xy-areas add up to 3 exactly.
  std::vector<Vec3> lifted{{2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}};
  for (std::size_t i = 0; i < lifted.size(); i += 2) lifted[i].z() = 0.3;
  ASSERT_FALSE(is_planar(lifted, 0.1));
  const auto triangles = triangulate_polygon(lifted);
  ASSERT_EQ(triangles.size(), 4u);
  double area = 0;
  for (const auto& t : triangles) {
    const double z = newell_normal(std::vector<Vec3>{lifted[t[0]], lifted[t[1]], lifted[t[2]]}).z();
    EXPECT_GT(z, 0);
    area += z;
  }
  EXPECT_EQ(area, 3.0);
  // A bow-tie lifted off its plane still crosses itself in projection: refused.
  EXPECT_THROW(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {2, 2, 0.1}, {2, 0, 0}, {0, 1, 0.1}}), InvalidInput);
}

TEST(Triangulate, RefusesSelfIntersectingAndDegeneratePolygons) {
  const auto expect_refused = [](const std::vector<Vec3>& polygon, const std::string& part) {
    try {
      triangulate_polygon(polygon);
      ADD_FAILURE() << "no InvalidInput";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  // The bow-tie: edges (0, 1) and (2, 3) cross at (0.5, 0.5).
  expect_refused({{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}, "edges (0, 1) and (2, 3) cross");
  // A pentagram (its Newell normal is not zero, its edges cross).
  std::vector<Vec3> star;
  for (int i = 0; i < 5; ++i) star.push_back(regular(5, 1.0)[(2 * i) % 5]);
  expect_refused(star, "cross");
  // Collinear corners only: zero area.
  expect_refused({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, "zero area");
  // A repeated corner.
  expect_refused({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}, "coincide");
  EXPECT_THROW(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}}), InvalidInput);
}

TEST(Triangulate, FacesOfAMeshNameTheFaceThatCannotBeTriangulated) {
  // Face 0: the L-hexagon; face 1: a triangle; face 2: a bow-tie.
  Positions positions(10, 3);
  positions << 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 5, 5, 0, 6, 6, 0, 6, 5, 0, 5, 6, 0;
  const FaceVertexMesh good(positions, {6, 3}, {0, 1, 2, 3, 4, 5, 2, 4, 3});  // the triangle is clockwise
  const std::vector<std::uint32_t> indices = triangulate_faces(good);
  ASSERT_EQ(indices.size(), 3u * 5);
  EXPECT_EQ(std::vector<std::uint32_t>(indices.end() - 3, indices.end()), (std::vector<std::uint32_t>{2, 4, 3}));
  double area = 0;
  for (std::size_t t = 0; t < 4; ++t) {
    const double z = newell_normal(std::vector<Vec3>{good.position(indices[3 * t]), good.position(indices[3 * t + 1]),
                                                     good.position(indices[3 * t + 2])})
                         .z();
    EXPECT_GT(z, 0) << t;
    area += z;
  }
  EXPECT_EQ(area, 3.0);
  const FaceVertexMesh bad(positions, {6, 3, 4}, {0, 1, 2, 3, 4, 5, 2, 4, 3, 6, 7, 8, 9});
  try {
    triangulate_faces(bad);
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "triangulate_faces: face 2 (4 corners) cannot be triangulated: the polygon is not simple (edges (0, 1) "
              "and (2, 3) cross)");
  }
}

// A star-shaped polygon on integer points: distinct angles about the origin, sorted, each gap
// below pi (so the origin is inside and the polygon is simple); points on one ray keep the first.
RC_GTEST_PROP(Triangulate, StarShapedPolygonsAreCoveredExactlyOnce, ()) {
  const int k = *rc::gen::inRange(4, 30);
  // Four points on the axes keep every angular gap at most pi/2.
  std::vector<Vec2> points = {{*rc::gen::inRange(1, 51), 0},
                              {0, *rc::gen::inRange(1, 51)},
                              {-*rc::gen::inRange(1, 51), 0},
                              {0, -*rc::gen::inRange(1, 51)}};
  for (int i = 0; i < k; ++i) {
    const int x = *rc::gen::inRange(-50, 51);
    const int y = *rc::gen::inRange(-50, 51);
    if (x != 0 || y != 0) points.emplace_back(x, y);
  }
  // Sort by angle exactly: half-plane, then cross product.
  const auto upper = [](const Vec2& p) { return p.y() > 0 || (p.y() == 0 && p.x() > 0); };
  std::sort(points.begin(), points.end(), [&](const Vec2& a, const Vec2& b) {
    if (upper(a) != upper(b)) return upper(a);
    return a.x() * b.y() - a.y() * b.x() > 0;
  });
  std::vector<Vec2> star;  // one point per direction
  for (const Vec2& p : points) {
    if (star.empty() || !(star.back().x() * p.y() - star.back().y() * p.x() == 0 && star.back().dot(p) > 0)) {
      star.push_back(p);
    }
  }
  if (star.size() >= 2 && star.front().x() * star.back().y() - star.front().y() * star.back().x() == 0 &&
      star.front().dot(star.back()) > 0) {
    star.pop_back();
  }
  for (std::size_t i = 0; i < star.size(); ++i) {  // every gap below pi: consecutive turns left
    const Vec2& a = star[i];
    const Vec2& b = star[(i + 1) % star.size()];
    RC_ASSERT(a.x() * b.y() - a.y() * b.x() > 0);
  }
  check_triangulation(star, *rc::gen::inRange(0, 6));
}

// A comb: a base of height 1 with teeth of random heights, every corner of the base's bottom
// edge kept (collinear corners).
RC_GTEST_PROP(Triangulate, CombShapedPolygonsAreCoveredExactlyOnce, ()) {
  const int m = *rc::gen::inRange(2, 12);
  std::vector<Vec2> comb;
  for (int x = 0; x <= 2 * m - 1; ++x) comb.emplace_back(x, 0);
  for (int j = m - 1; j >= 0; --j) {
    const int h = *rc::gen::inRange(2, 40);
    comb.emplace_back(2 * j + 1, h);
    comb.emplace_back(2 * j, h);
    if (j > 0) {
      comb.emplace_back(2 * j, 1);
      comb.emplace_back(2 * j - 1, 1);
    }
  }
  const int frame = *rc::gen::inRange(0, 6);
  check_triangulation(comb, frame);
  // Starting anywhere, the same properties.
  const std::size_t shift = *rc::gen::inRange<std::size_t>(0, comb.size());
  std::rotate(comb.begin(), comb.begin() + static_cast<std::ptrdiff_t>(shift), comb.end());
  check_triangulation(comb, frame);
}

}  // namespace
}  // namespace patchwork
