#include "curves/arc_length.h"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "curves/bernstein.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

constexpr int gauss_points = 10;

// Nodes and weights of the Gauss-Legendre rule on [-1, 1], by Newton's method on P_10.
struct GaussLegendre {
  std::array<double, gauss_points> nodes{};
  std::array<double, gauss_points> weights{};
  GaussLegendre() {
    for (int i = 0; i < gauss_points; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (gauss_points + 0.5));
      double derivative = 0.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0;
        double p1 = x;
        for (int k = 2; k <= gauss_points; ++k) {
          const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        derivative = gauss_points * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / derivative;
        x -= step;
        if (std::abs(step) < 1e-17) break;
      }
      nodes[i] = x;
      weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
  }
};

// The rule on [lo, hi]: the integral and the integral of |f| (the scale of its rounding).
struct GaussValue {
  double value;
  double magnitude;
};

GaussValue gauss(const std::function<double(double)>& f, double lo, double hi) {
  static const GaussLegendre rule;
  const double half = 0.5 * (hi - lo);
  const double mid = 0.5 * (hi + lo);
  double sum = 0.0;
  double magnitude = 0.0;
  for (int i = 0; i < gauss_points; ++i) {
    const double term = rule.weights[i] * f(mid + half * rule.nodes[i]);
    sum += term;
    magnitude += std::abs(term);
  }
  return {half * sum, std::abs(half) * magnitude};
}

// The difference is multiplied by this before it is compared with the tolerance: where the
// integrand is not yet resolved (a near-cusp at the end of an interval, |C'| ~ sqrt(t^2 + d^2))
// the rule converges only logarithmically and the finer value's error can exceed the difference
// several times (observed up to 78 times for sqrt(t^2 + d^2) on [0, 1] at factor 1, none at 16).
constexpr double safety = 16.0;

// Accepts [lo, hi] when safety * |left + right - whole| is within its share of the tolerance, or
// when the difference is at the rounding level of the integrand (`noise` per unit length):
// below that, bisection cannot improve the value, and without this floor a tolerance under the
// rounding level (1e-14 for a curve of length 500) bisected everything to depth 50, 2^50 rules.
void adaptive(const std::function<double(double)>& f, double lo, double hi, double whole, double tolerance,
              double noise, int depth, ArcLength& total) {
  const double mid = 0.5 * (lo + hi);
  const double left = gauss(f, lo, mid).value;
  const double right = gauss(f, mid, hi).value;
  const double difference = std::abs(left + right - whole);
  // |hi - lo|: the limits may run backwards (int_1^0), and then the interval is not "tiny".
  const double width = std::abs(hi - lo);
  if (safety * difference <= tolerance || difference <= noise * width ||
      width <= 1e-15 * std::max(1.0, std::abs(lo))) {
    total.length += left + right;
    total.error_estimate += difference;
    return;
  }
  if (depth >= 50) {
    throw NumericalError(detail::message("integrate_adaptive: no convergence to ", tolerance, " on [", lo, ", ", hi, "]"));
  }
  adaptive(f, lo, mid, left, 0.5 * tolerance, noise, depth + 1, total);
  adaptive(f, mid, hi, right, 0.5 * tolerance, noise, depth + 1, total);
}

void check_tolerance(double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("integrate_adaptive: tolerance ", tolerance, " is not positive"));
  }
}

// integrate_adaptive with a given rounding level of f: the larger of `noise` and 64 eps times the
// mean of |f| from the first rule.
ArcLength integrate(const std::function<double(double)>& f, double t0, double t1, double tolerance, double noise) {
  check_tolerance(tolerance);
  if (!std::isfinite(t0) || !std::isfinite(t1)) {
    throw InvalidInput(detail::message("integrate_adaptive: limits [", t0, ", ", t1, "] are not finite"));
  }
  ArcLength total{0.0, 0.0};
  if (t0 == t1) return total;
  const GaussValue whole = gauss(f, t0, t1);
  const double mean_magnitude = whole.magnitude / std::abs(t1 - t0);
  const double floor = std::max(noise, 64.0 * std::numeric_limits<double>::epsilon() * mean_magnitude);
  adaptive(f, t0, t1, whole.value, tolerance, floor, 0, total);
  return total;
}

// Where |C'| has a cusp (C' = 0) the integrand has a kink. A kink close to an end of an
// interval can fall before the first Gauss node of that interval and of its halves alike: both
// rules then integrate the smooth continuation, agree, and a wrong value is accepted (observed:
// error 1e-4 at tolerance 1e-11 for (t^2, t^3) on [-1.24, 1.22]). Cutting [t0, t1] at the
// critical points of the speed puts every kink, and every near-kink of a near-cusp, at an end of
// a piece, where |C'| = |t - t_c| g(t) is analytic on the piece.
ArcLength integrate_pieces(const std::function<double(double)>& speed, double t0, double t1, double tolerance,
                           double noise, const std::vector<double>& critical_local, double a, double b) {
  std::vector<double> breaks{t0};
  for (double s : critical_local) {  // ascending local parameters in [0, 1]
    const double t = a + s * (b - a);
    if (breaks.back() < t && t < t1) breaks.push_back(t);
  }
  breaks.push_back(t1);
  if (breaks.size() == 2) return integrate(speed, t0, t1, tolerance, noise);  // also t0 == t1
  ArcLength total{0.0, 0.0};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    // Each piece gets its share of the tolerance by length, so the shares add up to it.
    const double share = tolerance * ((breaks[k + 1] - breaks[k]) / (t1 - t0));
    const ArcLength piece = integrate(speed, breaks[k], breaks[k + 1], share, noise);
    total.length += piece.length;
    total.error_estimate += piece.error_estimate;
  }
  return total;
}

