#include "surfaces/patch_transform.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/surface_normal.h"
#include "tests/surfaces/nurbs_generators.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/rational_shapes.h"

namespace patchwork::patch_transform_test {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

/// An affine map with linear entries in [-2, 2], |det| >= 1/10, translation in [-5, 5].
rc::Gen<Eigen::Affine3d> random_affine() {
  const auto any = rc::gen::exec([] {
    Eigen::Affine3d map = Eigen::Affine3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) map.linear()(r, c) = *testing::coordinate(-2.0, 2.0);
      map.translation()[r] = *testing::coordinate(-5.0, 5.0);
    }
    return map;
  });
  return rc::gen::suchThat(any, [](const Eigen::Affine3d& map) { return std::abs(map.linear().determinant()) >= 0.1; });
}

/// max |A|_inf * 10 + |b|_inf: a bound on every image of a point with coordinates in [-10, 10].
double image_scale(const Eigen::Affine3d& map) {
  return map.linear().cwiseAbs().rowwise().sum().maxCoeff() * 10.0 + map.translation().cwiseAbs().maxCoeff();
}

/// The point map of a 4 x 4 projective matrix.
Vec3 apply(const Eigen::Matrix4d& M, const Vec3& x) {
  const Vec4 h = M * Vec4(x.x(), x.y(), x.z(), 1.0);
  return h.head<3>() / h[3];
}

/// A rational patch on a random polynomial patch, weights in [1/4, 4].
rc::Gen<RationalBezierPatch> random_rational_patch() {
  return rc::gen::exec([] {
    const BezierPatch3 net = *testing::random_patch(0, 4);
    std::vector<double> weights;
    for (std::size_t k = 0; k < net.control_points().size(); ++k) weights.push_back(*testing::coordinate(0.25, 4.0));
    return RationalBezierPatch(net.degree_u(), net.degree_v(), net.control_points(), weights);
  });
}

// Tensor de Casteljau rounds (n + m + 2) times per coordinate on convex combinations; the
// affine image adds 4 roundings, the rational quotient a factor of the weights' spread (16).
RC_GTEST_PROP(PatchTransform, AffineMapCommutesWithEvaluation, ()) {
  const BezierPatch3 patch = *testing::random_patch(0, 4);
  const RationalBezierPatch rational = *random_rational_patch();
  const NurbsSurface nurbs = *nurbs_gen::nurbs_surface(true);
  const Eigen::Affine3d map = *random_affine();
  const BezierPatch3 image = transform(patch, map);
  const RationalBezierPatch rational_image = transform(rational, map);
  const NurbsSurface nurbs_image = transform(nurbs, map);
  RC_ASSERT(nurbs_image.knots_u() == nurbs.knots_u());
  RC_ASSERT(nurbs_image.knots_v() == nurbs.knots_v());
  const double bound = 4.0 * (patch.degree_u() + patch.degree_v() + 6) * eps * image_scale(map);
  const double rational_bound = 16.0 * 4.0 * (8 + 8 + 6) * eps * image_scale(map);
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; b <= 4; ++b) {
      const double u = a / 4.0, v = b / 4.0;
      RC_ASSERT((image.evaluate(u, v) - map * patch.evaluate(u, v)).cwiseAbs().maxCoeff() <= bound);
      RC_ASSERT((rational_image.evaluate(u, v) - map * rational.evaluate(u, v)).cwiseAbs().maxCoeff() <=
                rational_bound);
      const double s = nurbs.knots_u().a() + (nurbs.knots_u().b() - nurbs.knots_u().a()) * u;
      const double t = nurbs.knots_v().a() + (nurbs.knots_v().b() - nurbs.knots_v().a()) * v;
      RC_ASSERT((nurbs_image.evaluate(s, t) - map * nurbs.evaluate(s, t)).cwiseAbs().maxCoeff() <= rational_bound);
    }
  }
  for (int i = 0; i <= rational.degree_u(); ++i) {
    for (int j = 0; j <= rational.degree_v(); ++j) RC_ASSERT(rational_image.weight(i, j) == rational.weight(i, j));
  }
}

