#include "io/bpt.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "tests/support/extreme_doubles.h"
#include "tests/support/parse_errors.h"
#include "tests/support/temporary_directory.h"
#include "io/atomic_file.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Helpers

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Whether two patch lists are equal bit for bit (operator== would call -0 and +0 equal).
bool bit_identical(const std::vector<BezierPatch3>& a, const std::vector<BezierPatch3>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t p = 0; p < a.size(); ++p) {
    if (a[p].degree_u() != b[p].degree_u() || a[p].degree_v() != b[p].degree_v()) return false;
    const auto& pa = a[p].control_points();
    const auto& pb = b[p].control_points();
    if (pa.size() != pb.size()) return false;
    for (std::size_t k = 0; k < pa.size(); ++k) {
      for (int c = 0; c < 3; ++c) {
        if (bits(pa[k][c]) != bits(pb[k][c])) return false;
      }
    }
  }
  return true;
}

// The ParseError that parse_bpt throws on `text`, or nothing (then the test has failed).
std::optional<ParseError> parse_error(const std::string& text, const std::string& name = "test.bpt") {
  return testing::parse_error_of([&] { parse_bpt(text, name); });
}

// A valid one-patch file of degrees (1, 1): point k on line 3 + k.
const std::string valid_lines[] = {"1", "1 1", "0 0 0", "1 0 0", "0 1 0", "1 1 1"};

// The valid file with line `line` (1-based) replaced; an empty `replacement` removes the line.
std::string with_line(int line, const std::string& replacement) {
  std::string text;
  for (int k = 0; k < 6; ++k) {
    if (k + 1 == line) {
      if (!replacement.empty()) text += replacement + "\n";
    } else {
      text += valid_lines[k] + "\n";
    }
  }
  return text;
}

// Every test folder is named after this test program.
struct TemporaryDirectory : testing::TemporaryDirectory {
  TemporaryDirectory() : testing::TemporaryDirectory("patchwork_io_test") {}
};

std::string file_content(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

// Patch of degrees (n, m) whose point P_ij is (i, j, 100 i + j + offset).
BezierPatch3 labelled_patch(int n, int m, double offset = 0.0) {
  std::vector<Vec3> points;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) points.emplace_back(i, j, 100.0 * i + j + offset);
  }
  return BezierPatch3(n, m, std::move(points));
}

// ---------------------------------------------------------------------------------------------
// Generators

// Finite doubles of every kind: raw bit patterns (all exponents, subnormals), the extremes,
// signed zeros, and ordinary decimals.
rc::Gen<double> finite_double() {
  const rc::Gen<double> from_bits = rc::gen::map(
      rc::gen::suchThat(rc::gen::arbitrary<std::uint64_t>(),
                        [](std::uint64_t b) { return std::isfinite(std::bit_cast<double>(b)); }),
      [](std::uint64_t b) { return std::bit_cast<double>(b); });
  const rc::Gen<double> special = rc::gen::element(
      0.0, -0.0, std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
      std::numeric_limits<double>::min(), std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
      1e-300, -1e300, 0.1, 1.0 / 3.0, 2.53125, -0.784, 1e22, 5e-324 * 3);
  const rc::Gen<double> decimal =
      rc::gen::map(rc::gen::inRange(-10000000, 10000001), [](int k) { return k / 1000.0; });
  return rc::gen::oneOf(from_bits, special, decimal);
}

