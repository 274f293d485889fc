// The patchwork command line, run as a user runs it: exit codes (0 success, 2 bad usage, 1 bad
// input or I/O failure with one line on stderr), the JSON keys it promises, files written whole
// or not at all, and glTF that passes the Khronos validator.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include "io/bpt.h"
#include "io/gltf.h"
#include "io/mesh_file.h"
#include "meshes/topology.h"
#include "tests/support/ci_environment.h"
#include "tests/support/cli_run.h"
#include "tests/support/temporary_directory.h"
#include "tests/support/moved_patches.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;
using testing::quote;
using testing::slurp;
constexpr auto& patchwork = testing::run_patchwork;

const std::string teapot = quote(PATCHWORK_DATA_DIR "/teapot.bpt");

bool validator_installed() {
  return std::system("node --version > /dev/null 2>&1") == 0 &&
         fs::exists(PATCHWORK_SOURCE_DIR "/tools/gltf-validate/node_modules/gltf-validator");
}

// Whether the Khronos validator can run; without it, a failure under CI=true (scripts/setup
// installs node and the validator).
bool validator_available() { return testing::tool_available(validator_installed(), "node or the glTF validator"); }

// Runs the Khronos validator; true when it reports no error and no warning.
bool validates(const fs::path& file) {
  const std::string command = "node " + quote(PATCHWORK_SOURCE_DIR "/tools/gltf-validate/validate.js") + " " +
                              quote(file.string()) + " > /dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

TEST(Cli, TessellatePrintsExactlyThePromisedJsonAndWritesValidGltf) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path glb = folder.path() / "teapot.glb";
  const CliRun run = patchwork(folder, "tessellate " + teapot + " -o " + quote(glb.string()) + " --relative-tolerance 1e-3 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  std::set<std::string> keys;
  for (const auto& [key, value] : summary.items()) keys.insert(key);
  EXPECT_EQ(keys, (std::set<std::string>{"patches", "triangles", "vertices", "seconds", "tessellation_seconds",
                                         "measure_seconds", "tolerance", "error_bound", "file_error_bound", "weld_gap",
                                         "measured_error", "culled_patches"}));
  EXPECT_EQ(summary["patches"], 32);
  // The two times split the run: tessellating and measuring, both positive.
  EXPECT_GT(summary["tessellation_seconds"].get<double>(), 0.0);
  EXPECT_GT(summary["measure_seconds"].get<double>(), 0.0);
  EXPECT_NEAR(summary["tessellation_seconds"].get<double>() + summary["measure_seconds"].get<double>(),
              summary["seconds"].get<double>(), 1e-9);
  EXPECT_LE(summary["measured_error"].get<double>(), summary["error_bound"].get<double>());
  EXPECT_LE(summary["error_bound"].get<double>(), summary["tolerance"].get<double>());
  EXPECT_NEAR(summary["tolerance"].get<double>(), 8.2048659851356535e-3, 1e-12);
  EXPECT_EQ(summary["culled_patches"], 0);
  ASSERT_TRUE(fs::exists(glb));
  if (!validator_installed()) PATCHWORK_SKIP_UNLESS_CI("node or tools/gltf-validate/node_modules missing: not validated");
  EXPECT_TRUE(validates(glb));
  // Every option that changes the file: tangents, atlas UVs, a camera, uniform segments, .gltf.
  for (const std::string& options :
       {std::string("--relative-tolerance 1e-2 --tangents --uv atlas"), std::string("--segments 4 --uv none"),
        std::string("--camera eye=8,-6,5 target=0,0,1.5 fov=40 width=640 height=480 --pixel-tolerance 1")}) {
    const fs::path gltf = folder.path() / "teapot.gltf";
    const CliRun other = patchwork(folder, "tessellate " + teapot + " -o " + quote(gltf.string()) + " " + options);
    ASSERT_EQ(other.exit_code, 0) << options << ": " << other.err;
    EXPECT_TRUE(validates(gltf)) << options;
  }
}

TEST(Cli, NoMeasureSkipsTheMeterAndKeepsTheMesh) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path measured = folder.path() / "measured.obj";
  const fs::path unmeasured = folder.path() / "unmeasured.obj";
  const CliRun a = patchwork(folder, "tessellate " + teapot + " -o " + quote(measured.string()) + " --json");
  const CliRun b = patchwork(folder, "tessellate " + teapot + " -o " + quote(unmeasured.string()) + " --json --no-measure");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json with = nlohmann::json::parse(a.out);
  const nlohmann::json without = nlohmann::json::parse(b.out);
  EXPECT_GT(with["measured_error"].get<double>(), 0.0);
  EXPECT_TRUE(without["measured_error"].is_null());
  EXPECT_TRUE(without["measure_seconds"].is_null());
  EXPECT_EQ(with["triangles"], without["triangles"]);
  EXPECT_EQ(with["error_bound"], without["error_bound"]);
  EXPECT_EQ(testing::slurp(measured), testing::slurp(unmeasured));
  const CliRun text = patchwork(folder, "tessellate " + teapot + " -o " + quote(unmeasured.string()) + " --no-measure");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("measured error: not measured (--no-measure)"), std::string::npos) << text.out;
}

