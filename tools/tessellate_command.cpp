#include "tools/tessellate_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <ostream>
#include <span>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "io/gltf.h"
#include "io/mesh_file.h"
#include "surfaces/batched_tessellation.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/tessellator.h"
#include "tools/default_tolerance.h"
#include "tools/output_files.h"
#include "tools/patch_input.h"

namespace patchwork::tools {
namespace {

double parse_number(const std::string& key, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) {
    throw InvalidInput(detail::message("--camera: ", key, "=", text, " is not a number"));
  }
  return value;
}

Vec3 parse_vector(const std::string& key, const std::string& text) {
  Vec3 v;
  std::size_t start = 0;
  for (int c = 0; c < 3; ++c) {
    const std::size_t comma = text.find(',', start);
    if ((c < 2) != (comma != std::string::npos)) {
      throw InvalidInput(detail::message("--camera: ", key, "=", text, " is not three numbers x,y,z"));
    }
    v[c] = parse_number(key, text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    start = comma + 1;
  }
  return v;
}

Camera parse_camera(const std::vector<std::string>& tokens) {
  Camera camera;
  bool eye = false, target = false, fov = false, width = false, height = false;
  for (const std::string& token : tokens) {
    const std::size_t equals = token.find('=');
    if (equals == std::string::npos) throw InvalidInput(detail::message("--camera: '", token, "' is not key=value"));
    const std::string key = token.substr(0, equals);
    const std::string value = token.substr(equals + 1);
    if (key == "eye") {
      camera.eye = parse_vector(key, value), eye = true;
    } else if (key == "target") {
      camera.target = parse_vector(key, value), target = true;
    } else if (key == "up") {
      camera.up = parse_vector(key, value);
    } else if (key == "fov") {
      camera.fov_degrees = parse_number(key, value), fov = true;
    } else if (key == "width" || key == "height") {
      const double pixels = parse_number(key, value);
      if (pixels != std::floor(pixels) || pixels < 1 || pixels > 1e6) {
        throw InvalidInput(detail::message("--camera: ", key, "=", value, " is not a whole number of pixels"));
      }
      (key == "width" ? camera.width : camera.height) = static_cast<int>(pixels);
      (key == "width" ? width : height) = true;
    } else {
      throw InvalidInput(detail::message("--camera: unknown key '", key, "' (eye, target, up, fov, width, height)"));
    }
  }
  if (!(eye && target && fov && width && height)) {
    throw InvalidInput("--camera needs eye=x,y,z target=x,y,z fov=deg width=px height=px");
  }
  validate(camera);
  return camera;
}

// The meshes of every level, finest first, moved out of their tessellations (not copied: the
// finest alone can take gigabytes) into the one array write_gltf_levels takes.
std::vector<RenderMesh> take_level_meshes(Tessellation& finest, std::vector<Tessellation>& coarser) {
  std::vector<RenderMesh> meshes;
  meshes.reserve(1 + coarser.size());
  meshes.push_back(std::move(finest.mesh));
  for (Tessellation& level : coarser) meshes.push_back(std::move(level.mesh));
  return meshes;
}

// MSFT_screencoverage: level k is shown down to the coverage at which level k + 1's error is
// `pixels` pixels on a 1080-pixel-high screen (the surface's box diagonal spanning that fraction
// of its height); the coarsest level down to 0.
std::vector<double> screen_coverages(const PatchSet& set, const std::vector<Tessellation>& coarser, double pixels) {
  if (!(pixels > 0.0) || !std::isfinite(pixels)) {
    throw InvalidInput(detail::message("--pixel-tolerance ", pixels, " is not positive"));
  }
  constexpr double screen_height = 1080.0;
  const double diagonal =
      bounding_box(set, 1e-6 * set.size()).diagonal().norm();
  std::vector<double> coverage;
  double previous = 1.0;
  for (const Tessellation& next : coarser) {
    previous = std::min(previous, pixels * diagonal / (next.tolerance * screen_height));
    coverage.push_back(previous);
  }
  coverage.push_back(0.0);
  return coverage;
}

BackFaceCulling parse_back_face_culling(const std::string& text) {
  if (text == "auto") return BackFaceCulling::automatic;
  if (text == "always") return BackFaceCulling::always;
  if (text == "never") return BackFaceCulling::never;
  throw InvalidInput(detail::message("--cull-back-faces: '", text, "' is not auto, always or never"));
}

UvMode parse_uv(const std::string& text) {
  if (text == "none") return UvMode::none;
  if (text == "patch") return UvMode::patch;
  if (text == "atlas") return UvMode::atlas;
  throw InvalidInput(detail::message("--uv: '", text, "' is not none, patch or atlas"));
}

}  // namespace

void run_tessellate(std::ostream& out, std::ostream& progress, const TessellateArguments& arguments) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // Everything is checked before anything is read or written.
  check_mesh_output("tessellate", arguments.output);
  const bool gltf = is_gltf(arguments.output);
  TessellationOptions options;
  // No mode given: the default relative tolerance (named in --help and in the summary).
  const bool default_tolerance =
      !arguments.tolerance && !arguments.relative_tolerance && !arguments.segments && arguments.camera.empty();
  options.tolerance = arguments.tolerance;
  options.relative_tolerance = relative_tolerance_or_default(arguments.relative_tolerance, default_tolerance);
  options.segments = arguments.segments;
  if (!arguments.camera.empty()) options.camera = parse_camera(arguments.camera);
  options.pixel_tolerance = arguments.pixel_tolerance;
  options.back_face_culling = parse_back_face_culling(arguments.cull_back_faces);
  options.threads = arguments.threads;
  options.uv = parse_uv(arguments.uv);
  options.tangents = arguments.tangents;
  options.split_patches = !arguments.no_split;
  options.measure = !arguments.no_measure;
  options.crease_angle = arguments.crease_angle_degrees * std::numbers::pi / 180.0;
  options.max_triangles = arguments.max_triangles;
  if (arguments.threads < 0) throw InvalidInput(detail::message("--threads ", arguments.threads, " is negative"));
  if (!arguments.lod_factors.empty()) {
    if (!gltf) throw InvalidInput("--lod: levels of detail need a .glb or .gltf output");
    if (!options.tolerance && !options.relative_tolerance) {
      throw InvalidInput("--lod: levels of detail need --tolerance or --relative-tolerance");
    }
    for (std::size_t k = 0; k < arguments.lod_factors.size(); ++k) {
      const double factor = arguments.lod_factors[k];
      const double previous = k == 0 ? 1.0 : arguments.lod_factors[k - 1];
      if (!std::isfinite(factor) || !(factor > previous)) {
        throw InvalidInput(detail::message("--lod: factor ", factor, " is not finite and larger than ", previous));
      }
    }
  }

