#include "curves/bspline_curve.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "curves/bspline_conversion.h"
#include "curves/bspline_measures.h"
#include "curves/homogeneous.h"
#include "curves/rational_bezier_curve.h"
#include "tests/curves/bspline_exact_reference.h"
#include "tests/curves/bspline_generators.h"
#include "tests/support/exact_rational.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// The unit circle as 4 quarter arcs (The NURBS Book, Ex. 7.2 / Fig. 7.16): 9 points on the
// square, weights 1 at the corners' neighbours and sqrt(2)/2 at the corners.
NurbsCurve2 unit_circle() {
  const double w = std::sqrt(2.0) / 2.0;
  return NurbsCurve2(KnotVector(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}),
                     {Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(-1, 1), Vec2(-1, 0), Vec2(-1, -1), Vec2(0, -1),
                      Vec2(1, -1), Vec2(1, 0)},
                     {1, w, 1, w, 1, w, 1, w, 1});
}

// sum_i B_i^n(s) P_i exactly, per coordinate (tests/support/exact_rational.h), at the global t.
template <int Dim>
ExactPoint<Dim> exact_bezier(const BezierCurve<Dim>& curve, const mpq_class& t) {
  const mpq_class s = (t - mpq_class(curve.a())) / (mpq_class(curve.b()) - mpq_class(curve.a()));
  ExactPoint<Dim> result;
  for (int c = 0; c < Dim; ++c) {
    std::vector<mpq_class> coefficients;
    for (const auto& p : curve.control_points()) coefficients.emplace_back(p[c]);
    result[static_cast<std::size_t>(c)] = exact::evaluate(coefficients, s);
  }
  return result;
}

RC_GTEST_PROP(BSplineCurve, DeBoorMatchesTheExactBasisSum, ()) {
  const auto curve = *bspline_gen::bspline_curve<3>(0, 5);
  const double u = *bspline_gen::parameter(curve.knot_vector());
  const auto exact = exact_bspline::evaluate(curve, mpq_class(u));
  // de Boor is p levels of convex combinations: gamma_{3p} relative to the largest point.
  RC_ASSERT(exact_bspline::distance<3>(curve.evaluate(u), exact) <=
            2.0 * gamma(3 * curve.degree() + 3) * exact_bspline::scale(curve));
}

RC_GTEST_PROP(BSplineCurve, ExtractedPiecesAreTheCurveExactly, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const auto pieces = bezier_pieces(curve);
  const double scale = exact_bspline::scale(curve);
  for (const auto& piece : pieces) {
    RC_ASSERT(piece.degree() == curve.degree());
    // The piece's rounded control points, evaluated exactly, against the exact B-spline: at both
    // ends and at a rational parameter inside (1/3 of the way, not a double).
    const mpq_class a(piece.a());
    const mpq_class b(piece.b());
    for (const mpq_class& t : std::vector<mpq_class>{a, b, mpq_class(a + (b - a) / 3)}) {
      const auto expected = exact_bspline::evaluate(curve, t);
      RC_ASSERT(exact_bspline::distance<2>(exact_bezier(piece, t), expected) <=
                2.0 * gamma(6 * curve.degree() + 6) * scale);
    }
  }
}

RC_GTEST_PROP(BSplineCurve, DerivativesMatchTheExactRecursionAndThePieces, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const double u = *bspline_gen::parameter(curve.knot_vector());
  const int p = curve.degree();
  const auto d = derivatives(curve, u, p + 1);
  const auto piece = bezier_piece(curve, curve.knot_vector().span(u));
  for (int k = 0; k <= p + 1; ++k) {
    const double scale = std::pow(16.0 * p, k) * exact_bspline::scale(curve);
    RC_ASSERT(exact_bspline::distance<2>(d[static_cast<std::size_t>(k)],
                                         exact_bspline::evaluate(curve, mpq_class(u), k)) <= 1e-12 * scale);
    RC_ASSERT((d[static_cast<std::size_t>(k)] - derivative(piece, u, k)).norm() <= 1e-10 * scale);
  }
  const std::vector<int> orders = curve.knot_vector().breakpoint_continuity();
  if (std::all_of(orders.begin(), orders.end(), [](int k) { return k >= 1; })) {
    const BSplineCurve2 hodograph = derivative_curve(curve);
    RC_ASSERT(hodograph.degree() == p - 1);
    RC_ASSERT((d[1] - hodograph.evaluate(u)).norm() <= 1e-12 * 16.0 * p * exact_bspline::scale(curve));
  } else {
    RC_ASSERT_THROWS_AS(derivative_curve(curve), InvalidInput);
  }
  RC_ASSERT(d[static_cast<std::size_t>(p + 1)].norm() == 0.0);
}