TEST(Cli, TessellateReportsTheBoundOfTheFileAsWritten) {
  // The teapot moved to (1e5, -2e5, 3e4), at an absolute tolerance of 0.002: as plain floats the
  // positions would round by up to 0.0087, four times the tolerance. The file's bound adds the
  // (tiny) rounding of positions stored from the box's centre, and every vertex read back is
  // within it of the vertex the tessellator computed.
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::vector<BezierPatch3> patches =
      testing::moved(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"), Vec3(1e5, -2e5, 3e4));
  const fs::path moved = folder.path() / "moved.bpt";
  write_bpt(moved, patches);
  const fs::path glb = folder.path() / "moved.glb";
  const fs::path obj = folder.path() / "moved.obj";
  const CliRun run = patchwork(folder, "tessellate " + quote(moved.string()) + " -o " + quote(glb.string()) +
                                           " --tolerance 0.002 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  const double bound = summary["error_bound"].get<double>();
  const double file_bound = summary["file_error_bound"].get<double>();
  EXPECT_LE(bound, 0.002);
  EXPECT_GT(file_bound, bound);
  EXPECT_LT(file_bound - bound, 1e-3 * 0.002);
  // The same tessellation to OBJ (doubles, exactly): the file's bound is the mesh's.
  const CliRun to_obj = patchwork(folder, "tessellate " + quote(moved.string()) + " -o " + quote(obj.string()) +
                                              " --tolerance 0.002 --json");
  ASSERT_EQ(to_obj.exit_code, 0) << to_obj.err;
  const nlohmann::json obj_summary = nlohmann::json::parse(to_obj.out);
  EXPECT_EQ(obj_summary["file_error_bound"].get<double>(), obj_summary["error_bound"].get<double>());
  EXPECT_EQ(obj_summary["error_bound"].get<double>(), bound);
  // Every glTF vertex is within the file's rounding of the OBJ's (the same tessellation,
  // welded): a vertex of the glb at a welded OBJ position, at most file_bound - bound away.
  const FaceVertexMesh exact = read_mesh(obj);
  const RenderMesh back = read_gltf(glb);
  ASSERT_EQ(back.triangle_count(), exact.face_count());
  double largest = 0;
  for (std::size_t t = 0; t < back.triangle_count(); ++t) {
    const auto face = exact.face(t);
    for (int k = 0; k < 3; ++k) {
      const double distance = (back.positions[back.indices[3 * t + k]] - exact.position(face[k])).norm();
      largest = std::max(largest, distance);
    }
  }
  EXPECT_LE(largest, file_bound - bound);
  EXPECT_GT(largest, 0.0);
  if (validator_available()) {
    EXPECT_TRUE(validates(glb));
  }
}

// --cull-back-faces: the teapot is open, so by default (auto) only the frustum culls, as with
// never; always culls the patches facing away too. A bad value is refused before anything is
// read or written.
TEST(Cli, BackFaceCullingFollowsTheOption) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string glb = quote((folder.path() / "view.glb").string());
  const std::string view = " --camera eye=0.3,-1.2,9 target=0,0,1.5 fov=40 width=400 height=300 --json";
  const auto culled = [&](const std::string& mode) {
    const CliRun run = patchwork(folder, "tessellate " + teapot + " -o " + glb + view + mode);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["culled_patches"].get<int>();
  };
  const int automatic = culled("");
  EXPECT_EQ(automatic, culled(" --cull-back-faces auto"));
  EXPECT_EQ(automatic, culled(" --cull-back-faces never"));
  EXPECT_GT(culled(" --cull-back-faces always"), automatic);
  const CliRun bad = patchwork(folder, "tessellate " + teapot + " -o " + glb + view + " --cull-back-faces sometimes");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--cull-back-faces: 'sometimes' is not auto, always or never"), std::string::npos) << bad.err;
}

// The diagonal of the teapot's box from dense samples of every patch (a lower bound of the tight
// box's; the teapot's extremes lie on patch edges and poles, which the samples include).
double sampled_teapot_diagonal() {
  Eigen::AlignedBox3d box;
  for (const BezierPatch3& patch : read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt")) {
    for (int i = 0; i <= 64; ++i) {
      for (int j = 0; j <= 64; ++j) box.extend(patch.evaluate(i / 64.0, j / 64.0));
    }
  }
  return box.diagonal().norm();
}

TEST(Cli, TessellateWithoutAModeUsesTheDefaultRelativeTolerance) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string glb = quote((folder.path() / "teapot.glb").string());
  const CliRun run = patchwork(folder, "tessellate " + teapot + " -o " + glb + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  // 1e-3 of the tight box's diagonal (the control points' box is 0.9% larger: excluded).
  const double diagonal = sampled_teapot_diagonal();
  EXPECT_GE(summary["tolerance"].get<double>(), 1e-3 * diagonal * (1 - 1e-12));
  EXPECT_LE(summary["tolerance"].get<double>(), 1e-3 * diagonal * (1 + 1e-4));
  EXPECT_LE(summary["error_bound"].get<double>(), summary["tolerance"].get<double>());
  // The same tessellation as the explicit --relative-tolerance 1e-3.
  const CliRun given = patchwork(folder, "tessellate " + teapot + " -o " + glb + " --relative-tolerance 1e-3 --json");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_EQ(nlohmann::json::parse(given.out)["triangles"], summary["triangles"]);
  EXPECT_EQ(nlohmann::json::parse(given.out)["tolerance"], summary["tolerance"]);
  // The summary names the default; the given tolerance is not called one.
  const CliRun text = patchwork(folder, "tessellate " + teapot + " -o " + glb);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("(the default: 0.001 of the box diagonal;"), std::string::npos) << text.out;
  const CliRun given_text = patchwork(folder, "tessellate " + teapot + " -o " + glb + " --relative-tolerance 1e-3");
  EXPECT_EQ(given_text.out.find("default"), std::string::npos) << given_text.out;
  EXPECT_NE(given_text.out.find("(0.001 of the box diagonal)"), std::string::npos) << given_text.out;
  // --help names it.
  const CliRun help = patchwork(folder, "tessellate --help");
  EXPECT_NE(
      help.out.find("relative to the tight bounding-box diagonal (the default, 0.001, when no other mode is given)"),
      std::string::npos)
      << help.out;
}

