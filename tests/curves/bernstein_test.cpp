#include "curves/bernstein.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "core/errors.h"

namespace patchwork {
namespace {

// Exact B_i^n(t) for a double t, in rational arithmetic.
mpq_class exact_bernstein(int n, int i, double t) {
  const mpq_class x(t);
  mpq_class result = 1;
  mpz_class c;
  mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(i));
  result = c;
  for (int k = 0; k < i; ++k) result *= x;
  for (int k = 0; k < n - i; ++k) result *= (1 - x);
  return result;
}

TEST(Bernstein, MatchesExactRationalValues) {
  for (int n : {0, 1, 2, 3, 7, 20, 40}) {
    for (double t : {0.0, 1e-12, 0.25, 0.5, 1.0 / 3.0, 1.0 - 1e-12, 1.0}) {
      const std::vector<double> all = bernstein_all(n, t);
      for (int i = 0; i <= n; ++i) {
        const double exact = exact_bernstein(n, i, t).get_d();
        // Satz 20's recursion: each value is a sum of non-negative terms, error <= gamma_{2n}.
        EXPECT_NEAR(all[static_cast<std::size_t>(i)], exact, 4.0 * n * 1.2e-16 * exact + 1e-300)
            << "n=" << n << " i=" << i << " t=" << t;
        EXPECT_EQ(bernstein(n, i, t), all[static_cast<std::size_t>(i)]);
      }
    }
  }
}

TEST(Bernstein, OutsideIndexRangeIsZero) {
  EXPECT_EQ(bernstein(3, -1, 0.5), 0.0);
  EXPECT_EQ(bernstein(3, 4, 0.5), 0.0);
}

TEST(Bernstein, HighDegreeStaysFinite) {
  // C(200, 100) ~ 9e58 would lose precision as a factorial quotient; the recursion does not need it.
  const std::vector<double> all = bernstein_all(200, 0.5);
  double sum = 0.0;
  for (double b : all) {
    EXPECT_TRUE(std::isfinite(b));
    sum += b;
  }
  EXPECT_NEAR(sum, 1.0, 1e-13);
  EXPECT_NEAR(all[100], exact_bernstein(200, 100, 0.5).get_d(), 1e-15);
}

TEST(Bernstein, RejectsBadInput) {
  EXPECT_THROW(bernstein(-1, 0, 0.5), InvalidInput);
  EXPECT_THROW(bernstein(3, 1, std::nan("")), InvalidInput);
  EXPECT_THROW(bernstein_all_derivatives(3, 0.5, -1), InvalidInput);
}

RC_GTEST_PROP(Bernstein, PartitionOfUnityAndNonNegative, ()) {
  const int n = *rc::gen::inRange(0, 60);
  const double t = *rc::gen::map(rc::gen::inRange(0, 1000001), [](int k) { return k / 1e6; });
  const std::vector<double> all = bernstein_all(n, t);
  double sum = 0.0;
  for (double b : all) {
    RC_ASSERT(b >= 0.0);
    sum += b;
  }
  RC_ASSERT(std::abs(sum - 1.0) <= 2.0 * (n + 1) * 1.2e-16);
}

}  // namespace
}  // namespace patchwork
