#include "tests/support/refined_maximum.h"
#include "curves/degree.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// Elevation by r in one step (not r single steps):
//   Q_i = sum_j C(n, j) C(r, i - j) / C(n + r, i) P_j,  i = 0..n+r.
template <int Dim>
std::vector<ExactPoint<Dim>> exact_elevation(const std::vector<Point<Dim>>& P, int r) {
  const int n = static_cast<int>(P.size()) - 1;
  std::vector<ExactPoint<Dim>> Q(static_cast<std::size_t>(n + r) + 1);
  for (int i = 0; i <= n + r; ++i) {
    for (int j = std::max(0, i - r); j <= std::min(n, i); ++j) {
      const mpq_class weight = mpq_class(exact_binomial(n, j) * exact_binomial(r, i - j)) / exact_binomial(n + r, i);
      for (std::size_t c = 0; c < Dim; ++c) {
        Q[static_cast<std::size_t>(i)][c] += weight * P[static_cast<std::size_t>(j)][static_cast<int>(c)];
      }
    }
  }
  return Q;
}

// int_0^1 B_k^m B_i^n ds = C(m,k) C(n,i) / ((m+n+1) C(m+n, k+i)), exactly.
mpq_class exact_gram(int m, int k, int n, int i) {
  return mpq_class(exact_binomial(m, k) * exact_binomial(n, i)) / (mpq_class(m + n + 1) * exact_binomial(m + n, k + i));
}

// The exact least-squares reduction to degree m: the normal equations G^{mm} R = G^{mn} P on
// the unknown points (all, or the inner ones with R_0 = P_0, R_m = P_n), solved by Gaussian
// elimination in rational arithmetic.
template <int Dim>
std::vector<ExactPoint<Dim>> exact_reduction(const std::vector<Point<Dim>>& P, int m, EndPoints end_points) {
  const int n = static_cast<int>(P.size()) - 1;
  std::vector<ExactPoint<Dim>> R(static_cast<std::size_t>(m) + 1);
  const int first = end_points == EndPoints::free ? 0 : 1;
  const int last = end_points == EndPoints::free ? m : m - 1;
  if (end_points == EndPoints::interpolate) {
    for (std::size_t c = 0; c < Dim; ++c) {
      R[0][c] = P.front()[static_cast<int>(c)];
      R[static_cast<std::size_t>(m)][c] = P.back()[static_cast<int>(c)];
    }
  }
  const int size = last - first + 1;
  if (size <= 0) return R;
  // Augmented matrix [G | rhs], one rhs column per coordinate.
  std::vector<std::vector<mpq_class>> A(static_cast<std::size_t>(size),
                                        std::vector<mpq_class>(static_cast<std::size_t>(size + Dim)));
  for (int k = first; k <= last; ++k) {
    auto& row = A[static_cast<std::size_t>(k - first)];
    for (int j = first; j <= last; ++j) row[static_cast<std::size_t>(j - first)] = exact_gram(m, k, m, j);
    for (std::size_t c = 0; c < Dim; ++c) {
      mpq_class rhs = 0;
      for (int i = 0; i <= n; ++i) rhs += exact_gram(m, k, n, i) * P[static_cast<std::size_t>(i)][static_cast<int>(c)];
      if (end_points == EndPoints::interpolate)
        rhs -= exact_gram(m, k, m, 0) * R[0][c] + exact_gram(m, k, m, m) * R[static_cast<std::size_t>(m)][c];
      row[static_cast<std::size_t>(size) + c] = rhs;
    }
  }
  // The Gram matrix is symmetric positive definite: elimination without pivoting is safe.
  const std::size_t width = static_cast<std::size_t>(size + Dim);
  for (std::size_t p = 0; p < static_cast<std::size_t>(size); ++p) {
    for (std::size_t r = p + 1; r < static_cast<std::size_t>(size); ++r) {
      const mpq_class factor = A[r][p] / A[p][p];
      for (std::size_t c = p; c < width; ++c) A[r][c] -= factor * A[p][c];
    }
  }
  for (std::size_t p = static_cast<std::size_t>(size); p-- > 0;) {
    for (std::size_t c = 0; c < Dim; ++c) {
      mpq_class value = A[p][static_cast<std::size_t>(size) + c];
      for (std::size_t j = p + 1; j < static_cast<std::size_t>(size); ++j)
        value -= A[p][j] * R[j + static_cast<std::size_t>(first)][c];
      R[p + static_cast<std::size_t>(first)][c] = value / A[p][p];
    }
  }
  return R;
}

