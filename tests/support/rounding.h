#pragma once
// Roundoff constants and exact-arithmetic helpers that the curve tests share (one definition, so
// that the tests also build as one unity translation unit per test program).

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/types.h"

namespace patchwork::testing {

/// Unit roundoff u of double.
inline constexpr double kUnit = 0x1p-53;
/// Machine epsilon of double (2u).
inline constexpr double eps = std::numeric_limits<double>::epsilon();
inline constexpr double pi = std::numbers::pi;

/// gamma_k = k u / (1 - k u), Higham's bound on k roundings.
inline double gamma(int k) { return k * kUnit / (1.0 - k * kUnit); }

/// A point with exact rational coordinates.
template <int Dim>
using ExactPoint = std::array<mpq_class, Dim>;

/// C(n, k) exactly; 0 outside 0 <= k <= n.
inline mpz_class exact_binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  mpz_class c;
  mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return c;
}

/// n (n - 1) ... (n - k + 1) in doubles, computed apart from the library's falling_factorial.
inline double reference_falling_factorial(int n, int k) {
  double result = 1.0;
  for (int j = 0; j < k; ++j) result *= n - j;
  return result;
}

/// Largest absolute coordinate of a point list.
template <int Dim>
double max_abs(const std::vector<Point<Dim>>& P) {
  double m = 0.0;
  for (const auto& p : P) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

/// Largest absolute coordinate of an exact point list (rounded to double).
template <int Dim>
double max_abs(const std::vector<ExactPoint<Dim>>& P) {
  double m = 0.0;
  for (const auto& p : P) {
    for (const auto& x : p) m = std::max(m, std::abs(x.get_d()));
  }
  return m;
}

/// Largest coordinate difference between computed and exact control points, exactly.
template <int Dim>
mpq_class max_difference(const std::vector<Point<Dim>>& Q, const std::vector<ExactPoint<Dim>>& exact) {
  mpq_class worst = 0;
  for (std::size_t i = 0; i < Q.size(); ++i) {
    for (std::size_t c = 0; c < Dim; ++c) {
      const mpq_class d = abs(mpq_class(Q[i][static_cast<int>(c)]) - exact[i][c]);
      if (d > worst) worst = d;
    }
  }
  return worst;
}

/// Largest norm of a point list.
template <int Dim>
double max_norm(const std::vector<Point<Dim>>& points) {
  double result = 0.0;
  for (const auto& p : points) result = std::max(result, p.norm());
  return result;
}

/// |p - q| for a double point and an exact one (each coordinate difference exact, then rounded).
template <int Dim>
double distance(const Point<Dim>& p, const ExactPoint<Dim>& q) {
  double sum = 0.0;
  for (int d = 0; d < Dim; ++d) {
    const double difference = mpq_class(mpq_class(p[d]) - q[static_cast<std::size_t>(d)]).get_d();
    sum += difference * difference;
  }
  return std::sqrt(sum);
}

/// A RapidCheck-drawn number in [0, 1] on a grid of 10^-6 (inside a property only).
inline double random_unit() { return *rc::gen::inRange(0, 1000001) / 1e6; }

/// Runs f and expects an InvalidInput whose message contains needle.
template <class F>
void expect_invalid_input(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected InvalidInput naming '" << needle << "'";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace patchwork::testing