// Projective maps [A b; c^T 1] with |c_i| <= 1/64 keep the new weights w (c.P + 1) positive
// on points within [-10, 10]^3 (c.P + 1 >= 34/64), and commute with evaluation: the image
// evaluates to the mapped points, for polynomial (then rational), rational and NURBS surfaces.
RC_GTEST_PROP(PatchTransform, ProjectiveMapCommutesWithEvaluation, ()) {
  const BezierPatch3 patch = *testing::random_patch(0, 4);
  const RationalBezierPatch rational = *random_rational_patch();
  const NurbsSurface nurbs = *nurbs_gen::nurbs_surface(true);
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topRows<3>() = (*random_affine()).matrix().topRows<3>();
  for (int c = 0; c < 3; ++c) M(3, c) = *testing::coordinate(-1.0 / 64, 1.0 / 64);
  const RationalBezierPatch image = projective_transform(patch, M);
  const RationalBezierPatch rational_image = projective_transform(rational, M);
  const NurbsSurface nurbs_image = projective_transform(nurbs, M);
  RC_ASSERT(nurbs_image.knots_u() == nurbs.knots_u());
  // The images are at most 64/34 times the affine scale; the quotients cost a few ulps more.
  const double bound = 2.0 * 16.0 * 4.0 * (8 + 8 + 6) * eps * image_scale(Eigen::Affine3d(M.topRows<3>()));
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; b <= 4; ++b) {
      const double u = a / 4.0, v = b / 4.0;
      RC_ASSERT((image.evaluate(u, v) - apply(M, patch.evaluate(u, v))).cwiseAbs().maxCoeff() <= bound);
      RC_ASSERT((rational_image.evaluate(u, v) - apply(M, rational.evaluate(u, v))).cwiseAbs().maxCoeff() <= bound);
      const double s = nurbs.knots_u().a() + (nurbs.knots_u().b() - nurbs.knots_u().a()) * u;
      const double t = nurbs.knots_v().a() + (nurbs.knots_v().b() - nurbs.knots_v().a()) * v;
      RC_ASSERT((nurbs_image.evaluate(s, t) - apply(M, nurbs.evaluate(s, t))).cwiseAbs().maxCoeff() <= bound);
    }
  }
}

// Dyadic points and maps: every product and sum is exact, so P'_ij = A P_ij + b bit for bit.
RC_GTEST_PROP(PatchTransform, ControlPointsAreExactlyTheAffineImage, ()) {
  const auto dyadic = [](int range, double unit) {
    return rc::gen::map(rc::gen::inRange(-range, range + 1), [unit](int k) { return k * unit; });
  };
  const int n = *rc::gen::inRange(0, 4), m = *rc::gen::inRange(0, 4);
  std::vector<Vec3> P;
  for (int k = 0; k < (n + 1) * (m + 1); ++k) {
    P.emplace_back(*dyadic(640, 1.0 / 64), *dyadic(640, 1.0 / 64), *dyadic(640, 1.0 / 64));
  }
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.linear() = Eigen::Matrix3d::Identity() * 2.0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) map.linear()(r, c) += *dyadic(8, 1.0 / 8);
    map.translation()[r] = *dyadic(80, 1.0 / 16);
  }
  RC_PRE(map.linear().determinant() != 0.0);
  const BezierPatch3 image = transform(BezierPatch3(n, m, P), map);
  for (int k = 0; k < (n + 1) * (m + 1); ++k) {
    for (int r = 0; r < 3; ++r) {
      double expected = map.translation()[r];
      for (int c = 0; c < 3; ++c) expected += map.linear()(r, c) * P[k][c];
      RC_ASSERT(image.control_points()[k][r] == expected);
    }
  }
}

