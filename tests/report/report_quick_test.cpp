// The report program's quick mode, run as a program: the pipeline works end to end (patchwork,
// the peers that this machine has, the meter, the tables, data and plots, the NURBS section) and
// patchwork's measured error is within its bound on every row (the program fails otherwise).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/ci_environment.h"
#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

bool command_exists(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

// The quick report, run once for the tests of this file.
class ReportQuick : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = std::make_unique<testing::TemporaryDirectory>("patchwork_report");
    const fs::path out = folder_->path() / "performance.md";
    const std::string command = std::string("'") + PATCHWORK_REPORT + "' --quick --out '" + out.string() +
                                "' --data '" + data_dir().string() + "' > '" + (folder_->path() / "log").string() +
                                "' 2>&1";
    status_ = std::system(command.c_str());
    if (fs::exists(out)) markdown_ = testing::slurp(out);
  }
  static void TearDownTestSuite() { folder_.reset(); }
  void SetUp() override { ASSERT_EQ(status_, 0) << testing::slurp(folder_->path() / "log"); }

  static fs::path data_dir() { return folder_->path() / "performance"; }

  static inline std::unique_ptr<testing::TemporaryDirectory> folder_;
  static inline int status_ = -1;
  static inline std::string markdown_;
};

TEST_F(ReportQuick, WritesEverySectionWithMeasuredRows) {
  const std::string& md = markdown_;
  const fs::path data = data_dir();
  for (const char* heading : {"## 1. The teapot: patchwork", "## 2. The peers", "## 3. Plots", "## 4. Ratios",
                              "## 5. Throughput", "## 6. Hard cases", "## 7. Subdivision", "## 8. NURBS"}) {
    EXPECT_NE(md.find(heading), std::string::npos) << heading;
  }
  EXPECT_NE(md.find("On every row the measured error is within the a-priori bound."), std::string::npos);
  EXPECT_NE(md.find("| r = 0.001 |"), std::string::npos);
  EXPECT_TRUE(fs::exists(data / "patchwork_adaptive.dat"));
  EXPECT_TRUE(fs::exists(data / "plots.gp"));
  if (testing::tool_available(
          fs::exists(fs::path(PATCHWORK_SOURCE_DIR) / "report/threejs/node_modules/three") && command_exists("node"),
          "node or three.js (report/threejs/node_modules)")) {
    EXPECT_TRUE(fs::exists(data / "three_js.dat"));
    EXPECT_EQ(md.find("Not run: the npm"), std::string::npos);
  }
#ifdef PATCHWORK_HAVE_OCCT
  EXPECT_TRUE(fs::exists(data / "open_cascade.dat"));
#endif
  if (testing::tool_available(command_exists("gnuplot"), "gnuplot")) {
    EXPECT_TRUE(fs::exists(data / "error_vs_triangles.png"));
    EXPECT_TRUE(fs::exists(data / "error_vs_time.png"));
  }
}

// The cells of the first table row at or after `from` whose first cell is `first` (empty if none).
std::vector<std::string> row(const std::string& md, std::size_t from, const std::string& first) {
  const std::size_t start = md.find("\n| " + first + " |", from);
  if (start == std::string::npos) return {};
  const std::string line = md.substr(start + 1, md.find('\n', start + 1) - start - 1);
  std::vector<std::string> cells;
  std::istringstream in(line.substr(1));
  for (std::string cell; std::getline(in, cell, '|');) {
    const auto begin = cell.find_first_not_of(' ');
    cells.push_back(begin == std::string::npos ? "" : cell.substr(begin, cell.find_last_not_of(' ') - begin + 1));
  }
  return cells;
}

// A number as the report prints it ("12,826", "0.000502"); NaN if it is not one.
double number(std::string cell) {
  std::erase(cell, ',');
  try {
    std::size_t used = 0;
    const double value = std::stod(cell, &used);
    return used == cell.size() ? value : std::nan("");
  } catch (const std::exception&) {
    return std::nan("");
  }
}

// Section 8: for both shapes a patchwork row at tolerance 10^-3 whose measured distance is
// positive and within its bound and the tolerance, with its ideal count at that distance (from the
// closed form of report/nurbs_section.h) and the ratio of the two; and Open CASCADE's row at
// deflection 0.003 with patchwork's triangles interpolated at its measured distance.
TEST_F(ReportQuick, NurbsSectionHasMeasuredRowsForBothShapes) {
  const std::string& md = markdown_;
  const std::size_t section = md.find("## 8. NURBS");
  ASSERT_NE(section, std::string::npos);
  EXPECT_NE(md.find("On every patchwork row the measured distance is within the a-priori bound.", section),
            std::string::npos);
  const double pi = std::numbers::pi;
  for (const auto& [shape, area_times_curvature] : {std::pair{"sphere", 4 * pi}, std::pair{"torus", 8 * pi * pi}}) {
    const std::size_t at = md.find(std::string("**The ") + shape + "**", section);
    ASSERT_NE(at, std::string::npos) << shape;
    // tolerance | triangles | vertices | ms | bound | e_par | measured | ideal | triangles / ideal
    const std::vector<std::string> ours = row(md, at, "0.001");
    ASSERT_EQ(ours.size(), 9u) << shape;
    const double triangles = number(ours[1]);
    const double measured = number(ours[6]);
    const double ideal = number(ours[7]);
    EXPECT_GT(triangles, 100) << shape;
    EXPECT_GT(number(ours[3]), 0) << shape;
    EXPECT_GT(measured, 0) << shape;
    EXPECT_LE(measured, number(ours[4])) << shape;
    EXPECT_LE(number(ours[4]), 1e-3) << shape;
    EXPECT_NEAR(ideal, area_times_curvature / (2.598076211353316 * measured), 1e-2 * ideal) << shape;
    EXPECT_NEAR(number(ours[8]), triangles / ideal, 0.01) << shape;
    EXPECT_TRUE(fs::exists(data_dir() / ("nurbs_" + std::string(shape) + "_patchwork.dat"))) << shape;
#ifdef PATCHWORK_HAVE_OCCT
    // deflection | triangles | ms | measured | ideal | / ideal | patchwork triangles | ms | ratios
    const std::size_t occt = md.find("Open CASCADE (linear deflection", at);
    ASSERT_NE(occt, std::string::npos) << shape;
    const std::vector<std::string> theirs = row(md, occt, "0.003");
    ASSERT_EQ(theirs.size(), 10u) << shape;
    EXPECT_GT(number(theirs[1]), 100) << shape;
    EXPECT_GT(number(theirs[3]), 0) << shape;
    EXPECT_GT(number(theirs[6]), 0) << shape << ": " << theirs[6];
    EXPECT_NEAR(number(theirs[8]), number(theirs[1]) / number(theirs[6]), 0.01 * number(theirs[8])) << shape;
    EXPECT_TRUE(fs::exists(data_dir() / ("nurbs_" + std::string(shape) + "_open_cascade.dat"))) << shape;
#endif
  }
}

}  // namespace
}  // namespace patchwork
