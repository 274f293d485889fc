#include "curves/continuity.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "curves/subdivision.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;
using testing::max_norm;  // beside arc_length_test's overload for curves (one unity translation unit)

template <int Dim>
ExactPoint<Dim> exact(const Point<Dim>& p) {
  ExactPoint<Dim> result;
  for (int d = 0; d < Dim; ++d) result[static_cast<std::size_t>(d)] = mpq_class(p[d]);
  return result;
}

template <int Dim>
std::vector<ExactPoint<Dim>> exact(const std::vector<Point<Dim>>& points) {
  std::vector<ExactPoint<Dim>> result;
  for (const auto& p : points) result.push_back(exact<Dim>(p));
  return result;
}

template <int Dim>
double norm(const ExactPoint<Dim>& q) {
  double sum = 0.0;
  for (const auto& c : q) sum += c.get_d() * c.get_d();
  return std::sqrt(sum);
}

// Exact derivatives with respect to s of sum_i B_i^n(s) P_i at s = 0 or s = 1: the hodograph
// n (P_{i+1} - P_i) taken j times (Satz 21), then its first or last control point.
template <int Dim>
ExactPoint<Dim> exact_end_derivative(std::vector<ExactPoint<Dim>> P, int j, bool at_end) {
  for (int order = 0; order < j; ++order) {
    const int n = static_cast<int>(P.size()) - 1;
    if (n == 0) {
      for (auto& c : P[0]) c = 0;
      return P[0];
    }
    std::vector<ExactPoint<Dim>> hodograph(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      for (int d = 0; d < Dim; ++d) {
        hodograph[i][d] = n * (P[i + 1][d] - P[i][d]);
      }
    }
    P = std::move(hodograph);
  }
  return at_end ? P.back() : P.front();
}

// Degree elevation n -> m (m >= n) in exact arithmetic: Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i.
template <int Dim>
std::vector<ExactPoint<Dim>> exact_elevate(std::vector<ExactPoint<Dim>> P, int m) {
  while (static_cast<int>(P.size()) - 1 < m) {
    const int n = static_cast<int>(P.size()) - 1;
    std::vector<ExactPoint<Dim>> Q(static_cast<std::size_t>(n) + 2);
    for (int i = 0; i <= n + 1; ++i) {
      const mpq_class alpha(i, n + 1);
      for (int d = 0; d < Dim; ++d) {
        mpq_class value = 0;
        if (i > 0) value += alpha * P[i - 1][d];
        if (i <= n) value += (1 - alpha) * P[i][d];
        Q[i][d] = value;
      }
    }
    P = std::move(Q);
  }
  return P;
}

// The blossom f(u_1, ..., u_m) of the polynomial with control points P (degree m, local
// parameter): de Casteljau with parameter u_l at level l.
template <int Dim>
ExactPoint<Dim> exact_blossom(std::vector<ExactPoint<Dim>> P, const std::vector<mpq_class>& u) {
  const int m = static_cast<int>(P.size()) - 1;
  for (int level = 1; level <= m; ++level) {
    const mpq_class& s = u[static_cast<std::size_t>(level - 1)];
    for (int i = 0; i + level <= m; ++i) {
      for (int d = 0; d < Dim; ++d) P[i][d] = (1 - s) * P[i][d] + s * P[i + 1][d];
    }
  }
  return P[0];
}

template <int Dim>
Point<Dim> random_point(double spread) {
  Point<Dim> p;
  for (int d = 0; d < Dim; ++d) p[d] = spread * (2.0 * random_unit() - 1.0);
  return p;
}

// An interval length in [2^-e, 2^e], log-uniform.
double random_length(double e) { return std::pow(2.0, e * (2.0 * random_unit() - 1.0)); }

// The cubic of the hand-made examples, on [0, 1.5].
BezierCurve2 first_cubic() { return BezierCurve2({Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)}, 0.0, 1.5); }

