#include "tools/subdivide_command.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <numbers>
#include <ostream>

#include "core/errors.h"
#include "io/gltf.h"
#include "io/mesh_file.h"
#include "meshes/edge_table.h"
#include "meshes/normals.h"
#include "subdivision/limit_tessellator.h"
#include "subdivision/orient_cage.h"
#include "subdivision/refine.h"
#include "tools/default_tolerance.h"
#include "tools/output_files.h"
#include "tools/patch_input.h"

namespace patchwork::tools {

namespace {

BoundaryInterpolation parse_boundary(const std::string& text) {
  if (text == "none") return BoundaryInterpolation::none;
  if (text == "edges") return BoundaryInterpolation::edges;
  if (text == "edges-and-corners") return BoundaryInterpolation::edges_and_corners;
  throw InvalidInput(detail::message("--boundary: '", text, "' is not none, edges or edges-and-corners"));
}

// Infinitely sharp creases on the edges whose two faces' normals differ by more than `degrees`.
std::vector<Crease> sharp_edges(const FaceVertexMesh& mesh, double degrees) {
  if (!(degrees >= 0.0 && degrees <= 180.0)) {
    throw InvalidInput(detail::message("--sharp-angle ", degrees, " is not in [0, 180]"));
  }
  const double cos_limit = std::cos(degrees * std::numbers::pi / 180.0);
  const std::vector<Vec3> normals = face_normals(mesh);
  const detail::EdgeTable table(mesh);
  std::vector<Crease> creases;
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    if (!table.has_two_uses(e)) continue;
    const auto uses = table.first_two_uses(e);
    if (normals[uses[0].face].dot(normals[uses[1].face]) < cos_limit) {
      const auto [a, b] = table.vertices(e);
      creases.push_back({a, b, infinitely_sharp});
    }
  }
  return creases;
}

std::string genus_text(const std::optional<Count>& genus) {
  return genus ? std::to_string(*genus) : std::string("undefined");
}

}  // namespace

