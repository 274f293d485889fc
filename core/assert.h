#pragma once
// PATCHWORK_ASSERT: internal invariants only, never user input (user input gets an exception
// from core/errors.h). On when PATCHWORK_ENABLE_ASSERTS is defined, which the build sets for
// Debug and sanitizer builds; a failure prints file:line, the expression and a message, then aborts.

namespace patchwork::detail {

/// Reports a failed invariant to stderr and aborts.
[[noreturn]] void assertion_failed(const char* file, int line, const char* expression,
                                   const char* message) noexcept;

}  // namespace patchwork::detail

#ifdef PATCHWORK_ENABLE_ASSERTS
#define PATCHWORK_ASSERT(condition, message)                                                 \
  ((condition) ? static_cast<void>(0)                                                        \
               : ::patchwork::detail::assertion_failed(__FILE__, __LINE__, #condition, message))
#else
#define PATCHWORK_ASSERT(condition, message) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif
