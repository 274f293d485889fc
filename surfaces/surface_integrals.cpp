#include "surfaces/surface_integrals.h"

#include <cmath>

#include "core/errors.h"
#include "curves/gauss_legendre.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

constexpr int cell_points = 8;

double cell_rule(const std::function<double(double, double)>& f, double u0, double u1, double v0, double v1) {
  static const GaussLegendre rule(cell_points);
  const std::vector<double> us = rule.nodes_on(u0, u1);
  const std::vector<double> wu = rule.weights_on(u0, u1);
  const std::vector<double> vs = rule.nodes_on(v0, v1);
  const std::vector<double> wv = rule.weights_on(v0, v1);
  double sum = 0.0;
  for (int j = 0; j < cell_points; ++j) {
    double row = 0.0;
    for (int i = 0; i < cell_points; ++i) row += wu[i] * f(us[i], vs[j]);
    sum += wv[j] * row;
  }
  return sum;
}

void adaptive(const std::function<double(double, double)>& f, double u0, double u1, double v0, double v1,
              double whole, double tolerance, int depth, SurfaceIntegral& total) {
  const double um = 0.5 * (u0 + u1);
  const double vm = 0.5 * (v0 + v1);
  const double q[4] = {cell_rule(f, u0, um, v0, vm), cell_rule(f, um, u1, v0, vm), cell_rule(f, u0, um, vm, v1),
                       cell_rule(f, um, u1, vm, v1)};
  const double refined = q[0] + q[1] + q[2] + q[3];
  const double difference = std::abs(refined - whole);
  if (difference <= tolerance) {
    total.value += refined;
    total.error_estimate += difference;
    return;
  }
  if (depth >= 20) {
    throw NumericalError(detail::message("integrate_over_square: no convergence to ", tolerance, " on [", u0, ", ", u1,
                                         "] x [", v0, ", ", v1, "]"));
  }
  const double quarter = 0.25 * tolerance;
  adaptive(f, u0, um, v0, vm, q[0], quarter, depth + 1, total);
  adaptive(f, um, u1, v0, vm, q[1], quarter, depth + 1, total);
  adaptive(f, u0, um, vm, v1, q[2], quarter, depth + 1, total);
  adaptive(f, um, u1, vm, v1, q[3], quarter, depth + 1, total);
}

}  // namespace

SurfaceIntegral integrate_over_square(const std::function<double(double, double)>& f, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("integrate_over_square: tolerance ", tolerance, " is not positive"));
  }
  SurfaceIntegral total{0.0, 0.0};
  adaptive(f, 0.0, 1.0, 0.0, 1.0, cell_rule(f, 0.0, 1.0, 0.0, 1.0), tolerance, 0, total);
  return total;
}

SurfaceIntegral area(const BezierPatch3& patch, double tolerance) {
  return integrate_over_square([&patch](double u, double v) { return normal(patch, u, v).norm(); }, tolerance);
}

SurfaceIntegral area(const RationalBezierPatch& patch, double tolerance) {
  return integrate_over_square([&patch](double u, double v) { return normal(patch, u, v).norm(); }, tolerance);
}

double volume_contribution(const BezierPatch3& patch) {
  const GaussLegendre rule_u((3 * patch.degree_u() + 1) / 2 + 1);
  const GaussLegendre rule_v((3 * patch.degree_v() + 1) / 2 + 1);
  const std::vector<double> us = rule_u.nodes_on(0.0, 1.0);
  const std::vector<double> wu = rule_u.weights_on(0.0, 1.0);
  const std::vector<double> vs = rule_v.nodes_on(0.0, 1.0);
  const std::vector<double> wv = rule_v.weights_on(0.0, 1.0);
  double sum = 0.0;
  for (std::size_t j = 0; j < vs.size(); ++j) {
    for (std::size_t i = 0; i < us.size(); ++i) {
      sum += wu[i] * wv[j] * patch.evaluate(us[i], vs[j]).dot(normal(patch, us[i], vs[j]));
    }
  }
  return sum / 3.0;
}

SurfaceIntegral volume_contribution(const RationalBezierPatch& patch, double tolerance) {
  SurfaceIntegral integral = integrate_over_square(
      [&patch](double u, double v) { return patch.evaluate(u, v).dot(normal(patch, u, v)); }, 3.0 * tolerance);
  return {integral.value / 3.0, integral.error_estimate / 3.0};
}

double enclosed_volume(std::span<const BezierPatch3> patches) {
  double sum = 0.0;
  for (const BezierPatch3& patch : patches) sum += volume_contribution(patch);
  return sum;
}

}  // namespace patchwork
