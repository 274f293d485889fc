#pragma once
// The runs of the speed-vs-error report: one tessellation of the teapot by one method and
// setting, its counts, its time and its error as the meter (measure/hausdorff.h) measures it.

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "measure/hausdorff.h"
#include "report/peer_mesh.h"
#include "report/tradeoff.h"
#include "surfaces/patch_set.h"

namespace patchwork::performance {

inline constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

/// Why a build has no Open CASCADE runs.
inline constexpr const char* kWithoutOcct =
    "this build has no Open CASCADE (Debian's libocct-*-dev, installed by scripts/setup)";

struct Run {
  /// "patchwork adaptive", "patchwork uniform", "three.js", "Open CASCADE", ...
  std::string method;
  /// The setting in the method's own terms ("r = 1e-3", "N = 16", "deflection 1e-2").
  std::string setting;
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  /// Median and minimum seconds of the tessellation alone, one thread.
  double seconds = kNone;
  double seconds_min = kNone;
  /// Median seconds on two threads (patchwork only).
  double seconds_two_threads = kNone;
  /// Median seconds, one thread, through a PreparedSurface made once and one Tessellation
  /// reused from call to call: the per-frame call (patchwork only).
  double seconds_prepared = kNone;
  /// The method's own a-priori bound and its own measured error, absolute (patchwork only).
  double error_bound = kNone;
  double own_error = kNone;
  /// The meter's two-sided distance and its two sides, absolute.
  HausdorffDistance distance;
};

/// What the runs are measured with.
struct RunSettings {
  int repeats = 5;
  HausdorffOptions meter;
};

/// Median and minimum seconds of at least `repeats` calls of `work` (after one untimed call),
/// and of as many more as fit in a quarter second (up to 200): a few-millisecond run is
/// otherwise at the mercy of one interruption.
std::pair<double, double> median_seconds(int repeats, const std::function<void()>& work);

/// The runs as (error, cost) points for report/tradeoff.h: the two-sided distance divided by
/// `scale`, and the triangles or the seconds (one thread).
std::vector<TradeoffPoint> tradeoff(const std::vector<Run>& runs, double scale, bool by_time);

/// patchwork's tessellator at relative tolerances (adaptive) and at N x N per patch (uniform).
std::vector<Run> patchwork_runs(const PatchSet& teapot, std::span<const double> relative_tolerances,
                                std::span<const int> segments, const RunSettings& settings);

/// The meter on a peer's mesh, filling the run's counts and distance.
void measure_peer(const PatchSet& teapot, const PeerMesh& mesh, Run& run, const HausdorffOptions& meter);

/// three.js's TeapotGeometry through node (report/threejs/teapot.mjs writes the meshes and times
/// into `folder`); empty with `why` set when node or the three package is missing or it failed.
std::vector<Run> threejs_runs(const PatchSet& teapot, const std::filesystem::path& source_dir,
                              const std::filesystem::path& folder, std::span<const int> segments,
                              const RunSettings& settings, std::string& why);

/// Open CASCADE's BRepMesh at linear deflections (absolute) and one angular deflection; empty
/// with `why` set when this build has no Open CASCADE.
std::vector<Run> occt_runs(const PatchSet& teapot, std::span<const double> linear_deflections,
                           double angular_deflection, const std::string& method, const RunSettings& settings,
                           std::string& why);

}  // namespace patchwork::performance
