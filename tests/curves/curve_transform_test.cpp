#include "curves/curve_transform.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.h"
#include "tests/curves/bspline_generators.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/exact_rational.h"

namespace patchwork::curve_transform_test {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

/// An affine map with linear entries in [-2, 2] and translation in [-5, 5].
template <int Dim>
rc::Gen<AffineMap<Dim>> random_affine() {
  return rc::gen::exec([] {
    AffineMap<Dim> map = AffineMap<Dim>::Identity();
    for (int r = 0; r < Dim; ++r) {
      for (int c = 0; c < Dim; ++c) map.linear()(r, c) = *curve_gen::coordinate(-2.0, 2.0);
      map.translation()[r] = *curve_gen::coordinate(-5.0, 5.0);
    }
    return map;
  });
}

/// A projective map [A b; c^T 1] with A, b as random_affine and |c_i| <= 1/64: on points with
/// coordinates in [-10, 10] the new weight w (c.P + 1) stays positive (c.P >= -30/64).
template <int Dim>
rc::Gen<ProjectiveMap<Dim>> random_projective() {
  return rc::gen::exec([] {
    ProjectiveMap<Dim> M = projective_matrix<Dim>(*random_affine<Dim>());
    for (int c = 0; c < Dim; ++c) M(Dim, c) = *curve_gen::coordinate(-1.0 / 64, 1.0 / 64);
    return M;
  });
}

/// The point map of a projective matrix: x -> (M (x, 1))_head / (M (x, 1))_last.
template <int Dim>
Point<Dim> apply(const ProjectiveMap<Dim>& M, const Point<Dim>& x) {
  Point<Dim + 1> h;
  h << x, 1.0;
  const Point<Dim + 1> image = M * h;
  return image.template head<Dim>() / image[Dim];
}

/// The scale of A P + b over the points: max |A|_inf |P|_inf + |b|_inf, bounding every image.
template <int Dim>
double image_scale(const AffineMap<Dim>& map, const std::vector<Point<Dim>>& points) {
  double largest = 0.0;
  for (const auto& p : points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  const double A = map.linear().cwiseAbs().rowwise().sum().maxCoeff();
  return A * largest + map.translation().cwiseAbs().maxCoeff() + 1e-300;
}

// De Casteljau's points are convex combinations, each step rounding once per coordinate: the
// curve's value is within (n + 1) eps of the exact one per unit of scale, and so is A C + b
// (Dim + 1 more roundings). 4 (n + Dim + 2) eps covers both sides with room.
template <int Dim>
void expect_commutes(const BezierCurve<Dim>& curve, const AffineMap<Dim>& map) {
  const BezierCurve<Dim> image = transform(curve, map);
  const double bound = 4.0 * (curve.degree() + Dim + 2) * eps * image_scale(map, curve.control_points());
  for (int k = 0; k <= 16; ++k) {
    const double t = curve.a() + (curve.b() - curve.a()) * k / 16.0;
    const Point<Dim> expected = map * curve.evaluate(t);
    RC_ASSERT((image.evaluate(t) - expected).cwiseAbs().maxCoeff() <= bound);
  }
}

RC_GTEST_PROP(CurveTransform, AffineMapCommutesWithEvaluationOfBezierCurves, ()) {
  expect_commutes(*curve_gen::bezier_curve_on_interval<2>(0, 10), *random_affine<2>());
  expect_commutes(*curve_gen::bezier_curve_on_interval<3>(0, 10), *random_affine<3>());
}

// Dyadic data small enough that every product and sum is exact: the control points must be
// A P + b exactly, whatever the order of the operations.
RC_GTEST_PROP(CurveTransform, ControlPointsAreExactlyTheAffineImage, ()) {
  const int n = *rc::gen::inRange(0, 8);
  const auto dyadic = [](int range, double unit) {
    return rc::gen::map(rc::gen::inRange(-range, range + 1), [unit](int k) { return k * unit; });
  };
  std::vector<Vec3> P;
  for (int i = 0; i <= n; ++i) P.emplace_back(*dyadic(640, 1.0 / 64), *dyadic(640, 1.0 / 64), *dyadic(640, 1.0 / 64));
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) map.linear()(r, c) = *dyadic(16, 1.0 / 8);
    map.translation()[r] = *dyadic(80, 1.0 / 16);
  }
  const BezierCurve3 image = transform(BezierCurve3(P, -1.0, 2.0), map);
  RC_ASSERT(image.a() == -1.0);
  RC_ASSERT(image.b() == 2.0);
  for (int i = 0; i <= n; ++i) {
    for (int r = 0; r < 3; ++r) {
      double expected = map.translation()[r];
      for (int c = 0; c < 3; ++c) expected += map.linear()(r, c) * P[i][c];
      RC_ASSERT(image.control_points()[i][r] == expected);
    }
  }
}