// Condition number (2-norm) of the Gram matrix of the unknowns, in doubles: the matrix is
// symmetric positive definite, so it is the ratio of its extreme eigenvalues.
double gram_condition(int m, EndPoints end_points) {
  const int first = end_points == EndPoints::free ? 0 : 1;
  const int last = end_points == EndPoints::free ? m : m - 1;
  const int size = last - first + 1;
  if (size <= 0) return 1.0;
  Eigen::MatrixXd G(size, size);
  for (int k = first; k <= last; ++k) {
    for (int j = first; j <= last; ++j) G(k - first, j - first) = exact_gram(m, k, m, j).get_d();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(G, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues()(size - 1) / eigen.eigenvalues()(0);
}

// Forward error of the reduction's linear solve: a backward-stable solve refined once with the
// residual in extended precision leaves a relative error of about u + kappa eps_ld + kappa^2 u^2
// (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., section 12.1), here with a
// small multiple of the n + 2 terms of each sum, on the scale of data and solution.
double solve_tolerance(int n, int m, EndPoints end_points, double scale) {
  const double kappa = gram_condition(m, end_points);
  const double eps_ld = static_cast<double>(std::numeric_limits<long double>::epsilon());
  return 16 * (n + 2) * (kUnit + kappa * eps_ld + kappa * kappa * kUnit * kUnit) * scale;
}

// max_s |C(s) - R(s)| found without the implementation's root finder: 256 samples refined by
// golden-section search (tests/support/refined_maximum.h). Coordinates are evaluated by scalar de Casteljau (bernstein_evaluate) in the local parameter.
template <int Dim>
double sampled_max_distance(const BezierCurve<Dim>& C, const BezierCurve<Dim>& R) {
  std::array<std::vector<double>, Dim> c_coordinates;
  std::array<std::vector<double>, Dim> r_coordinates;
  for (int c = 0; c < Dim; ++c) {
    for (const auto& p : C.control_points()) c_coordinates[static_cast<std::size_t>(c)].push_back(p[c]);
    for (const auto& p : R.control_points()) r_coordinates[static_cast<std::size_t>(c)].push_back(p[c]);
  }
  const auto distance = [&](double s) {
    double squared = 0.0;
    for (std::size_t c = 0; c < Dim; ++c) {
      const double d = bernstein_evaluate(c_coordinates[c], s) - bernstein_evaluate(r_coordinates[c], s);
      squared += d * d;
    }
    return std::sqrt(squared);
  };
  return testing::refined_max(distance, 256);
}

TEST(DegreeElevation, MatchesClosedFormOnSmallExample) {
  // Quadratic (0,0), (2,4), (4,0) elevated once: Q_1 = (1/3) P_0 + (2/3) P_1 = (4/3, 8/3), Q_2 =
  // (2/3) P_1 + (1/3) P_2 = (8/3, 8/3). 4/3 and 8/3 are rounded once: 1 ulp.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(2, 4), Vec2(4, 0)}, -1.0, 1.0);
  const BezierCurve2 cubic = elevate_degree(curve);
  ASSERT_EQ(cubic.degree(), 3);
  EXPECT_EQ(cubic.a(), -1.0);
  EXPECT_EQ(cubic.b(), 1.0);
  const std::vector<Vec2> expected{Vec2(0, 0), Vec2(4.0 / 3, 8.0 / 3), Vec2(8.0 / 3, 8.0 / 3), Vec2(4, 0)};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_LE((cubic.control_points()[i] - expected[i]).cwiseAbs().maxCoeff(),
              4 * std::numeric_limits<double>::epsilon())
        << i;
  }
  EXPECT_EQ(elevate_degree(curve, 0), curve);
}

RC_GTEST_PROP(DegreeElevation, MatchesExactMultipleElevation, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<3>();
  const int r = *rc::gen::inRange(0, 6);
  const BezierCurve3 elevated = elevate_degree(curve, r);
  RC_ASSERT(elevated.degree() == curve.degree() + r);
  RC_ASSERT(elevated.a() == curve.a() && elevated.b() == curve.b());
  // Each single step forms convex combinations with a rounded weight: <= 4u M per step.
  const double M = max_abs<3>(curve.control_points());
  RC_ASSERT(max_difference<3>(elevated.control_points(), exact_elevation<3>(curve.control_points(), r)) <=
            mpq_class(4 * r * kUnit * M));
  RC_ASSERT(elevated.control_points().front() == curve.control_points().front());
  RC_ASSERT(elevated.control_points().back() == curve.control_points().back());
}

RC_GTEST_PROP(DegreeElevation, LeavesEveryPointUnchanged, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<2>();
  const int r = *rc::gen::inRange(1, 6);
  const BezierCurve2 elevated = elevate_degree(curve, r);
  const int n = curve.degree();
  const double M = max_abs<2>(curve.control_points());
  // Elevation's 4 r u M, then de Casteljau on both curves: gamma_{2n} M and gamma_{2(n+r)} M.
  const double tolerance = (4 * r * kUnit + gamma(2 * n) + gamma(2 * (n + r))) * M;
  for (int trial = 0; trial < 4; ++trial) {
    const double t = *curve_gen::parameter(curve.a(), curve.b());
    RC_ASSERT((elevated.evaluate(t) - curve.evaluate(t)).cwiseAbs().maxCoeff() <= tolerance);
  }
}

TEST(DegreeReduction, CubicToChordWithClosedFormError) {
  // x = 3s, y = 3s(1-s): reduced to a line through the ends it is the chord y = 0, and the error
  // 3s(1-s) peaks at s = 1/2 with 3/4. Without end constraints the best line in L2 is y = 1/2
  // (the mean of y, by symmetry), with error max(|0 - 1/2|, |3/4 - 1/2|) = 1/2 at the ends.
  const BezierCurve2 cubic({Vec2(0, 0), Vec2(1, 1), Vec2(2, 1), Vec2(3, 0)}, 2.0, 4.0);
  const double eps = std::numeric_limits<double>::epsilon();
  const DegreeReduction<2> chord = reduce_degree(cubic, 1, EndPoints::interpolate);
  ASSERT_EQ(chord.curve.degree(), 1);
  EXPECT_EQ(chord.curve.a(), 2.0);
  EXPECT_EQ(chord.curve.b(), 4.0);
  EXPECT_EQ(chord.curve.control_points()[0], Vec2(0, 0));
  EXPECT_EQ(chord.curve.control_points()[1], Vec2(3, 0));
  // The maximiser is found by a root finder (to ~1e-16 in s); the error is flat there.
  EXPECT_NEAR(chord.max_error, 0.75, 4 * eps);
  const DegreeReduction<2> line = reduce_degree(cubic, 1, EndPoints::free);
  // A 2x2 solve with rounded Gram entries: a few ulps.
  EXPECT_NEAR(line.curve.control_points()[0].x(), 0.0, 8 * eps);
  EXPECT_NEAR(line.curve.control_points()[0].y(), 0.5, 8 * eps);
  EXPECT_NEAR(line.curve.control_points()[1].x(), 3.0, 8 * 3 * eps);
  EXPECT_NEAR(line.curve.control_points()[1].y(), 0.5, 8 * eps);
  EXPECT_NEAR(line.max_error, 0.5, 16 * eps);
  // y is a parabola: the cubic is a quadratic in disguise and reduces with no error.
  const DegreeReduction<2> quadratic = reduce_degree(cubic, 2);
  EXPECT_LE(quadratic.max_error, 16 * eps);
  EXPECT_LE((quadratic.curve.control_points()[1] - Vec2(1.5, 1.5)).norm(), 16 * eps);
}

RC_GTEST_PROP(DegreeReduction, OneDegreeDownMatchesLegendreClosedForm, ()) {
  // Free reduction n -> n-1 leaves C - R = Delta^n P_0 / C(2n, n) * P~_n(s) (P~_n the shifted
  // Legendre polynomial, leading coefficient C(2n, n), |P~_n| <= 1 with equality at s = 0, 1):
  // max_error = |Delta^n P_0| / C(2n, n), attained at both ends.
  const auto curve = *curve_gen::bezier_curve_on_interval<3>(1, 10);
  const int n = curve.degree();
  const auto& P = curve.control_points();
  ExactPoint<3> difference;
  for (int i = 0; i <= n; ++i) {
    const mpq_class weight = ((n - i) % 2 == 0 ? 1 : -1) * mpq_class(exact_binomial(n, i));
    for (std::size_t c = 0; c < 3; ++c) difference[c] += weight * P[static_cast<std::size_t>(i)][static_cast<int>(c)];
  }
  mpq_class squared = 0;
  for (const auto& x : difference) squared += x * x;
  const double expected = std::sqrt(squared.get_d()) / exact_binomial(2 * n, n).get_d();
  const DegreeReduction<3> reduced = reduce_degree(curve, n - 1);
  const std::vector<ExactPoint<3>> exact = exact_reduction<3>(P, n - 1, EndPoints::free);
  const double M = std::max(max_abs<3>(P), max_abs<3>(exact));
  const double point_tolerance = solve_tolerance(n, n - 1, EndPoints::free, M);
  RC_ASSERT(max_difference<3>(reduced.curve.control_points(), exact) <= mpq_class(point_tolerance));
  // The error curve moves by at most sqrt(3) point_tolerance; evaluating it costs gamma_{2n} M.
  RC_ASSERT(std::abs(reduced.max_error - expected) <= std::sqrt(3.0) * (point_tolerance + 2 * gamma(2 * n) * M));
}

RC_GTEST_PROP(DegreeReduction, MatchesExactLeastSquaresSolution, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<2>(1, 12);
  const int n = curve.degree();
  const EndPoints end_points = n >= 2 && *rc::gen::arbitrary<bool>() ? EndPoints::interpolate : EndPoints::free;
  const int m = *rc::gen::inRange(end_points == EndPoints::free ? 0 : 1, n);
  const DegreeReduction<2> reduced = reduce_degree(curve, m, end_points);
  RC_ASSERT(reduced.curve.degree() == m);
  RC_ASSERT(reduced.curve.a() == curve.a() && reduced.curve.b() == curve.b());
  const auto& P = curve.control_points();
  const auto& R = reduced.curve.control_points();
  if (end_points == EndPoints::interpolate) RC_ASSERT(R.front() == P.front() && R.back() == P.back());
  const std::vector<ExactPoint<2>> exact = exact_reduction<2>(P, m, end_points);
  const double M = std::max(max_abs<2>(P), max_abs<2>(exact));
  const double tolerance = solve_tolerance(n, m, end_points, M);
  RC_ASSERT(max_difference<2>(R, exact) <= mpq_class(tolerance));
  // Least squares does not depend on the parameter interval.
  const DegreeReduction<2> unit = reduce_degree(with_interval(curve, 0.0, 1.0), m, end_points);
  RC_ASSERT(unit.curve.control_points() == R);
  RC_ASSERT(unit.max_error == reduced.max_error);
}

RC_GTEST_PROP(DegreeReduction, ResidualIsOrthogonalToReducedSpace, ()) {
  // Normal equations, checked exactly on the computed points: int (C - R) B_k^m ds ~ 0 for every
  // free index k. A backward-stable solve leaves a residual of a small multiple of (n+2) u times
  // |G| |R| + |G^{mn}| |P|, and the rows of both Gram matrices sum to 1/(m+1).
  const auto curve = *curve_gen::bezier_curve<3>(1, 12);
  const int n = curve.degree();
  const EndPoints end_points = n >= 2 && *rc::gen::arbitrary<bool>() ? EndPoints::interpolate : EndPoints::free;
  const int m = *rc::gen::inRange(end_points == EndPoints::free ? 0 : 1, n);
  const DegreeReduction<3> reduced = reduce_degree(curve, m, end_points);
  const auto& P = curve.control_points();
  const auto& R = reduced.curve.control_points();
  const mpq_class bound(32 * (n + 2) * kUnit * (max_abs<3>(P) + max_abs<3>(R)) / (m + 1));
  const int first = end_points == EndPoints::free ? 0 : 1;
  const int last = end_points == EndPoints::free ? m : m - 1;
  for (int k = first; k <= last; ++k) {
    for (int c = 0; c < 3; ++c) {
      mpq_class residual = 0;
      for (int j = 0; j <= m; ++j) residual += exact_gram(m, k, m, j) * R[static_cast<std::size_t>(j)][c];
      for (int i = 0; i <= n; ++i) residual -= exact_gram(m, k, n, i) * P[static_cast<std::size_t>(i)][c];
      RC_ASSERT(abs(residual) <= bound);
    }
  }
}

RC_GTEST_PROP(DegreeReduction, ReducesElevatedCurveToOriginal, ()) {
  // Integer control points times the lcm of C(m+r, i), i = 0..m+r, elevated exactly (the
  // elevated points are integers below 2^53): reduction must give back the original curve.
  const int m = *curve_gen::degree(0, 9);
  const int r = *rc::gen::inRange(1, 4);
  mpz_class lcm = 1;
  for (int i = 0; i <= m + r; ++i) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), exact_binomial(m + r, i).get_mpz_t());
  const auto units =
      *rc::gen::container<std::vector<int>>(3 * static_cast<std::size_t>(m + 1), rc::gen::inRange(-1000, 1001));
  std::vector<Vec3> P(static_cast<std::size_t>(m) + 1);
  for (std::size_t i = 0; i < P.size(); ++i) {
    for (int c = 0; c < 3; ++c) P[i][c] = units[3 * i + static_cast<std::size_t>(c)] * lcm.get_d();
  }
  std::vector<Vec3> Q;
  for (const ExactPoint<3>& q : exact_elevation<3>(P, r)) {
    RC_ASSERT(q[0].get_den() == 1 && q[1].get_den() == 1 && q[2].get_den() == 1);
    Q.emplace_back(q[0].get_d(), q[1].get_d(), q[2].get_d());
  }
  const EndPoints end_points = m >= 1 && *rc::gen::arbitrary<bool>() ? EndPoints::interpolate : EndPoints::free;
  const DegreeReduction<3> reduced = reduce_degree(BezierCurve3(Q, -1.0, 2.0), m, end_points);
  const double M = max_abs<3>(P);
  const double tolerance = solve_tolerance(m + r, m, end_points, M);
  for (std::size_t i = 0; i < P.size(); ++i) {
    RC_ASSERT((reduced.curve.control_points()[i] - P[i]).cwiseAbs().maxCoeff() <= tolerance);
  }
  // The error curve is the elevated difference: sqrt(3) tolerance, plus elevating R (4 r u M) and
  // evaluating (gamma_{2(m+r)} M).
  RC_ASSERT(reduced.max_error <= std::sqrt(3.0) * (tolerance + (4 * r * kUnit + gamma(2 * (m + r))) * M));
}

