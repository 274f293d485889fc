#pragma once
// Exact rational references for the accuracy tests: the GoogleTest checks on top of
// tests/support/exact_rational.h (the gtest-free part: exact evaluation, basis conversions,
// ulps, measure_errors; shared with the report's hard-case section).

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <sstream>

#include "tests/support/exact_rational.h"

namespace patchwork::exact {

/// Both a-priori bounds hold, the reported bound covers the actual error, and the reported bound
/// is not vacuous (at most twice the theorem's bound: it only adds rounding of the bound itself
/// and p~ computed in floating point, factors 1 + O(n u)).
inline ::testing::AssertionResult within_bounds(const EvaluationErrors& e) {
  std::ostringstream why;
  if (e.plain > e.plain_bound) why << " plain error exceeds its a-priori bound;";
  if (e.compensated > e.compensated_bound) why << " compensated error exceeds u|p| + 2 gamma^2 p~;";
  if (e.compensated > e.reported) why << " reported error_bound is below the actual error;";
  if (e.reported > 2 * e.compensated_bound) why << " reported error_bound is above twice the theorem bound;";
  if (why.str().empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << why.str() << " p=" << e.exact.get_d() << " p~=" << e.magnitude.get_d()
                                       << " plain=" << e.plain.get_d() << " compensated=" << e.compensated.get_d()
                                       << " reported=" << e.reported.get_d();
}

}  // namespace patchwork::exact