// F'_u x F'_v = det(A) A^-T (F_u x F_v) (the cofactor matrix of A applied to the normal).
RC_GTEST_PROP(PatchTransform, NormalsMapByTheCofactorMatrix, ()) {
  const BezierPatch3 patch = *testing::random_patch(1, 4);
  const Eigen::Affine3d map = *random_affine();
  const Eigen::Matrix3d A = map.linear();
  const Eigen::Matrix3d cofactor = A.determinant() * A.inverse().transpose();
  const BezierPatch3 image = transform(patch, map);
  // |F_u| <= 2 n 10 sqrt 3 per unit of A; the products round in the last few bits of that size.
  const double size = 40.0 * patch.degree_u() * patch.degree_v() * 3.0 * 100.0;
  const double bound = 64.0 * eps * size * cofactor.cwiseAbs().sum();
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; b <= 3; ++b) {
      const Vec3 expected = cofactor * normal(patch, a / 3.0, b / 3.0);
      RC_ASSERT((normal(image, a / 3.0, b / 3.0) - expected).cwiseAbs().maxCoeff() <= bound);
    }
  }
}

// The report of a set before and after must agree on its counts and orientation.
void expect_same_adjacency(const PatchSet& before, const PatchSet& after) {
  const PatchSetReport a = report(before);
  const PatchSetReport b = report(after);
  EXPECT_EQ(a.patches, b.patches);
  EXPECT_EQ(a.shared_edges, b.shared_edges);
  EXPECT_EQ(a.open_edges, b.open_edges);
  EXPECT_EQ(a.collapsed_edges, b.collapsed_edges);
  EXPECT_EQ(a.t_junctions, b.t_junctions);
  EXPECT_EQ(a.touching_points, b.touching_points);
  EXPECT_EQ(a.consistently_oriented, b.consistently_oriented);
  EXPECT_EQ(a.closed, b.closed);
}

// The mirror x -> -x about the plane x = 1 (then moved): outward normals of the unit sphere
// turn inward under the map alone, and stay outward when the orientation is kept.
TEST(PatchTransform, MirroredSphereIsInwardUnlessOrientationIsKept) {
  const PatchSet sphere(testing::as_any(testing::unit_sphere_octants()));
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.linear()(0, 0) = -1.0;
  mirror.translation() = Vec3(2.0, 0.5, -0.25);
  const Vec3 centre = mirror * Vec3::Zero();
  for (const TransformOrientation orientation : {TransformOrientation::follow_map, TransformOrientation::keep}) {
    const TransformedPatchSet mapped = transform(sphere, mirror, orientation);
    EXPECT_TRUE(mapped.orientation_reversed);
    EXPECT_EQ(mapped.u_reversed, orientation == TransformOrientation::keep);
    expect_same_adjacency(sphere, mapped.set);
    EXPECT_TRUE(report(mapped.set).consistently_oriented);
    EXPECT_TRUE(report(mapped.set).closed);
    const double side = orientation == TransformOrientation::keep ? 1.0 : -1.0;
    for (std::uint32_t p = 0; p < mapped.set.count(); ++p) {
      const RationalBezierPatch patch = mapped.set.rational_patch(p);
      for (const double u : {0.0, 0.3, 0.5, 1.0}) {
        for (const double v : {0.0, 0.4, 1.0}) {
          const Vec3 x = patch.evaluate(u, v);
          EXPECT_NEAR((x - centre).norm(), 1.0, 1e-15 * 8);
          EXPECT_LT((unit_normal(patch, u, v) - side * (x - centre)).norm(), 1e-14)
              << "patch " << p << " at " << u << ", " << v;
        }
      }
    }
  }
  // A rotation keeps the orientation: nothing is reversed.
  const TransformedPatchSet turned = transform(
      sphere, Eigen::Affine3d(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())), TransformOrientation::keep);
  EXPECT_FALSE(turned.orientation_reversed);
  EXPECT_FALSE(turned.u_reversed);
  expect_same_adjacency(sphere, turned.set);
}