rc::Gen<BezierPatch3> any_patch() {
  return rc::gen::mapcat(rc::gen::pair(rc::gen::inRange(0, 7), rc::gen::inRange(0, 7)), [](std::pair<int, int> nm) {
    const int n = nm.first;
    const int m = nm.second;
    const auto count = static_cast<std::size_t>((n + 1) * (m + 1));
    return rc::gen::map(rc::gen::container<std::vector<double>>(3 * count, finite_double()),
                        [n, m, count](const std::vector<double>& xyz) {
                          std::vector<Vec3> points;
                          for (std::size_t k = 0; k < count; ++k) points.emplace_back(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
                          return BezierPatch3(n, m, std::move(points));
                        });
  });
}

rc::Gen<std::vector<BezierPatch3>> any_patches() {
  return rc::gen::mapcat(rc::gen::inRange(1, 4), [](int count) {
    return rc::gen::container<std::vector<BezierPatch3>>(static_cast<std::size_t>(count), any_patch());
  });
}

// ---------------------------------------------------------------------------------------------
// Round trip and layout

RC_GTEST_PROP(Bpt, RoundTripIsBitExact, ()) {
  const std::vector<BezierPatch3> patches = *any_patches();
  const std::string text = format_bpt(patches);
  const std::vector<BezierPatch3> read = parse_bpt(text, "roundtrip.bpt");
  RC_ASSERT(bit_identical(read, patches));
  RC_ASSERT(format_bpt(read) == text);
}

TEST(Bpt, RoundTripKeepsSignedZeroSubnormalsAndExtremes) {
  std::vector<Vec3> points;
  for (double x : testing::extreme_doubles()) points.emplace_back(x, -x, x * 0.5);
  points.resize(12, Vec3(1, 2, 3));
  const std::vector<BezierPatch3> patches{BezierPatch3(2, 3, points)};  // non-square: 3 x 4 points
  const std::vector<BezierPatch3> read = parse_bpt(format_bpt(patches), "extremes.bpt");
  EXPECT_TRUE(bit_identical(read, patches));
  EXPECT_TRUE(std::signbit(read[0].control_points()[0].x()));
  EXPECT_FALSE(std::signbit(read[0].control_points()[0].y()));  // -(-0) = +0
}

TEST(Bpt, FirstIndexVariesFastest) {
  // Degrees (1, 2): 2 x 3 points, point k = i + 2 j is P_ij; x = i, y = j, z = 10 i + j.
  const std::string text =
      "1\n"
      "1 2\n"
      "0 0 0\n"    // k = 0: P_00
      "1 0 10\n"   // k = 1: P_10
      "0 1 1\n"    // k = 2: P_01
      "1 1 11\n"   // k = 3: P_11
      "0 2 2\n"    // k = 4: P_02
      "1 2 12\n";  // k = 5: P_12
  const std::vector<BezierPatch3> patches = parse_bpt(text, "layout.bpt");
  ASSERT_EQ(patches.size(), 1U);
  const BezierPatch3& patch = patches[0];
  EXPECT_EQ(patch.degree_u(), 1);
  EXPECT_EQ(patch.degree_v(), 2);
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 1; ++i) EXPECT_EQ(patch.control_point(i, j), Vec3(i, j, 10 * i + j)) << "P_" << i << j;
  }
  // Corners of the surface are corner points: F(1, 0) = P_10, F(0, 1) = P_02.
  EXPECT_EQ(patch.evaluate(1.0, 0.0), Vec3(1, 0, 10));
  EXPECT_EQ(patch.evaluate(0.0, 1.0), Vec3(0, 2, 2));
  // format_bpt writes the same order back.
  EXPECT_EQ(format_bpt(patches), text);
}

TEST(Bpt, HonoursTheDegreeLineOfEveryPatch) {
  const std::vector<BezierPatch3> patches{labelled_patch(0, 0), labelled_patch(2, 5), labelled_patch(5, 2),
                                          labelled_patch(3, 3), labelled_patch(6, 0)};
  const std::vector<BezierPatch3> read = parse_bpt(format_bpt(patches), "degrees.bpt");
  ASSERT_EQ(read.size(), patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p) EXPECT_EQ(read[p], patches[p]) << "patch " << p;
}

TEST(Bpt, DegreeLimitIsInclusive) {
  // Degree 64 (65 points) is the largest a file may declare; 65 is refused.
  std::string text = "1\n64 0\n";
  for (int i = 0; i <= 64; ++i) text += std::to_string(i) + " 0 0\n";
  const std::vector<BezierPatch3> read = parse_bpt(text, "max.bpt");
  ASSERT_EQ(read.size(), 1U);
  EXPECT_EQ(read[0].degree_u(), max_bpt_degree);
  EXPECT_EQ(read[0].control_point(64, 0), Vec3(64, 0, 0));
  text.replace(2, 4, "65 0");
  const auto error = parse_error(text);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->line(), 2);
  EXPECT_EQ(error->column(), 1);
}

