// The report program's quick mode, run as a program: the pipeline works end to end (patchwork,
// the peers that this machine has, the meter, the tables, data and plots) and patchwork's
// measured error is within its bound on every row (the program fails otherwise).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/ci_environment.h"
#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

bool command_exists(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

TEST(ReportQuick, WritesEverySectionWithMeasuredRows) {
  testing::TemporaryDirectory folder("patchwork_report");
  const fs::path out = folder.path() / "performance.md";
  const fs::path data = folder.path() / "performance";
  const std::string command = std::string("'") + PATCHWORK_REPORT + "' --quick --out '" + out.string() + "' --data '" +
                              data.string() + "' > '" + (folder.path() / "log").string() + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << testing::slurp(folder.path() / "log");
  const std::string md = testing::slurp(out);
  for (const char* heading : {"## 1. The teapot: patchwork", "## 2. The peers", "## 3. Plots", "## 4. Ratios",
                              "## 5. Throughput", "## 6. Hard cases", "## 7. Subdivision"}) {
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

}  // namespace
}  // namespace patchwork