// The shared edges of `before` are those of `after` (u0 and u1 exchanged where the u direction
// was reversed), each with the same C^k and walked consistently.
void expect_same_joins(const PatchSet& before, const PatchSet& after, bool u_reversed) {
  const auto renamed = [&](PatchEdge edge) {
    if (!u_reversed) return edge;
    return edge == PatchEdge::u0 ? PatchEdge::u1 : edge == PatchEdge::u1 ? PatchEdge::u0 : edge;
  };
  ASSERT_EQ(before.shared_edges().size(), after.shared_edges().size());
  for (const SharedEdge& edge : before.shared_edges()) {
    const auto same = [&](const SharedEdge& other) {
      return other.first == EdgeRef{edge.first.patch, renamed(edge.first.edge)} &&
             other.second == EdgeRef{edge.second.patch, renamed(edge.second.edge)};
    };
    const auto found = std::find_if(after.shared_edges().begin(), after.shared_edges().end(), same);
    ASSERT_NE(found, after.shared_edges().end());
    EXPECT_EQ(found->continuity.ck, edge.continuity.ck);
    EXPECT_EQ(found->consistently_oriented, edge.consistently_oriented);
  }
}

// Bezier pieces of a NURBS surface come with known joins whose C^k is the knots', not what a
// search measures on the patches: the plane on U = {0, 0, 1, 2, 2} (degree 1, the interior knot
// of multiplicity 1 = p) is C^0 by its knots, while its two equal squares measure C^1. The mapped
// set keeps every join with its C^k, also under the u-reversal's renaming (u0 <-> u1); so does
// the NURBS torus' set (its seam found by the search).
TEST(PatchTransform, KnownJoinsAreKept) {
  const NurbsSurface plane(KnotVector(1, {0, 0, 1, 2, 2}), KnotVector(1, {0, 0, 1, 1}),
                           {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 1, 0)});
  const NurbsBezierPatches plane_pieces = bezier_patches(plane);
  const PatchSet known(plane_pieces.patches, plane_pieces.joins);
  ASSERT_EQ(known.shared_edges().size(), 1u);
  EXPECT_EQ(known.shared_edges()[0].continuity.ck, 0);
  EXPECT_EQ(PatchSet(plane_pieces.patches).shared_edges()[0].continuity.ck, 1);  // measured
  const NurbsBezierPatches torus_pieces = bezier_patches(nurbs_torus(Vec3::Zero(), 2.0, 0.5));
  const PatchSet torus(torus_pieces.patches, torus_pieces.joins);
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.linear() = Vec3(1.0, -2.0, 0.5).asDiagonal();
  for (const PatchSet* set : {&known, &torus}) {
    for (const TransformOrientation orientation : {TransformOrientation::follow_map, TransformOrientation::keep}) {
      const TransformedPatchSet mapped = transform(*set, mirror, orientation);
      expect_same_adjacency(*set, mapped.set);
      expect_same_joins(*set, mapped.set, mapped.u_reversed);
    }
  }
}

