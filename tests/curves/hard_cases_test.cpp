// Hard cases for polynomial evaluation in Bernstein form: high-order roots, large offsets,
// clustered control points, and the power basis as the comparison that shows why the
// Bernstein form is used. Every error is measured against exact rational arithmetic.
//
// The polynomials are given exactly (mpq), converted exactly to Bernstein form, and rounded to
// double: those doubles ARE the polynomial under test, the reference evaluates them exactly.

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "curves/compensated.h"
#include "tests/curves/exact_reference.h"

namespace patchwork {
namespace {

const std::vector<double> kIssueParameters = {0.0, 1e-12, 0.5, 1.0 - 1e-12, 1.0};

// (t - 1/2)^n. Its Bernstein coefficients are (-1)^(n-i) 2^-n, exact in double.
std::vector<double> power_of_half(int n) {
  return exact::bernstein_from_roots(std::vector<mpq_class>(static_cast<std::size_t>(n), mpq_class(1, 2)));
}

// (t - 3/4)^7 (t - 1), the classic ill-conditioned example of the compensated-evaluation papers.
std::vector<double> seventh_power_times_linear() {
  std::vector<mpq_class> roots(7, mpq_class(3, 4));
  roots.emplace_back(1);
  return exact::bernstein_from_roots(roots);
}

std::vector<double> random_around(std::mt19937_64& random, int n, double center, double spread) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> c(static_cast<std::size_t>(n) + 1);
  for (double& v : c) v = center + spread * uniform(random);
  return c;
}

TEST(HardCases, PowerOfLinearFactorNearItsRoot) {
  const std::vector<double> near_root = {0.5 + 1e-12, 0.5 - 1e-9, 0.5 + 1e-6, 0.501, 0.49, 0.55, 0.45, 0.3, 0.7};
  for (int n = 1; n <= 40; ++n) {
    const std::vector<double> c = power_of_half(n);
    for (const std::vector<double>* ts : {&kIssueParameters, &near_root}) {
      for (double t : *ts) {
        EXPECT_TRUE(exact::within_bounds(exact::measure_errors(c, t))) << "(t-0.5)^" << n << " at t=" << t;
      }
    }
  }
}

TEST(HardCases, SeventhPowerTimesLinearNearBothRoots) {
  const std::vector<double> c = seventh_power_times_linear();
  std::vector<double> ts = kIssueParameters;
  for (double d : {1e-12, 1e-8, 1e-5, 1e-3, 1e-2, 5e-2}) {
    ts.push_back(0.75 - d);
    ts.push_back(0.75 + d);
    ts.push_back(1.0 - d);
  }
  for (double t : ts) EXPECT_TRUE(exact::within_bounds(exact::measure_errors(c, t))) << "t=" << t;
}

TEST(HardCases, LargeOffsetWithSmallVariations) {
  // b_i = 1e8 + v_i, |v_i| <= 1: p~ = |p| ~ 1e8, so the compensated result must be faithful
  // (error below one ulp of p: u|p| < ulp(p) and 2 gamma^2 p~ is 1e-11 ulp).
  std::mt19937_64 random(23);
  for (int n = 1; n <= 40; ++n) {
    const std::vector<double> c = random_around(random, n, 1e8, 1.0);
    for (double t : {0.0, 1e-12, 0.25, 0.5, 0.8, 1.0 - 1e-12, 1.0}) {
      const exact::EvaluationErrors e = exact::measure_errors(c, t);
      EXPECT_TRUE(exact::within_bounds(e)) << "n=" << n << " t=" << t;
      EXPECT_LT(e.compensated, mpq_class(exact::ulp(exact::nearest_double(e.exact)))) << "n=" << n << " t=" << t;
    }
  }
}

TEST(HardCases, ClusteredControlPoints) {
  // All control points within 1e-10 of each other, around 0.3 (p~ = |p|: compensated faithful)
  // and around 0 (mixed signs, |p| can be far below p~: only the bounds are asserted).
  std::mt19937_64 random(29);
  for (int n = 1; n <= 40; ++n) {
    const std::vector<double> around_value = random_around(random, n, 0.3, 0.5e-10);
    const std::vector<double> around_zero = random_around(random, n, 0.0, 0.5e-10);
    for (double t : {0.0, 1e-12, 0.125, 0.5, 0.7, 1.0 - 1e-12, 1.0}) {
      const exact::EvaluationErrors e = exact::measure_errors(around_value, t);
      EXPECT_TRUE(exact::within_bounds(e)) << "n=" << n << " t=" << t;
      EXPECT_LT(e.compensated, mpq_class(exact::ulp(exact::nearest_double(e.exact)))) << "n=" << n << " t=" << t;
      EXPECT_TRUE(exact::within_bounds(exact::measure_errors(around_zero, t))) << "n=" << n << " t=" << t;
    }
  }
}

TEST(HardCases, PowerBasisIsFarWorseAtHighDegree) {
  // The same polynomial (t - 1/2)^n in the power basis: a_j = C(n,j) (-1/2)^(n-j), exact in
  // double for n <= 40, so only Horner's rounding differs. Horner's error is of order
  // u sum_j |a_j| t^j = u (t + 1/2)^n ~ u near the root, while de Casteljau's a-priori bound
  // is at most gamma_{3n} p~ = gamma_{3n} 2^-n.
  const std::vector<double> near_root = {0.5 + 1e-12, 0.5 + 1e-6, 0.501, 0.49, 0.51, 0.55, 0.45};
  for (int n : {20, 25, 30, 40}) {
    const std::vector<double> c = power_of_half(n);
    const std::vector<double> a = exact::power_coefficients(c);
    const std::vector<mpq_class> a_exact = exact::bernstein_to_power(exact::rationals(c));
    for (std::size_t j = 0; j < a.size(); ++j) ASSERT_EQ(mpq_class(a[j]), a_exact[j]) << "n=" << n << " j=" << j;
    mpq_class power_error = 0;
    mpq_class plain_error = 0;
    mpq_class plain_bound = 0;
    for (double t : near_root) {
      const exact::EvaluationErrors e = exact::measure_errors(c, t);
      power_error = std::max(power_error, mpq_class(abs(mpq_class(exact::horner(a, t)) - e.exact)));
      plain_error = std::max(plain_error, e.plain);
      plain_bound = std::max(plain_bound, e.plain_bound);
    }
    // Far worse than what de Casteljau actually does (observed ratios exceed 1e20) ...
    EXPECT_GT(power_error, 1e3 * plain_error) << "n=" << n;
    // ... and, from degree 25 on, than even de Casteljau's worst case: the bound ratio is
    // about 2^n (t + 1/2)^n / (3n) ~ 4e5 at n = 25, and Horner's error is a fair fraction of its
    // own bound.
    if (n >= 25) {
      EXPECT_GT(power_error, 1e3 * plain_bound) << "n=" << n;
    }
  }
}

TEST(HardCases, PrintErrorTable) {
  // Observed errors in ulps of |p(t)|, for quoting in the docs; cond = p~/|p|.
  struct Row {
    std::string name;
    std::vector<double> c;
    double t;
  };
  std::mt19937_64 random(31);
  std::vector<Row> rows;
  for (int n : {5, 10, 20, 40}) rows.push_back({"(t-0.5)^" + std::to_string(n), power_of_half(n), 0.55});
  for (double t : {0.76, 0.7501, 0.750001, 1.0 - 1e-12})
    rows.push_back({"(t-0.75)^7(t-1)", seventh_power_times_linear(), t});
  rows.push_back({"1e8+v, n=40", random_around(random, 40, 1e8, 1.0), 0.3});
  rows.push_back({"0.3+1e-10v, n=40", random_around(random, 40, 0.3, 0.5e-10), 0.3});
  std::printf("%-18s %-14s %-9s %-9s %-9s %-9s %-9s\n", "polynomial", "t", "|p|", "cond", "plain", "compens.", "power");
  for (const Row& row : rows) {
    const exact::EvaluationErrors e = exact::measure_errors(row.c, row.t);
    ASSERT_NE(e.exact, 0) << row.name;
    const mpq_class power = abs(mpq_class(exact::horner(exact::power_coefficients(row.c), row.t)) - e.exact);
    std::printf("%-18s %-14.12g %-9.2e %-9.2e %-9.2e %-9.2e %-9.2e\n", row.name.c_str(), row.t,
                std::abs(e.exact.get_d()), mpq_class(e.magnitude / abs(e.exact)).get_d(),
                exact::in_ulps(e.plain, e.exact), exact::in_ulps(e.compensated, e.exact),
                exact::in_ulps(power, e.exact));
    EXPECT_TRUE(exact::within_bounds(e)) << row.name << " t=" << row.t;
  }
}

}  // namespace
}  // namespace patchwork
