// `patchwork closest` and `patchwork raycast` as a user runs them: the JSON keys the README
// promises, answers equal to the library's, one-line errors naming the file or the argument.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "io/bpt.h"
#include "tests/support/cli_run.h"
#include "tests/support/temporary_directory.h"

namespace query_cli_test {
namespace {

using patchwork::testing::quote;
using patchwork::testing::run_patchwork;
using patchwork::testing::TemporaryDirectory;

const std::string teapot = quote(PATCHWORK_DATA_DIR "/teapot.bpt");

TEST(QueryCli, ClosestPrintsTheCertifiedAnswer) {
  const TemporaryDirectory folder;
  const auto run = run_patchwork(folder, "closest " + teapot + " 0 0 5 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  for (const char* key : {"distance", "point", "patch", "u", "v", "bound", "attained_more_than_once"})
    EXPECT_TRUE(json.contains(key)) << key;
  // Straight above the lid's knob, whose top is the pole at height 3.15.
  EXPECT_NEAR(json["distance"].get<double>(), 5 - 3.15, 1e-12);
  EXPECT_LE(json["bound"][0].get<double>(), json["distance"].get<double>());
  EXPECT_EQ(json["bound"][1].get<double>(), json["distance"].get<double>());
  // The foot is the patch's point at (u, v), to the last bit.
  const auto patches = patchwork::read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  const patchwork::Vec3 foot = patches.at(json["patch"].get<std::size_t>()).evaluate(json["u"].get<double>(), json["v"].get<double>());
  for (int c = 0; c < 3; ++c) EXPECT_EQ(json["point"][c].get<double>(), foot[c]);
  // Negative coordinates are numbers, not options; the text form names the interval.
  const auto text = run_patchwork(folder, "closest " + teapot + " 4 1 -2");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("certified"), std::string::npos);
}

TEST(QueryCli, RaycastPrintsEveryHitInOrder) {
  const TemporaryDirectory folder;
  // Along the x axis at height 1 through the spout, the body (twice) and the handle.
  const auto run = run_patchwork(folder, "raycast " + teapot + " --origin -5,0.1,1 --direction 1,0,0 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto hits = nlohmann::json::parse(run.out)["hits"];
  ASSERT_EQ(hits.size(), 5u);
  double previous = 0.0;
  for (const auto& hit : hits) {
    for (const char* key : {"t", "patch", "u", "v", "point", "normal", "grazing"}) EXPECT_TRUE(hit.contains(key)) << key;
    EXPECT_GT(hit["t"].get<double>(), previous);
    previous = hit["t"].get<double>();
    EXPECT_NEAR(hit["point"][0].get<double>(), -5 + previous, 1e-12);
    EXPECT_NEAR(hit["point"][1].get<double>(), 0.1, 1e-12);
  }
}

TEST(QueryCli, BadInputIsOneLine) {
  const TemporaryDirectory folder;
  const auto zero = run_patchwork(folder, "raycast " + teapot + " --origin 0,0,0 --direction 0,0,0");
  EXPECT_EQ(zero.exit_code, 1);
  EXPECT_NE(zero.err.find("teapot.bpt: ray_cast: argument 'direction' is the zero vector"), std::string::npos) << zero.err;
  const auto short_origin = run_patchwork(folder, "raycast " + teapot + " --origin 0,0 --direction 0,0,1");
  EXPECT_EQ(short_origin.exit_code, 1);
  EXPECT_NE(short_origin.err.find("--origin takes three numbers"), std::string::npos) << short_origin.err;
  const auto not_finite = run_patchwork(folder, "closest " + teapot + " 0 nan 0");
  EXPECT_EQ(not_finite.exit_code, 1);
  EXPECT_NE(not_finite.err.find("argument 'point' is not finite"), std::string::npos) << not_finite.err;
  const auto missing = run_patchwork(folder, "closest " + quote(folder.path().string() + "/missing.bpt") + " 0 0 0");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("missing.bpt"), std::string::npos);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1);
  const auto two = run_patchwork(folder, "closest " + teapot + " 0 0");
  EXPECT_EQ(two.exit_code, 2);
}

}  // namespace
}  // namespace query_cli_test