TEST(Cli, SubdivideLimitWithoutAModeUsesTheDefaultRelativeTolerance) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string cube = quote(PATCHWORK_DATA_DIR "/cube.obj");
  const std::string glb = quote((folder.path() / "cube.glb").string());
  const CliRun run = patchwork(folder, "subdivide " + cube + " -o " + glb + " --limit --isolation 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const CliRun given =
      patchwork(folder, "subdivide " + cube + " -o " + glb + " --limit --isolation 2 --relative-tolerance 1e-3 --json");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const nlohmann::json a = nlohmann::json::parse(run.out);
  const nlohmann::json b = nlohmann::json::parse(given.out);
  EXPECT_EQ(a["tolerance"], b["tolerance"]);
  EXPECT_EQ(a["triangles"], b["triangles"]);
  // Relative to the cage's box: the unit cube's diagonal is sqrt(3).
  EXPECT_NEAR(a["tolerance"].get<double>(), 1e-3 * std::sqrt(3.0), 1e-15);
  const CliRun text = patchwork(folder, "subdivide " + cube + " -o " + glb + " --limit --isolation 2");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("(the default: 0.001 of the box diagonal;"), std::string::npos) << text.out;
  const CliRun help = patchwork(folder, "subdivide --help");
  EXPECT_NE(
      help.out.find("relative to the cage's bounding-box diagonal (the default, 0.001, when no other mode is given)"),
      std::string::npos)
      << help.out;
}

TEST(Cli, CurveDemoShowsWhatTheCurvesModuleDoes) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const CliRun run = patchwork(folder, "curve-demo --evaluations 1000");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Nothing stale: the tessellator exists and is its own command.
  EXPECT_EQ(run.out.find("does not exist"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("patchwork tessellate"), std::string::npos) << run.out;
  // Its three parts, and the arc length of the unit circle within the stated 1e-13 of 2 pi.
  EXPECT_NE(run.out.find("1. Accuracy near a root of multiplicity 20: p(t) = (t - 3/4)^20"), std::string::npos);
  EXPECT_NE(run.out.find("3. Speed: 1000 evaluations of a cubic in 3D"), std::string::npos);
  const std::size_t at = run.out.find("   length ");
  ASSERT_NE(at, std::string::npos) << run.out;
  const double length = std::stod(run.out.substr(at + 10));
  EXPECT_NEAR(length, 2.0 * std::acos(-1.0), 1e-13);
  // Each row: the compensated error within its bound; at t = 0.7 (condition 10^18) plain de
  // Casteljau has no correct digit, the compensated one is exact to rounding.
  int rows = 0;
  for (const char* t : {"0.4 ", "0.6 ", "0.7 ", "0.72 ", "0.74 "}) {
    const std::size_t row = run.out.find(std::string("\n   ") + t);
    ASSERT_NE(row, std::string::npos) << t << "\n" << run.out;
    std::istringstream fields(run.out.substr(row + 1));
    double at = 0, condition = 0, plain = 0, compensated = 0, bound = 0;
    fields >> at >> condition >> plain >> compensated >> bound;
    ASSERT_TRUE(fields) << t;
    EXPECT_LE(compensated, bound) << t;
    if (at == 0.7) {
      EXPECT_GT(plain, 1.0) << run.out;
      EXPECT_LT(compensated, 1e-15) << run.out;
    }
    ++rows;
  }
  EXPECT_EQ(rows, 5);
}

