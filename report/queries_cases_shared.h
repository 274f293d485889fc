#pragma once
// What the queries cross-check's case files share (report/queries_cases.cpp for points and
// curves against surfaces, report/queries_pair_cases.cpp for planar curve pairs): the random
// source and exact polynomials over GMP rationals. Internal to report/.

#include <gmpxx.h>

#include <random>
#include <utility>
#include <vector>

#include "tests/queries/exact_root_count.h"

namespace patchwork::crosscheck::cases {

using Random = std::mt19937_64;

inline double uniform(Random& random, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(random);
}

using exact::Polynomial;

// The power-basis polynomial of one coordinate of Bernstein coefficients, exactly.
inline Polynomial power_of(const std::vector<double>& bernstein) {
  const std::vector<mpq_class> c = exact::rationals(bernstein);
  return exact::bernstein_to_power(c);
}

inline Polynomial product(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial c(a.size() + b.size() - 1, mpq_class(0));
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

inline Polynomial sum(Polynomial a, const Polynomial& b, int sign = 1) {
  if (a.size() < b.size()) a.resize(b.size(), mpq_class(0));
  for (std::size_t j = 0; j < b.size(); ++j) a[j] += sign * b[j];
  return exact::trimmed(std::move(a));
}

// The middle of a root interval, rounded to double.
inline double middle(const exact::RootInterval& x) { return exact::nearest_double((x.lo + x.hi) / 2); }

// The multiplicity of the root in `x` (an isolating interval of f's distinct roots): the number of
// repeated gcds f, gcd(f, f'), ... that still vanish in it.
inline int multiplicity_in(const Polynomial& f, const exact::RootInterval& x) {
  int m = 1;
  Polynomial h = exact::trimmed(f);
  while (true) {
    h = exact::trimmed(exact::gcd(h, exact::differentiated(h)));
    if (h.size() <= 1 || exact::distinct_roots(h, x.lo, x.hi) == 0) return m;
    ++m;
  }
}

// The interval [0, 1] and the width roots are narrowed to.
inline const mpq_class& zero() {
  static const mpq_class value(0);
  return value;
}
inline const mpq_class& one() {
  static const mpq_class value(1);
  return value;
}
inline mpq_class root_width() {
  mpq_class w(1);
  w /= mpz_class(1) << 60;
  return w;
}

}  // namespace patchwork::crosscheck::cases
