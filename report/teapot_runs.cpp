#include "report/teapot_runs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.h"
#include "io/obj.h"
#include "report/format.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator.h"

#ifdef PATCHWORK_HAVE_OCCT
#include "report/occt_peer.h"
#endif

namespace patchwork::performance {
namespace {

Run patchwork_run(const PatchSet& teapot, const TessellationOptions& base, const std::string& method,
                  const std::string& setting, const RunSettings& settings) {
  Run run;
  run.method = method;
  run.setting = setting;
  TessellationOptions options = base;
  options.threads = 1;
  const Tessellation result = tessellate(teapot, options);
  run.triangles = result.mesh.triangle_count();
  run.vertices = result.mesh.vertex_count();
  run.error_bound = result.error_bound;
  run.own_error = result.measured_error;
  // The timed runs are what a user calls: render-ready output, no self-measurement.
  options.measure = false;
  std::tie(run.seconds, run.seconds_min) = median_seconds(settings.repeats, [&] { tessellate(teapot, options); });
  const PreparedSurface prepared(teapot);
  Tessellation reused;
  run.seconds_prepared = median_seconds(settings.repeats, [&] { tessellate(prepared, options, reused); }).first;
  options.threads = 2;
  run.seconds_two_threads = median_seconds(settings.repeats, [&] { tessellate(teapot, options); }).first;
  run.distance = hausdorff_distance(teapot.patches(), result.mesh.positions, result.mesh.indices, settings.meter);
  return run;
}

}  // namespace

std::pair<double, double> median_seconds(int repeats, const std::function<void()>& work) {
  work();
  std::vector<double> seconds;
  double total = 0.0;
  for (int r = 0; r < repeats || (total < 0.25 && r < 200); ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    total += seconds.back();
  }
  std::sort(seconds.begin(), seconds.end());
  const std::size_t mid = seconds.size() / 2;
  const double median = seconds.size() % 2 ? seconds[mid] : 0.5 * (seconds[mid - 1] + seconds[mid]);
  return {median, seconds.front()};
}

std::vector<TradeoffPoint> tradeoff(const std::vector<Run>& runs, double scale, bool by_time) {
  std::vector<TradeoffPoint> points;
  for (const Run& run : runs) {
    points.push_back({run.distance.hausdorff() / scale, by_time ? run.seconds : static_cast<double>(run.triangles)});
  }
  return points;
}

std::vector<Run> patchwork_runs(const PatchSet& teapot, std::span<const double> relative_tolerances,
                                std::span<const int> segments, const RunSettings& settings) {
  std::vector<Run> runs;
  for (double r : relative_tolerances) {
    TessellationOptions options;
    options.relative_tolerance = r;
    runs.push_back(patchwork_run(teapot, options, "patchwork adaptive", text("r = %g", r), settings));
  }
  for (int n : segments) {
    TessellationOptions options;
    options.segments = n;
    runs.push_back(patchwork_run(teapot, options, "patchwork uniform", text("N = %g", n), settings));
  }
  return runs;
}

void measure_peer(const PatchSet& teapot, const PeerMesh& mesh, Run& run, const HausdorffOptions& meter) {
  run.triangles = mesh.triangle_count();
  run.vertices = mesh.positions.size();
  run.distance = hausdorff_distance(teapot.patches(), mesh.positions, mesh.indices, meter);
}

std::vector<Run> threejs_runs(const PatchSet& teapot, const std::filesystem::path& source_dir,
                              const std::filesystem::path& folder, std::span<const int> segments,
                              const RunSettings& settings, std::string& why) {
  const std::filesystem::path script = source_dir / "report/threejs/teapot.mjs";
  if (!std::filesystem::exists(source_dir / "report/threejs/node_modules/three")) {
    why = "the npm package three is not installed (scripts/setup installs it in report/threejs)";
    return {};
  }
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    why = "node is not installed";
    return {};
  }
  std::filesystem::create_directories(folder);
  std::ostringstream command;
  command << "node '" << script.string() << "' --bpt '" << (source_dir / "data/teapot.bpt").string() << "' --out '"
          << folder.string() << "' --repeats " << std::max(settings.repeats, 3) << " --segments ";
  for (std::size_t k = 0; k < segments.size(); ++k) command << (k ? "," : "") << segments[k];
  command << " > '" << (folder / "threejs.log").string() << "' 2>&1";
  if (std::system(command.str().c_str()) != 0) {
    why = "report/threejs/teapot.mjs failed (see " + (folder / "threejs.log").string() + ")";
    return {};
  }
  std::ifstream in(folder / "threejs.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  std::vector<Run> runs;
  for (const nlohmann::json& entry : summary.at("runs")) {
    const int n = entry.at("segments").get<int>();
    Run run;
    run.method = "three.js";
    run.setting = text("N = %g", n);
    run.seconds = entry.at("seconds_median").get<double>();
    run.seconds_min = entry.at("seconds_min").get<double>();
    const FaceVertexMesh mesh = read_obj(folder / ("threejs_" + std::to_string(n) + ".obj"));
    PeerMesh peer;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) peer.positions.push_back(mesh.position(v));
    peer.indices = mesh.face_indices();
    measure_peer(teapot, peer, run, settings.meter);
    runs.push_back(std::move(run));
  }
  why = "three " + summary.at("three_version").get<std::string>() + "; patch corners land on control points to " +
        text("%.2g", summary.at("max_corner_deviation").get<double>()) + " after mapping back";
  return runs;
}

std::vector<Run> occt_runs(const PatchSet& teapot, std::span<const double> linear_deflections,
                           double angular_deflection, const std::string& method, const RunSettings& settings,
                           std::string& why) {
#ifdef PATCHWORK_HAVE_OCCT
  std::vector<Run> runs;
  for (double deflection : linear_deflections) {
    Run run;
    run.method = method;
    run.setting = text("%g", deflection);
    const OcctRun occt = timed_enough(
        [&](int repeats) { return occt_tessellate(teapot.patches(), deflection, angular_deflection, repeats); },
        settings.repeats);
    run.seconds = occt.seconds_median;
    run.seconds_min = occt.seconds_min;
    measure_peer(teapot, occt.mesh, run, settings.meter);
    runs.push_back(std::move(run));
  }
  why = "Open CASCADE " + occt_version();
  return runs;
#else
  static_cast<void>(teapot), static_cast<void>(linear_deflections), static_cast<void>(angular_deflection);
  static_cast<void>(method), static_cast<void>(settings);
  why = kWithoutOcct;
  return {};
#endif
}

}  // namespace patchwork::performance