RC_GTEST_PROP(DegreeReduction, MaxErrorMatchesDenseSampling, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<2>(2, 10);
  const int n = curve.degree();
  const EndPoints end_points = *rc::gen::arbitrary<bool>() ? EndPoints::interpolate : EndPoints::free;
  const int m = *rc::gen::inRange(end_points == EndPoints::free ? 0 : 1, n);
  const DegreeReduction<2> reduced = reduce_degree(curve, m, end_points);
  const double sampled = sampled_max_distance<2>(curve, reduced.curve);
  // Both sides evaluate C - R in doubles: gamma_{2n} on C, gamma_{2n} on the elevated R, 4(n-m)u
  // for elevating R, on the scale M + |R|, times sqrt(2) for the norm (~1e-13 here).
  const double scale = max_abs<2>(curve.control_points()) + max_abs<2>(reduced.curve.control_points());
  const double tolerance = 2 * std::sqrt(2.0) * (2 * gamma(2 * n) + 4 * (n - m) * kUnit) * scale;
  RC_ASSERT(sampled <= reduced.max_error + tolerance);  // never below a sampled value
  RC_ASSERT(reduced.max_error <= sampled + tolerance);  // and attained
}

TEST(DegreeReduction, SameDegreeReturnsCurveWithZeroError) {
  const BezierCurve2 curve({Vec2(1, 2), Vec2(3, -4), Vec2(5, 6)}, 1.0, 2.0);
  const DegreeReduction<2> same = reduce_degree(curve, 2, EndPoints::interpolate);
  EXPECT_EQ(same.curve, curve);
  EXPECT_EQ(same.max_error, 0.0);
}