TEST(Continuity, Def58OnTheUnitIntervalMatchesExactDerivatives) {
  // Two cubics on [0, 1] (Def 58 verbatim): Q_0 = P_3, Q_1 = 2 P_3 - P_2, Q_2 = 4 P_3 - 4 P_2 + P_1
  // make the first and second differences agree, Q_3 is free.
  const std::vector<Vec2> P{Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)};
  const std::vector<Vec2> Q{Vec2(4, 1), Vec2(5, -1), Vec2(5, -6), Vec2(2, 2)};
  const BezierCurve2 first(P);
  const BezierCurve2 second(Q);
  // How many derivatives agree exactly, from Satz 21 in rational arithmetic.
  int exact_order = -1;
  while (exact_order < 3) {
    const int j = exact_order + 1;
    if (exact_end_derivative<2>(exact<2>(P), j, true) != exact_end_derivative<2>(exact<2>(Q), j, false)) break;
    exact_order = j;
  }
  ASSERT_EQ(exact_order, 2);
  const Continuity result = continuity(first, second, 3);
  EXPECT_EQ(result.ck, 2);
  EXPECT_TRUE(result.g1);
  EXPECT_EQ(result.gap, 0.0);
  // max_order caps the answer.
  EXPECT_EQ(continuity(first, second, 1).ck, 1);
  EXPECT_EQ(continuity(first, second, 0).ck, 0);
  // Exact agreement needs no tolerance at all.
  EXPECT_EQ(continuity(first, second, 3, 0.0).ck, 2);
}

TEST(Continuity, Bemerkung18WithDifferentDegreesAndIntervals) {
  // n = 3 on [0, 1.5], m = 4 on [1.5, 4.5]: Q_1 = Q_0 + (n/m) (h2/h1) (P_3 - P_2)
  //   = (4, 1) + (3/4)(3/1.5)(1, -2) = (5.5, -2), all dyadic, so exact.
  const BezierCurve2 first = first_cubic();
  const std::vector<Vec2> start = continue_ck(first, 1, 4, 3.0);
  ASSERT_EQ(start.size(), 2u);
  EXPECT_EQ(start[0], Vec2(4, 1));
  EXPECT_EQ(start[1], Vec2(5.5, -2));
  const BezierCurve2 second({start[0], start[1], Vec2(7, 0), Vec2(6, 3), Vec2(9, 9)}, 1.5, 4.5);
  const Continuity result = continuity(first, second, 4);
  EXPECT_EQ(result.ck, 1);
  EXPECT_TRUE(result.g1);
  // The same join read on [0, 1] each (Def 58 verbatim) is only G^1: the speeds differ.
  const Continuity unit = continuity(with_interval(first, 0.0, 1.0), with_interval(second, 0.0, 1.0), 4);
  EXPECT_EQ(unit.ck, 0);
  EXPECT_TRUE(unit.g1);
}

TEST(Continuity, TangentScaledIsG1ButNotC1) {
  const BezierCurve2 first = first_cubic();
  // Twice the C^1 step Q_1 - Q_0 = (1.5, -3): same direction, double speed.
  const BezierCurve2 second({Vec2(4, 1), Vec2(7, -5), Vec2(7, 0), Vec2(6, 3), Vec2(9, 9)}, 1.5, 4.5);
  const Continuity result = continuity(first, second, 3);
  EXPECT_EQ(result.ck, 0);
  EXPECT_TRUE(result.g1);
  EXPECT_EQ(result.gap, 0.0);
}

TEST(Continuity, KinkAndReversalAreNotG1) {
  const BezierCurve2 first = first_cubic();
  // A different direction, and the exact opposite direction (the curve turns back).
  for (const Vec2& step : {Vec2(1.5, 3), Vec2(-1.5, 3), Vec2(0, 1)}) {
    const BezierCurve2 second({Vec2(4, 1), Vec2(4, 1) + step, Vec2(7, 0)}, 1.5, 2.5);
    const Continuity result = continuity(first, second, 2);
    EXPECT_EQ(result.ck, 0);
    EXPECT_FALSE(result.g1) << step.transpose();
  }
}

