#include "curves/arc_length.h"

#include <array>
#include <cmath>
#include <numbers>

#include "core/errors.h"
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

double gauss(const std::function<double(double)>& f, double lo, double hi) {
  static const GaussLegendre rule;
  const double half = 0.5 * (hi - lo);
  const double mid = 0.5 * (hi + lo);
  double sum = 0.0;
  for (int i = 0; i < gauss_points; ++i) sum += rule.weights[i] * f(mid + half * rule.nodes[i]);
  return half * sum;
}

void adaptive(const std::function<double(double)>& f, double lo, double hi, double whole,
              double tolerance, int depth, ArcLength& total) {
  const double mid = 0.5 * (lo + hi);
  const double left = gauss(f, lo, mid);
  const double right = gauss(f, mid, hi);
  const double difference = std::abs(left + right - whole);
  if (difference <= tolerance || hi - lo <= 1e-15 * std::max(1.0, std::abs(lo))) {
    total.length += left + right;
    total.error_estimate += difference;
    return;
  }
  if (depth >= 50) {
    throw NumericalError(detail::message("integrate_adaptive: no convergence to ", tolerance, " on [", lo, ", ", hi, "]"));
  }
  adaptive(f, lo, mid, left, 0.5 * tolerance, depth + 1, total);
  adaptive(f, mid, hi, right, 0.5 * tolerance, depth + 1, total);
}

}  // namespace

ArcLength integrate_adaptive(const std::function<double(double)>& f, double t0, double t1, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("integrate_adaptive: tolerance ", tolerance, " is not positive"));
  }
  if (!std::isfinite(t0) || !std::isfinite(t1)) {
    throw InvalidInput(detail::message("integrate_adaptive: limits [", t0, ", ", t1, "] are not finite"));
  }
  ArcLength total{0.0, 0.0};
  if (t0 == t1) return total;
  adaptive(f, t0, t1, gauss(f, t0, t1), tolerance, 0, total);
  return total;
}

template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double t0, double t1, double tolerance) {
  if (!(curve.a() <= t0 && t0 <= t1 && t1 <= curve.b())) {
    throw InvalidInput(detail::message("arc_length: [", t0, ", ", t1, "] is not within [", curve.a(), ", ", curve.b(), "]"));
  }
  const BezierCurve<Dim> hodograph = derivative_curve(curve);
  return integrate_adaptive([&hodograph](double t) { return hodograph.evaluate(t).norm(); }, t0, t1, tolerance);
}

template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double tolerance) {
  return arc_length(curve, curve.a(), curve.b(), tolerance);
}

template <int Dim>
ArcLength arc_length(const RationalBezierCurve<Dim>& curve, double tolerance) {
  return integrate_adaptive([&curve](double t) { return derivative(curve, t, 1).norm(); }, curve.a(), curve.b(),
                            tolerance);
}

#define PATCHWORK_INSTANTIATE(D)                                                   \
  template ArcLength arc_length(const BezierCurve<D>&, double);                    \
  template ArcLength arc_length(const BezierCurve<D>&, double, double, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE
template ArcLength arc_length(const RationalBezierCurve<2>&, double);
template ArcLength arc_length(const RationalBezierCurve<3>&, double);

}  // namespace patchwork
