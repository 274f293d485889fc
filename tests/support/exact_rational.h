#pragma once
// Exact rational references for the accuracy tests and the report's hard-case section (no
// GoogleTest here: tests/curves/exact_reference.h adds the test checks). Every double is a
// rational number, so a polynomial with double coefficients, evaluated at a double t, has an
// exact value in GMP's mpq_class; the floating-point algorithms are measured against it.
//
//   p(t)  = sum_i c_i  B_i^n(t)     Bernstein form (seed Def 56)
//   p~(t) = sum_i |c_i| B_i^n(t)    the magnitude that scales every error bound
//   p'    has the coefficients n (c_{i+1} - c_i), i = 0..n-1 (the hodograph, seed Satz 21)
//
// Basis conversions (exact, in rationals):
//
//   power -> Bernstein:  c_i = sum_{j<=i} C(i,j) / C(n,j) a_j
//   Bernstein -> power:  a_j = C(n,j) sum_{i<=j} (-1)^(j-i) C(j,i) c_i
//
// Rounding a rational to double is round-to-nearest-even (mpq_class::get_d truncates, so it is
// not used for that).

#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "curves/compensated.h"

namespace patchwork::exact {

/// u = 2^-53, exactly.
inline mpq_class unit_roundoff() {
  mpq_class u(1);
  u /= mpz_class(1) << 53;
  return u;
}

/// gamma_k = k u / (1 - k u), exactly.
inline mpq_class gamma(int k) {
  const mpq_class ku = k * unit_roundoff();
  return ku / (1 - ku);
}

/// C(n, k) as an exact integer.
inline mpz_class binomial(int n, int k) {
  mpz_class c;
  mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return c;
}

/// The doubles as exact rationals.
inline std::vector<mpq_class> rationals(std::span<const double> values) {
  std::vector<mpq_class> result;
  result.reserve(values.size());
  for (double v : values) result.emplace_back(v);
  return result;
}

/// The double nearest to q (ties to even).
inline double nearest_double(const mpq_class& q) {
  const double truncated = q.get_d();  // rounds toward zero
  if (mpq_class(truncated) == q) return truncated;
  const double away = std::nextafter(
      truncated, q > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
  const mpq_class to_truncated = abs(q - mpq_class(truncated));
  const mpq_class to_away = abs(mpq_class(away) - q);
  if (to_truncated < to_away) return truncated;
  if (to_away < to_truncated) return away;
  return (std::bit_cast<std::uint64_t>(truncated) & 1u) == 0 ? truncated : away;
}

/// Each rational rounded to the nearest double.
inline std::vector<double> nearest_doubles(std::span<const mpq_class> values) {
  std::vector<double> result;
  result.reserve(values.size());
  for (const mpq_class& v : values) result.push_back(nearest_double(v));
  return result;
}

/// sum_i c_i B_i^n(t), exactly (n = c.size() - 1). Computed over the integers: with
/// t = x/d, c_i = m_i/D (D a common denominator) it is sum_i m_i C(n,i) x^i (d-x)^(n-i) / (D d^n),
/// one fraction reduced once instead of one per operation.
inline mpq_class evaluate(std::span<const mpq_class> c, const mpq_class& t) {
  const int n = static_cast<int>(c.size()) - 1;
  mpz_class denominator = 1;
  for (const mpq_class& v : c) mpz_lcm(denominator.get_mpz_t(), denominator.get_mpz_t(), v.get_den_mpz_t());
  const mpz_class x = t.get_num();
  const mpz_class y = t.get_den() - t.get_num();
  std::vector<mpz_class> x_powers(c.size(), mpz_class(1));
  std::vector<mpz_class> y_powers(c.size(), mpz_class(1));
  for (int k = 1; k <= n; ++k) {
    x_powers[static_cast<std::size_t>(k)] = x_powers[static_cast<std::size_t>(k) - 1] * x;
    y_powers[static_cast<std::size_t>(k)] = y_powers[static_cast<std::size_t>(k) - 1] * y;
  }
  mpz_class sum = 0;
  for (int i = 0; i <= n; ++i) {
    const mpq_class& ci = c[static_cast<std::size_t>(i)];
    if (ci == 0) continue;
    const mpz_class m = ci.get_num() * (denominator / ci.get_den());
    sum += m * binomial(n, i) * x_powers[static_cast<std::size_t>(i)] * y_powers[static_cast<std::size_t>(n - i)];
  }
  mpz_class d_power;
  mpz_pow_ui(d_power.get_mpz_t(), t.get_den_mpz_t(), static_cast<unsigned long>(n));
  mpq_class result(sum, denominator * d_power);
  result.canonicalize();
  return result;
}

/// p(t) for double coefficients at a double t, exactly.
inline mpq_class evaluate(std::span<const double> c, double t) {
  const std::vector<mpq_class> q = rationals(c);
  return evaluate(q, mpq_class(t));
}

/// p~(t) = sum_i |c_i| B_i^n(t), exactly (t in [0, 1]).
inline mpq_class absolute_value_sum(std::span<const double> c, double t) {
  std::vector<mpq_class> q = rationals(c);
  for (mpq_class& v : q) v = abs(v);
  return evaluate(q, mpq_class(t));
}

/// The hodograph coefficients n (c_{i+1} - c_i) (seed Satz 21); {0} for degree 0.
inline std::vector<mpq_class> derivative_coefficients(std::span<const mpq_class> c) {
  const int n = static_cast<int>(c.size()) - 1;
  if (n == 0) return {mpq_class(0)};
  std::vector<mpq_class> d;
  d.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) d.emplace_back(n * (c[static_cast<std::size_t>(i) + 1] - c[static_cast<std::size_t>(i)]));
  return d;
}

/// Bernstein coefficients of the polynomial sum_j a_j t^j (degree n = a.size() - 1).
inline std::vector<mpq_class> power_to_bernstein(std::span<const mpq_class> a) {
  const int n = static_cast<int>(a.size()) - 1;
  std::vector<mpq_class> c(a.size(), mpq_class(0));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= i; ++j) {
      mpq_class ratio(binomial(i, j), binomial(n, j));
      ratio.canonicalize();
      c[static_cast<std::size_t>(i)] += ratio * a[static_cast<std::size_t>(j)];
    }
  }
  return c;
}

