// The patchwork command-line tool. Exit codes: 0 success, 2 bad usage (CLI11 parse errors),
// 1 bad input or a failed read or write, with one line on stderr naming the file and the problem.

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "core/errors.h"
#include "tools/convert_command.h"
#include "tools/curve_demo.h"
#include "tools/default_tolerance.h"
#include "tools/info_command.h"
#include "tools/patch_input.h"
#include "tools/patches_command.h"
#include "tools/query_commands.h"
#include "tools/subdivide_command.h"
#include "tools/tessellate_command.h"

int main(int argc, char** argv) {
  CLI::App app{
      "patchwork: Bezier patch sets to render-ready meshes within a guaranteed error; meshes, subdivision "
      "surfaces and curves"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "patchwork 0.1.0");

  int degree = 20;
  long evaluations = 2'000'000;
  CLI::App* demo = app.add_subcommand(
      "curve-demo",
      "Accuracy and speed of the curves module (a root of high multiplicity, arc length, evaluation speed)");
  demo->add_option("--degree", degree, "Degree of the hard-case polynomial (the multiplicity of its root)")
      ->check(CLI::Range(2, 33))
      ->capture_default_str();
  demo->add_option("--evaluations", evaluations, "Evaluations timed per method")
      ->check(CLI::Range(1000L, 1'000'000'000L))
      ->capture_default_str();

  std::string patch_file;
  bool json = false;
  CLI::App* patches = app.add_subcommand("patches", "Adjacency, continuity and area of a patch set (BPT or free-form OBJ)");
  patches->add_option("file", patch_file, "BPT or free-form OBJ file (e.g. data/teapot.bpt)")->required();
  patches->add_flag("--json", json, "Print the report as JSON");

  std::string info_file;
  bool info_json = false;
  CLI::App* info = app.add_subcommand("info", "Topology of a mesh (OBJ, OFF, PLY) or patch set (BPT, free-form OBJ) file");
  info->add_option("file", info_file, "Mesh, BPT or free-form OBJ file")->required();
  info->add_flag("--json", info_json, "Print the report as JSON");

  const std::string default_relative_text = patchwork::detail::message(patchwork::tools::default_relative_tolerance);
  patchwork::tools::TessellateArguments tess;
  CLI::App* tessellate = app.add_subcommand("tessellate", "Patch set (BPT, free-form OBJ) to a render-ready mesh within an error");
  tessellate->add_option("input", tess.input, "BPT or free-form OBJ (NURBS) file")->required();
  tessellate->add_option("-o,--output", tess.output, "Output .glb, .gltf, .obj, .off or .ply")->required();
  auto* tolerance = tessellate->add_option("--tolerance", tess.tolerance, "Absolute tolerance (model units)");
  auto* relative = tessellate->add_option("--relative-tolerance", tess.relative_tolerance,
                                          "Tolerance relative to the tight bounding-box diagonal (the default, " +
                                              default_relative_text + ", when no other mode is given)");
  auto* segments = tessellate->add_option("--segments", tess.segments, "Uniform N x N grid per patch");
  auto* camera = tessellate->add_option("--camera", tess.camera,
                                        "eye=x,y,z target=x,y,z fov=deg width=px height=px [up=x,y,z]")
                     ->expected(5, 6);
  tessellate
      ->add_option("--pixel-tolerance", tess.pixel_tolerance,
                   "Tolerance in pixels with --camera (and of --lod's screen coverages)")
      ->capture_default_str();
  tolerance->excludes(relative, segments, camera);
  relative->excludes(segments, camera);
  segments->excludes(camera);
  tessellate
      ->add_option("--cull-back-faces", tess.cull_back_faces,
                   "With --camera: auto (only patches of closed, outward shells seen from outside, where no "
                   "hole can open), always or never")
      ->capture_default_str();
  tessellate->add_option("--threads", tess.threads, "Threads (0: all cores)")->capture_default_str();
  tessellate->add_option("--uv", tess.uv, "UVs: none, patch (surface parameters) or atlas")->capture_default_str();
  tessellate->add_flag("--tangents", tess.tangents, "Write glTF TANGENT");
  tessellate->add_flag("--no-split", tess.no_split,
                       "One grid per patch (by default patches split 2 x 2 or 4 x 4 where that saves triangles)");
  tessellate->add_flag("--no-measure", tess.no_measure,
                       "Skip the measured error (sampled |S - L|); the guaranteed bound is computed anyway");
  tessellate
      ->add_option("--crease-angle", tess.crease_angle_degrees,
                   "Split vertices where normals differ by more than this (degrees)")
      ->capture_default_str();
  tessellate->add_option("--lod", tess.lod_factors,
                         "Coarser levels of detail in the glTF file (MSFT_lod), each this factor times the tolerance")
      ->delimiter(',');
  tessellate->add_flag("--json", tess.json,
                       "Print the summary as JSON (error_bound: the mesh's; file_error_bound: the file's, adding "
                       "the float rounding of glTF positions)");
  tessellate->add_option("--max-triangles", tess.max_triangles, "Refuse to make more triangles than this")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{2'000'000'000}))
      ->capture_default_str();

  patchwork::tools::SubdivideArguments sub;
  CLI::App* subdivide = app.add_subcommand(
      "subdivide",
      "Subdivision surfaces (OpenSubdiv): refine a mesh, or tessellate its limit; wrongly wound faces are flipped "
      "(and said so on stderr)");
  subdivide->add_option("input", sub.input, "Cage mesh (.obj, .off, .ply, .glb, .gltf)")->required();
  subdivide->add_option("-o,--output", sub.output, "Output .obj, .off, .ply, .glb or .gltf")->required();
  subdivide->add_option("--scheme", sub.scheme, "catmull-clark, loop or bilinear")->capture_default_str();
  subdivide->add_option("--levels", sub.levels, "Uniform refinement levels (0..10; default 1, or 0 with --limit)");
  subdivide->add_option("--boundary", sub.boundary, "Boundary interpolation: none, edges, edges-and-corners")
      ->capture_default_str();
  subdivide->add_option("--sharp-angle", sub.sharp_angle_degrees,
                        "Edges whose faces meet at more than this angle (degrees) become infinitely sharp creases");
  subdivide->add_flag("--limit", sub.limit, "Write the limit surface, tessellated");
  auto* sub_tolerance = subdivide->add_option("--tolerance", sub.tolerance, "With --limit: absolute tolerance");
  auto* sub_relative =
      subdivide->add_option("--relative-tolerance", sub.relative_tolerance,
                            "With --limit: tolerance relative to the cage's bounding-box diagonal (the "
                            "default, " +
                                default_relative_text + ", when no other mode is given)");
  auto* sub_segments = subdivide->add_option("--segments", sub.segments, "With --limit: uniform N x N per face");
  sub_tolerance->excludes(sub_relative, sub_segments);
  sub_relative->excludes(sub_segments);
  subdivide->add_option("--isolation", sub.isolation_level, "With --limit: adaptive isolation level (1..10)")
      ->capture_default_str();
  subdivide->add_flag("--json", sub.json, "Print the summary as JSON");

  std::string convert_input;
  std::string convert_output;
  CLI::App* convert = app.add_subcommand("convert", "Between mesh files (OBJ, OFF, PLY) and glTF (.glb, .gltf), and between BPT and free-form OBJ");
  convert->add_option("input", convert_input, "Input file")->required();
  convert->add_option("output", convert_output, "Output file")->required();

  std::string closest_file;
  std::vector<double> closest_point;
  bool closest_json = false;
  CLI::App* closest = app.add_subcommand(
      "closest", "The closest point of a patch set (BPT, free-form OBJ) to a point, with a certified interval");
  closest->add_option("file", closest_file, "BPT or free-form OBJ file")->required();
  closest->add_option("point", closest_point, "The point X Y Z")->required()->expected(3)->allow_extra_args(false);
  closest->add_flag("--json", closest_json, "Print JSON: distance, point, patch, u, v, bound [lower, upper]");

  std::string ray_file;
  std::vector<double> ray_origin, ray_direction;
  bool ray_json = false;
  CLI::App* raycast = app.add_subcommand("raycast", "Every hit of a ray with a patch set (BPT, free-form OBJ), in order");
  raycast->add_option("file", ray_file, "BPT or free-form OBJ file")->required();
  raycast->add_option("--origin", ray_origin, "The ray's origin X,Y,Z")->required()->delimiter(',');
  raycast->add_option("--direction", ray_direction, "The ray's direction X,Y,Z (any length but zero)")
      ->required()
      ->delimiter(',');
  raycast->add_flag("--json", ray_json, "Print JSON: hits [{t, patch, u, v, point, normal, grazing}]");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  // The file a command reads, named in every error line (ParseError and IoError name theirs).
  const auto input_file = [&]() -> const std::string& {
    static const std::string none;
    if (patches->parsed()) return patch_file;
    if (info->parsed()) return info_file;
    if (convert->parsed()) return convert_input;
    if (subdivide->parsed()) return sub.input;
    if (tessellate->parsed()) return tess.input;
    if (closest->parsed()) return closest_file;
    if (raycast->parsed()) return ray_file;
    return none;
  };
  try {
    if (demo->parsed()) patchwork::tools::run_curve_demo(std::cout, degree, evaluations);
    if (patches->parsed()) patchwork::tools::run_patches_report(std::cout, patch_file, json);
    if (info->parsed()) {
      if (patchwork::is_patch_file(info_file)) {
        patchwork::tools::run_patches_report(std::cout, info_file, info_json);
      } else {
        patchwork::tools::run_info(std::cout, info_file, info_json);
      }
    }
    if (convert->parsed()) patchwork::tools::run_convert(convert_input, convert_output);
    if (closest->parsed()) patchwork::tools::run_closest(std::cout, closest_file, {closest_point[0], closest_point[1], closest_point[2]}, closest_json);
    if (raycast->parsed()) patchwork::tools::run_raycast(std::cout, ray_file, ray_origin, ray_direction, ray_json);
    if (subdivide->parsed()) patchwork::tools::run_subdivide(std::cout, std::cerr, sub);
    if (tessellate->parsed()) {
      tess.show_progress = ::isatty(STDERR_FILENO) != 0;
      // A number of seconds, or the default where it is absent or not one.
      if (const char* after = std::getenv("PATCHWORK_PROGRESS_AFTER")) {
        char* end = nullptr;
        const double seconds = std::strtod(after, &end);
        if (end != after && *end == '\0' && std::isfinite(seconds) && seconds >= 0.0) tess.progress_after = seconds;
      }
      patchwork::tools::run_tessellate(std::cout, std::cerr, tess);
    }
  } catch (const patchwork::ParseError& error) {
    std::cerr << "patchwork: " << error.what() << "\n";  // "path:line:column: message"
    return 1;
  } catch (const patchwork::IoError& error) {
    std::cerr << "patchwork: " << error.what() << "\n";  // "path: message"
    return 1;
  } catch (const std::exception& error) {
    // Library errors name the function and the element; the line names the file being processed.
    const std::string& file = input_file();
    std::cerr << "patchwork: " << (file.empty() ? "" : file + ": ") << error.what() << "\n";
    return 1;
  }
  return 0;
}