TEST(Continuity, GapIsReported) {
  const BezierCurve2 first = first_cubic();
  // Q_0 = P_3 + (0.375, 0.5): the gap is 0.625, exactly representable and exactly computed.
  const BezierCurve2 second({Vec2(4.375, 1.5), Vec2(6, -2), Vec2(7, 0)}, 1.5, 2.5);
  const Continuity result = continuity(first, second, 2);
  EXPECT_EQ(result.ck, -1);
  EXPECT_FALSE(result.g1);
  EXPECT_EQ(result.gap, 0.625);
}

TEST(Continuity, LimitTangentsDecideG1AtACusp) {
  // First: P_1 = P_2, so C'(1) = 0; C''(1) = 2 (P_0 - 2 P_1 + P_2) = (-2, 0), and from the left the
  // curve arrives moving in +x. Second leaves in +x: G^1 but not C^1 (speeds 0 and 2).
  const BezierCurve2 first({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0)});
  const BezierCurve2 second({Vec2(1, 0), Vec2(2, 0), Vec2(2, 1)}, 1.0, 2.0);
  const Continuity result = continuity(first, second, 2);
  EXPECT_EQ(result.ck, 0);
  EXPECT_TRUE(result.g1);
  // Leaving in -x turns back: not G^1.
  const BezierCurve2 back({Vec2(1, 0), Vec2(0, 0), Vec2(0, 1)}, 1.0, 2.0);
  EXPECT_FALSE(continuity(first, back, 2).g1);
  // A point curve has no tangent at all.
  const BezierCurve2 point({Vec2(1, 0), Vec2(1, 0)});
  const Continuity with_point = continuity(point, second, 2);
  EXPECT_EQ(with_point.ck, 0);
  EXPECT_FALSE(with_point.g1);
}

TEST(Continuity, ToleranceIsRelativeToTheControlPoints) {
  const BezierCurve2 first = first_cubic();
  // The C^1 join of Bemerkung 18 with Q_1 moved by 1e-6: derivatives differ by (m/h2) 1e-6 =
  // 1.3e-6, above the default 1e-10 * 2 n max|P| / h1 ~ 5e-9, below 1e-5 times that.
  const BezierCurve2 second({Vec2(4, 1), Vec2(5.5, -2 + 1e-6), Vec2(7, 0), Vec2(6, 3), Vec2(9, 9)}, 1.5, 4.5);
  EXPECT_EQ(continuity(first, second, 3).ck, 0);
  EXPECT_EQ(continuity(first, second, 3, 1e-5).ck, 1);
}

TEST(Continuity, LongContinuationDoesNotHideCurvature) {
  // A slightly bent quadratic (Delta^2 P = (0, 1e-6), 5e-7 of its size: far above the relative
  // tolerance 1e-10) continued C^1 by a straight line over an interval 1e4 times longer. The
  // join is C^1 and not C^2: C''(1) = (0, 2e-6) on the left, 0 on the right. The line's control
  // points are 1e4 times larger, which must not inflate the tolerance of the quadratic's C''.
  const BezierCurve2 first({Vec2(0, 0), Vec2(1, 0), Vec2(2, 1e-6)});
  const std::vector<Vec2> start = continue_ck(first, 1, 1, 1e4);
  const BezierCurve2 second(start, 1.0, 1.0 + 1e4);
  const Continuity result = continuity(first, second, 3);
  EXPECT_EQ(result.ck, 1);
  EXPECT_TRUE(result.g1);
}