/// Power-basis coefficients a_0..a_n of the Bernstein-form polynomial c.
inline std::vector<mpq_class> bernstein_to_power(std::span<const mpq_class> c) {
  const int n = static_cast<int>(c.size()) - 1;
  std::vector<mpq_class> a(c.size(), mpq_class(0));
  for (int j = 0; j <= n; ++j) {
    mpq_class sum = 0;
    for (int i = 0; i <= j; ++i) {
      const mpq_class term = binomial(j, i) * c[static_cast<std::size_t>(i)];
      if ((j - i) % 2 == 0) {
        sum += term;
      } else {
        sum -= term;
      }
    }
    a[static_cast<std::size_t>(j)] = binomial(n, j) * sum;
  }
  return a;
}

/// Power-basis coefficients of prod_j (t - r_j), lowest degree first.
inline std::vector<mpq_class> power_from_roots(std::span<const mpq_class> roots) {
  std::vector<mpq_class> a{mpq_class(1)};
  for (const mpq_class& r : roots) {
    std::vector<mpq_class> next(a.size() + 1, mpq_class(0));
    for (std::size_t j = 0; j < a.size(); ++j) {
      next[j + 1] += a[j];
      next[j] -= r * a[j];
    }
    a = std::move(next);
  }
  return a;
}

/// Horner's rule in double: sum_j a_j t^j.
inline double horner(std::span<const double> a, double t) {
  double result = 0.0;
  for (std::size_t j = a.size(); j-- > 0;) result = result * t + a[j];
  return result;
}

/// The spacing of doubles at |x| (ulp(x)); the smallest subnormal for x = 0.
inline double ulp(double x) {
  const double magnitude = std::abs(x);
  return std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude;
}

/// error / ulp(p), rounded for printing.
inline double in_ulps(const mpq_class& error, const mpq_class& p) {
  return nearest_double(error / mpq_class(ulp(nearest_double(p))));
}

