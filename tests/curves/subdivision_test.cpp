#include "curves/subdivision.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// The blossom (polar form) f(u_1, ..., u_n) of the curve with control points P, in rational
// arithmetic: de Casteljau with parameter u_k at level k. The piece of C on [s0, s1] (local
// parameters) has control points f(s0^(n-i), s1^i), i = 0..n.
template <int Dim>
ExactPoint<Dim> exact_blossom(const std::vector<Point<Dim>>& P, const std::vector<mpq_class>& u) {
  std::vector<ExactPoint<Dim>> work(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    for (std::size_t c = 0; c < Dim; ++c) work[i][c] = P[i][static_cast<int>(c)];
  }
  for (std::size_t k = 1; k < P.size(); ++k) {
    for (std::size_t i = 0; i + k < P.size(); ++i) {
      for (std::size_t c = 0; c < Dim; ++c) work[i][c] = (1 - u[k - 1]) * work[i][c] + u[k - 1] * work[i + 1][c];
    }
  }
  return work[0];
}

// Control points of the piece on [s0, s1] of the local parameter, exactly.
template <int Dim>
std::vector<ExactPoint<Dim>> exact_piece(const std::vector<Point<Dim>>& P, const mpq_class& s0, const mpq_class& s1) {
  const std::size_t n = P.size() - 1;
  std::vector<ExactPoint<Dim>> Q;
  for (std::size_t i = 0; i <= n; ++i) {
    std::vector<mpq_class> u(n, s0);
    std::fill(u.begin(), u.begin() + static_cast<std::ptrdiff_t>(i), s1);
    Q.push_back(exact_blossom<Dim>(P, u));
  }
  return Q;
}

template <int Dim>
std::vector<Point<Dim>> to_double(const std::vector<ExactPoint<Dim>>& exact) {
  std::vector<Point<Dim>> result(exact.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    for (std::size_t c = 0; c < Dim; ++c) result[i][static_cast<int>(c)] = exact[i][c].get_d();
  }
  return result;
}

// Integer control points: de Casteljau at s = 1/4 or 1/2 only produces short dyadic numbers,
// so the computed pieces must equal the exact ones bit for bit.
BezierCurve2 integer_quintic(double a = 0.0, double b = 1.0) {
  return BezierCurve2({Vec2(0, 0), Vec2(3, 7), Vec2(-2, 5), Vec2(8, -4), Vec2(5, 9), Vec2(11, 1)}, a, b);
}

TEST(Subdivision, SplitIsTheDeCasteljauTriangle) {
  // Satz 22: the left piece is b_0^0, b_0^1, ..., b_0^n, the right b_0^n, b_1^(n-1), ..., b_n^0.
  const BezierCurve2 curve = integer_quintic(2.0, 6.0);
  const auto [left, right] = split(curve, 3.0);  // s = 1/4
  EXPECT_EQ(left.a(), 2.0);
  EXPECT_EQ(left.b(), 3.0);
  EXPECT_EQ(right.a(), 3.0);
  EXPECT_EQ(right.b(), 6.0);
  const mpq_class s(1, 4);
  EXPECT_EQ(left.control_points(), to_double<2>(exact_piece<2>(curve.control_points(), 0, s)));
  EXPECT_EQ(right.control_points(), to_double<2>(exact_piece<2>(curve.control_points(), s, 1)));
  EXPECT_EQ(max_difference<2>(left.control_points(), exact_piece<2>(curve.control_points(), 0, s)), 0);
  EXPECT_EQ(max_difference<2>(right.control_points(), exact_piece<2>(curve.control_points(), s, 1)), 0);
}