TEST(Bpt, AcceptsWindowsLineEndingsBlankLinesAndSpacing) {
  const std::vector<BezierPatch3> expected = parse_bpt(with_line(0, ""), "plain.bpt");
  std::string crlf;
  for (const std::string& line : valid_lines) crlf += line + "\r\n";
  EXPECT_TRUE(bit_identical(parse_bpt(crlf, "crlf.bpt"), expected));
  const std::string spaced = "\n\n  1  \n\n\t1\t1\n0 0 0\n \n1   0 0\r\n\r\n0 1 0\n1 1 1";  // no final newline
  EXPECT_TRUE(bit_identical(parse_bpt(spaced, "spaced.bpt"), expected));
  // Other spellings of the same numbers.
  const std::string spellings = "1\n1 1\n0.0 -0 0e5\n1.000 0 0\n0 1e0 0\n10e-1 .1e1 1\n";
  const auto read = parse_bpt(spellings, "spellings.bpt");
  EXPECT_EQ(read, expected);
  EXPECT_TRUE(std::signbit(read[0].control_points()[0].y()));
}

// ---------------------------------------------------------------------------------------------
// Malformed input: every case is a ParseError at the right place, naming what was expected.

using testing::Malformed;

TEST(Bpt, MalformedTextIsAParseErrorAtTheRightPlace) {
  using namespace std::string_literals;
  // Positions: 1-based line and byte column; a missing value is reported just after the last
  // token before it, at the end of the data just after the last token of the file.
  const std::vector<Malformed> cases = {
      {"empty text", "", 1, 1, {"end of file", "number of patches"}},
      {"blank text", " \n\t\n\r\n", 1, 1, {"end of file", "number of patches"}},
      {"count 0", with_line(1, "0"), 1, 1, {"at least 1", "found 0"}},
      {"negative count", with_line(1, "-2"), 1, 1, {"at least 1", "found -2"}},
      {"count not an integer", with_line(1, "1.0"), 1, 1, {"number of patches", "integer", "'1.0'"}},
      {"count overflows", with_line(1, "99999999999999999999"), 1, 1, {"number of patches", "integer"}},
      {"two numbers on the count line", with_line(1, "1 1"), 1, 3, {"number of patches", "1 number", "found 2"}},
      {"count larger than the data", with_line(1, "2"), 6, 6, {"end of file", "degrees 'n m' of patch 1"}},
      {"huge count, little data", with_line(1, "1000000000000"), 6, 6, {"end of file", "patch 1"}},
      {"count near the int64 limit", with_line(1, "9223372036854775807"), 6, 6, {"end of file", "patch 1"}},
      {"one degree only", with_line(2, "1"), 2, 2, {"degrees 'n m' of patch 0", "2 numbers", "found 1"}},
      {"three degrees", with_line(2, "1 1 1"), 2, 5, {"degrees 'n m' of patch 0", "found 3"}},
      {"negative degree", with_line(2, "1 -1"), 2, 3, {"degree -1 of patch 0", "[0, 64]"}},
      {"degree 65", with_line(2, "65 1"), 2, 1, {"degree 65 of patch 0", "[0, 64]"}},
      {"absurd degree", with_line(2, "1 4000000000"), 2, 3, {"degree 4000000000", "[0, 64]"}},
      {"degree not an integer", with_line(2, "1.5 1"), 2, 1, {"degree n", "integer", "'1.5'"}},
      {"degree with garbage", with_line(2, "1 1;"), 2, 3, {"degree m", "'1;'"}},
      {"extra number on a point line", with_line(4, "1 0 0 7"), 4, 7, {"point 1 of patch 0", "'x y z'", "found 4"}},
      {"comment after a point", with_line(4, "1 0 0 # corner"), 4, 7, {"point 1 of patch 0", "found 5"}},
      {"missing number on a point line", with_line(4, "1 0"), 4, 4, {"point 1 of patch 0", "3 numbers", "found 2"}},
      {"commas instead of spaces", with_line(4, "1,0,0"), 4, 6, {"point 1 of patch 0", "found 1"}},
      {"missing point line", with_line(6, ""), 5, 6, {"end of file", "point 3 of patch 0"}},
      {"nan", with_line(5, "0 nan 0"), 5, 3, {"finite coordinate", "'nan'"}},
      {"NaN spelled otherwise", with_line(5, "0 1 -NaN"), 5, 5, {"finite coordinate", "'-NaN'"}},
      {"inf", with_line(5, "inf 1 0"), 5, 1, {"finite coordinate", "'inf'"}},
      {"-infinity", with_line(5, "0 1 -infinity"), 5, 5, {"finite coordinate", "'-infinity'"}},
      {"overflowing 1e999", with_line(6, "1 1 1e999"), 6, 5, {"finite coordinate", "'1e999'"}},
      {"non-numeric token", with_line(5, "0 1 x"), 5, 5, {"finite coordinate", "'x'"}},
      {"number with garbage", with_line(3, "0 0 0abc"), 3, 5, {"finite coordinate", "'0abc'"}},
      {"hexadecimal", with_line(3, "0x1p3 0 0"), 3, 1, {"finite coordinate", "'0x1p3'"}},
      {"trailing garbage", with_line(0, "") + "junk\n", 7, 1, {"after the last of 1 patches", "'junk'"}},
      {"trailing extra point", with_line(0, "") + "\n2 2 2\n", 8, 1, {"after the last of 1 patches", "'2'"}},
      {"binary garbage", "\x7f" "ELF\x02\x01\x01\x00\x00\xff\xfe"s, 1, 1, {"number of patches", "'\\x7fELF\\x02\\x01\\x01\\x00\\x00\\xff\\xfe'"}},
      {"binary garbage after a valid count", "1\n\x01\x02 \x03\n"s, 2, 1, {"degree n", "'\\x01\\x02'"}},
      {"error after CRLF lines", "1\r\n1 1\r\n0 0 0\r\n1 0 0\r\n0 nan 0\r\n1 1 1\r\n", 5, 3, {"finite coordinate", "'nan'"}},
      {"error after blank lines", "\n\n1\n\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1\n", 9, 4, {"point 3 of patch 0"}},
  };
  testing::expect_parse_errors(cases, "bad.bpt",
                               [](const std::string& text, const std::string& name) { parse_bpt(text, name); });
}

