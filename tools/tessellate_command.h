#pragma once
// `patchwork tessellate IN.bpt -o OUT.(glb|gltf|obj|off|ply) [--tolerance E |
// --relative-tolerance R | --segments N | --camera ... --pixel-tolerance T] [--threads T]
// [--uv none|patch|atlas] [--tangents] [--no-split] [--crease-angle DEG] [--lod F1,F2,...] [--json]`.
// Without a mode the relative tolerance is 1e-3 (tools/default_tolerance.h), and the summary says so.
//
// Prints patches, triangles, vertices, seconds (the tessellation alone, every level with --lod), the absolute tolerance,
// the guaranteed error bound, the file's bound, the measured error and the culled patches; with
// --json one object with exactly the keys patches, triangles, vertices, seconds, tolerance,
// error_bound, file_error_bound, weld_gap, measured_error, culled_patches. error_bound is the mesh's (in
// double); file_error_bound is the file's: error_bound plus the bound on the float rounding of
// the positions glTF stores (GltfEncoding::position_rounding, io/gltf.h), and error_bound itself
// for OBJ, OFF and PLY, which hold the doubles exactly. OBJ, OFF and PLY get the welded
// triangles (positions only); glTF gets the render mesh (normals, UVs, tangents).
//
// --lod F1,F2,... adds coarser levels of detail to a glTF file (MSFT_lod, io/gltf.h): level k is
// tessellated at F_k times the tolerance. Each level's screen coverage hint is where the next
// level's error is --pixel-tolerance pixels (0.5 by default) on a screen 1080 pixels high when
// the surface's box diagonal spans that fraction of it: coverage_k = tau D / (eps_{k+1} 1080),
// clamped to 1, and 0 for the coarsest level. The summary lists every level; the JSON object
// speaks of level 0 (its keys do not change).

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace patchwork::tools {

struct TessellateArguments {
  std::string input;
  std::string output;
  std::optional<double> tolerance;
  std::optional<double> relative_tolerance;
  std::optional<int> segments;
  /// key=value tokens: eye=x,y,z target=x,y,z fov=deg width=px height=px [up=x,y,z].
  std::vector<std::string> camera;
  double pixel_tolerance = 0.5;
  /// With --camera: auto (back faces culled only on shells that bound a solid, seen from
  /// outside), always or never (BackFaceCulling).
  std::string cull_back_faces = "auto";
  int threads = 0;
  std::string uv = "patch";
  bool tangents = false;
  bool no_split = false;
  /// Skip the measured error (the guaranteed bound is computed either way).
  bool no_measure = false;
  double crease_angle_degrees = 1.0;
  /// Coarser levels of detail: level k at lod_factors[k-1] times the tolerance (increasing,
  /// each > 1); glTF output only, with a tolerance (given, or the default relative one).
  std::vector<double> lod_factors;
  bool json = false;
  /// Refuse above this many triangles (the message gives the count needed).
  std::int64_t max_triangles = 100'000'000;
  /// Show progress (each stage that ends after the run's first second: read, tessellated,
  /// written) on the progress stream: the CLI sets it when stderr is a terminal, so that logs
  /// and pipes stay quiet.
  bool show_progress = false;
  /// Seconds into the run before stages are shown (the CLI takes PATCHWORK_PROGRESS_AFTER from
  /// the environment, 1 without it: a test sets 0 to see every stage of a short run).
  double progress_after = 1.0;
};

/// Runs the command; the summary goes to `out`; warnings, and progress for long runs when
/// `show_progress`, to `progress`.
/// \throws InvalidInput for bad arguments, IoError/ParseError for bad files (nothing written).
void run_tessellate(std::ostream& out, std::ostream& progress, const TessellateArguments& arguments);

}  // namespace patchwork::tools