TEST(Subdivision, HalvingFollowsDef59) {
  // Def 59: the halves have control points b_i^i and b_n^(n-i) of the triangle at t0 = 1/2 and
  // join C^n: every derivative agrees at the midpoint. All values here are exact.
  const BezierCurve2 curve = integer_quintic(-1.0, 3.0);
  const auto [left, right] = halve(curve);
  EXPECT_EQ(left.b(), 1.0);
  EXPECT_EQ(right.a(), 1.0);
  const mpq_class half(1, 2);
  EXPECT_EQ(max_difference<2>(left.control_points(), exact_piece<2>(curve.control_points(), 0, half)), 0);
  EXPECT_EQ(max_difference<2>(right.control_points(), exact_piece<2>(curve.control_points(), half, 1)), 0);
  for (int k = 0; k <= 6; ++k) EXPECT_EQ(derivative(left, 1.0, k), derivative(right, 1.0, k)) << "k=" << k;
  // Bemerkung 18's C^1 condition for equal degrees: P_n - P_{n-1} = Q_1 - Q_0.
  const auto& P = left.control_points();
  const auto& Q = right.control_points();
  EXPECT_EQ(P[5] - P[4], Q[1] - Q[0]);
}

TEST(Subdivision, SplitOfPointCurveGivesPoints) {
  const BezierCurve3 point({Vec3(1, 2, 3)}, 0.0, 4.0);
  const auto [left, right] = split(point, 1.0);
  EXPECT_EQ(left, BezierCurve3({Vec3(1, 2, 3)}, 0.0, 1.0));
  EXPECT_EQ(right, BezierCurve3({Vec3(1, 2, 3)}, 1.0, 4.0));
}

RC_GTEST_PROP(Subdivision, SplitPiecesMatchExactBlossom, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const double t = *curve_gen::interior_parameter(curve.a(), curve.b());
  const auto [left, right] = split(curve, t);
  RC_ASSERT(left.a() == curve.a() && left.b() == t && right.a() == t && right.b() == curve.b());
  RC_ASSERT(left.degree() == curve.degree() && right.degree() == curve.degree());
  // Each level-k point of the triangle is a de Casteljau value: error <= gamma_{2n} M, with the
  // split parameter s taken as computed.
  const int n = curve.degree();
  const auto& P = curve.control_points();
  const mpq_class s(curve.local_parameter(t));
  const mpq_class bound = mpq_class(gamma(2 * n) * max_abs<3>(P));
  RC_ASSERT(max_difference<3>(left.control_points(), exact_piece<3>(P, 0, s)) <= bound);
  RC_ASSERT(max_difference<3>(right.control_points(), exact_piece<3>(P, s, 1)) <= bound);
  // The pieces share the computed C(t) and keep the end points, bit for bit.
  RC_ASSERT(left.control_points().front() == P.front());
  RC_ASSERT(right.control_points().back() == P.back());
  RC_ASSERT(left.control_points().back() == right.control_points().front());
}

RC_GTEST_PROP(Subdivision, SplitThenEvaluateEqualsEvaluate, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const double t = *curve_gen::interior_parameter(curve.a(), curve.b());
  const auto [left, right] = split(curve, t);
  const int n = curve.degree();
  const double M = max_abs<3>(curve.control_points());
  // gamma_{2n} M for the pieces' control points plus gamma_{2n} M for evaluating a piece, and
  // the rounding of the local parameters (a few u relative) times |dC/ds| <= 2 n M.
  const double tolerance = (2 * gamma(2 * n) + 16 * n * kUnit) * M;
  const double t_left = *curve_gen::parameter(curve.a(), t);
  const double t_right = *curve_gen::parameter(t, curve.b());
  RC_ASSERT((left.evaluate(t_left) - curve.evaluate(t_left)).cwiseAbs().maxCoeff() <= tolerance);
  RC_ASSERT((right.evaluate(t_right) - curve.evaluate(t_right)).cwiseAbs().maxCoeff() <= tolerance);
}

RC_GTEST_PROP(Subdivision, HalvesJoinWithAllDerivativesEqual, ()) {
  // Def 59 for any interval: the halves form a C^n patch at the midpoint m.
  const auto curve = *curve_gen::bezier_curve_on_interval<2>(0, 10);
  const auto [left, right] = halve(curve);
  const double m = 0.5 * (curve.a() + curve.b());
  RC_ASSERT(left.a() == curve.a() && left.b() == m && right.a() == m && right.b() == curve.b());
  const int n = curve.degree();
  const double h = 0.5 * (curve.b() - curve.a());
  const double M = max_abs<2>(curve.control_points());
  for (int k = 0; k <= n; ++k) {
    // Each side: the halves' control points (gamma_{2n} M) and the derivative's own rounding
    // ((4n + 4k + 8) u), both amplified by n!/(n-k)! 2^k / h^k.
    const double scale = reference_falling_factorial(n, k) * std::pow(2.0, k) * M / std::pow(h, k);
    const double tolerance = 2 * (gamma(2 * n) + (4 * n + 4 * k + 8) * kUnit) * scale;
    RC_ASSERT((derivative(left, m, k) - derivative(right, m, k)).cwiseAbs().maxCoeff() <= tolerance);
    RC_ASSERT((derivative(left, m, k) - derivative(curve, m, k)).cwiseAbs().maxCoeff() <= tolerance);
  }
}