// Local parameters of the critical points of |C'|^2 (a polynomial of degree 2n-2 in Bernstein
// form, the sum of the squared hodograph coordinates).
template <int Dim>
std::vector<double> speed_critical_points(const BezierCurve<Dim>& curve) {
  const int n = curve.degree();
  if (n < 2) return {};  // constant speed
  const auto& P = curve.control_points();
  std::vector<double> speed2(static_cast<std::size_t>(2 * n - 1), 0.0);
  std::vector<double> coordinate(static_cast<std::size_t>(n));
  for (int d = 0; d < Dim; ++d) {
    for (int i = 0; i < n; ++i) coordinate[static_cast<std::size_t>(i)] = P[i + 1][d] - P[i][d];
    const std::vector<double> square = bernstein_product(coordinate, coordinate);
    for (std::size_t i = 0; i < square.size(); ++i) speed2[i] += square[i];
  }
  return bernstein_roots(bernstein_derivative_coefficients(speed2));
}

// The same for a rational curve: C' = N / w^2 with N = X' w - X w' (X the homogeneous
// coordinates), so |C'|^2 = M / w^4 with M = |N|^2 and (M / w^4)' = (M' w - 4 M w') / w^5.
template <int Dim>
std::vector<double> speed_critical_points(const RationalBezierCurve<Dim>& curve) {
  const int n = curve.degree();
  if (n < 1) return {};
  const auto& H = curve.homogeneous().control_points();
  std::vector<double> w(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) w[static_cast<std::size_t>(i)] = H[i][Dim];
  const std::vector<double> dw = bernstein_derivative_coefficients(w);
  std::vector<double> M(static_cast<std::size_t>(4 * n - 1), 0.0);
  std::vector<double> X(static_cast<std::size_t>(n) + 1);
  for (int d = 0; d < Dim; ++d) {
    for (int i = 0; i <= n; ++i) X[static_cast<std::size_t>(i)] = H[i][d];
    std::vector<double> N = bernstein_product(bernstein_derivative_coefficients(X), w);
    const std::vector<double> X_dw = bernstein_product(X, dw);
    for (std::size_t i = 0; i < N.size(); ++i) N[i] -= X_dw[i];
    const std::vector<double> square = bernstein_product(N, N);
    for (std::size_t i = 0; i < square.size(); ++i) M[i] += square[i];
  }
  std::vector<double> numerator = bernstein_product(bernstein_derivative_coefficients(M), w);
  const std::vector<double> M_dw = bernstein_product(M, dw);
  for (std::size_t i = 0; i < numerator.size(); ++i) numerator[i] -= 4.0 * M_dw[i];
  return bernstein_roots(numerator);
}

}  // namespace

ArcLength integrate_adaptive(const std::function<double(double)>& f, double t0, double t1, double tolerance) {
  return integrate(f, t0, t1, tolerance, 0.0);
}

template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double t0, double t1, double tolerance) {
  if (!(curve.a() <= t0 && t0 <= t1 && t1 <= curve.b())) {
    throw InvalidInput(detail::message("arc_length: [", t0, ", ", t1, "] is not within [", curve.a(), ", ", curve.b(), "]"));
  }
  const BezierCurve<Dim> hodograph = derivative_curve(curve);
  // de Casteljau on the hodograph errs by <= gamma_{2n} max_i |D_i| per coordinate.
  double largest = 0.0;
  for (const auto& D : hodograph.control_points()) largest = std::max(largest, D.norm());
  const double noise = 8.0 * (curve.degree() + 1) * std::numeric_limits<double>::epsilon() * largest;
  return integrate_pieces([&hodograph](double t) { return hodograph.evaluate(t).norm(); }, t0, t1, tolerance, noise,
                          speed_critical_points(curve), curve.a(), curve.b());
}

template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double tolerance) {
  return arc_length(curve, curve.a(), curve.b(), tolerance);
}

template <int Dim>
ArcLength arc_length(const RationalBezierCurve<Dim>& curve, double tolerance) {
  // C' = (H' - w' C) / w: H' and w' err by <= gamma_{2n} (2n/h) max|H_i| and (2n/h) max w_i,
  // amplified by |C| <= max|P_i| and divided by w >= min w_i.
  const int n = curve.degree();
  double largest_h = 0.0;
  double largest_p = 0.0;
  double largest_w = 0.0;
  double smallest_w = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    largest_h = std::max(largest_h, curve.homogeneous().control_points()[static_cast<std::size_t>(i)].norm());
    largest_p = std::max(largest_p, curve.control_point(i).norm());
    largest_w = std::max(largest_w, curve.weight(i));
    smallest_w = std::min(smallest_w, curve.weight(i));
  }
  const double noise = 8.0 * (n + 1) * std::numeric_limits<double>::epsilon() * (2.0 * n / (curve.b() - curve.a())) *
                       (largest_h + largest_w * largest_p) / smallest_w;
  return integrate_pieces([&curve](double t) { return derivative(curve, t, 1).norm(); }, curve.a(), curve.b(),
                          tolerance, noise, speed_critical_points(curve), curve.a(), curve.b());
}

#define PATCHWORK_INSTANTIATE(D)                                                   \
  template ArcLength arc_length(const BezierCurve<D>&, double);                    \
  template ArcLength arc_length(const BezierCurve<D>&, double, double, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE
template ArcLength arc_length(const RationalBezierCurve<2>&, double);
template ArcLength arc_length(const RationalBezierCurve<3>&, double);

}  // namespace patchwork