// On any doubles each image coordinate sum_k a_rk P_k + b_r rounds at most Dim + 1 times per
// term (one product, Dim additions, in whatever order), so it is within
// gamma_(Dim+1) (sum_k |a_rk P_k| + |b_r|) of the exact value (Higham, Accuracy and Stability,
// 3.1), computed here in rationals.
RC_GTEST_PROP(CurveTransform, ControlPointsAreWithinTheDotProductBound, ()) {
  const BezierCurve3 curve = *curve_gen::bezier_curve<3>(0, 6);
  const Eigen::Affine3d map = *random_affine<3>();
  const BezierCurve3 image = transform(curve, map);
  const mpq_class gamma = exact::gamma(4);
  for (std::size_t i = 0; i < curve.control_points().size(); ++i) {
    const Vec3& P = curve.control_points()[i];
    for (int r = 0; r < 3; ++r) {
      mpq_class exact_value(map.translation()[r]);
      mpq_class magnitude(std::abs(map.translation()[r]));
      for (int c = 0; c < 3; ++c) {
        const mpq_class term = mpq_class(map.linear()(r, c)) * mpq_class(P[c]);
        exact_value += term;
        magnitude += abs(term);
      }
      const mpq_class error = abs(mpq_class(image.control_points()[i][r]) - exact_value);
      RC_ASSERT(error <= gamma * magnitude);
    }
  }
}

// A translation by dyadic numbers is exact on the points and on the curve: de Casteljau on
// P_i + b (all on the grid 1/64, within 2^10) gives C(t) + b bit for bit at dyadic t = k/8,
// since every intermediate point is then exact as well.
TEST(CurveTransform, DyadicTranslationIsBitExact) {
  const std::vector<Vec2> P = {Vec2(0.25, -1.5), Vec2(3.125, 2.0), Vec2(-0.75, 0.5), Vec2(1.0, 1.0)};
  Eigen::Affine2d shift = Eigen::Affine2d::Identity();
  shift.translation() = Vec2(0.375, -2.25);
  const BezierCurve2 curve(P);
  const BezierCurve2 image = transform(curve, shift);
  for (std::size_t i = 0; i < P.size(); ++i) EXPECT_EQ(image.control_points()[i], P[i] + Vec2(0.375, -2.25));
  for (int k = 0; k <= 8; ++k) EXPECT_EQ(image.evaluate(k / 8.0), curve.evaluate(k / 8.0) + Vec2(0.375, -2.25));
}

