#include "curves/compensated.h"

#include <array>
#include <cmath>
#include <limits>

#include "curves/curve_checks.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

// Error-free transformations: a + b = sum + error and a * b = product + error, exactly.
inline void two_sum(double a, double b, double& sum, double& error) {
  sum = a + b;
  const double z = sum - a;
  error = (a - (sum - z)) + (b - z);
}

inline void two_product(double a, double b, double& product, double& error) {
  product = a * b;
  error = std::fma(a, b, -product);
}

// Compensated de Casteljau on n+1 coefficients read with stride; `work` holds 3(n+1) doubles.
// Returns the compensated value; `abs_sum` receives p~(s) computed alongside.
double compensated_de_casteljau(const double* b, std::size_t stride, int n, double s,
                                double* work, double& abs_sum) {
  double* value = work;            // b_i^(j)
  double* correction = work + n + 1;  // the propagated rounding errors
  double* magnitude = work + 2 * (n + 1);  // de Casteljau on |b_i|
  for (int i = 0; i <= n; ++i) {
    value[i] = b[static_cast<std::size_t>(i) * stride];
    correction[i] = 0.0;
    magnitude[i] = std::abs(value[i]);
  }
  double r = 0.0;
  double rho = 0.0;
  two_sum(1.0, -s, r, rho);  // 1 - s = r + rho exactly
  for (int j = 1; j <= n; ++j) {
    for (int i = 0; i + j <= n; ++i) {
      double p1 = 0.0, pi1 = 0.0, p2 = 0.0, pi2 = 0.0, sigma = 0.0;
      two_product(r, value[i], p1, pi1);
      two_product(s, value[i + 1], p2, pi2);
      const double old_value = value[i];
      two_sum(p1, p2, value[i], sigma);
      const double w = pi1 + pi2 + sigma + rho * old_value;
      correction[i] = w + r * correction[i] + s * correction[i + 1];
      magnitude[i] = r * magnitude[i] + s * magnitude[i + 1];
    }
  }
  abs_sum = magnitude[0];
  return value[0] + correction[0];
}

}  // namespace

double gamma_constant(int k) {
  const double ku = k * unit_roundoff;
  return ku / (1.0 - ku);
}

template <int Dim>
CompensatedPoint<Dim> evaluate_compensated(const BezierCurve<Dim>& curve, double t) {
  detail::check_parameter("evaluate_compensated", t);
  const int n = curve.degree();
  const double s = curve.local_parameter(t);
  std::array<double, 3 * 32> small{};
  std::vector<double> large;
  double* work = small.data();
  if (3 * (n + 1) > static_cast<int>(small.size())) {
    large.resize(3 * static_cast<std::size_t>(n + 1));
    work = large.data();
  }
  // Theorem bound u|p| + 2 gamma_{3n+2}^2 p~, made computable: |p| <= |res| + err gives the
  // factor 1/(1-u); p~ computed in floating point (n levels, each with the rounded 1 - s, a
  // product and a sum of non-negative terms) is at least (1 - u)^(3n) p~ >= (1 - gamma_{3n}) p~.
  const double gamma = gamma_constant(3 * n + 2);
  const double magnitude_factor = 1.0 / (1.0 - gamma_constant(3 * n));
  CompensatedPoint<Dim> result;
  const double* base = curve.control_points().front().data();
  for (int c = 0; c < Dim; ++c) {
    double abs_sum = 0.0;
    const double value = compensated_de_casteljau(base + c, Dim, n, s, work, abs_sum);
    result.value[c] = value;
    result.error_bound[c] =
        (unit_roundoff * std::abs(value) + 2.0 * gamma * gamma * abs_sum * magnitude_factor) /
        (1.0 - unit_roundoff) * (1.0 + 4.0 * unit_roundoff);  // rounding of this expression
  }
  return result;
}

template <int Dim>
Point<Dim> absolute_value_sum(const BezierCurve<Dim>& curve, double t) {
  std::vector<Point<Dim>> magnitudes = curve.control_points();
  for (auto& p : magnitudes) p = p.cwiseAbs();
  return BezierCurve<Dim>(std::move(magnitudes), curve.a(), curve.b()).evaluate(t);
}

#define PATCHWORK_INSTANTIATE(D)                                                        \
  template CompensatedPoint<D> evaluate_compensated(const BezierCurve<D>&, double);     \
  template Point<D> absolute_value_sum(const BezierCurve<D>&, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