/// Exact errors of plain and compensated de Casteljau on one scalar polynomial at t in [0, 1].
struct EvaluationErrors {
  mpq_class exact;              ///< p(t)
  mpq_class magnitude;          ///< p~(t)
  mpq_class plain;              ///< |BezierCurve<1>::evaluate - p(t)|
  mpq_class compensated;        ///< |evaluate_compensated - p(t)|
  mpq_class reported;           ///< evaluate_compensated's error_bound
  mpq_class plain_bound;        ///< gamma_{3n} p~(t); gamma_{2n} p~(t) if 1 - t is exact
  mpq_class compensated_bound;  ///< u |p(t)| + 2 gamma_{3n+2}^2 p~(t)
};

/// Evaluates c on [0, 1] at t both ways and measures both against the exact value.
inline EvaluationErrors measure_errors(std::span<const double> c, double t) {
  std::vector<Point<1>> points;
  for (double v : c) points.push_back(Point<1>(v));
  const BezierCurve<1> curve(points);
  const int n = curve.degree();
  EvaluationErrors e;
  e.exact = evaluate(c, t);
  e.magnitude = absolute_value_sum(c, t);
  e.plain = abs(mpq_class(curve.evaluate(t)[0]) - e.exact);
  const CompensatedPoint<1> compensated = evaluate_compensated(curve, t);
  e.compensated = abs(mpq_class(compensated.value[0]) - e.exact);
  e.reported = mpq_class(compensated.error_bound[0]);
  // Per de Casteljau level a product and a sum round, and so does 1 - t unless it is exact.
  const bool exact_complement = mpq_class(1.0 - t) == 1 - mpq_class(t);
  e.plain_bound = gamma(exact_complement ? 2 * n : 3 * n) * e.magnitude;
  const mpq_class g = gamma(3 * n + 2);
  e.compensated_bound = unit_roundoff() * abs(e.exact) + 2 * g * g * e.magnitude;
  return e;
}

/// Bernstein coefficients (rounded to double) of prod_j (t - r_j), r_j given exactly.
inline std::vector<double> bernstein_from_roots(std::span<const mpq_class> roots) {
  return nearest_doubles(power_to_bernstein(power_from_roots(roots)));
}

/// Power-basis coefficients of the Bernstein-form c (exact conversion of the doubles, rounded).
inline std::vector<double> power_coefficients(std::span<const double> c) {
  return nearest_doubles(bernstein_to_power(rationals(c)));
}

/// Bernstein coefficients of k prod_j (t - r_j) for the k > 0 that makes them exact in double
/// where 53 bits suffice: k clears the odd part of every denominator and brings max |c_i| into
/// [1/2, 1). The roots, and so the condition numbers, are those of prod_j (t - r_j); where a
/// coefficient still needs more bits it is rounded (the doubles are the polynomial under test).
inline std::vector<double> scaled_bernstein_from_roots(std::span<const mpq_class> roots) {
  std::vector<mpq_class> c = power_to_bernstein(power_from_roots(roots));
  mpz_class odd_denominators = 1;
  for (const mpq_class& v : c) {
    mpz_class d = v.get_den();
    const auto twos = mpz_scan1(d.get_mpz_t(), 0);
    mpz_fdiv_q_2exp(d.get_mpz_t(), d.get_mpz_t(), twos);
    mpz_lcm(odd_denominators.get_mpz_t(), odd_denominators.get_mpz_t(), d.get_mpz_t());
  }
  mpq_class largest = 0;
  for (mpq_class& v : c) {
    v *= odd_denominators;
    largest = std::max(largest, mpq_class(abs(v)));
  }
  if (largest == 0) return nearest_doubles(c);
  int exponent = 0;  // largest * 2^exponent in [1/2, 1)
  while (largest >= 1) {
    largest /= 2;
    --exponent;
  }
  while (largest < mpq_class(1, 2)) {
    largest *= 2;
    ++exponent;
  }
  const mpq_class scale =
      exponent >= 0 ? mpq_class(mpz_class(1) << exponent) : mpq_class(mpz_class(1), mpz_class(1) << -exponent);
  for (mpq_class& v : c) v *= scale;
  return nearest_doubles(c);
}

}  // namespace patchwork::exact