TEST(Cli, TessellateWritesALevelOfDetailChain) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path gltf = folder.path() / "teapot.gltf";
  const CliRun run =
      patchwork(folder, "tessellate " + teapot + " -o " + quote(gltf.string()) + " --relative-tolerance 1e-3 --lod 4,16");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("level 2:"), std::string::npos) << run.out;
  std::ifstream in(gltf);
  const nlohmann::json document = nlohmann::json::parse(in);
  ASSERT_EQ(document["nodes"].size(), 3u);
  EXPECT_EQ(document["nodes"][0]["extensions"]["MSFT_lod"]["ids"], nlohmann::json::parse("[1, 2]"));
  // Coverage where the next level's error is half a pixel on 1080 rows: 0.5 D / (eps 1080),
  // eps = r D, so 0.5 / (r 1080) for r = 4e-3 and 1.6e-2 (the box diagonal D cancels).
  const nlohmann::json& coverage = document["nodes"][0]["extras"]["MSFT_screencoverage"];
  ASSERT_EQ(coverage.size(), 3u);
  EXPECT_NEAR(coverage[0].get<double>(), 0.5 / (4e-3 * 1080), 1e-9);
  EXPECT_NEAR(coverage[1].get<double>(), 0.5 / (1.6e-2 * 1080), 1e-9);
  EXPECT_EQ(coverage[2].get<double>(), 0.0);
  // Coarser levels have fewer triangles.
  std::vector<std::int64_t> triangles;
  for (const auto& mesh : document["meshes"]) {
    triangles.push_back(document["accessors"][mesh["primitives"][0]["indices"].get<int>()]["count"].get<std::int64_t>() / 3);
  }
  ASSERT_EQ(triangles.size(), 3u);
  EXPECT_GT(triangles[0], triangles[1]);
  EXPECT_GT(triangles[1], triangles[2]);
  if (!validator_installed()) PATCHWORK_SKIP_UNLESS_CI("node or tools/gltf-validate/node_modules missing: not validated");
  EXPECT_TRUE(validates(gltf));
}

TEST(Cli, TessellateToAMeshFormatKeepsThePatchSetsTopology) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path obj = folder.path() / "teapot.obj";
  const CliRun run = patchwork(folder, "tessellate " + teapot + " -o " + quote(obj.string()) + " --tolerance 0.01");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("measured error"), std::string::npos);
  const TopologyReport report = analyze(read_mesh(obj));
  EXPECT_EQ(report.components, 4);
  EXPECT_EQ(report.boundary_loops, 6);
  EXPECT_TRUE(report.manifold);
  const CliRun info = patchwork(folder, "info " + quote(obj.string()) + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["components"], 4);
}

TEST(Cli, ConvertBetweenMeshFormatsAndGltfKeepsTheMesh) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path obj = folder.path() / "teapot.obj";
  ASSERT_EQ(patchwork(folder, "tessellate " + teapot + " -o " + quote(obj.string()) + " --segments 6").exit_code, 0);
  const fs::path glb = folder.path() / "teapot.glb";
  const fs::path ply = folder.path() / "back.ply";
  const CliRun to_glb = patchwork(folder, "convert " + quote(obj.string()) + " " + quote(glb.string()));
  ASSERT_EQ(to_glb.exit_code, 0) << to_glb.err;
  const CliRun back = patchwork(folder, "convert " + quote(glb.string()) + " " + quote(ply.string()));
  ASSERT_EQ(back.exit_code, 0) << back.err;
  // Same faces over the same (float-rounded) points. glTF has no welding of its own: reading
  // welds equal positions, which joins the two vertices the tessellator keeps where the handle
  // touches the body; everything else is unchanged.
  const TopologyReport before = analyze(read_mesh(obj));
  const TopologyReport after = analyze(read_mesh(ply));
  EXPECT_EQ(after.vertices, before.vertices - 1);
  EXPECT_EQ(after.faces, before.faces);
  EXPECT_EQ(after.components, before.components);
  EXPECT_EQ(after.boundary_loops, before.boundary_loops);
  if (validator_available()) {
    EXPECT_TRUE(validates(glb));
  }
  const CliRun bad = patchwork(folder, "convert " + quote(obj.string()) + " " + quote((folder.path() / "x.stl").string()));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(lines(bad.err), 1);
}

TEST(Cli, ConvertTriangulatesANonConvexPolygonToGltf) {
  // One L-shaped hexagon of area 3, counter-clockwise seen from +z, from corner (2, 1): the fan
  // from it has a clockwise triangle (2, 1) (1, 1) (1, 2) over the notch, 4 triangles of total
  // area 4.
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path obj = folder.path() / "l.obj";
  std::ofstream(obj) << "v 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nf 1 2 3 4 5 6\n";
  const fs::path glb = folder.path() / "l.glb";
  const CliRun run = patchwork(folder, "convert " + quote(obj.string()) + " " + quote(glb.string()));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const RenderMesh mesh = read_gltf(glb);
  ASSERT_EQ(mesh.triangle_count(), 4u);
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    const Vec3 n = (b - a).cross(c - a) / 2;  // small integers: exact
    EXPECT_EQ(n.x(), 0) << t;
    EXPECT_EQ(n.y(), 0) << t;
    EXPECT_GT(n.z(), 0) << "triangle " << t << " turns against the polygon";
    area += std::abs(n.z());
  }
  EXPECT_EQ(area, 3.0);
}