RC_GTEST_PROP(NurbsCurve, DerivativesMatchTheExactQuotientRule, ()) {
  const auto curve = *bspline_gen::nurbs_curve<2>(1, 4);
  const double u = *bspline_gen::parameter(curve.knot_vector());
  const int order = *rc::gen::inRange(0, 4);
  const auto d = derivatives(curve, u, order);
  // Exact homogeneous derivatives, then Leibniz in rationals: C^(k) = (A^(k) - sum C(k,j) w^(j) C^(k-j)) / w.
  std::vector<ExactPoint<3>> H;
  for (int k = 0; k <= order; ++k) H.push_back(exact_bspline::evaluate(curve.homogeneous(), mpq_class(u), k));
  std::vector<ExactPoint<2>> C;
  double largest = 0.0;
  for (int i = 0; i < curve.control_point_count(); ++i) largest = std::max(largest, curve.control_point(i).norm());
  for (int k = 0; k <= order; ++k) {
    ExactPoint<2> numerator{H[static_cast<std::size_t>(k)][0], H[static_cast<std::size_t>(k)][1]};
    for (int j = 1; j <= k; ++j) {
      for (std::size_t c = 0; c < 2; ++c) {
        numerator[c] -=
            mpq_class(exact_binomial(k, j)) * H[static_cast<std::size_t>(j)][2] * C[static_cast<std::size_t>(k - j)][c];
      }
    }
    for (auto& x : numerator) x /= H[0][2];
    C.push_back(numerator);
    // Weights in [1/4, 4] and knot gaps >= 1/8: derivatives grow by at most ~ 16 (8p) per order.
    const double scale = std::pow(128.0 * curve.degree(), k) * largest;
    RC_ASSERT(exact_bspline::distance<2>(d[static_cast<std::size_t>(k)], numerator) <= 1e-11 * scale);
  }
  // The rational Bezier piece of the span agrees (its derivatives are tested on their own).
  const auto piece = bezier_piece(curve, curve.knot_vector().span(u));
  RC_ASSERT((d.back() - derivative(piece, u, order)).norm() <=
            1e-9 * std::pow(128.0 * curve.degree(), order) * largest);
}

RC_GTEST_PROP(BSplineCurve, BlossomIsSymmetricMultiAffineAndThePointOnTheDiagonal, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const int p = curve.degree();
  const KnotVector& knots = curve.knot_vector();
  const int s = knots.span(*bspline_gen::parameter(knots));
  const auto argument = curve_gen::coordinate(knots[s], knots[s + 1]);
  std::vector<double> t = *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(p), argument);
  const double tolerance = 1e-12 * exact_bspline::scale(curve);
  const Vec2 f = blossom(curve, s, t);
  std::vector<double> reversed(t.rbegin(), t.rend());
  RC_ASSERT((blossom(curve, s, reversed) - f).norm() <= tolerance);
  // Affine in the first argument: f(x, ...) and f(y, ...) give f((x + y)/2, ...) halfway.
  const double x = *argument;
  const double y = *argument;
  std::vector<double> tx = t, ty = t, tm = t;
  tx[0] = x;
  ty[0] = y;
  tm[0] = 0.5 * (x + y);
  RC_ASSERT((blossom(curve, s, tm) - 0.5 * (blossom(curve, s, tx) + blossom(curve, s, ty))).norm() <= tolerance);
  const double u = *argument;
  RC_ASSERT((blossom(curve, s, std::vector<double>(static_cast<std::size_t>(p), u)) - curve.evaluate(u)).norm() <=
            tolerance);
}