void run_subdivide(std::ostream& out, std::ostream& notes, const SubdivideArguments& arguments) {
  // Everything is checked before anything is read or written.
  check_mesh_output("subdivide", arguments.output);
  SubdivisionCage cage;
  cage.options.scheme = parse_scheme(arguments.scheme);
  cage.options.boundary = parse_boundary(arguments.boundary);
  const int levels = arguments.levels.value_or(arguments.limit ? 0 : 1);
  if (levels < 0 || levels > max_refinement_levels) {
    throw InvalidInput(detail::message("--levels ", levels, " is not in 0..", max_refinement_levels));
  }
  const int modes = arguments.tolerance.has_value() + arguments.relative_tolerance.has_value() +
                    arguments.segments.has_value();
  if (modes > 1) throw InvalidInput("subdivide --limit: give one of --tolerance, --relative-tolerance, --segments");
  if (!arguments.limit && modes != 0) {
    throw InvalidInput("subdivide: --tolerance, --relative-tolerance and --segments need --limit");
  }
  refuse_patch_file_as_mesh("subdivide", arguments.input);
  cage.mesh = read_polygon_mesh(arguments.input);
  // Faces wound the wrong way are flipped (the fewest, per component) and the user is told.
  const CageOrientation oriented = orient_cage(cage);
  cage = oriented.cage;
  if (arguments.limit) validate_limit_cage(cage, "subdivide --limit");
  if (arguments.sharp_angle_degrees) cage.creases = sharp_edges(cage.mesh, *arguments.sharp_angle_degrees);
  const std::size_t cage_faces = cage.mesh.face_count();
  // Said once the output is written (an error line stays the only line).
  const auto note_orientation = [&] {
    if (!oriented.flipped.empty()) {
      notes << "patchwork: " << arguments.input << ": " << oriented.flipped.size() << " of " << cage_faces
            << " faces flipped to orient the mesh consistently\n";
    }
    if (oriented.non_orientable_components > 0) {
      notes << "patchwork: " << arguments.input << ": the mesh is not orientable; its " << oriented.seam_edges
            << (oriented.seam_edges == 1 ? " edge" : " edges")
            << " walked the same way by both faces refined as a non-manifold seam (infinitely sharp)\n";
    }
  };

  const auto start = std::chrono::steady_clock::now();
  UniformRefinement refined = refine_uniform(cage, levels);
  nlohmann::json summary = {{"input", arguments.input},
                            {"output", arguments.output},
                            {"scheme", arguments.scheme},
                            {"levels", levels},
                            {"cage_faces", cage_faces},
                            {"creases", cage.creases.size()}};
  if (!arguments.limit) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_polygon_mesh(arguments.output, surface_faces(refined.cage));
    note_orientation();
    const TopologyReport& t = refined.topology;
    summary.update({{"faces", t.faces}, {"vertices", t.vertices}, {"euler", t.euler}, {"genus", nullptr},
                    {"boundary_loops", t.boundary_loops}, {"seconds", seconds}});
    if (t.genus) summary["genus"] = *t.genus;
    if (arguments.json) {
      out << summary.dump(2) << "\n";
      return;
    }
    out << arguments.input << " -> " << arguments.output << " (" << arguments.scheme << ", " << levels
        << (levels == 1 ? " level)\n" : " levels)\n");
    out << "  faces:          " << cage_faces << " -> " << t.faces << "\n";
    out << "  vertices:       " << t.vertices << "\n";
    out << "  euler, genus:   " << t.euler << ", " << genus_text(t.genus) << " (" << t.boundary_loops
        << " boundary loops)\n";
    out << "  seconds:        " << seconds << "\n";
    return;
  }

  const LimitSurface surface(refined.cage, arguments.isolation_level);
  TessellationOptions options;
  // No mode given: the default relative tolerance (named in --help and in the summary).
  const bool default_tolerance = modes == 0;
  options.tolerance = arguments.tolerance;
  options.relative_tolerance = relative_tolerance_or_default(arguments.relative_tolerance, default_tolerance);
  options.segments = arguments.segments;
  const Tessellation result = tessellate_limit(surface, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double deviation = isolation_deviation(surface);
  const TopologyReport topology = analyze(welded_faces(result.mesh));
  if (is_gltf(arguments.output)) {
    GltfOptions gltf_options;
    gltf_options.double_sided = !topology.closed;
    write_gltf(arguments.output, result.mesh, gltf_options);
  } else {
    write_mesh(arguments.output, welded_faces(result.mesh));
  }
  note_orientation();
  summary.update({{"patches", surface.patch_count()},
                  {"triangles", result.mesh.triangle_count()},
                  {"vertices", result.mesh.vertex_count()},
                  {"euler", topology.euler},
                  {"boundary_loops", topology.boundary_loops},
                  {"seconds", seconds},
                  {"tolerance", arguments.segments ? nlohmann::json(nullptr) : nlohmann::json(result.tolerance)},
                  {"error_bound", std::isfinite(result.error_bound) ? nlohmann::json(result.error_bound)
                                                                    : nlohmann::json(nullptr)},
                  {"measured_error", result.measured_error},
                  {"isolation_level", arguments.isolation_level},
                  {"isolation_deviation", deviation}});
  if (arguments.json) {
    out << summary.dump(2) << "\n";
    return;
  }
  out << arguments.input << " -> " << arguments.output << " (" << arguments.scheme << " limit surface)\n";
  out << "  cage faces:     " << cage_faces << " (" << surface.face_count() << " base faces, "
      << surface.patch_count() << " patches)\n";
  out << "  triangles:      " << result.mesh.triangle_count() << "\n";
  out << "  vertices:       " << result.mesh.vertex_count() << " (" << result.welded_vertices << " welded points)\n";
  out << "  euler:          " << topology.euler << " (" << topology.boundary_loops << " boundary loops)\n";
  out << "  seconds:        " << seconds << "\n";
  if (arguments.segments) {
    out << "  tolerance:      none (uniform " << *arguments.segments << " x " << *arguments.segments << " per face)\n";
  } else {
    out << "  tolerance:      " << tolerance_summary(result.tolerance, options.relative_tolerance, default_tolerance)
        << "\n";
  }
  if (std::isfinite(result.error_bound)) {
    out << "  error bound:    " << result.error_bound << " (guaranteed)\n";
  } else {
    out << "  error bound:    none (no derivative bound for this scheme)\n";
  }
  out << "  measured error: " << result.measured_error << "\n";
  out << "  isolation:      level " << arguments.isolation_level << "; one level deeper moves the surface by "
      << deviation << " (end caps at extraordinary vertices approximate the exact limit)\n";
}

}  // namespace patchwork::tools
