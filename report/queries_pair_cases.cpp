// The queries cross-check's planar curve pairs and their exact truths (report/queries_cases.h):
// pairs built from dyadic points so that every contact is exact, and their intersections from
// the resultant in GMP rationals.

#include "report/queries_cases.h"

#include <gmpxx.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

#include "core/errors.h"
#include "report/queries_cases_shared.h"
#include "tests/queries/exact_root_count.h"

namespace patchwork::crosscheck {
using namespace cases;  // the shared random source and exact polynomials

// ---------------------------------------------------------------------------------------------
// Planar curves

namespace {

// A polynomial curve on [0, 1] as a rational one with every weight 1.
RationalBezierCurve2 polynomial(std::vector<Vec2> P) {
  const std::size_t n = P.size();
  return RationalBezierCurve2(std::move(P), std::vector<double>(n, 1.0));
}

// The curve with (x, y) -> (y, -x) applied k times, then moved by `offset` (exact on dyadics).
RationalBezierCurve2 turned(const RationalBezierCurve2& curve, int k, const Vec2& offset) {
  std::vector<Vec2> P;
  std::vector<double> w;
  for (int i = 0; i <= curve.degree(); ++i) {
    Vec2 p = curve.control_point(i);
    for (int j = 0; j < k; ++j) p = Vec2(p.y(), -p.x());
    P.push_back(p + offset);
    w.push_back(curve.weight(i));
  }
  return RationalBezierCurve2(P, w);
}

// The curve run backwards.
RationalBezierCurve2 reversed(const RationalBezierCurve2& curve) {
  std::vector<Vec2> P;
  std::vector<double> w;
  for (int i = curve.degree(); i >= 0; --i) P.push_back(curve.control_point(i)), w.push_back(curve.weight(i));
  return RationalBezierCurve2(P, w);
}

// The piece of a polynomial curve over [t0, t1] (reparametrised to [0, 1]): control point i is the
// blossom at (t0 x (n - i), t1 x i) (de Casteljau with t1 in i of the n steps), in rationals, so
// dyadic ends and points give the exact piece (checked: every point must round to itself).
RationalBezierCurve2 piece(const RationalBezierCurve2& curve, double t0, double t1) {
  const int n = curve.degree();
  std::vector<Vec2> P;
  for (int i = 0; i <= n; ++i) {
    std::vector<std::array<mpq_class, 2>> level;
    for (int k = 0; k <= n; ++k)
      level.push_back({mpq_class(curve.control_point(k).x()), mpq_class(curve.control_point(k).y())});
    for (int step = 0; step < n; ++step) {
      const mpq_class t(step < i ? t1 : t0);
      for (std::size_t k = 0; k + 1 < level.size(); ++k) {
        for (int c = 0; c < 2; ++c) level[k][c] = (1 - t) * level[k][c] + t * level[k + 1][c];
      }
      level.pop_back();
    }
    const Vec2 p(level[0][0].get_d(), level[0][1].get_d());
    if (mpq_class(p.x()) != level[0][0] || mpq_class(p.y()) != level[0][1]) {
      throw NumericalError("crosscheck piece: a control point is not a double");
    }
    P.push_back(p);
  }
  return polynomial(P);
}

Vec2 random_dyadic2(Random& random) { return Vec2(dyadic(uniform(random, 0, 1), 6), dyadic(uniform(random, 0, 1), 6)); }

}  // namespace

std::vector<PairFamily> curve_pair_families(int count, std::uint64_t seed) {
  Random random(seed);
  std::vector<PairFamily> families{{"cubic pairs, random", {}},      {"rational cubic pairs, random", {}},
                                   {"tangent (multiplicity 2)", {}}, {"inflection contact (multiplicity 3)", {}},
                                   {"near-parallel crossings", {}},  {"overlapping", {}},
                                   {"meeting at end points", {}}};
  for (int k = 0; k < count; ++k) {
    std::vector<Vec2> A, B;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random)), B.push_back(random_dyadic2(random));
    families[0].pairs.push_back({polynomial(A), polynomial(B), false, {}});
    std::vector<double> wa, wb;
    for (int i = 0; i < 4; ++i) {
      wa.push_back(0.5 + 0.25 * static_cast<double>(random() % 7));  // 1/2 .. 2
      wb.push_back(0.5 + 0.25 * static_cast<double>(random() % 7));
    }
    families[1].pairs.push_back({RationalBezierCurve2(A, wa), RationalBezierCurve2(B, wb), true, {}});
  }
  // x = 3t and y = (2t - 1)^2 (t + 1): Bernstein y (1, 0, -1, 2), touching y = 0 at t = 1/2.
  const RationalBezierCurve2 touching = polynomial({Vec2(0, 1), Vec2(1, 0), Vec2(2, -1), Vec2(3, 2)});
  // x = 3t and y = (2t - 1)^3 (Bernstein -1, 1, -1, 1): the inflection tangent is y = 0.
  const RationalBezierCurve2 inflection = polynomial({Vec2(0, -1), Vec2(1, 1), Vec2(2, -1), Vec2(3, 1)});
  const RationalBezierCurve2 parabola({Vec2(0, 1), Vec2(0.5, -1), Vec2(1, 1)}, {1.0, 1.0, 1.0});
  const RationalBezierCurve2 axis({Vec2(-1, 0), Vec2(4, 0)}, {1.0, 1.0});
  // The rotations and translations below keep every point dyadic and every contact exact.
  for (int k = 0; k < 4; ++k) {
    const Vec2 offset(0.25 * k, -0.125 * k);
    families[2].pairs.push_back({turned(touching, k, offset), turned(axis, k, offset), false, {}});
    families[2].pairs.push_back({turned(parabola, k, offset), turned(axis, k, offset), false, {}});
    // The curve and its mirror image in y = 0: they touch at (3/2, 0) only.
    const RationalBezierCurve2 mirror = polynomial({Vec2(0, -1), Vec2(1, 0), Vec2(2, 1), Vec2(3, -2)});
    families[2].pairs.push_back({turned(touching, k, offset), turned(mirror, k, offset), false, {}});
    families[3].pairs.push_back({turned(inflection, k, offset), turned(axis, k, offset), false, {}});
    // y = (2t - 1)^3 against y = c (2s - 1)^3, same x: A - B = (1 - c)(2t - 1)^3.
    const double scale = std::array<double, 4>{-1.0, 0.5, 2.0, -0.5}[static_cast<std::size_t>(k)];  // never 1
    const RationalBezierCurve2 flatter = polynomial({Vec2(0, -scale), Vec2(1, scale), Vec2(2, -scale), Vec2(3, scale)});
    families[3].pairs.push_back({turned(inflection, k, offset), turned(flatter, k, offset), false, {}});
    // Lines at an angle of about 2^-(10 + 8k), crossing at t = s = 2/3 (as in the tests):
    // t e = e/4 + s (e - e/8 - e/4).
    const double e = std::ldexp(1.0, -(10 + 8 * k));
    families[4].pairs.push_back(
        {polynomial({Vec2(0, 0), Vec2(1, e)}), polynomial({Vec2(0, e / 4), Vec2(1, e - e / 8)}), false, {}});
    // A cubic and the same cubic lifted by e (-3/2, -1/2, 1/2, 3/2), that is e (3t - 3/2): they cross at
    // t = s = 1/2 at an angle of about 3e.
    const RationalBezierCurve2 lifted =
        polynomial({Vec2(0, 1 - 1.5 * e), Vec2(1, 0 - 0.5 * e), Vec2(2, -1 + 0.5 * e), Vec2(3, 2 + 1.5 * e)});
    families[4].pairs.push_back({turned(touching, k, offset), turned(lifted, k, offset), false, {}});
  }
  // Overlaps: a cubic against its middle half, reversed or not, and two pieces sharing [3/8, 5/8].
  for (int k = 0; k < count / 10 + 4; ++k) {
    // x increasing along the control points: x(t) is monotone, so the curve is a graph over x
    // and its pieces meet only where they overlap (a loop would add crossings the truth, which
    // only knows the overlap, leaves out).
    std::vector<Vec2> A;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random));
    std::sort(A.begin(), A.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); });
    for (int i = 1; i < 4; ++i) A[i].x() = std::max(A[i].x(), A[i - 1].x() + 1.0 / 64);
    const RationalBezierCurve2 curve = polynomial(A);
    if (k % 2 == 0) {
      const RationalBezierCurve2 middle_half = piece(curve, 0.25, 0.75);
      families[5].pairs.push_back({curve, k % 4 == 0 ? middle_half : reversed(middle_half), false, Vec2(0.25, 0.75)});
    } else {
      // first = curve on [0, 5/8], second = curve on [3/8, 1]: the overlap is first's [3/5, 1].
      families[5].pairs.push_back({piece(curve, 0, 0.625), piece(curve, 0.375, 1), false, Vec2(0.6, 1.0)});
    }
  }
  // End points: end to end at an angle, and an end on the other's inside (at t = 1/2).
  for (int k = 0; k < count / 10 + 4; ++k) {
    std::vector<Vec2> A, B;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random)), B.push_back(random_dyadic2(random));
    const RationalBezierCurve2 first = polynomial(A);
    B[0] = k % 2 == 0 ? A[3] : first.evaluate(0.5);
    families[6].pairs.push_back({first, polynomial(B), false, {}});
  }
  return families;
}