  // Progress once the run has taken a second, each stage as it ends (issue: long scenes).
  const auto report_progress = [&](const std::string& what) {
    if (arguments.show_progress && elapsed() > arguments.progress_after) progress << "patchwork: " << what << " (" << elapsed() << " s)" << std::endl;
  };
  const PatchSet set = read_patch_set(arguments.input);
  report_progress(detail::message("read ", arguments.input, ": ", set.count(), " patches; tessellating"));
  const auto tessellation_start = std::chrono::steady_clock::now();
  // A batch of whole shells at a time (surfaces/batched_tessellation.h): a scene of many objects
  // holds one batch's working memory, not the whole scene's.
  Tessellation result = tessellate_in_batches(set, options);
  // Coarser levels of detail, each at its factor times the tolerance.
  std::vector<Tessellation> coarser;
  for (const double factor : arguments.lod_factors) {
    TessellationOptions level = options;
    if (level.tolerance) *level.tolerance *= factor;
    if (level.relative_tolerance) *level.relative_tolerance *= factor;
    coarser.push_back(tessellate_in_batches(set, level));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tessellation_start).count();
  // The meter's share of that, every level's (the rest is tessellating).
  double measure_seconds = result.measure_seconds;
  for (const Tessellation& level : coarser) measure_seconds += level.measure_seconds;
  // What the summary says of the meshes, kept before writing gives the meshes away.
  const std::size_t triangles = result.mesh.triangle_count();
  const std::size_t vertices = result.mesh.vertex_count();
  std::vector<std::size_t> level_triangles;
  level_triangles.reserve(coarser.size());
  for (const Tessellation& level : coarser) level_triangles.push_back(level.mesh.triangle_count());
  report_progress(
      detail::message("tessellated in ", seconds, " s: ", triangles, " triangles; writing ", arguments.output));
  // No file holds the patch of each triangle (4 bytes a triangle): freed before writing.
  result.triangle_patches = std::vector<std::uint32_t>();
  for (Tessellation& level : coarser) level.triangle_patches = std::vector<std::uint32_t>();
  // The float rounding of each level's positions as written (OBJ, OFF and PLY hold doubles exactly).
  std::vector<double> rounding(1 + coarser.size(), 0.0);
  if (gltf) {
    // The patch set knows whether the surface has a boundary (an open edge): the lid gap shows
    // the inside, so such a mesh is double-sided.
    GltfOptions gltf_options;
    gltf_options.double_sided = !set.open_edges().empty();
    // The writer streams the buffer from the mesh arrays (io/gltf.h): no copy of the file in memory.
    if (coarser.empty()) {
      rounding[0] = write_gltf(arguments.output, result.mesh, gltf_options);
    } else {
      const std::vector<double> coverage = screen_coverages(set, coarser, arguments.pixel_tolerance);
      rounding = write_gltf_levels(arguments.output, take_level_meshes(result, coarser), coverage, gltf_options);
    }
  } else {
    // The welded triangles are all an OBJ, OFF or PLY file holds: the render mesh (normals, split
    // vertices) goes before the writer builds the file's text.
    const FaceVertexMesh faces = welded_faces(result.mesh);
    result.mesh = RenderMesh();
    write_mesh(arguments.output, faces);
  }
  report_progress(detail::message("wrote ", arguments.output));
  // Edges joined across gaps (PatchSet's tolerance) can push the bound past the tolerance: said
  // on stderr, since the tolerance asked for is not met.
  if (!arguments.segments && result.error_bound > result.tolerance) {
    progress << "patchwork: " << arguments.input << ": the error bound " << result.error_bound
             << " is above the tolerance " << result.tolerance << ": patch edges are joined across gaps of up to "
             << result.weld_gap << "\n";
  }
  // The bound for the file: the mesh's plus what writing moved a vertex (io/gltf.h).
  const double file_error_bound = result.error_bound + rounding[0];
  if (arguments.json) {
    const nlohmann::json document = {{"patches", set.count()},
                                     {"triangles", triangles},
                                     {"vertices", vertices},
                                     {"seconds", seconds},
                                     {"tessellation_seconds", seconds - measure_seconds},
                                     // Not measured (--no-measure): null, as measured_error.
                                     {"measure_seconds", options.measure ? nlohmann::json(measure_seconds) : nlohmann::json(nullptr)},
                                     // Uniform grids have no tolerance: null.
                                     {"tolerance", arguments.segments ? nlohmann::json(nullptr) : nlohmann::json(result.tolerance)},
                                     {"error_bound", result.error_bound},
                                     {"file_error_bound", file_error_bound},
                                     {"weld_gap", result.weld_gap},
                                     {"measured_error", options.measure ? nlohmann::json(result.measured_error) : nlohmann::json(nullptr)},
                                     {"culled_patches", result.culled_patches}};
    out << document.dump(2) << "\n";
    return;
  }
  out << arguments.input << " -> " << arguments.output << "\n";
  out << "  patches:        " << set.count() << " (" << result.culled_patches << " culled, "
      << result.culled_triangles << " triangles saved)\n";
  out << "  triangles:      " << triangles << "\n";
  out << "  vertices:       " << vertices << " (" << result.welded_vertices << " welded points)\n";
  out << "  seconds:        " << seconds - measure_seconds << " tessellating";
  if (options.measure) out << ", " << measure_seconds << " measuring";
  out << "\n";
  if (arguments.segments) {
    out << "  tolerance:      none (uniform " << *arguments.segments << " x " << *arguments.segments << " per patch)\n";
  } else {
    out << "  tolerance:      " << tolerance_summary(result.tolerance, options.relative_tolerance, default_tolerance)
        << "\n";
  }
  out << "  error bound:    " << result.error_bound << " (guaranteed";
  if (result.weld_gap > 0.0) out << "; includes a weld gap of " << result.weld_gap;
  out << ")\n";
  out << "  file bound:     " << file_error_bound << " (guaranteed for the file: + " << rounding[0]
      << " float rounding of its positions)\n";
  if (options.measure) {
    out << "  measured error: " << result.measured_error << "\n";
  } else {
    out << "  measured error: not measured (--no-measure)\n";
  }
  for (std::size_t k = 0; k < coarser.size(); ++k) {
    out << "  level " << k + 1 << ":        " << level_triangles[k] << " triangles, tolerance "
        << coarser[k].tolerance << ", bound " << coarser[k].error_bound << " (file "
        << coarser[k].error_bound + rounding[k + 1] << "), measured " << coarser[k].measured_error
        << "\n";
  }
}

}  // namespace patchwork::tools
