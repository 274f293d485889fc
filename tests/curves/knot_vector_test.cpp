#include "curves/knot_vector.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "core/errors.h"
#include "curves/bspline_basis.h"
#include "tests/curves/bspline_exact_reference.h"
#include "tests/curves/bspline_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// p = 2, n = 5: valid range [u_2, u_6] = [0, 3], breakpoint 1 (C^1) and 2 (double knot, C^0).
KnotVector example_knots() { return KnotVector(2, {0, 0, 0, 1, 2, 2, 3, 3, 3}); }

TEST(KnotVector, RangeSpansAndMultiplicitiesOfAnExample) {
  const KnotVector knots = example_knots();
  EXPECT_EQ(knots.control_point_count(), 6);
  EXPECT_EQ(knots.a(), 0.0);
  EXPECT_EQ(knots.b(), 3.0);
  EXPECT_EQ(knots.span(0.0), 2);
  EXPECT_EQ(knots.span(0.5), 2);
  EXPECT_EQ(knots.span(1.0), 3);  // a breakpoint belongs to the span starting there
  EXPECT_EQ(knots.span(1.999), 3);
  EXPECT_EQ(knots.span(2.0), 5);  // [u_4, u_5] is empty
  EXPECT_EQ(knots.span(3.0), 5);  // the right end: the last non-empty span
  EXPECT_EQ(knots.multiplicity(2.0), 2);
  EXPECT_EQ(knots.multiplicity(0.0), 3);
  EXPECT_EQ(knots.multiplicity(0.5), 0);
  EXPECT_EQ(knots.breakpoints(), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(knots.breakpoint_continuity(), (std::vector<int>{1, 0}));
  EXPECT_TRUE(knots.is_clamped());
  EXPECT_FALSE(uniform_knots(2, 5).is_clamped());
}

TEST(KnotVector, UniformConstructorsHaveTheClosedForm) {
  EXPECT_EQ(clamped_uniform_knots(2, 5).knots(), (std::vector<double>{0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1}));
  const KnotVector uniform = uniform_knots(2, 4, 0.0, 2.0);  // spans of length 1 on [0, 2]
  EXPECT_EQ(uniform.knots(), (std::vector<double>{-2, -1, 0, 1, 2, 3, 4}));
  EXPECT_EQ(uniform.a(), 0.0);
  EXPECT_EQ(uniform.b(), 2.0);
  EXPECT_EQ(periodic_knots(3, 4).control_point_count(), 7);
}

TEST(KnotVector, BadKnotsAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_input([] { KnotVector(2, {0, 0, 0, 1, 0.5, 1, 1, 1}); }, "is below knot");
  expect_invalid_input([&] { KnotVector(1, {0, 0, nan, 1, 1}); }, "not finite");
  expect_invalid_input([] { KnotVector(2, {0, 0, 1, 1, 1}); }, "need at least 6");
  expect_invalid_input([] { KnotVector(2, {0, 0, 0, 1, 1, 1, 2, 2, 2}); }, "multiplicity 3 > 2");
  expect_invalid_input([] { KnotVector(1, {0, 0, 0, 0, 1, 1}); }, "multiplicity 4 > 2");
  expect_invalid_input([] { KnotVector(1, {0, 1, 1, 2}); }, "is empty");
  expect_invalid_input([] { KnotVector(-1, {0, 1}); }, "negative");
  expect_invalid_input([] { (void)example_knots().span(3.5); }, "outside the valid range");
  expect_invalid_input([&] { (void)example_knots().span(nan); }, "not finite");
  expect_invalid_input([] { clamped_uniform_knots(3, 3); }, "need at least 4");
}

RC_GTEST_PROP(KnotVector, SpanHoldsTheParameterAndIsNonEmpty, ()) {
  const KnotVector knots = *bspline_gen::knot_vector(0, 5);
  const double u = *bspline_gen::parameter(knots);
  const int s = knots.span(u);
  RC_ASSERT(s >= knots.degree());
  RC_ASSERT(s < knots.control_point_count());
  RC_ASSERT(knots[s] < knots[s + 1]);
  RC_ASSERT(knots[s] <= u);
  RC_ASSERT(u < knots[s + 1] || (u == knots.b() && knots[s + 1] == knots.b()));
}

RC_GTEST_PROP(KnotVector, BreakpointContinuityIsDegreeMinusMultiplicity, ()) {
  const KnotVector knots = *bspline_gen::knot_vector(1, 5);
  const std::vector<double> breakpoints = knots.breakpoints();
  const std::vector<int> orders = knots.breakpoint_continuity();
  RC_ASSERT(orders.size() + 2 == breakpoints.size());
  for (std::size_t i = 0; i < orders.size(); ++i) {
    const int m = static_cast<int>(std::count(knots.knots().begin(), knots.knots().end(), breakpoints[i + 1]));
    RC_ASSERT(orders[i] == knots.degree() - m);
    RC_ASSERT(orders[i] >= 0);
  }
}

RC_GTEST_PROP(BSplineBasis, PartitionOfUnityNonNegativeAndExact, ()) {
  const KnotVector knots = *bspline_gen::knot_vector(0, 5);
  const double u = *bspline_gen::parameter(knots);
  const std::vector<double> N = basis_functions(knots, u);
  RC_ASSERT(static_cast<int>(N.size()) == knots.degree() + 1);
  const std::vector<mpq_class> U = exact_bspline::knots_of(knots);
  const int s = knots.span(u);
  double sum = 0.0;
  for (int r = 0; r <= knots.degree(); ++r) {
    RC_ASSERT(N[static_cast<std::size_t>(r)] >= 0.0);
    sum += N[static_cast<std::size_t>(r)];
    const mpq_class exact = exact_bspline::basis(U, s, s - knots.degree() + r, knots.degree(), mpq_class(u), 0);
    RC_ASSERT(std::abs(mpq_class(mpq_class(N[static_cast<std::size_t>(r)]) - exact).get_d()) <=
              gamma(4 * knots.degree() + 2));
  }
  RC_ASSERT(std::abs(sum - 1.0) <= gamma(4 * knots.degree() + 2));
}

RC_GTEST_PROP(BSplineBasis, DerivativesMatchTheExactRecursion, ()) {
  const KnotVector knots = *bspline_gen::knot_vector(1, 5);
  const double u = *bspline_gen::parameter(knots);
  const int p = knots.degree();
  const int order = *rc::gen::inRange(0, p + 2);
  const Eigen::MatrixXd ders = basis_function_derivatives(knots, u, order);
  const std::vector<mpq_class> U = exact_bspline::knots_of(knots);
  const int s = knots.span(u);
  // Knot gaps are >= 1/8, so the k-th derivative is a sum of terms up to (8p)^k in size.
  for (int k = 0; k <= order; ++k) {
    const double scale = std::pow(8.0 * p, k);
    double sum = 0.0;
    for (int r = 0; r <= p; ++r) {
      const mpq_class exact = exact_bspline::basis(U, s, s - p + r, p, mpq_class(u), k);
      RC_ASSERT(std::abs(mpq_class(mpq_class(ders(k, r)) - exact).get_d()) <= 1e-13 * scale);
      sum += ders(k, r);
    }
    // The derivatives of a partition of unity sum to 0.
    if (k > 0) RC_ASSERT(std::abs(sum) <= 1e-13 * scale * (p + 1));
  }
  RC_ASSERT(
      ders.row(0).transpose().isApprox(Eigen::Map<const Eigen::VectorXd>(basis_functions(knots, u).data(), p + 1)));
}

}  // namespace
}  // namespace patchwork