RC_GTEST_PROP(CurveTransform, RationalCurvesKeepTheirWeightsAndCommute, ()) {
  const BezierCurve3 net = *curve_gen::bezier_curve<3>(0, 8);
  const auto weights =
      *rc::gen::container<std::vector<double>>(net.control_points().size(), curve_gen::coordinate(0.25, 4.0));
  const RationalBezierCurve3 curve(net.control_points(), weights);
  const Eigen::Affine3d map = *random_affine<3>();
  const RationalBezierCurve3 image = transform(curve, map);
  const double scale = image_scale(map, net.control_points());
  for (int i = 0; i <= curve.degree(); ++i) {
    RC_ASSERT(image.weight(i) == curve.weight(i));
    RC_ASSERT((image.control_point(i) - map * curve.control_point(i)).cwiseAbs().maxCoeff() <= 16 * eps * scale);
  }
  // The rational value's rounding grows with the weights' spread (at most 16 here).
  const double bound = 64.0 * (curve.degree() + 5) * eps * scale;
  for (int k = 0; k <= 16; ++k) {
    RC_ASSERT((image.evaluate(k / 16.0) - map * curve.evaluate(k / 16.0)).cwiseAbs().maxCoeff() <= bound);
  }
}

RC_GTEST_PROP(CurveTransform, BSplineAndNurbsCurvesKeepTheirKnotsAndCommute, ()) {
  const BSplineCurve3 spline = *bspline_gen::bspline_curve<3>(1, 4, 3);
  const NurbsCurve3 nurbs = *bspline_gen::nurbs_curve<3>(1, 4, 3);
  const Eigen::Affine3d map = *random_affine<3>();
  const BSplineCurve3 spline_image = transform(spline, map);
  const NurbsCurve3 nurbs_image = transform(nurbs, map);
  RC_ASSERT(spline_image.knot_vector() == spline.knot_vector());
  RC_ASSERT(nurbs_image.knot_vector() == nurbs.knot_vector());
  for (int i = 0; i < nurbs.control_point_count(); ++i) RC_ASSERT(nurbs_image.weight(i) == nurbs.weight(i));
  const double scale = image_scale(map, spline.control_points()) + image_scale(map, {Vec3::Constant(10.0)});
  for (int k = 0; k <= 16; ++k) {
    const double u = spline.a() + (spline.b() - spline.a()) * k / 16.0;
    RC_ASSERT((spline_image.evaluate(u) - map * spline.evaluate(u)).cwiseAbs().maxCoeff() <= 64 * eps * scale);
    const double s = nurbs.a() + (nurbs.b() - nurbs.a()) * k / 16.0;
    RC_ASSERT((nurbs_image.evaluate(s) - map * nurbs.evaluate(s)).cwiseAbs().maxCoeff() <= 1024 * eps * scale);
  }
}

// The projective image evaluates to the projectively mapped points: image(t) = M (C(t), 1)
// projected. The division by the new weight (c.P + 1 in [34/64, 94/64]) loses at most a few
// ulps more than the affine case.
RC_GTEST_PROP(CurveTransform, ProjectiveMapCommutesWithEvaluation, ()) {
  const BezierCurve3 polynomial = *curve_gen::bezier_curve<3>(0, 8);
  const auto weights =
      *rc::gen::container<std::vector<double>>(polynomial.control_points().size(), curve_gen::coordinate(0.25, 4.0));
  const RationalBezierCurve3 rational(polynomial.control_points(), weights);
  const NurbsCurve3 nurbs = *bspline_gen::nurbs_curve<3>(1, 4, 3);
  const Eigen::Matrix4d M = *random_projective<3>();
  const RationalBezierCurve3 polynomial_image = projective_transform(polynomial, M);
  const RationalBezierCurve3 rational_image = projective_transform(rational, M);
  const NurbsCurve3 nurbs_image = projective_transform(nurbs, M);
  const double scale = 4.0 * image_scale(AffineMap<3>(M.topLeftCorner<3, 4>()), {Vec3::Constant(10.0)});
  for (int k = 0; k <= 16; ++k) {
    const double t = k / 16.0;
    RC_ASSERT((polynomial_image.evaluate(t) - apply<3>(M, polynomial.evaluate(t))).cwiseAbs().maxCoeff() <=
              256 * eps * scale);
    RC_ASSERT((rational_image.evaluate(t) - apply<3>(M, rational.evaluate(t))).cwiseAbs().maxCoeff() <=
              1024 * eps * scale);
    const double u = nurbs.a() + (nurbs.b() - nurbs.a()) * t;
    RC_ASSERT((nurbs_image.evaluate(u) - apply<3>(M, nurbs.evaluate(u))).cwiseAbs().maxCoeff() <= 1024 * eps * scale);
  }
}