TEST(Continuity, RejectsBadInput) {
  const BezierCurve2 first = first_cubic();
  const BezierCurve2 second({Vec2(4, 1), Vec2(5, 0)}, 1.5, 2.5);
  EXPECT_THROW(continuity(first, second, -1), InvalidInput);
  EXPECT_THROW(continuity(first, second, 2, -1e-10), InvalidInput);
  EXPECT_THROW(continuity(first, second, 2, std::nan("")), InvalidInput);
  EXPECT_THROW(continuity(first, second, 2, std::numeric_limits<double>::infinity()), InvalidInput);
  EXPECT_THROW(continue_ck(first, 3, 2, 1.0), InvalidInput);  // k > m
  EXPECT_THROW(continue_ck(first, -1, 2, 1.0), InvalidInput);
  EXPECT_THROW(continue_ck(first, 1, 2, 0.0), InvalidInput);
  EXPECT_THROW(continue_ck(first, 1, 2, -1.0), InvalidInput);
  EXPECT_THROW(continue_ck(first, 1, 2, std::nan("")), InvalidInput);
  EXPECT_THROW(continue_ck(first, 1, 2, std::numeric_limits<double>::infinity()), InvalidInput);
}

// Builds first (degree n on [a, a+h1]) and a second curve of degree m on [a+h1, a+h1+h2] whose
// first k+1 points come from continue_ck and whose other points are random; every control point
// is offset by `offset`. Checks that exactly C^k is reported.
template <int Dim>
void check_constructed_join(double offset, double spread, int max_degree) {
  const int n = *rc::gen::inRange(1, max_degree + 1);
  const int m = *rc::gen::inRange(0, max_degree + 1);
  const int k = *rc::gen::inRange(0, m + 1);
  const int max_order = k + *rc::gen::inRange(0, 3);
  const double a = 4.0 * random_unit() - 2.0;
  const double h1 = random_length(4.0);
  const double h2 = random_length(4.0);
  const Point<Dim> shift = Point<Dim>::Constant(offset);
  std::vector<Point<Dim>> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = shift + random_point<Dim>(spread);
  const BezierCurve<Dim> first(P, a, a + h1);
  std::vector<Point<Dim>> Q = continue_ck(first, k, m, h2);
  RC_ASSERT(static_cast<int>(Q.size()) == k + 1);
  while (static_cast<int>(Q.size()) <= m) Q.push_back(shift + random_point<Dim>(spread));
  const BezierCurve<Dim> second(Q, a + h1, a + h1 + h2);
  const Continuity result = continuity(first, second, max_order);
  // With k = m >= n the second curve continues the same polynomial (all derivatives agree: C^inf,
  // capped at max_order); otherwise the random Q_{k+1} (or the first curve's nonzero
  // (m+1)-th difference) breaks C^(k+1).
  const int expected = (k == m && n <= m) ? max_order : k;
  RC_ASSERT(result.ck == expected);
  RC_ASSERT(result.gap <= 4.0 * eps * (offset + spread) * Dim);
  if (k >= 1) RC_ASSERT(result.g1);
}

RC_GTEST_PROP(Continuity, ConstructedJoinsAreExactlyCk2D, ()) { check_constructed_join<2>(0.0, 1.0, 8); }

RC_GTEST_PROP(Continuity, ConstructedJoinsAreExactlyCk3D, ()) { check_constructed_join<3>(0.0, 1.0, 8); }

// Far from the origin the relative tolerance grows with the coordinates: the data keep a spread
// of 1e-5 relative to 1e8, far above 1e-10 * 2^j, so generic data still break C^(k+1).
RC_GTEST_PROP(Continuity, ConstructedJoinsAreExactlyCkFarFromTheOrigin, ()) { check_constructed_join<3>(1e8, 1e3, 8); }

