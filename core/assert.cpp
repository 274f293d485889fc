#include "core/assert.h"

#include <cstdio>
#include <cstdlib>

namespace patchwork::detail {

void assertion_failed(const char* file, int line, const char* expression,
                      const char* message) noexcept {
  std::fprintf(stderr, "%s:%d: patchwork invariant violated: %s (%s)\n", file, line, expression,
               message);
  std::fflush(stderr);
  std::abort();
}

}  // namespace patchwork::detail
