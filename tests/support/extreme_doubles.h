#pragma once
// Doubles that a text or binary round trip must keep bit for bit: signed zeros, subnormals, the
// extremes, and values without a short decimal form.

#include <cmath>
#include <limits>
#include <vector>

namespace patchwork::testing {

/// -0, +0, the smallest subnormals, the smallest normal and its predecessor, the extremes, 0.1, 1/3.
inline std::vector<double> extreme_doubles() {
  return {-0.0,
          0.0,
          std::numeric_limits<double>::denorm_min(),
          -std::numeric_limits<double>::denorm_min(),
          std::numeric_limits<double>::min(),
          std::nextafter(std::numeric_limits<double>::min(), 0.0),
          std::numeric_limits<double>::max(),
          std::numeric_limits<double>::lowest(),
          0.1,
          1.0 / 3.0};
}

}  // namespace patchwork::testing
