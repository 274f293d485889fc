#pragma once
// Input checks shared by the curve types: they throw InvalidInput naming the function and the
// offending element, before anything is built.

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/types.h"

namespace patchwork::detail {

/// Throws unless t is finite.
inline void check_parameter(const char* function, double t) {
  if (!std::isfinite(t)) throw InvalidInput(message(function, ": parameter t = ", t, " is not finite"));
}

/// Throws unless a and b are finite and a < b.
inline void check_interval(const char* function, double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b) || !(a < b)) {
    throw InvalidInput(message(function, ": interval [", a, ", ", b, "] is not finite with a < b"));
  }
}

/// Throws if there is no point or a coordinate is not finite.
template <int Dim>
void check_control_points(const char* function, const std::vector<Point<Dim>>& points) {
  if (points.empty()) throw InvalidInput(message(function, ": no control points"));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InvalidInput(message(function, ": control point ", i, " is not finite (", points[i].transpose(), ")"));
    }
  }
}

}  // namespace patchwork::detail
