#pragma once
// Numbers as the report prints them.

#include <cstddef>
#include <cstdio>
#include <string>

namespace patchwork::performance {

/// One value through a printf format ("%.3g").
inline std::string text(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

/// A count with thousands separators: 12,826.
inline std::string count(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string grouped;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) grouped += ',';
    grouped += digits[k];
  }
  return grouped;
}

}  // namespace patchwork::performance