namespace {

// The homogeneous coordinates (X, Y, w) of a planar rational curve, power basis, exactly.
std::array<Polynomial, 3> homogeneous_power(const RationalBezierCurve2& curve) {
  std::array<std::vector<double>, 3> c;
  for (int i = 0; i <= curve.degree(); ++i) {
    const auto& h = curve.homogeneous().control_points()[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)].push_back(h[k]);
  }
  return {exact::trimmed(power_of(c[0])), exact::trimmed(power_of(c[1])), exact::trimmed(power_of(c[2]))};
}

// det M by Gaussian elimination in rationals (M square; destroyed).
mpq_class determinant(std::vector<std::vector<mpq_class>> M) {
  const std::size_t n = M.size();
  mpq_class det = 1;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    while (pivot < n && M[pivot][col] == 0) ++pivot;
    if (pivot == n) return 0;
    if (pivot != col) std::swap(M[pivot], M[col]), det = -det;
    det *= M[col][col];
    for (std::size_t row = col + 1; row < n; ++row) {
      if (M[row][col] == 0) continue;
      const mpq_class factor = M[row][col] / M[col][col];
      for (std::size_t k = col; k < n; ++k) M[row][k] -= factor * M[col][k];
    }
  }
  return det;
}

// Res_t(P, Q) of two polynomials in t of formal degrees p, q (Sylvester's matrix).
mpq_class resultant(const Polynomial& P, const Polynomial& Q, std::size_t p, std::size_t q) {
  const std::size_t n = p + q;
  std::vector<std::vector<mpq_class>> M(n, std::vector<mpq_class>(n, mpq_class(0)));
  const auto coefficient = [](const Polynomial& f, std::size_t j) { return j < f.size() ? f[j] : mpq_class(0); };
  for (std::size_t row = 0; row < q; ++row) {
    for (std::size_t j = 0; j <= p; ++j) M[row][row + j] = coefficient(P, p - j);
  }
  for (std::size_t row = 0; row < p; ++row) {
    for (std::size_t j = 0; j <= q; ++j) M[q + row][row + j] = coefficient(Q, q - j);
  }
  return determinant(std::move(M));
}