TEST(Bpt, LongGarbageTokenIsShortenedInTheMessage) {
  const auto error = parse_error(std::string(100000, 'z'));
  ASSERT_TRUE(error);
  EXPECT_LT(std::string(error->what()).size(), 200U) << error->what();
}

// Any damage to a valid text either still parses or is a ParseError: never another exception,
// never a crash (the sanitizer build checks memory).
RC_GTEST_PROP(Bpt, DamagedTextParsesOrIsAParseError, ()) {
  using namespace std::string_literals;
  std::string text = format_bpt(*any_patches());
  const int edits = *rc::gen::inRange(1, 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = *rc::gen::inRange<std::size_t>(0, text.size() + 1);
    switch (*rc::gen::inRange(0, 4)) {
      case 0: text.insert(at, 1, *rc::gen::arbitrary<char>()); break;
      case 1: text.erase(at, *rc::gen::inRange<std::size_t>(0, 20)); break;
      case 2: text.insert(at, *rc::gen::element(" "s, "\n"s, "\r\n"s, " 1"s, "nan"s, "-"s, "e999"s, "1e-400"s, "99999999999"s)); break;
      default: text.resize(at); break;
    }
  }
  try {
    const std::vector<BezierPatch3> patches = parse_bpt(text, "damaged.bpt");
    // Whatever was read is a valid patch set that writes and reads back unchanged.
    RC_ASSERT(!patches.empty());
    RC_ASSERT(bit_identical(parse_bpt(format_bpt(patches), "again.bpt"), patches));
  } catch (const ParseError& error) {
    RC_ASSERT(error.line() >= 1);
    RC_ASSERT(error.column() >= 1);
  }
}

// ---------------------------------------------------------------------------------------------
// The writer writes only what the reader reads.

TEST(Bpt, FormatRefusesWhatCannotBeRead) {
  EXPECT_THROW(format_bpt({}), InvalidInput);
  const std::vector<BezierPatch3> too_high{labelled_patch(max_bpt_degree + 1, 0)};
  EXPECT_THROW(format_bpt(too_high), InvalidInput);
  const std::vector<BezierPatch3> at_limit{labelled_patch(max_bpt_degree, 1)};
  EXPECT_EQ(parse_bpt(format_bpt(at_limit), "limit.bpt"), at_limit);
}

