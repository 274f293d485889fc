#pragma once
// Tests that need a tool scripts/setup installs (node and the Khronos glTF validator, three.js,
// gnuplot, pkg-config) skip without it on a developer's machine, but fail when the environment
// variable CI is "true": there scripts/setup has run, so a missing tool is a broken set-up, not
// a reason to pass in silence.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace patchwork::testing {

/// Whether CI=true: every tool scripts/setup installs must be present.
inline bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

/// Whether a tool that scripts/setup installs is here; when it is not, a failure under CI=true
/// (the test goes on with what it can check) and a note otherwise. For a check inside a test.
inline bool tool_available(bool available, const std::string& what) {
  if (!available) {
    if (running_in_ci()) {
      ADD_FAILURE() << what << " is missing, and CI=true: scripts/setup installs it";
    } else {
      std::cout << "note: " << what << " is missing (scripts/setup installs it): not checked\n";
    }
  }
  return available;
}

}  // namespace patchwork::testing

/// Ends the test when a tool scripts/setup installs is missing: skipped, or failed under CI=true.
#define PATCHWORK_SKIP_UNLESS_CI(reason)                                                                      \
  do {                                                                                                        \
    if (::patchwork::testing::running_in_ci()) FAIL() << (reason) << " (CI=true: scripts/setup installs it)"; \
    GTEST_SKIP() << (reason);                                                                                 \
  } while (false)