// The two equations of A(t) = B(s) at a fixed s, as polynomials in t:
// X_A(t) w_B(s) - X_B(s) w_A(t) and Y_A(t) w_B(s) - Y_B(s) w_A(t).
std::pair<Polynomial, Polynomial> equations_at(const std::array<Polynomial, 3>& A, const std::array<Polynomial, 3>& B,
                                               const mpq_class& s) {
  const mpq_class wB = exact::value(B[2], s);
  const auto scaled = [](const Polynomial& f, const mpq_class& c) {
    Polynomial g = f;
    for (mpq_class& x : g) x *= c;
    return g;
  };
  return {sum(scaled(A[0], wB), scaled(A[2], exact::value(B[0], s)), -1),
          sum(scaled(A[1], wB), scaled(A[2], exact::value(B[1], s)), -1)};
}

// The resultant in s: degree at most 2 n_A n_B, so interpolated exactly from that many + 1 values
// (Newton's divided differences at s = 0, 1, 2, ...).
Polynomial resultant_in_s(const CurvePair& pair) {
  const auto A = homogeneous_power(pair.first), B = homogeneous_power(pair.second);
  // Formal degrees in t: the largest over the sample points (the same for all but finitely many s).
  const std::size_t points = static_cast<std::size_t>(2 * pair.first.degree() * pair.second.degree() + 1);
  std::vector<mpq_class> xs, ys;
  std::size_t p = 0, q = 0;
  std::vector<std::pair<Polynomial, Polynomial>> equations;
  for (std::size_t k = 0; k < points; ++k) {
    xs.emplace_back(static_cast<long>(k));
    equations.push_back(equations_at(A, B, xs.back()));
    p = std::max(p, equations.back().first.size());
    q = std::max(q, equations.back().second.size());
  }
  if (p <= 1 || q <= 1) return {};  // a constant equation: degenerate, not among the cases
  for (const auto& [P, Q] : equations) ys.push_back(resultant(P, Q, p - 1, q - 1));
  // Divided differences, then the Newton form expanded.
  std::vector<mpq_class> c = ys;
  for (std::size_t j = 1; j < points; ++j) {
    for (std::size_t i = points - 1; i >= j; --i) c[i] = (c[i] - c[i - 1]) / (xs[i] - xs[i - j]);
  }
  Polynomial result{c[points - 1]};
  for (std::size_t i = points - 1; i-- > 0;) {
    result = sum(product(result, Polynomial{-xs[i], mpq_class(1)}), Polynomial{c[i]});
  }
  return exact::trimmed(result);
}