RC_GTEST_PROP(Continuity, ContinueCkMatchesTheExactBlossom, ()) {
  // For m >= n the C^k continuation Q_0..Q_k is the first curve's own polynomial on [b, b + h2]
  // (degree-elevated to m): Q_j = blossom(1, .., 1, 1 + h2/h1, .., 1 + h2/h1) with j copies of
  // the end parameter, in the first curve's local parameter.
  const int n = *rc::gen::inRange(0, 7);
  const int m = *rc::gen::inRange(n, 9);
  const int k = *rc::gen::inRange(0, m + 1);
  const double h1 = random_length(2.0);
  const double h2 = random_length(2.0);
  std::vector<Vec2> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = random_point<2>(1.0);
  const BezierCurve2 first(P, 1.0, 1.0 + h1);
  const std::vector<Vec2> Q = continue_ck(first, k, m, h2);
  const std::vector<ExactPoint<2>> elevated = exact_elevate<2>(exact<2>(P), m);
  // The exact local end parameter uses the interval length as the implementation sees it.
  const mpq_class end = 1 + mpq_class(h2) / mpq_class(first.b() - first.a());
  double largest = max_norm(P);
  for (int j = 0; j <= k; ++j) {
    std::vector<mpq_class> u(static_cast<std::size_t>(m), mpq_class(1));
    for (int l = 0; l < j; ++l) u[static_cast<std::size_t>(l)] = end;
    const ExactPoint<2> expected = exact_blossom<2>(elevated, u);
    largest = std::max(largest, norm<2>(expected));
    // Q_j = target_j - sum_{l<j} (-1)^(j-l) C(j,l) Q_l: each level adds rounding of 2^j times
    // the largest point so far and inherits the earlier errors times C(j,l), so the error is
    // below 4^(j+1) eps max(|P|, |Q_0..Q_j|).
    RC_ASSERT(distance<2>(Q[static_cast<std::size_t>(j)], expected) <= std::pow(4.0, j + 1) * eps * largest);
  }
}

RC_GTEST_PROP(Continuity, Bemerkung18HoldsForAnyDegreesAndIntervals, ()) {
  const int n = *rc::gen::inRange(1, 12);
  const int m = *rc::gen::inRange(1, 12);
  const double h1 = random_length(2.0);
  const double h2 = random_length(2.0);
  std::vector<Vec3> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = random_point<3>(1.0);
  const BezierCurve3 first(P, 0.0, h1);
  const std::vector<Vec3> Q = continue_ck(first, 1, m, h2);
  RC_ASSERT(Q[0] == P.back());
  // Q_1 = Q_0 + (n/m) (h2/h1) (P_n - P_{n-1}), exactly.
  ExactPoint<3> expected;
  const mpq_class factor = mpq_class(n, m) * mpq_class(h2) / mpq_class(h1);
  for (int d = 0; d < 3; ++d) {
    expected[static_cast<std::size_t>(d)] = mpq_class(P[n][d]) + factor * (mpq_class(P[n][d]) - mpq_class(P[n - 1][d]));
  }
  // A handful of roundings of quantities below (1 + 2 (n/m)(h2/h1)) max|P|.
  RC_ASSERT(distance<3>(Q[1], expected) <= 8.0 * eps * (1.0 + 2.0 * factor.get_d()) * max_norm(P));
}

RC_GTEST_PROP(Continuity, SplitPiecesJoinWithEveryDerivative, ()) {
  // Def 59 generalised: the two pieces of a split are one polynomial, so every derivative
  // agrees, C^(n+2) when asked for n+2; also far from the origin.
  const int n = *rc::gen::inRange(1, 11);
  const double offset = *rc::gen::element(0.0, 1e8);
  std::vector<Vec3> P(static_cast<std::size_t>(n) + 1);
  for (auto& p : P) p = Vec3::Constant(offset) + random_point<3>(1.0);
  const BezierCurve3 curve(P, -1.0, 2.0);
  const double t = -1.0 + 3.0 * (*rc::gen::inRange(1, 1000) / 1000.0);
  const auto [left, right] = split(curve, t);
  const Continuity result = continuity(left, right, n + 2);
  RC_ASSERT(result.ck == n + 2);
  // G^1 unless C'(t) vanishes there at the tolerance's resolution (a point-like piece, or a cusp
  // where the direction reverses): asked only where |C'(t)| is 1e4 times the tolerance of the
  // first derivatives, 1e-10 * 2 n max|P| / min(h_left, h_right).
  const double tolerance1 = 1e-10 * 2.0 * n * max_norm(P) / std::min(t + 1.0, 2.0 - t);
  if (derivative(curve, t, 1).norm() > 1e4 * tolerance1) RC_ASSERT(result.g1);
}

}  // namespace
}  // namespace patchwork
