#pragma once
// The maximum of a function on [0, 1] without a root finder, for tests that compare a computed
// bound or distance with the truth.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace patchwork::testing {

/// max of f on [0, 1]: `samples` + 1 samples, then a golden-section search on the two steps
/// around every sampled local maximum (the first sample of a plateau). After 40 steps the
/// bracket is 1e-10 wide, so f is off its maximum by ~|f''| 1e-20: rounding only.
inline double refined_max(const std::function<double(double)>& f, int samples = 128) {
  std::vector<double> values(static_cast<std::size_t>(samples) + 1);
  for (int i = 0; i <= samples; ++i) values[static_cast<std::size_t>(i)] = f(static_cast<double>(i) / samples);
  double best = -std::numeric_limits<double>::infinity();
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i <= samples; ++i) {
    const double v = values[static_cast<std::size_t>(i)];
    best = std::max(best, v);
    const bool rises_to = i == 0 || values[static_cast<std::size_t>(i - 1)] < v;
    const bool falls_from = i == samples || values[static_cast<std::size_t>(i + 1)] <= v;
    if (!rises_to || !falls_from) continue;
    double lo = std::max(0, i - 1) / static_cast<double>(samples);
    double hi = std::min(samples, i + 1) / static_cast<double>(samples);
    double x1 = hi - ratio * (hi - lo);
    double x2 = lo + ratio * (hi - lo);
    double f1 = f(x1);
    double f2 = f(x2);
    for (int iteration = 0; iteration < 40; ++iteration) {
      if (f1 < f2) {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + ratio * (hi - lo);
        f2 = f(x2);
      } else {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - ratio * (hi - lo);
        f1 = f(x1);
      }
    }
    best = std::max({best, f1, f2});
  }
  return best;
}

}  // namespace patchwork::testing