TEST(Cli, SubdivideRefinesAMeshAndTessellatesItsLimit) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string cube = quote(PATCHWORK_DATA_DIR "/cube.obj");
  const fs::path refined = folder.path() / "refined.obj";
  const CliRun run = patchwork(folder, "subdivide " + cube + " -o " + quote(refined.string()) + " --levels 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_EQ(summary["faces"], 96);
  EXPECT_EQ(summary["euler"], 2);
  EXPECT_EQ(summary["genus"], 0);
  EXPECT_EQ(analyze(read_mesh(refined)).faces, 96);

  const fs::path limit = folder.path() / "limit.glb";
  const CliRun tessellated =
      patchwork(folder, "subdivide " + cube + " -o " + quote(limit.string()) + " --limit --relative-tolerance 1e-3 --json");
  ASSERT_EQ(tessellated.exit_code, 0) << tessellated.err;
  const nlohmann::json result = nlohmann::json::parse(tessellated.out);
  EXPECT_EQ(result["euler"], 2);
  EXPECT_EQ(result["boundary_loops"], 0);
  EXPECT_LE(result["measured_error"].get<double>(), result["error_bound"].get<double>());
  EXPECT_LE(result["error_bound"].get<double>(), result["tolerance"].get<double>());
  EXPECT_GT(result["isolation_deviation"].get<double>(), 0.0);
  if (validator_available()) {
    EXPECT_TRUE(validates(limit));
  }

  // Loop needs triangles; a tolerance needs --limit; a non-manifold cage is refused: one line, no file.
  const fs::path book = folder.path() / "book.obj";
  std::ofstream(book) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  const fs::path output = folder.path() / "out.glb";
  const std::string o = " -o " + quote(output.string());
  for (const std::string& arguments : {"subdivide " + cube + o + " --scheme loop", "subdivide " + cube + o + " --tolerance 0.1",
                                       "subdivide " + cube + o + " --scheme doo-sabin",
                                       "subdivide " + cube + o + " --levels 11",
                                       "subdivide " + quote(book.string()) + o}) {
    const CliRun bad = patchwork(folder, arguments);
    EXPECT_EQ(bad.exit_code, 1) << arguments;
    EXPECT_EQ(lines(bad.err), 1) << arguments << "\n" << bad.err;
    EXPECT_FALSE(fs::exists(output)) << arguments;
  }
}

// A 6 x 4 quad torus as OBJ text, the faces f with flip(f) wound the other way (all corners
// after the first reversed).
std::string torus_obj(const std::function<bool(int)>& flip) {
  std::ostringstream out;
  out.precision(17);
  constexpr int rows = 6, cols = 4;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double a = 2 * M_PI * i / rows, b = 2 * M_PI * j / cols;
      out << "v " << (3 + std::cos(b)) * std::cos(a) << " " << (3 + std::cos(b)) * std::sin(a) << " " << std::sin(b)
          << "\n";
    }
  }
  const auto id = [](int i, int j) { return (i % rows) * cols + j % cols + 1; };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const int f = i * cols + j;
      if (flip(f)) {
        out << "f " << id(i, j) << " " << id(i, j + 1) << " " << id(i + 1, j + 1) << " " << id(i + 1, j) << "\n";
      } else {
        out << "f " << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << " " << id(i, j + 1) << "\n";
      }
    }
  }
  return out.str();
}

TEST(Cli, SubdivideOrientsAnInconsistentlyWoundCageAndSaysSo) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path consistent = folder.path() / "torus.obj";
  const fs::path flipped = folder.path() / "flipped.obj";
  std::ofstream(consistent) << torus_obj([](int) { return false; });
  // 5 of the 24 faces, face 0 among them.
  std::ofstream(flipped) << torus_obj([](int f) { return f % 5 == 0; });
  const fs::path a = folder.path() / "a.obj";
  const fs::path b = folder.path() / "b.obj";
  const CliRun reference =
      patchwork(folder, "subdivide " + quote(consistent.string()) + " -o " + quote(a.string()) + " --levels 2 --json");
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  EXPECT_EQ(reference.err, "");
  const CliRun run =
      patchwork(folder, "subdivide " + quote(flipped.string()) + " -o " + quote(b.string()) + " --levels 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "patchwork: " + flipped.string() + ": 5 of 24 faces flipped to orient the mesh consistently\n");
  // The same surface, written byte for byte the same, and the same report.
  EXPECT_EQ(slurp(a), slurp(b));
  nlohmann::json mine = nlohmann::json::parse(run.out), theirs = nlohmann::json::parse(reference.out);
  for (const char* key : {"faces", "vertices", "euler", "genus", "boundary_loops"})
    EXPECT_EQ(mine[key], theirs[key]) << key;
  EXPECT_EQ(mine["faces"], 24 * 16);
  EXPECT_EQ(mine["genus"], 1);
}