TEST(Subdivision, SubcurveOfDyadicIntervalIsExact) {
  // [1/4, 1/2]: split at 1/2, then the left piece at its own midpoint; all values exact.
  const BezierCurve2 curve = integer_quintic();
  const BezierCurve2 piece = subcurve(curve, 0.25, 0.5);
  EXPECT_EQ(piece.a(), 0.25);
  EXPECT_EQ(piece.b(), 0.5);
  EXPECT_EQ(max_difference<2>(piece.control_points(),
                              exact_piece<2>(curve.control_points(), mpq_class(1, 4), mpq_class(1, 2))),
            0);
  // The whole interval is the curve itself; a prefix is split's left piece.
  EXPECT_EQ(subcurve(curve, 0.0, 1.0), curve);
  EXPECT_EQ(subcurve(curve, 0.0, 0.5), split(curve, 0.5).first);
  EXPECT_EQ(subcurve(curve, 0.5, 1.0), split(curve, 0.5).second);
}

RC_GTEST_PROP(Subdivision, SubcurveMatchesExactPieceAndCurve, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const auto range = *curve_gen::interval(curve.a(), curve.b());
  const BezierCurve3 piece = subcurve(curve, range.a, range.b);
  RC_ASSERT(piece.a() == range.a && piece.b() == range.b && piece.degree() == curve.degree());
  const int n = curve.degree();
  const auto& P = curve.control_points();
  const double M = max_abs<3>(P);
  // Two splits: twice gamma_{2n} M for the control points, and each split parameter is rounded
  // (a few u), moving the blossom by at most 2 n M per unit of parameter.
  const double tolerance = (2 * gamma(2 * n) + 32 * n * kUnit) * M;
  const mpq_class h = mpq_class(curve.b()) - mpq_class(curve.a());
  const mpq_class s0 = (mpq_class(range.a) - mpq_class(curve.a())) / h;
  const mpq_class s1 = (mpq_class(range.b) - mpq_class(curve.a())) / h;
  RC_ASSERT(max_difference<3>(piece.control_points(), exact_piece<3>(P, s0, s1)) <= mpq_class(tolerance));
  const double t = *curve_gen::parameter(range.a, range.b);
  RC_ASSERT((piece.evaluate(t) - curve.evaluate(t)).cwiseAbs().maxCoeff() <= tolerance + 2 * gamma(2 * n) * M);
}

TEST(Subdivision, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const BezierCurve2 curve = integer_quintic(1.0, 2.0);
  expect_invalid_input([&] { split(curve, 1.0); }, "split");
  expect_invalid_input([&] { split(curve, 2.0); }, "split");
  expect_invalid_input([&] { split(curve, 0.5); }, "split");
  expect_invalid_input([&] { split(curve, 2.5); }, "split");
  expect_invalid_input([&] { split(curve, nan); }, "not finite");
  expect_invalid_input([&] { subcurve(curve, 1.5, 1.5); }, "subcurve");
  expect_invalid_input([&] { subcurve(curve, 1.7, 1.2); }, "subcurve");
  expect_invalid_input([&] { subcurve(curve, 0.9, 1.5); }, "subcurve");
  expect_invalid_input([&] { subcurve(curve, 1.5, 2.1); }, "subcurve");
  expect_invalid_input([&] { subcurve(curve, nan, 1.5); }, "not finite");
  expect_invalid_input([&] { subcurve(curve, 1.5, std::numeric_limits<double>::infinity()); }, "not finite");
}

}  // namespace
}  // namespace patchwork