TEST(DegreeReduction, ToPointIsTheMean) {
  // Degree 0, free: the L2-best constant is the mean int_0^1 C = (sum P_i)/(n+1) = (2, 1). With
  // u = s - 1/2, |C - (2, 1)|^2 = 1/4 + 10 u^2 + 36 u^4 peaks at the ends: sqrt(5).
  const BezierCurve2 curve({Vec2(0, 0), Vec2(2, 3), Vec2(4, 0)});
  const DegreeReduction<2> point = reduce_degree(curve, 0);
  ASSERT_EQ(point.curve.degree(), 0);
  // One 1x1 solve with a rounded Gram entry: a few ulps of the scale 4.
  EXPECT_LE((point.curve.control_points()[0] - Vec2(2, 1)).norm(), 16 * std::numeric_limits<double>::epsilon());
  EXPECT_NEAR(point.max_error, std::sqrt(5.0), 32 * std::numeric_limits<double>::epsilon());
}

TEST(DegreeReduction, RejectsBadInput) {
  const BezierCurve2 curve({Vec2(1, 2), Vec2(3, -4), Vec2(5, 6)});
  expect_invalid_input([&] { reduce_degree(curve, -1); }, "reduce_degree");
  expect_invalid_input([&] { reduce_degree(curve, 3); }, "reduce_degree");
  expect_invalid_input([&] { reduce_degree(curve, 0, EndPoints::interpolate); }, "reduce_degree");
  expect_invalid_input([&] { elevate_degree(curve, -1); }, "elevate_degree");
}

}  // namespace
}  // namespace patchwork
