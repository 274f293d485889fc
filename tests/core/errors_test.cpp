#include "core/errors.h"

#include <gtest/gtest.h>

namespace patchwork {
namespace {

TEST(Errors, ParseErrorCarriesLocation) {
  const ParseError error("data/x.bpt", 12, 3, "expected 16 points");
  EXPECT_EQ(error.path(), "data/x.bpt");
  EXPECT_EQ(error.line(), 12);
  EXPECT_EQ(error.column(), 3);
  EXPECT_STREQ(error.what(), "data/x.bpt:12:3: expected 16 points");
}

TEST(Errors, FamilyDerivesFromStandardTypes) {
  EXPECT_THROW(throw TopologyError("edge (4,9) used by 3 faces"), std::invalid_argument);
  EXPECT_THROW(throw IoError("out.glb", "disk full"), std::runtime_error);
  EXPECT_THROW(throw NumericalError("no convergence"), std::runtime_error);
  const IoError io("out.glb", "disk full");
  EXPECT_STREQ(io.what(), "out.glb: disk full");
}

// Doubles print in the shortest form that reads back to the same value: exact, and readable.
TEST(Errors, MessageJoinsPartsWithShortestRoundTripDoubles) {
  EXPECT_EQ(detail::message("f: t = ", 0.1, ", n = ", 3), "f: t = 0.1, n = 3");
  EXPECT_EQ(detail::message(1e-12, " ", 0.1 + 0.2, " ", -0.0, " ", 1.0f / 3), "1e-12 0.30000000000000004 -0 0.3333333432674408");
  const double x = 2.0 / 3.0;
  EXPECT_EQ(std::stod(detail::message(x)), x);
}

}  // namespace
}  // namespace patchwork