TEST(Cli, SubdivideRefinesANonOrientableCageAndRefusesItsLimit) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  // A Moebius band of four quads: the last one glued to the first with a twist.
  const fs::path band = folder.path() / "band.obj";
  std::ofstream(band) << "v 0.5 0 0\nv 0 0.646 -0.354\nv 0 1.354 0.354\nv 1.5 0 0\nv -1 0 -0.5\nv -1 0 0.5\n"
                         "v 0 -1.354 -0.354\nv 0 -0.646 0.354\nf 1 2 3 4\nf 2 5 6 3\nf 5 7 8 6\nf 7 4 1 8\n";
  const fs::path refined = folder.path() / "refined.obj";
  const CliRun run =
      patchwork(folder, "subdivide " + quote(band.string()) + " -o " + quote(refined.string()) + " --levels 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "patchwork: " + band.string() +
                         ": the mesh is not orientable; its 1 edge walked the same way by both faces refined as a "
                         "non-manifold seam (infinitely sharp)\n");
  const TopologyReport report = analyze(read_mesh(refined));
  EXPECT_EQ(report.faces, 4 * 16);
  EXPECT_EQ(report.euler, 0);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_FALSE(report.orientable);
  EXPECT_TRUE(report.manifold);
  EXPECT_EQ(nlohmann::json::parse(run.out)["faces"], 64);
  // The limit surface needs an orientation: refused, one line naming the file, nothing written.
  const fs::path limit = folder.path() / "limit.glb";
  const CliRun refused =
      patchwork(folder, "subdivide " + quote(band.string()) + " -o " + quote(limit.string()) + " --limit");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(lines(refused.err), 1) << refused.err;
  EXPECT_EQ(refused.err.rfind("patchwork: " + band.string() + ": subdivide --limit: the cage is not orientable", 0), 0u)
      << refused.err;
  EXPECT_FALSE(fs::exists(limit));
}

TEST(Cli, InfoOnAPatchSetGivesItsAdjacency) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const CliRun run = patchwork(folder, "info " + teapot + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["patches"], 32);
  EXPECT_EQ(report["shared_edges"], 52);
  EXPECT_EQ(report["open_edges"], 16);
  EXPECT_EQ(report["collapsed_edges"], 8);
  EXPECT_EQ(report["boundary_loops"], 6);
}

const std::string nurbs_torus = quote(PATCHWORK_DATA_DIR "/nurbs_torus.obj");

