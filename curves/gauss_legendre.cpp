#include "curves/gauss_legendre.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace patchwork {

GaussLegendre::GaussLegendre(int points) {
  if (points < 1 || points > 64) throw InvalidInput(detail::message("GaussLegendre: ", points, " points not in [1, 64]"));
  nodes_.resize(static_cast<std::size_t>(points));
  weights_.resize(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    // Tricomi's initial guess, then Newton on P_points with the three-term recurrence.
    double x = -std::cos(std::numbers::pi * (i + 0.75) / (points + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = x;
      for (int k = 2; k <= points; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (points == 1) p0 = 1.0;
      derivative = points * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) <= 1e-16) break;
    }
    nodes_[static_cast<std::size_t>(i)] = x;
    weights_[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  if (points == 1) {
    nodes_[0] = 0.0;
    weights_[0] = 2.0;
  }
}

std::vector<double> GaussLegendre::nodes_on(double lo, double hi) const {
  std::vector<double> mapped(nodes_.size());
  for (std::size_t k = 0; k < nodes_.size(); ++k) mapped[k] = 0.5 * (lo + hi) + 0.5 * (hi - lo) * nodes_[k];
  return mapped;
}

std::vector<double> GaussLegendre::weights_on(double lo, double hi) const {
  std::vector<double> scaled(weights_.size());
  for (std::size_t k = 0; k < weights_.size(); ++k) scaled[k] = 0.5 * (hi - lo) * weights_[k];
  return scaled;
}

}  // namespace patchwork