// The circle |x - c| = r is the conic X^T Q X = 0 with Q = [I, -c; -c^T, |c|^2 - r^2]; its
// image under M is the conic Q' = M^-T Q M^-1. The mapped exact circle must evaluate to the
// mapped points, and lie on Q'.
TEST(CurveTransform, ProjectiveImageOfACircleIsTheMappedConic) {
  const Vec2 c(1.0, 2.0);
  const double r = 3.0;
  Eigen::Matrix3d M;
  M << 1.0, 0.2, 0.5, 0.1, 1.5, -1.0, 0.05, 0.02, 1.0;
  Eigen::Matrix3d Q;
  Q << 1.0, 0.0, -c.x(), 0.0, 1.0, -c.y(), -c.x(), -c.y(), c.squaredNorm() - r * r;
  const Eigen::Matrix3d Minv = M.inverse();
  const Eigen::Matrix3d image_conic = Minv.transpose() * Q * Minv;
  int checked = 0;
  for (const RationalBezierCurve2& piece : circle_arc(c, r, 0.0, 2.0 * std::numbers::pi)) {
    const RationalBezierCurve2 image = projective_transform(piece, M);
    for (int k = 0; k <= 32; ++k) {
      const double t = k / 32.0;
      const Vec2 x = image.evaluate(t);
      EXPECT_LT((x - apply<2>(M, piece.evaluate(t))).norm(), 1e-14 * 8.0) << "t " << t;
      const Vec3 X(x.x(), x.y(), 1.0);
      EXPECT_LT(std::abs(X.dot(image_conic * X)), 1e-13 * image_conic.norm() * X.squaredNorm()) << "t " << t;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4 * 33);
}

// Weights that come out all negative are negated (the same curve); mixed signs are refused,
// naming the first control point whose weight differs in sign from control point 0's.
TEST(CurveTransform, WeightsOfOneSignOrAnError) {
  const BezierCurve2 line({Vec2(-2.0, 0.0), Vec2(0.0, 1.0), Vec2(2.0, 0.0)});
  Eigen::Matrix3d negating = -Eigen::Matrix3d::Identity();
  negating(2, 0) = -0.25;  // w' = -(x/4 + 1) < 0 for x > -4
  const RationalBezierCurve2 negated = projective_transform(line, negating);
  for (int i = 0; i <= 2; ++i) EXPECT_GT(negated.weight(i), 0.0);
  for (int k = 0; k <= 8; ++k) {
    EXPECT_LT((negated.evaluate(k / 8.0) - apply<2>(negating, line.evaluate(k / 8.0))).norm(), 1e-15);
  }
  Eigen::Matrix3d crossing = Eigen::Matrix3d::Identity();
  crossing(2, 0) = 0.75;  // w' = 3x/4 + 1: 1 - 3/2 < 0 at x = -2, 1 at x = 0, 5/2 at x = 2
  try {
    projective_transform(line, crossing);
    FAIL() << "no error";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()),
              "projective_transform: control point 1 maps to weight 1 (control point 0 to -0.5): the image may cross "
              "the plane at infinity, and has no form with positive weights");
  }
  crossing(2, 0) = 0.5;  // w' = 0 at x = -2
  EXPECT_THROW(projective_transform(line, crossing), InvalidInput);
  EXPECT_THROW(projective_transform(line, Eigen::Matrix3d::Zero()), InvalidInput);  // singular
  Eigen::Affine2d infinite = Eigen::Affine2d::Identity();
  infinite.translation().x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(transform(line, infinite), InvalidInput);
}

}  // namespace
}  // namespace patchwork::curve_transform_test