// A free-form OBJ (data/nurbs_torus.obj: one rational B-spline surface, the torus R = 2,
// r = 1/2) goes where a BPT file goes: tessellate with its options and JSON, info with the
// surfaces and the patch set.
TEST(Cli, FreeformObjIsTessellatedAndReportedLikeABptFile) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path glb = folder.path() / "torus.glb";
  const CliRun run =
      patchwork(folder, "tessellate " + nurbs_torus + " -o " + quote(glb.string()) + " --tolerance 1e-3 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_EQ(summary["patches"], 16);
  EXPECT_LE(summary["measured_error"].get<double>(), summary["error_bound"].get<double>());
  EXPECT_LE(summary["error_bound"].get<double>(), 1e-3);
  // Every vertex written lies on the torus within the file's bound, and the mesh is closed.
  const RenderMesh mesh = read_gltf(glb);
  double worst = 0.0;
  for (const Vec3& p : mesh.positions) worst = std::max(worst, std::abs(std::hypot(std::hypot(p.x(), p.y()) - 2.0, p.z()) - 0.5));
  EXPECT_LE(worst, summary["file_error_bound"].get<double>());
  const TopologyReport topology = analyze(welded_faces(mesh));
  EXPECT_TRUE(topology.closed);
  EXPECT_EQ(topology.euler, 0);
  for (const std::string& options : {std::string("--segments 4 --uv atlas --tangents"),
                                     std::string("--camera eye=8,-6,5 target=0,0,0 fov=40 width=640 height=480 --pixel-tolerance 1")}) {
    const CliRun other = patchwork(folder, "tessellate " + nurbs_torus + " -o " + quote(glb.string()) + " " + options);
    EXPECT_EQ(other.exit_code, 0) << options << ": " << other.err;
  }
  const CliRun info = patchwork(folder, "info " + nurbs_torus + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json report = nlohmann::json::parse(info.out);
  EXPECT_EQ(report["patches"], 16);
  EXPECT_EQ(report["rational_patches"], 16);
  EXPECT_EQ(report["closed"], true);
  ASSERT_EQ(report["surfaces"].size(), 1u);
  const nlohmann::json& surface = report["surfaces"][0];
  EXPECT_EQ(surface["name"], "torus");
  EXPECT_EQ(surface["basis"], "bspline");
  EXPECT_EQ(surface["rational"], true);
  EXPECT_EQ(surface["degree"], nlohmann::json({2, 2}));
  EXPECT_EQ(surface["spans"], nlohmann::json({4, 4}));
  EXPECT_EQ(surface["continuity_u"], nlohmann::json({0, 0, 0}));
  EXPECT_NEAR(report["area"].get<double>(), 4 * M_PI * M_PI * 2.0 * 0.5, 1e-8);
  const CliRun text = patchwork(folder, "info " + nurbs_torus);
  EXPECT_NE(text.out.find("surface 'torus' (line 87): rational bspline, degrees 2 x 2, 9 x 9 control points, 4 x 4 spans"),
            std::string::npos)
      << text.out;
}

// BPT to free-form OBJ and back gives the same patches bit for bit, and the OBJ tessellates as
// the BPT does; a rational surface is refused as BPT, naming the file, and nothing is written.
TEST(Cli, ConvertBetweenBptAndFreeformObj) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path obj = folder.path() / "teapot.obj";
  const fs::path bpt = folder.path() / "again.bpt";
  ASSERT_EQ(patchwork(folder, "convert " + teapot + " " + quote(obj.string())).exit_code, 0);
  ASSERT_EQ(patchwork(folder, "convert " + quote(obj.string()) + " " + quote(bpt.string())).exit_code, 0);
  const std::vector<BezierPatch3> original = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  const std::vector<BezierPatch3> again = read_bpt(bpt);
  ASSERT_EQ(again.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) EXPECT_EQ(again[k].control_points(), original[k].control_points()) << k;
  const CliRun from_bpt = patchwork(folder, "tessellate " + teapot + " -o " + quote((folder.path() / "a.obj").string()) + " --json");
  const CliRun from_obj = patchwork(folder, "tessellate " + quote(obj.string()) + " -o " + quote((folder.path() / "b.obj").string()) + " --json");
  ASSERT_EQ(from_obj.exit_code, 0) << from_obj.err;
  EXPECT_EQ(nlohmann::json::parse(from_obj.out)["triangles"], nlohmann::json::parse(from_bpt.out)["triangles"]);
  EXPECT_EQ(slurp(folder.path() / "a.obj"), slurp(folder.path() / "b.obj"));
  const fs::path refused = folder.path() / "torus.bpt";
  const CliRun rational = patchwork(folder, "convert " + nurbs_torus + " " + quote(refused.string()));
  EXPECT_EQ(rational.exit_code, 1);
  EXPECT_EQ(lines(rational.err), 1) << rational.err;
  EXPECT_NE(rational.err.find("nurbs_torus.obj: 16 of its 16 Bezier patches are rational"), std::string::npos) << rational.err;
  EXPECT_FALSE(fs::exists(refused));
}

// Two B-spline surfaces that meet along an edge (the second continues the first in x), each
// over a range inside its knots: one patch set, one component; `patches` lists both surfaces;
// `convert` writes the file again, and refuses it as a mesh.
TEST(Cli, SeveralFreeformSurfacesFormOnePatchSet) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path obj = folder.path() / "two.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0.5\nv 2 0 0\nv 0 1 0\nv 1 1 0.5\nv 2 1 0\n"
                        "v 3 0 1\nv 4 0 0\nv 3 1 1\nv 4 1 0\n"
                        "g first\ncstype bspline\ndeg 2 1\nsurf 0 1 0 1 1 2 3 4 5 6\nparm u 0 0 0 1 1 1\nparm v 0 0 1 1\nend\n"
                        "g second\ncstype bspline\ndeg 2 1\nsurf 0 1 0 1 3 7 8 6 9 10\nparm u 0 0 0 1 1 1\nparm v 0 0 1 1\nend\n";
  const CliRun run = patchwork(folder, "patches " + quote(obj.string()) + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["patches"], 2);
  EXPECT_EQ(report["shared_edges"], 1);
  ASSERT_EQ(report["surfaces"].size(), 2u);
  EXPECT_EQ(report["surfaces"][1]["name"], "second");
  EXPECT_EQ(report["surfaces"][1]["rational"], false);
  const fs::path out = folder.path() / "out.obj";
  const CliRun tess = patchwork(folder, "tessellate " + quote(obj.string()) + " -o " + quote(out.string()) + " --tolerance 1e-3");
  ASSERT_EQ(tess.exit_code, 0) << tess.err;
  EXPECT_EQ(analyze(read_mesh(out)).components, 1);
  const fs::path again = folder.path() / "again.obj";
  ASSERT_EQ(patchwork(folder, "convert " + quote(obj.string()) + " " + quote(again.string())).exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(patchwork(folder, "patches " + quote(again.string()) + " --json").out)["shared_edges"], 1);
  const CliRun mesh = patchwork(folder, "convert " + quote(obj.string()) + " " + quote((folder.path() / "x.glb").string()));
  EXPECT_EQ(mesh.exit_code, 1);
  EXPECT_NE(mesh.err.find("two.obj: convert to a mesh format reads meshes; this is a file of patches"), std::string::npos)
      << mesh.err;
  EXPECT_FALSE(fs::exists(folder.path() / "x.glb"));
}

