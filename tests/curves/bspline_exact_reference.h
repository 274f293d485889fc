#pragma once
// Exact rational references for the B-spline tests, written from the definitions, apart from the
// library's algorithms:
//
//   N_{i,0}(u) = [u_i <= u < u_{i+1}] (on the span s that evaluates u: i = s)
//   N_{i,q}    = (u - u_i)/(u_{i+q} - u_i) N_{i,q-1} + (u_{i+q+1} - u)/(u_{i+q+1} - u_{i+1}) N_{i+1,q-1}
//   N'_{i,q}   = q/(u_{i+q} - u_i) N_{i,q-1} - q/(u_{i+q+1} - u_{i+1}) N_{i+1,q-1}     (0/0 = 0)
//
// evaluated in mpq_class on the span s of the library's convention (u = b: last non-empty span),
// so one-sided values at breakpoints agree.

#include <gmpxx.h>

#include <vector>

#include "curves/bspline_curve.h"
#include "tests/support/rounding.h"

namespace patchwork::exact_bspline {

using testing::ExactPoint;

/// The knots as exact rationals.
inline std::vector<mpq_class> knots_of(const KnotVector& knots) {
  std::vector<mpq_class> U;
  for (double u : knots.knots()) U.emplace_back(u);
  return U;
}

/// d^k/du^k N_{i,q}(u) exactly, with the degree-0 functions taken on span s.
inline mpq_class basis(const std::vector<mpq_class>& U, int s, int i, int q, const mpq_class& u, int k) {
  const auto at = [&U](int j) { return U[static_cast<std::size_t>(j)]; };
  if (q == 0) return (k == 0 && i == s) ? mpq_class(1) : mpq_class(0);
  mpq_class result = 0;
  const mpq_class left_gap = at(i + q) - at(i);
  const mpq_class right_gap = at(i + q + 1) - at(i + 1);
  if (k == 0) {
    if (left_gap != 0) result += (u - at(i)) / left_gap * basis(U, s, i, q - 1, u, 0);
    if (right_gap != 0) result += (at(i + q + 1) - u) / right_gap * basis(U, s, i + 1, q - 1, u, 0);
  } else {
    if (left_gap != 0) result += q / left_gap * basis(U, s, i, q - 1, u, k - 1);
    if (right_gap != 0) result -= q / right_gap * basis(U, s, i + 1, q - 1, u, k - 1);
  }
  return result;
}

/// d^k C/du^k = sum_i N^(k)_{i,p}(u) P_i exactly, on the span the library uses for u.
template <int Dim>
ExactPoint<Dim> evaluate(const BSplineCurve<Dim>& curve, const mpq_class& u, int k = 0) {
  const std::vector<mpq_class> U = knots_of(curve.knot_vector());
  const int s = curve.knot_vector().span(u.get_d());
  const int p = curve.degree();
  ExactPoint<Dim> sum;
  for (auto& c : sum) c = 0;
  for (int i = s - p; i <= s; ++i) {
    const mpq_class N = basis(U, s, i, p, u, k);
    for (int c = 0; c < Dim; ++c)
      sum[static_cast<std::size_t>(c)] += N * mpq_class(curve.control_points()[static_cast<std::size_t>(i)][c]);
  }
  return sum;
}

/// |p - q| for two exact points (rounded at the end).
template <int Dim>
double distance(const ExactPoint<Dim>& p, const ExactPoint<Dim>& q) {
  double sum = 0.0;
  for (std::size_t c = 0; c < Dim; ++c) {
    const double d = mpq_class(p[c] - q[c]).get_d();
    sum += d * d;
  }
  return std::sqrt(sum);
}

/// Largest control point norm of a curve.
template <int Dim>
double scale(const BSplineCurve<Dim>& curve) {
  return testing::max_norm(curve.control_points());
}

using testing::distance;

}  // namespace patchwork::exact_bspline

namespace patchwork::exact_bspline {

/// The blossom f_s(t_1, ..., t_p) of the piece on span s exactly (de Boor with t_r at level r).
template <int Dim>
ExactPoint<Dim> blossom(const BSplineCurve<Dim>& curve, int s, const std::vector<mpq_class>& t) {
  const std::vector<mpq_class> U = knots_of(curve.knot_vector());
  const int p = curve.degree();
  std::vector<ExactPoint<Dim>> d;
  for (int j = 0; j <= p; ++j) {
    ExactPoint<Dim> point;
    for (int c = 0; c < Dim; ++c)
      point[static_cast<std::size_t>(c)] = curve.control_points()[static_cast<std::size_t>(s - p + j)][c];
    d.push_back(point);
  }
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const mpq_class& lo = U[static_cast<std::size_t>(s - p + j)];
      const mpq_class alpha =
          (t[static_cast<std::size_t>(r) - 1] - lo) / (U[static_cast<std::size_t>(s + j + 1 - r)] - lo);
      for (std::size_t c = 0; c < Dim; ++c) {
        d[static_cast<std::size_t>(j)][c] =
            (1 - alpha) * d[static_cast<std::size_t>(j) - 1][c] + alpha * d[static_cast<std::size_t>(j)][c];
      }
    }
  }
  return d[static_cast<std::size_t>(p)];
}

/// The exact control points of `curve` written on the finer knots `refined` (which contain its
/// knots): Q_i = f(v_{i+1}, ..., v_{i+p}) (the blossom's dual functional property), with f the
/// piece on a non-empty span of `refined` in [i, i+p], i.e. of `curve` containing it.
template <int Dim>
std::vector<ExactPoint<Dim>> refined_points(const BSplineCurve<Dim>& curve, const KnotVector& refined) {
  const int p = curve.degree();
  std::vector<ExactPoint<Dim>> Q;
  for (int i = 0; i < refined.control_point_count(); ++i) {
    int fine_span = std::max(i, p);
    while (!(refined[fine_span] < refined[fine_span + 1])) ++fine_span;
    const int s = curve.knot_vector().span(refined[fine_span]);
    std::vector<mpq_class> t;
    for (int j = 1; j <= p; ++j) t.emplace_back(refined[i + j]);
    Q.push_back(blossom(curve, s, t));
  }
  return Q;
}

}  // namespace patchwork::exact_bspline