// ---------------------------------------------------------------------------------------------
// Files

TEST(BptFile, WriteThenReadGivesTheSamePatchesAndLeavesNoTemporaryFile) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "two.bpt";
  const std::vector<BezierPatch3> patches{labelled_patch(2, 5), labelled_patch(3, 3, -0.5)};
  write_bpt(path, patches);
  EXPECT_EQ(read_bpt(path), patches);
  EXPECT_EQ(file_content(path), format_bpt(patches));
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"two.bpt"});
}

TEST(BptFile, ExistingFileIsReplacedWhole) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "replace.bpt";
  const std::vector<BezierPatch3> long_set{labelled_patch(6, 6), labelled_patch(6, 6, 1), labelled_patch(6, 6, 2)};
  const std::vector<BezierPatch3> short_set{labelled_patch(0, 1)};
  write_bpt(path, long_set);
  write_bpt(path, short_set);
  EXPECT_EQ(file_content(path), format_bpt(short_set));  // no tail of the longer file remains
  EXPECT_EQ(read_bpt(path), short_set);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"replace.bpt"});
}

TEST(BptFile, RefusedWriteLeavesTheOldFileIntact) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "keep.bpt";
  const std::vector<BezierPatch3> original{labelled_patch(1, 1)};
  write_bpt(path, original);
  EXPECT_THROW(write_bpt(path, {}), InvalidInput);
  EXPECT_EQ(file_content(path), format_bpt(original));
  EXPECT_THROW(write_bpt(folder.path() / "new.bpt", {}), InvalidInput);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"keep.bpt"});
}

TEST(BptFile, WritingIntoAMissingFolderIsAnIoErrorAndLeavesNothing) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "missing" / "a.bpt";
  try {
    write_bpt(path, std::vector<BezierPatch3>{labelled_patch(1, 1)});
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& error) {
    EXPECT_EQ(error.path(), path.string());
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(folder.path() / "missing"));
  EXPECT_TRUE(folder.entries().empty());
}

TEST(BptFile, WritingOverAFolderIsAnIoErrorAndLeavesNothing) {
  const TemporaryDirectory folder;
  const fs::path target = folder.path() / "sub";
  fs::create_directory(target);
  put_file(target / "inside.txt", "kept");
  EXPECT_THROW(write_bpt(target, std::vector<BezierPatch3>{labelled_patch(1, 1)}), IoError);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(file_content(target / "inside.txt"), "kept");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"sub"});
}

TEST(BptFile, ReadingAMissingFileOrAFolderIsAnIoError) {
  const TemporaryDirectory folder;
  const fs::path missing = folder.path() / "absent.bpt";
  try {
    read_bpt(missing);
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& error) {
    EXPECT_EQ(error.path(), missing.string());
  }
  EXPECT_THROW(read_bpt(folder.path()), IoError);
  EXPECT_THROW(read_file(folder.path()), IoError);
}

TEST(BptFile, ParseErrorsNameTheFile) {
  const TemporaryDirectory folder;
  const fs::path empty = folder.path() / "empty.bpt";
  put_file(empty, "");
  try {
    read_bpt(empty);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.path(), empty.string());
    EXPECT_EQ(error.line(), 1);
    EXPECT_EQ(std::string(error.what()).rfind(empty.string() + ":1:1: ", 0), 0U) << error.what();
  }
  const fs::path bad = folder.path() / "bad.bpt";
  put_file(bad, with_line(5, "0 1 nan"));
  try {
    read_bpt(bad);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.path(), bad.string());
    EXPECT_EQ(error.line(), 5);
    EXPECT_EQ(error.column(), 5);
  }
}

TEST(BptFile, ReadsWindowsLineEndingsFromDisk) {
  const TemporaryDirectory folder;
  const fs::path path = folder.path() / "crlf.bpt";
  std::string crlf;
  for (const std::string& line : valid_lines) crlf += line + "\r\n";
  put_file(path, crlf);
  EXPECT_EQ(read_bpt(path), parse_bpt(with_line(0, ""), "lf.bpt"));
}

}  // namespace
}  // namespace patchwork