// The t in [-1/4, 5/4] where |A(t) - B(s)| is least (dense sampling, then Gauss-Newton), and that
// distance.
std::pair<double, double> partner(const RationalBezierCurve2& A, const Vec2& point) {
  double best_t = 0, best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 3000; ++k) {
    const double t = -0.25 + 1.5 * k / 3000.0;
    const double d = (A.evaluate(t) - point).norm();
    if (d < best) best = d, best_t = t;
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Vec2 r = A.evaluate(best_t) - point;
    const Vec2 d1 = derivative(A, best_t, 1);
    if (d1.squaredNorm() == 0) break;
    const double next = best_t - r.dot(d1) / d1.squaredNorm();
    const double dn = (A.evaluate(next) - point).norm();
    if (!(dn < best)) break;
    best = dn, best_t = next;
  }
  return {best_t, best};
}

}  // namespace

PairTruth pair_truth(const CurvePair& pair) {
  PairTruth truth;
  const Polynomial R = resultant_in_s(pair);
  if (R.empty()) {
    truth.overlap = true;
    return truth;
  }
  const double size = 4.0;  // the cases lie within [-1, 4]^2
  for (const exact::RootInterval& x : exact::isolated_roots(R, zero(), one(), root_width())) {
    const double s = middle(x);
    const auto [t, distance] = partner(pair.first, pair.second.evaluate(s));
    if (!(distance <= 1e-9 * size)) continue;  // a root whose t is complex or beyond the sampled range
    if (t > 1e-9 && t < 1 - 1e-9) {
      truth.points.emplace_back(t, s);
      truth.multiplicity.push_back(multiplicity_in(R, x));
      continue;
    }
    if (t < -1e-9 || t > 1 + 1e-9) continue;
    // Within rounding of an end of A: decide exactly whether the end lies on B at a rational s.
    const double end = t < 0.5 ? 0.0 : 1.0;
    const auto A = homogeneous_power(pair.first);
    const auto B = homogeneous_power(pair.second);
    const mpq_class te(end);
    const bool exact_root = x.lo == x.hi;
    const bool on =
        exact_root &&
        exact::value(A[0], te) * exact::value(B[2], x.lo) == exact::value(B[0], x.lo) * exact::value(A[2], te) &&
        exact::value(A[1], te) * exact::value(B[2], x.lo) == exact::value(B[1], x.lo) * exact::value(A[2], te);
    if (on) {
      truth.points.emplace_back(end, s);
      truth.multiplicity.push_back(multiplicity_in(R, x));
    } else {
      ++truth.undecided;
    }
  }
  return truth;
}

}  // namespace patchwork::crosscheck
