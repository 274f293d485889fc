#pragma once
// Internal: the unit tangent as the limit direction of the first derivative that does not
// vanish, shared by polynomial and rational curves.
//
// Near t0, C'(t0 + e) ~ C^(k)(t0) e^(k-1) / (k-1)! when C' .. C^(k-1) vanish at t0, so the
// direction from the right (e > 0) is that of C^(k), from the left it is (-1)^(k-1) C^(k).

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/types.h"

namespace patchwork::detail {

/// Derivative scale n!/(n-k)! / h^k * 2^k * magnitude: the size of the rounding in the k-th
/// difference of control points of norm <= magnitude on an interval of length h.
inline double derivative_scale(int n, int k, double h, double magnitude) {
  double scale = magnitude;
  for (int j = 0; j < k; ++j) scale *= 2.0 * (n - j) / h;
  return scale;
}

/// d[0..n] = C, C', ..., C^(n) at t; returns the limit unit tangent (from the left if from_left).
/// \throws NumericalError if every derivative vanishes relative to 1e-13 of its scale.
template <int Dim>
Point<Dim> limit_tangent(const std::vector<Point<Dim>>& d, int n, double h, double magnitude,
                         bool from_left, double t) {
  for (int k = 1; k <= n && k < static_cast<int>(d.size()); ++k) {
    const double length = d[static_cast<std::size_t>(k)].norm();
    if (length > 1e-13 * derivative_scale(n, k, h, magnitude)) {
      const double sign = (from_left && (k - 1) % 2 == 1) ? -1.0 : 1.0;
      return sign * d[static_cast<std::size_t>(k)] / length;
    }
  }
  throw NumericalError(message("tangent: every derivative vanishes at t = ", t, " (the curve is a point)"));
}

}  // namespace patchwork::detail
