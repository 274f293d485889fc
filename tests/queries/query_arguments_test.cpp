// The argument checks every query shares: the message names the function and the argument.

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/errors.h"
#include "queries/query_arguments.h"

namespace query_arguments_test {
namespace {

using patchwork::InvalidInput;
using patchwork::Vec2;
using patchwork::Vec3;

// The message of the InvalidInput that `call` throws ("" if it throws none).
template <class Call>
std::string message_of(Call call) {
  try {
    call();
  } catch (const InvalidInput& error) {
    return error.what();
  }
  return "";
}

TEST(QueryArguments, NonFinitePointNamesFunctionAndArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of([&] { patchwork::require_finite(Vec3(1, nan, 0), "closest_point", "point"); }),
            "closest_point: argument 'point' is not finite (1, nan, 0)");
  EXPECT_EQ(message_of([&] { patchwork::require_finite(Vec3(1, 2, 3), "closest_point", "point"); }), "");
  EXPECT_NE(message_of([&] { patchwork::require_finite(Vec2(std::numeric_limits<double>::infinity(), 0), "f", "p"); }), "");
}

TEST(QueryArguments, ZeroDirectionIsRejectedTinyOneIsNot) {
  EXPECT_EQ(message_of([] { patchwork::require_direction(Vec3(0, -0.0, 0), "ray_cast", "direction"); }),
            "ray_cast: argument 'direction' is the zero vector");
  // A direction whose squared norm underflows is still a direction.
  EXPECT_EQ(message_of([] { patchwork::require_direction(Vec3(1e-200, 0, 0), "ray_cast", "direction"); }), "");
}

TEST(QueryArguments, PositiveValues) {
  EXPECT_NE(message_of([] { patchwork::require_positive(0.0, "section", "tolerance"); }), "");
  EXPECT_NE(message_of([] { patchwork::require_positive(std::numeric_limits<double>::infinity(), "section", "tolerance"); }), "");
  EXPECT_EQ(message_of([] { patchwork::require_positive(1e-300, "section", "tolerance"); }), "");
}

}  // namespace
}  // namespace query_arguments_test