RC_GTEST_PROP(BSplineCurve, TangentIsTheUnitFirstDerivative, ()) {
  const auto curve = *bspline_gen::bspline_curve<3>(1, 5);
  const double u = *bspline_gen::parameter(curve.knot_vector());
  const Vec3 d = derivative(curve, u, 1);
  RC_PRE(d.norm() > 1e-6 * exact_bspline::scale(curve));
  RC_ASSERT((tangent(curve, u) - d / d.norm()).norm() <= 1e-9);
}

TEST(NurbsCurve, CircleLiesOnTheUnitCircle) {
  const NurbsCurve2 circle = unit_circle();
  double worst = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double u = i / 1000.0;
    const Vec2 point = circle.evaluate(u);
    worst = std::max(worst, std::abs(point.norm() - 1.0));
    // The tangent is perpendicular to the radius and turns counter-clockwise.
    const Vec2 t = tangent(circle, u);
    EXPECT_NEAR(t.dot(point), 0.0, 1e-15);
    EXPECT_NEAR(point[0] * t[1] - point[1] * t[0], 1.0, 1e-15);
  }
  EXPECT_LE(worst, 4.0 * eps);
  EXPECT_EQ(circle.evaluate(0.0), Vec2(1, 0));
  EXPECT_NEAR((circle.evaluate(0.25) - Vec2(0, 1)).norm(), 0.0, eps);
  EXPECT_NEAR((circle.evaluate(0.5) - Vec2(-1, 0)).norm(), 0.0, eps);
}

TEST(NurbsCurve, CircleHasLengthTwoPiAndTheUnitBox) {
  const NurbsCurve2 circle = unit_circle();
  const ArcLength length = arc_length(circle, 1e-13);
  EXPECT_NEAR(length.length, 2.0 * pi, 1e-12);
  const Box<2> box = bounding_box(circle);
  EXPECT_NEAR((box.min() - Vec2(-1, -1)).norm(), 0.0, 4.0 * eps);
  EXPECT_NEAR((box.max() - Vec2(1, 1)).norm(), 0.0, 4.0 * eps);
  const Box<2> controls = control_box(circle);
  EXPECT_EQ(controls.min(), Vec2(-1, -1));
  EXPECT_EQ(controls.max(), Vec2(1, 1));
  // Four quarter arcs, each C^1 (G^1 and equal speed) at the double knots: pieces of degree 2.
  const auto pieces = bezier_pieces(circle);
  ASSERT_EQ(pieces.size(), 4u);
  for (const auto& piece : pieces) EXPECT_NEAR(piece.weight(1), std::sqrt(2.0) / 2.0, eps);
}

TEST(BSplineCurve, ParabolaHasItsClosedFormLength) {
  // y = x^2 on [0, 1] as a clamped quadratic with one interior knot (inserted into the Bezier
  // form): length = (2 sqrt 5 + asinh 2) / 4.
  const BSplineCurve2 parabola(KnotVector(2, {0, 0, 0, 1, 1, 1}), {Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 1)});
  EXPECT_NEAR(arc_length(parabola).length, (2.0 * std::sqrt(5.0) + std::asinh(2.0)) / 4.0, 1e-13);
  const Box<2> box = bounding_box(parabola);
  EXPECT_EQ(box.min(), Vec2(0, 0));
  EXPECT_EQ(box.max(), Vec2(1, 1));
}