// A run shows its stages on stderr, once it has taken PATCHWORK_PROGRESS_AFTER seconds (1 by
// default), when stderr is a terminal (util-linux `script` gives it one), and says nothing when
// it is a file. With 0 every stage of a short run shows: the test does not depend on how fast
// the machine is (it did, with a run made long enough to pass the second: a fast run's
// tessellation ended within it). Release only, as before.
#ifndef PATCHWORK_ENABLE_ASSERTS
TEST(Cli, ProgressOnlyOnATerminal) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string glb = quote((folder.path() / "fine.glb").string());
  const std::string arguments = "tessellate " + teapot + " -o " + glb + " --segments 16";
  ASSERT_EQ(::setenv("PATCHWORK_PROGRESS_AFTER", "0", 1), 0);
  const CliRun quiet = patchwork(folder, arguments);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  if (std::system("script --version > /dev/null 2>&1") != 0) {
    PATCHWORK_SKIP_UNLESS_CI("util-linux script (Debian's essential bsdutils) missing: no terminal to test with");
  }
  const fs::path log = folder.path() / "terminal.txt";
  const std::string command = "script -qec " + quote(quote(PATCHWORK_CLI) + " " + arguments + " > /dev/null") + " " +
                              quote(log.string()) + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string shown = slurp(log);
  EXPECT_NE(shown.find("patchwork: read"), std::string::npos) << shown;
  EXPECT_NE(shown.find("patchwork: tessellated in"), std::string::npos) << shown;
  EXPECT_NE(shown.find("patchwork: wrote"), std::string::npos) << shown;
  // The default second: a run this short shows nothing, terminal or not.
  ASSERT_EQ(::unsetenv("PATCHWORK_PROGRESS_AFTER"), 0);
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(slurp(log).find("patchwork: read"), std::string::npos) << slurp(log);
}
#endif

TEST(Cli, BadInputFailsWithOneLineAndWritesNothing) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const fs::path malformed = folder.path() / "bad.bpt";
  std::ofstream(malformed) << "2\n3 3\n0 0 0\n";
  const fs::path output = folder.path() / "out.glb";
  const std::string o = " -o " + quote(output.string());
  for (const std::string& arguments :
       {"tessellate " + quote((folder.path() / "missing.bpt").string()) + o + " --tolerance 0.01",
        "tessellate " + quote(malformed.string()) + o + " --tolerance 0.01",
        "tessellate " + teapot + o + " --tolerance -0.01", "tessellate " + teapot + o + " --relative-tolerance 0",
        "tessellate " + teapot + o + " --segments 0",
        "tessellate " + teapot + " -o " + quote((folder.path() / "no" / "such" / "folder.glb").string()) + " --segments 2",
        "tessellate " + teapot + " -o " + quote((folder.path() / "teapot.stl").string()) + " --segments 2",
        "tessellate " + teapot + o + " --camera eye=0,0,0 target=0,0,0 fov=40 width=10 height=10",
        "tessellate " + teapot + o + " --relative-tolerance 1e-2 --lod 0.5",
        "tessellate " + teapot + o + " --relative-tolerance 1e-2 --lod 4,2",
        "tessellate " + teapot + o + " --segments 4 --lod 2",
        "tessellate " + teapot + " -o " + quote((folder.path() / "teapot.obj").string()) + " --tolerance 0.1 --lod 2"}) {
    const CliRun run = patchwork(folder, arguments);
    EXPECT_EQ(run.exit_code, 1) << arguments;
    EXPECT_EQ(lines(run.err), 1) << arguments << "\n" << run.err;
    EXPECT_EQ(run.err.rfind("patchwork: ", 0), 0u) << run.err;
    EXPECT_EQ(folder.entries(), std::vector<std::string>{"bad.bpt"}) << arguments;
  }
}

TEST(Cli, BadUsageExitsWithTwo) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const std::string o = " -o " + quote((folder.path() / "out.glb").string());
  for (const std::string& arguments :
       {std::string("tessellate"), "tessellate " + teapot, "tessellate " + teapot + o + " --segments 4 --tolerance 1",
        "tessellate " + teapot + o + " --no-such-option", std::string("no-such-command"), std::string("")}) {
    const CliRun run = patchwork(folder, arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.err;
    EXPECT_TRUE(folder.entries().empty()) << arguments;
  }
}

TEST(Cli, HelpAndVersion) {
  const testing::TemporaryDirectory folder("patchwork_cli_test");
  const CliRun version = patchwork(folder, "--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, "patchwork 0.1.0\n");
  for (const std::string command : {"", "tessellate ", "info ", "patches ", "curve-demo ", "convert "}) {
    const CliRun help = patchwork(folder, command + "--help");
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_NE(help.out.find("Usage"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace patchwork
