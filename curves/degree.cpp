#include "curves/degree.h"

#include <Eigen/Dense>
#include <cmath>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

// int_0^1 B_k^m B_i^n ds.
double gram(int m, int k, int n, int i) {
  return binomial(m, k) * binomial(n, i) / ((m + n + 1) * binomial(m + n, k + i));
}

// The same in extended precision, for the residual of iterative refinement.
long double gram_extended(int m, int k, int n, int i) {
  return static_cast<long double>(binomial(m, k)) * binomial(n, i) /
         ((m + n + 1) * static_cast<long double>(binomial(m + n, k + i)));
}

// max_{s in [0,1]} |D(s)| for a curve D: the extremes of |D|^2 lie at the ends or at roots of
// its derivative, a scalar polynomial in Bernstein form of degree 2n-1.
template <int Dim>
double max_norm(const BezierCurve<Dim>& difference) {
  const int n = difference.degree();
  const auto& D = difference.control_points();
  std::vector<double> squared(static_cast<std::size_t>(2 * n) + 1, 0.0);
  std::vector<double> coordinate(static_cast<std::size_t>(n) + 1);
  for (int c = 0; c < Dim; ++c) {
    for (int i = 0; i <= n; ++i) coordinate[i] = D[i][c];
    const std::vector<double> product = bernstein_product(coordinate, coordinate);
    for (std::size_t i = 0; i < product.size(); ++i) squared[i] += product[i];
  }
  const BezierCurve<Dim> local = with_interval(difference, 0.0, 1.0);
  double result = std::max(local.evaluate(0.0).norm(), local.evaluate(1.0).norm());
  for (double s : bernstein_roots(bernstein_derivative_coefficients(squared))) {
    result = std::max(result, local.evaluate(s).norm());
  }
  return result;
}

}  // namespace

template <int Dim>
BezierCurve<Dim> elevate_degree(const BezierCurve<Dim>& curve, int times) {
  if (times < 0) throw InvalidInput(detail::message("elevate_degree: times = ", times, " is negative"));
  std::vector<Point<Dim>> P = curve.control_points();
  for (int step = 0; step < times; ++step) {
    const int n = static_cast<int>(P.size()) - 1;
    std::vector<Point<Dim>> Q(P.size() + 1);
    Q[0] = P[0];
    Q[n + 1] = P[n];
    for (int i = 1; i <= n; ++i) {
      const double alpha = static_cast<double>(i) / (n + 1);
      Q[i] = alpha * P[i - 1] + (1.0 - alpha) * P[i];
    }
    P = std::move(Q);
  }
  return BezierCurve<Dim>(std::move(P), curve.a(), curve.b());
}

template <int Dim>
DegreeReduction<Dim> reduce_degree(const BezierCurve<Dim>& curve, int m, EndPoints end_points) {
  const int n = curve.degree();
  if (m < 0 || m > n) throw InvalidInput(detail::message("reduce_degree: target degree ", m, " not in [0, ", n, "]"));
  if (m < 1 && end_points == EndPoints::interpolate) {
    throw InvalidInput("reduce_degree: degree 0 cannot interpolate both end points");
  }
  if (m == n) return {curve, 0.0};
  const auto& P = curve.control_points();
  // Unknowns: all m+1 points (free) or the m-1 inner ones (interpolate); the normal equations
  // G^{mm} R = G^{mn} P restricted to the unknown rows, fixed points moved to the right side.
  const int first = end_points == EndPoints::free ? 0 : 1;
  const int last = end_points == EndPoints::free ? m : m - 1;
  const int unknowns = last - first + 1;
  std::vector<Point<Dim>> R(static_cast<std::size_t>(m) + 1, Point<Dim>::Zero());
  if (end_points == EndPoints::interpolate) {
    R[0] = P[0];
    R[m] = P[n];
  }
  if (unknowns > 0) {
    Eigen::MatrixXd G(unknowns, unknowns);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(unknowns, Dim);
    for (int k = first; k <= last; ++k) {
      for (int j = first; j <= last; ++j) G(k - first, j - first) = gram(m, k, m, j);
      for (int i = 0; i <= n; ++i) rhs.row(k - first) += gram(m, k, n, i) * P[i].transpose();
      if (end_points == EndPoints::interpolate) {
        rhs.row(k - first) -= gram(m, k, m, 0) * R[0].transpose() + gram(m, k, m, m) * R[m].transpose();
      }
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt = G.ldlt();
    Eigen::MatrixXd solution = ldlt.solve(rhs);
    // The Bernstein Gram matrix has condition ~4^m / sqrt(m) (2.4e4 at m = 8, 5e6 at m = 12),
    // which a plain solve passes on to the points. One step of iterative refinement with the
    // residual in extended precision brings the error down to ~u + kappa * eps(long double).
    Eigen::MatrixXd residual(unknowns, Dim);
    for (int k = first; k <= last; ++k) {
      for (int c = 0; c < Dim; ++c) {
        long double r = 0.0L;
        for (int i = 0; i <= n; ++i) r += gram_extended(m, k, n, i) * P[i][c];
        if (end_points == EndPoints::interpolate) {
          r -= gram_extended(m, k, m, 0) * R[0][c] + gram_extended(m, k, m, m) * R[m][c];
        }
        for (int j = first; j <= last; ++j) r -= gram_extended(m, k, m, j) * solution(j - first, c);
        residual(k - first, c) = static_cast<double>(r);
      }
    }
    solution += ldlt.solve(residual);
    for (int k = first; k <= last; ++k) R[k] = solution.row(k - first).transpose();
  }
  BezierCurve<Dim> reduced(std::move(R), curve.a(), curve.b());
  const BezierCurve<Dim> elevated = elevate_degree(reduced, n - m);
  std::vector<Point<Dim>> difference(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) difference[i] = elevated.control_points()[i] - P[i];
  const double error = max_norm(BezierCurve<Dim>(std::move(difference), curve.a(), curve.b()));
  return {std::move(reduced), error};
}

#define PATCHWORK_INSTANTIATE(D)                                                      \
  template BezierCurve<D> elevate_degree(const BezierCurve<D>&, int);                 \
  template DegreeReduction<D> reduce_degree(const BezierCurve<D>&, int, EndPoints);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
