// bernstein_roots on polynomials with known roots. Each polynomial is built exactly from its
// roots, prod_j (t - r_j) in rationals, and converted exactly to Bernstein form; then either
// scaled by the common denominator of its coefficients (integers below 2^53: the doubles handed
// to bernstein_roots have exactly the roots r_j) or rounded to double (the tolerance then
// includes the root shift caused by that rounding).

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "tests/curves/exact_reference.h"

namespace patchwork {
namespace {

// Exact Bernstein coefficients of L prod_j (t - r_j), L > 0 the least common denominator.
// Empty if a coefficient is not exactly representable (the caller asserts it is not).
std::vector<double> exact_bernstein_from_roots(const std::vector<mpq_class>& roots) {
  std::vector<mpq_class> c = exact::power_to_bernstein(exact::power_from_roots(roots));
  mpz_class denominator = 1;
  for (const mpq_class& v : c) mpz_lcm(denominator.get_mpz_t(), denominator.get_mpz_t(), v.get_den_mpz_t());
  std::vector<double> result;
  for (mpq_class& v : c) {
    v *= denominator;
    const double d = exact::nearest_double(v);
    if (mpq_class(d) != v) return {};
    result.push_back(d);
  }
  return result;
}

// The tolerance for a simple root r of p: the refinement brackets a sign change of p evaluated
// by de Casteljau, whose sign can be wrong only where |p| <= gamma_{3n} p~, so to first order
// within gamma_{3n} p~(r) / |p'(r)| of r. (The bracket's first end signs come from subdivided
// coefficients; one of those can only be wrong where p is at the rounding level, i.e. at a root
// on a subdivision point, which the bracket then closes onto.) Twice that covers second-order
// terms, plus 4 eps for the final bracket.
double simple_root_tolerance(const std::vector<double>& c, const mpq_class& r) {
  const std::vector<mpq_class> q = exact::rationals(c);
  const int n = static_cast<int>(c.size()) - 1;
  std::vector<mpq_class> magnitudes = q;
  for (mpq_class& v : magnitudes) v = abs(v);
  const mpq_class slope = abs(exact::evaluate(exact::derivative_coefficients(q), r));
  const mpq_class bound = 2 * exact::gamma(3 * n) * exact::evaluate(magnitudes, r) / slope;
  return bound.get_d() + 4.0 * std::numeric_limits<double>::epsilon();
}

// Bernstein coefficients of prod_j (t - r_j), each rounded to the nearest double.
std::vector<double> rounded_bernstein_from_roots(const std::vector<mpq_class>& roots) {
  return exact::nearest_doubles(exact::power_to_bernstein(exact::power_from_roots(roots)));
}

// simple_root_tolerance plus the effect of rounding the coefficients: each moves by at most
// u |c_i|, so p moves by at most u p~, and the root by u p~(r) / |p'(r)| to first order; doubled.
double rounded_root_tolerance(const std::vector<double>& c, const mpq_class& r) {
  const std::vector<mpq_class> q = exact::rationals(c);
  std::vector<mpq_class> magnitudes = q;
  for (mpq_class& v : magnitudes) v = abs(v);
  const mpq_class slope = abs(exact::evaluate(exact::derivative_coefficients(q), r));
  const mpq_class shift = 2 * exact::unit_roundoff() * exact::evaluate(magnitudes, r) / slope;
  return simple_root_tolerance(c, r) + shift.get_d();
}

// The tolerance for a root r of multiplicity m: a reported point x has |p(x)| at most about the
// noise level 4 (n+1) u max|c_i| of bernstein_roots (plus as much again for rounding), and
// p(x) ~ p^(m)(r)/m! (x - r)^m, so |x - r| <= (2 noise m! / |p^(m)(r)|)^(1/m); doubled.
double multiple_root_tolerance(const std::vector<double>& c, const mpq_class& r, int m) {
  const int n = static_cast<int>(c.size()) - 1;
  double magnitude = 0.0;
  for (double v : c) magnitude = std::max(magnitude, std::abs(v));
  const double noise = 4.0 * (n + 1) * std::ldexp(1.0, -53) * magnitude;
  std::vector<mpq_class> q = exact::rationals(c);
  mpq_class factorial = 1;
  for (int j = 1; j <= m; ++j) {
    q = exact::derivative_coefficients(q);
    factorial *= j;
  }
  const double leading = mpq_class(abs(exact::evaluate(q, r)) / factorial).get_d();
  return 2.0 * std::pow(2.0 * noise / leading, 1.0 / m);
}

TEST(BernsteinRoots, SimpleRootsFromExactFactors) {
  const std::vector<std::vector<mpq_class>> cases = {
      {mpq_class(1, 2)},
      {mpq_class(1, 3)},
      {mpq_class(1, 8), mpq_class(5, 8)},
      {mpq_class(1, 10), mpq_class(1, 2), mpq_class(9, 10)},
      {mpq_class(1, 7), mpq_class(2, 7), mpq_class(3, 7), mpq_class(4, 7)},
      {mpq_class(1, 1024), mpq_class(1023, 1024)},
      {mpq_class(1, 4), mpq_class(1, 2), mpq_class(3, 4), mpq_class(5, 4), mpq_class(-1, 3)},  // two outside
  };
  for (const std::vector<mpq_class>& roots : cases) {
    const std::vector<double> c = exact_bernstein_from_roots(roots);
    ASSERT_FALSE(c.empty());
    std::vector<mpq_class> inside;
    for (const mpq_class& r : roots) {
      if (r >= 0 && r <= 1) inside.push_back(r);
    }
    std::sort(inside.begin(), inside.end());
    const std::vector<double> found = bernstein_roots(c);
    ASSERT_EQ(found.size(), inside.size()) << "first root " << roots[0].get_d();
    for (std::size_t j = 0; j < inside.size(); ++j) {
      EXPECT_LE(std::abs(found[j] - inside[j].get_d()), simple_root_tolerance(c, inside[j])) << inside[j].get_d();
      EXPECT_NEAR(found[j], inside[j].get_d(), 1e-12);  // these roots are well conditioned
    }
  }
}

TEST(BernsteinRoots, RootsAtTheEndsAreExact) {
  // p(0) = c_0 and p(1) = c_n exactly: a zero end coefficient is the root 0 or 1 itself.
  for (const std::vector<mpq_class>& roots :
       {std::vector<mpq_class>{0, 1}, std::vector<mpq_class>{0, mpq_class(1, 2), 1}, std::vector<mpq_class>{0, 0, 1},
        std::vector<mpq_class>{1, mpq_class(1, 3)}}) {
    const std::vector<double> c = exact_bernstein_from_roots(roots);
    ASSERT_FALSE(c.empty());
    const std::vector<double> found = bernstein_roots(c);
    ASSERT_FALSE(found.empty());
    if (roots[0] == 0) {
      EXPECT_EQ(found.front(), 0.0);
    }
    EXPECT_EQ(found.back(), 1.0);
  }
}

TEST(BernsteinRoots, NoRoots) {
  // All coefficients positive (p > 0 on [0, 1] by the convex hull property), roots outside
  // [0, 1], no real roots at all ((t - 1/2)^2 + 1/100), and non-zero constants.
  EXPECT_TRUE(bernstein_roots(std::vector<double>{1.0, 0.5, 2.0, 0.25}).empty());
  EXPECT_TRUE(bernstein_roots(exact_bernstein_from_roots({mpq_class(-1, 2), mpq_class(3, 2)})).empty());
  const std::vector<mpq_class> no_real_roots = exact::power_to_bernstein(
      std::vector<mpq_class>{mpq_class(1, 4) + mpq_class(1, 100), mpq_class(-1), mpq_class(1)});
  EXPECT_TRUE(bernstein_roots(exact::nearest_doubles(no_real_roots)).empty());
  EXPECT_TRUE(bernstein_roots(std::vector<double>{3.0}).empty());
  EXPECT_TRUE(bernstein_roots(std::vector<double>{-2.0, -2.0}).empty());
}

TEST(BernsteinRoots, ZeroPolynomialHasNoIsolatedRoots) {
  EXPECT_TRUE(bernstein_roots(std::vector<double>{0.0}).empty());
  EXPECT_TRUE(bernstein_roots(std::vector<double>(8, 0.0)).empty());
}

TEST(BernsteinRoots, RejectsBadInput) {
  EXPECT_THROW(bernstein_roots(std::vector<double>{}), InvalidInput);
  EXPECT_THROW(bernstein_roots(std::vector<double>{1.0, std::nan(""), 2.0}), InvalidInput);
}

TEST(BernsteinRoots, DoubleRootIsReportedOnce) {
  // (t - 1/4)^2 (t - 3/4): the double root at a subdivision point; (t - 1/3)^2 (t - 3/4): not.
  for (const mpq_class& double_root : {mpq_class(1, 4), mpq_class(1, 3)}) {
    const std::vector<double> c = exact_bernstein_from_roots({double_root, double_root, mpq_class(3, 4)});
    ASSERT_FALSE(c.empty());
    const std::vector<double> found = bernstein_roots(c);
    ASSERT_EQ(found.size(), 2u) << double_root.get_d();
    EXPECT_LE(std::abs(found[0] - double_root.get_d()), multiple_root_tolerance(c, double_root, 2));
    EXPECT_LE(std::abs(found[1] - 0.75), simple_root_tolerance(c, mpq_class(3, 4)));
  }
}

TEST(BernsteinRoots, MultipleRootsAreReportedOnceNearTheRoot) {
  // (97 t - k)^m has Bernstein coefficients (-k)^(m-i) (97-k)^i, exact integers for m <= 7; for
  // larger m they are rounded, and the rounded polynomial's roots lie within the same tolerance
  // (it is of the noise level). One root, k/97, of multiplicity m, never at a subdivision point.
  for (int m = 2; m <= 12; ++m) {
    for (int k = 1; k < 97; ++k) {
      std::vector<double> c(static_cast<std::size_t>(m) + 1);
      for (int i = 0; i <= m; ++i) c[static_cast<std::size_t>(i)] = std::pow(-k, m - i) * std::pow(97 - k, i);
      const mpq_class r(k, 97);
      const std::vector<double> found = bernstein_roots(c);
      ASSERT_EQ(found.size(), 1u) << "m=" << m << " k=" << k;
      EXPECT_LE(std::abs(found[0] - r.get_d()), multiple_root_tolerance(c, r, m)) << "m=" << m << " k=" << k;
    }
  }
}

TEST(BernsteinRoots, HighMultiplicityReturnsQuickly) {
  // (t - 1/2)^20 (coefficients (-1)^(20-i) 2^-20) and (3t - 1)^20 (coefficients (-1)^(20-i) 2^i):
  // one root each, near 1/2 and 1/3, without subdividing without end. The time limit is a
  // thousand times what these take in a sanitizer build.
  std::vector<double> half(21);
  std::vector<double> third(21);
  for (int i = 0; i <= 20; ++i) {
    const double sign = (20 - i) % 2 == 0 ? 1.0 : -1.0;
    half[static_cast<std::size_t>(i)] = sign * std::ldexp(1.0, -20);
    third[static_cast<std::size_t>(i)] = sign * std::ldexp(1.0, i);
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> at_half = bernstein_roots(half);
  const std::vector<double> at_third = bernstein_roots(third);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  ASSERT_EQ(at_half.size(), 1u);
  EXPECT_LE(std::abs(at_half[0] - 0.5), multiple_root_tolerance(half, mpq_class(1, 2), 20));
  ASSERT_EQ(at_third.size(), 1u);
  EXPECT_LE(std::abs(at_third[0] - 1.0 / 3.0), multiple_root_tolerance(third, mpq_class(1, 3), 20));
}

TEST(BernsteinRoots, RootAtASubdivisionPointWithRoundedCoefficients) {
  // The rounded coefficients put p(1/8) at the rounding level, with different signs depending on
  // how it is computed; the root must still be reported at 1/8 (it once came back as 1/4).
  const std::vector<mpq_class> roots = {mpq_class(102, 1001), mpq_class(1, 8), mpq_class(553, 1001),
                                        mpq_class(596, 1001)};
  const std::vector<double> c = rounded_bernstein_from_roots(roots);
  const std::vector<double> found = bernstein_roots(c);
  ASSERT_EQ(found.size(), roots.size());
  for (std::size_t j = 0; j < roots.size(); ++j) {
    EXPECT_LE(abs(mpq_class(found[j]) - roots[j]), rounded_root_tolerance(c, roots[j])) << roots[j].get_d();
  }
}

RC_GTEST_PROP(BernsteinRoots, RoundedPolynomialsKeepTheirRoots, ()) {
  // One root at a subdivision point k/2^e (e <= 4) and up to five more k/1001, at least 2e-3
  // apart, coefficients rounded to double.
  std::vector<mpq_class> roots;
  const int e = *rc::gen::inRange(1, 5);
  roots.emplace_back(*rc::gen::inRange(1, 1 << e), 1 << e);
  const int more = *rc::gen::inRange(0, 6);
  for (int k : *rc::gen::unique<std::vector<int>>(static_cast<std::size_t>(more), rc::gen::inRange(1, 1001))) {
    roots.emplace_back(k, 1001);
  }
  std::sort(roots.begin(), roots.end());
  for (std::size_t j = 1; j < roots.size(); ++j) RC_PRE(roots[j] - roots[j - 1] >= mpq_class(2, 1000));
  const std::vector<double> c = rounded_bernstein_from_roots(roots);
  const std::vector<double> found = bernstein_roots(c);
  RC_ASSERT(found.size() == roots.size());
  for (std::size_t j = 0; j < roots.size(); ++j) {
    RC_ASSERT(abs(mpq_class(found[j]) - roots[j]) <= rounded_root_tolerance(c, roots[j]));
  }
}

RC_GTEST_PROP(BernsteinRoots, SeparatedSimpleRootsAreFound, ()) {
  // Up to four distinct roots k/q, q in {512, 1000} (a grid with many subdivision points, and one
  // with none), at least 1e-3 apart.
  const int q = *rc::gen::element(512, 1000);
  const int count = *rc::gen::inRange(1, 5);
  std::vector<int> grid =
      *rc::gen::unique<std::vector<int>>(static_cast<std::size_t>(count), rc::gen::inRange(0, q + 1));
  std::sort(grid.begin(), grid.end());
  for (std::size_t j = 1; j < grid.size(); ++j) RC_PRE((grid[j] - grid[j - 1]) * 1000 > q);
  std::vector<mpq_class> roots;
  for (int k : grid) roots.emplace_back(k, q);
  const std::vector<double> c = exact_bernstein_from_roots(roots);
  RC_ASSERT(!c.empty());
  const std::vector<double> found = bernstein_roots(c);
  RC_ASSERT(found.size() == roots.size());
  for (std::size_t j = 0; j < roots.size(); ++j) {
    const mpq_class error = abs(mpq_class(found[j]) - roots[j]);
    RC_ASSERT(error <= simple_root_tolerance(c, roots[j]));
  }
}

}  // namespace
}  // namespace patchwork
