#include "curves/bspline_basis.h"

#include "core/assert.h"
#include "core/errors.h"

namespace patchwork {

std::vector<double> detail::basis_functions_on_span(const KnotVector& knots, int s, double u) {
  const int p = knots.degree();
  PATCHWORK_ASSERT(s >= p && s < knots.control_point_count() && knots[s] < knots[s + 1], "not a non-empty span");
  std::vector<double> N(static_cast<std::size_t>(p) + 1, 0.0);
  std::vector<double> left(static_cast<std::size_t>(p) + 1, 0.0);
  std::vector<double> right(static_cast<std::size_t>(p) + 1, 0.0);
  N[0] = 1.0;
  // A2.2: degree j from degree j - 1; left[j] = u - u_{s+1-j}, right[j] = u_{s+j} - u, and the
  // denominators right[r+1] + left[j-r] = u_{s+r+1} - u_{s+1-j+r} are at least the span's length.
  for (int j = 1; j <= p; ++j) {
    left[static_cast<std::size_t>(j)] = u - knots[s + 1 - j];
    right[static_cast<std::size_t>(j)] = knots[s + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[static_cast<std::size_t>(r)] /
                          (right[static_cast<std::size_t>(r) + 1] + left[static_cast<std::size_t>(j - r)]);
      N[static_cast<std::size_t>(r)] = saved + right[static_cast<std::size_t>(r) + 1] * temp;
      saved = left[static_cast<std::size_t>(j - r)] * temp;
    }
    N[static_cast<std::size_t>(j)] = saved;
  }
  return N;
}

std::vector<double> basis_functions(const KnotVector& knots, double u) {
  return detail::basis_functions_on_span(knots, knots.span(u), u);
}

Eigen::MatrixXd basis_function_derivatives(const KnotVector& knots, double u, int order) {
  if (order < 0) throw InvalidInput(detail::message("basis_function_derivatives: order ", order, " is negative"));
  const int s = knots.span(u);
  const int p = knots.degree();
  // ndu: basis functions of every degree (upper triangle, ndu(r, j) = N_{s-j+r,j}) and the knot
  // differences (lower triangle), as in A2.3.
  Eigen::MatrixXd ndu(p + 1, p + 1);
  Eigen::VectorXd left(p + 1);
  Eigen::VectorXd right(p + 1);
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots[s + 1 - j];
    right[j] = knots[s + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = right[r + 1] + left[j - r];
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu(j, j) = saved;
  }
  Eigen::MatrixXd ders = Eigen::MatrixXd::Zero(order + 1, p + 1);
  for (int j = 0; j <= p; ++j) ders(0, j) = ndu(j, p);
  const int top = std::min(order, p);
  // a holds the coefficients a_{k,j} of the k-th derivative as differences of lower-degree
  // functions (eq. 2.9), two alternating rows.
  Eigen::MatrixXd a(2, p + 1);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a(0, 0) = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
        d += a(s2, k) * ndu(r, pk);
      }
      ders(k, r) = d;
      std::swap(s1, s2);
    }
  }
  // The factor p!/(p-k)! of the k-th derivative.
  double factor = p;
  for (int k = 1; k <= top; ++k) {
    ders.row(k) *= factor;
    factor *= (p - k);
  }
  return ders;
}

}  // namespace patchwork
