#pragma once
// Exact counts of the real roots of a polynomial with rational coefficients, for the
// intersection tests: Sturm's theorem on the square-free part g = f / gcd(f, f').
//
//   p_0 = g,  p_1 = g',  p_{k+1} = -rem(p_{k-1}, p_k)          (until the remainder is 0)
//   #{distinct roots of f in [lo, hi]} = V(lo) - V(hi) + [g(lo) = 0]
//
// with V(x) the number of sign changes in p_0(x), p_1(x), ... (zeros skipped). Polynomials are
// power-basis coefficient vectors, lowest degree first, in GMP rationals.

#include <gmpxx.h>

#include <span>
#include <vector>

#include "tests/support/exact_rational.h"

namespace patchwork::exact {

using Polynomial = std::vector<mpq_class>;

/// Drops leading zero coefficients (the zero polynomial becomes empty).
inline Polynomial trimmed(Polynomial p) {
  while (!p.empty() && p.back() == 0) p.pop_back();
  return p;
}

/// p(x) by Horner's rule.
inline mpq_class value(const Polynomial& p, const mpq_class& x) {
  mpq_class result = 0;
  for (std::size_t j = p.size(); j-- > 0;) result = result * x + p[j];
  return result;
}

/// p'.
inline Polynomial differentiated(const Polynomial& p) {
  Polynomial d;
  for (std::size_t j = 1; j < p.size(); ++j) d.push_back(mpq_class(static_cast<long>(j)) * p[j]);
  return trimmed(d);
}

/// The quotient and remainder of p / q. \pre q is not zero.
inline std::pair<Polynomial, Polynomial> divided(Polynomial p, const Polynomial& q) {
  p = trimmed(std::move(p));
  Polynomial quotient(p.size() >= q.size() ? p.size() - q.size() + 1 : 0, mpq_class(0));
  while (p.size() >= q.size() && !p.empty()) {
    const std::size_t shift = p.size() - q.size();
    const mpq_class factor = p.back() / q.back();
    quotient[shift] = factor;
    for (std::size_t j = 0; j < q.size(); ++j) p[shift + j] -= factor * q[j];
    p = trimmed(std::move(p));
  }
  return {trimmed(quotient), p};
}

/// gcd(p, q), not normalised.
inline Polynomial gcd(Polynomial p, Polynomial q) {
  p = trimmed(std::move(p)), q = trimmed(std::move(q));
  while (!q.empty()) {
    Polynomial r = divided(p, q).second;
    p = std::move(q);
    q = std::move(r);
  }
  return p;
}

/// The square-free part f / gcd(f, f'): the same roots, each simple. \pre f is not the zero polynomial.
inline Polynomial square_free(const Polynomial& f) {
  const Polynomial p = trimmed(f);
  return divided(p, gcd(p, differentiated(p))).first;
}

/// The Sturm sequence p_0 = g, p_1 = g', p_{k+1} = -rem(p_{k-1}, p_k) of a square-free g.
inline std::vector<Polynomial> sturm_sequence(const Polynomial& g) {
  std::vector<Polynomial> sequence{g, differentiated(g)};
  while (!sequence.back().empty()) {
    Polynomial r = divided(sequence[sequence.size() - 2], sequence.back()).second;
    for (mpq_class& c : r) c = -c;
    sequence.push_back(std::move(r));
  }
  return sequence;
}

/// V(x): the sign changes of the sequence at x, zeros skipped.
inline int sign_changes(std::span<const Polynomial> sequence, const mpq_class& x) {
  int count = 0, last = 0;
  for (const Polynomial& q : sequence) {
    const int sign = sgn(value(q, x));
    if (sign != 0) {
      if (last != 0 && sign != last) ++count;
      last = sign;
    }
  }
  return count;
}

/// The number of distinct roots in [lo, hi] of the square-free g whose Sturm sequence is given.
inline int distinct_roots(std::span<const Polynomial> sequence, const mpq_class& lo, const mpq_class& hi) {
  return sign_changes(sequence, lo) - sign_changes(sequence, hi) + (value(sequence.front(), lo) == 0 ? 1 : 0);
}

/// The number of distinct real roots of f in [lo, hi]. \pre f is not the zero polynomial.
inline int distinct_roots(const Polynomial& f, const mpq_class& lo, const mpq_class& hi) {
  const std::vector<Polynomial> sequence = sturm_sequence(square_free(f));
  return distinct_roots(sequence, lo, hi);
}

/// An interval [lo, hi] holding exactly one distinct root (lo = hi: the root itself).
struct RootInterval {
  mpq_class lo;
  mpq_class hi;
};

/// The distinct real roots of f in [a, b], each in an interval of width at most `width`, in
/// increasing order: Sturm counts separate them, then bisection on the sign of the square-free
/// part (whose roots are simple, so it changes sign at each) narrows them.
/// \pre f is not the zero polynomial, a <= b, width > 0.
inline std::vector<RootInterval> isolated_roots(const Polynomial& f, const mpq_class& a, const mpq_class& b,
                                                const mpq_class& width) {
  const Polynomial g = square_free(f);
  const std::vector<Polynomial> sequence = sturm_sequence(g);
  std::vector<RootInterval> roots;
  if (value(g, a) == 0) roots.push_back({a, a});
  // Roots in (lo, hi] number V(lo) - V(hi); intervals are examined left to right.
  std::vector<RootInterval> stack{{a, b}};
  while (!stack.empty()) {
    RootInterval x = stack.back();
    stack.pop_back();
    const int count = sign_changes(sequence, x.lo) - sign_changes(sequence, x.hi);
    if (count == 0) continue;
    if (count > 1) {
      const mpq_class mid = (x.lo + x.hi) / 2;
      stack.push_back({mid, x.hi});
      stack.push_back({x.lo, mid});
      continue;
    }
    if (value(g, x.hi) == 0) {
      roots.push_back({x.hi, x.hi});
      continue;
    }
    // g changes sign at its simple root only; if lo is a root itself (the end a, or a split point),
    // the sign just right of it is the opposite of g(hi)'s.
    const int sign_lo = value(g, x.lo) != 0 ? sgn(value(g, x.lo)) : -sgn(value(g, x.hi));
    while (x.hi - x.lo > width) {
      const mpq_class mid = (x.lo + x.hi) / 2;
      const int sign = sgn(value(g, mid));
      if (sign == 0) {
        x.lo = x.hi = mid;
      } else if (sign == sign_lo) {
        x.lo = mid;
      } else {
        x.hi = mid;
      }
    }
    roots.push_back(x);
  }
  return roots;
}

/// The multiplicity of the root x of f (0 if f(x) != 0). \pre f is not the zero polynomial.
inline int multiplicity(Polynomial f, const mpq_class& x) {
  int m = 0;
  f = trimmed(std::move(f));
  while (!f.empty() && value(f, x) == 0) ++m, f = differentiated(f);
  return m;
}

}  // namespace patchwork::exact