// The teapot (polynomial patches, T-junctions none, a touching point, poles) mirrored: the
// adjacency is the same, with or without the orientation kept.
TEST(PatchTransform, MirroredTeapotKeepsItsAdjacency) {
  const PatchSet teapot(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.linear()(1, 1) = -1.0;
  for (const TransformOrientation orientation : {TransformOrientation::follow_map, TransformOrientation::keep}) {
    const TransformedPatchSet mapped = transform(teapot, mirror, orientation);
    expect_same_adjacency(teapot, mapped.set);
    EXPECT_EQ(mapped.set.rational_count(), 0u);
    // Patch 0's normal at its centre: turned by the mirror, kept with TransformOrientation::keep.
    const BezierPatch3& before = teapot.patches()[0];
    const BezierPatch3& after = mapped.set.patches()[0];
    const Vec3 expected = mirror.linear() * unit_normal(before, 0.5, 0.5);
    const double side = orientation == TransformOrientation::keep ? 1.0 : -1.0;
    EXPECT_LT((unit_normal(after, 0.5, 0.5) - side * expected).norm(), 1e-14);
  }
}

// The unit sphere x^T Q x = 0 (Q = diag(1, 1, 1, -1)) maps to the quadric M^-T Q M^-1; the
// projective image of each octant evaluates to the mapped points, which lie on it. The image is
// convex (no weight vanishes: it stays off the plane at infinity) around the image of the centre,
// so the outward normal n has n . (x - M(0)) > 0: kept with TransformOrientation::keep whatever the sign
// of det M (M and M with its first row negated, det < 0).
TEST(PatchTransform, ProjectiveImageOfTheSphereIsTheMappedQuadric) {
  Eigen::Matrix4d M;
  M << 1.0, 0.2, 0.0, 0.5, 0.1, 1.5, -0.3, -1.0, 0.0, 0.4, 0.8, 0.25, 0.1, -0.05, 0.2, 1.0;
  const Eigen::Matrix4d Q = Vec4(1.0, 1.0, 1.0, -1.0).asDiagonal();
  const PatchSet sphere(testing::as_any(testing::unit_sphere_octants()));
  Eigen::Matrix4d mirrored = M;
  mirrored.row(0) *= -1.0;
  ASSERT_GT(M.determinant(), 0.0);
  for (const Eigen::Matrix4d& map : {M, mirrored}) {
    const Eigen::Matrix4d Minv = map.inverse();
    const Eigen::Matrix4d quadric = Minv.transpose() * Q * Minv;
    const Vec3 inside = apply(map, Vec3::Zero());
    const TransformedPatchSet mapped = projective_transform(sphere, map, TransformOrientation::keep);
    EXPECT_EQ(mapped.orientation_reversed, map.determinant() < 0.0);
    expect_same_adjacency(sphere, mapped.set);
    for (std::uint32_t p = 0; p < sphere.count(); ++p) {
      const RationalBezierPatch before = sphere.rational_patch(p);
      const RationalBezierPatch after = mapped.set.rational_patch(p);
      for (int a = 0; a <= 4; ++a) {
        for (int b = 0; b <= 4; ++b) {
          const Vec3 x = after.evaluate(a / 4.0, b / 4.0);
          // u reversed where det < 0: the same point is at (1 - u, v) of the original.
          const double u = mapped.u_reversed ? 1.0 - a / 4.0 : a / 4.0;
          EXPECT_LT((x - apply(map, before.evaluate(u, b / 4.0))).norm(), 1e-14 * 16);
          const Vec4 X(x.x(), x.y(), x.z(), 1.0);
          EXPECT_LT(std::abs(X.dot(quadric * X)), 1e-13 * quadric.norm() * X.squaredNorm());
          EXPECT_GT(unit_normal(after, a / 4.0, b / 4.0).dot((x - inside).normalized()), 0.1);
        }
      }
    }
  }
}

// A projective map that sends part of a net across the plane at infinity names the patch and
// the control point; a singular map and a non-finite one are refused.
TEST(PatchTransform, BadMapsAreRefused) {
  const BezierPatch3 square = testing::bilinear(Vec3(-2, 0, 0), Vec3(2, 0, 0), Vec3(-2, 1, 0), Vec3(2, 1, 0));
  Eigen::Matrix4d crossing = Eigen::Matrix4d::Identity();
  crossing(3, 0) = 0.75;  // w' = 3x/4 + 1: -1/2 at x = -2, 5/2 at x = 2
  try {
    projective_transform(PatchSet(std::vector<BezierPatch3>{square, square}), crossing);
    FAIL() << "no error";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()),
              "projective_transform: patch 0, control point (1, 0) maps to weight 2.5 (control point (0, 0) to -0.5): "
              "the image may cross the plane at infinity, and has no form with positive weights");
  }
  Eigen::Affine3d flat = Eigen::Affine3d::Identity();
  flat.linear()(2, 2) = 0.0;
  EXPECT_THROW(transform(square, flat), InvalidInput);
  EXPECT_THROW(transform(PatchSet(std::vector<BezierPatch3>{square}), flat), InvalidInput);
  Eigen::Affine3d infinite = Eigen::Affine3d::Identity();
  infinite.translation().z() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(transform(square, infinite), InvalidInput);
  EXPECT_THROW(projective_transform(square, Eigen::Matrix4d::Zero()), InvalidInput);
}

}  // namespace
}  // namespace patchwork::patch_transform_test