RC_GTEST_PROP(BSplineCurve, BoxesContainTheCurve, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const Box<2> tight = bounding_box(curve);
  const Box<2> loose = control_box(curve);
  const double slack = 1e-12 * exact_bspline::scale(curve);
  RC_ASSERT((loose.min().array() <= tight.min().array() + slack).all());
  RC_ASSERT((tight.max().array() <= loose.max().array() + slack).all());
  for (int i = 0; i <= 64; ++i) {
    const double u = curve.a() + (curve.b() - curve.a()) * i / 64.0;
    const Vec2 p = curve.evaluate(std::min(u, curve.b()));
    RC_ASSERT((tight.min().array() <= p.array() + slack).all());
    RC_ASSERT((p.array() <= tight.max().array() + slack).all());
  }
}

RC_GTEST_PROP(BSplineCurve, PeriodicCurveClosesWithDegreeMinusOneDerivatives, ()) {
  const int p = *rc::gen::inRange(1, 6);
  const int k = *rc::gen::inRange(std::max(2, p), 9);
  const auto polygon = *curve_gen::control_points<3>(k - 1);
  const BSplineCurve3 closed = periodic_curve<3>(p, polygon);
  RC_ASSERT(closed.a() == 0.0);
  RC_ASSERT(closed.b() == 1.0);
  const auto start = derivatives(closed, 0.0, p);
  const auto end = derivatives(closed, 1.0, p);
  // The rational closed curve over the same polygon with weights in [1/4, 4].
  const auto weights = *rc::gen::container<std::vector<double>>(polygon.size(), curve_gen::coordinate(0.25, 4.0));
  const NurbsCurve3 rational = periodic_curve<3>(p, polygon, weights);
  const auto rational_start = derivatives(rational, 0.0, p);
  const auto rational_end = derivatives(rational, 1.0, p);
  double scale = exact_bspline::scale(closed);
  for (int j = 0; j < p; ++j) {
    const auto at = static_cast<std::size_t>(j);
    RC_ASSERT((start[at] - end[at]).norm() <= 1e-12 * scale);
    RC_ASSERT((rational_start[at] - rational_end[at]).norm() <= 1e-10 * scale * std::pow(16.0, j));
    scale *= 2.0 * k;
  }
  // Not C^p: the p-th derivative jumps for a generic polygon (p >= 1, k >= 3 distinct points).
  if (k >= 3) RC_ASSERT((start[static_cast<std::size_t>(p)] - end[static_cast<std::size_t>(p)]).norm() > 1e-9 * scale);
}

TEST(BSplineCurve, BadInputIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const KnotVector knots = clamped_uniform_knots(2, 4);
  const std::vector<Vec2> points{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  expect_invalid_input([&] { BSplineCurve2(knots, {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)}); }, "need 4");
  expect_invalid_input([&] { BSplineCurve2(knots, {Vec2(0, 0), Vec2(1, nan), Vec2(1, 1), Vec2(0, 1)}); }, "not finite");
  const BSplineCurve2 curve(knots, points);
  expect_invalid_input([&] { (void)curve.evaluate(1.5); }, "outside the valid range");
  expect_invalid_input([&] { (void)curve.evaluate(-1e-300); }, "outside the valid range");
  expect_invalid_input([&] { (void)curve.evaluate(nan); }, "not finite");
  expect_invalid_input([&] { (void)derivative(curve, 0.5, -1); }, "negative");
  expect_invalid_input([&] { NurbsCurve2(knots, points, {1, 0, 1, 1}); }, "weight 1 = 0 is not positive");
  expect_invalid_input([&] { NurbsCurve2(knots, points, {1, -2, 1, 1}); }, "not positive");
  expect_invalid_input([&] { NurbsCurve2(knots, points, {1, nan, 1, 1}); }, "not positive and finite");
  expect_invalid_input([&] { NurbsCurve2(knots, points, {1, 1, 1}); }, "3 weights");
  const NurbsCurve2 rational(knots, points, {1, 2, 1, 1});
  expect_invalid_input([&] { (void)rational.evaluate(2.0); }, "outside the valid range");
  expect_invalid_input([&] { (void)blossom(curve, 1, std::vector<double>{0.5, 0.5}); }, "not a non-empty span");
  expect_invalid_input([&] { (void)bezier_piece(curve, 4); }, "not a non-empty span");
}

}  // namespace
}  // namespace patchwork
