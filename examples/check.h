// examples/check.h: how the example programs check what they print.
#pragma once

#include <iostream>

namespace examples {

inline int failures = 0;

/// Prints "ok" or "FAILED" with what was checked, and counts the failures.
inline void check(bool ok, const char* what) {
  std::cout << (ok ? "  ok: " : "  FAILED: ") << what << '\n';
  failures += ok ? 0 : 1;
}

/// main's exit code: 0 when every check passed, else 1.
inline int exit_code() { return failures == 0 ? 0 : 1; }

}  // namespace examples
