#include "tools/patches_command.h"

#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "io/freeform_surfaces.h"
#include "surfaces/patch_set.h"
#include "surfaces/surface_integrals.h"
#include "tools/output_files.h"
#include "tools/patch_input.h"

namespace patchwork::tools {
namespace {

// What a free-form OBJ file's surfaces are: basis, degrees, control points, spans over the
// range, rational or not, and the continuity the knots give across each interior breakpoint.
nlohmann::json surfaces_of(const FreeformDocument& document) {
  nlohmann::json surfaces = nlohmann::json::array();
  for (const FreeformSurface& surface : document.surfaces) {
    const NurbsBezierPatches pieces = freeform_bezier_patches(surface);
    const auto [count_u, count_v] = control_point_counts(surface);
    surfaces.push_back({{"name", surface.name},
                        {"line", surface.line},
                        {"basis", surface.basis == FreeformBasis::bspline ? "bspline" : "bezier"},
                        {"rational", surface.rational},
                        {"degree", {surface.degree_u, surface.degree_v}},
                        {"control_points", {count_u, count_v}},
                        {"range", {surface.u0, surface.u1, surface.v0, surface.v1}},
                        {"spans", {pieces.spans_u, pieces.spans_v}},
                        {"continuity_u", pieces.continuity_u},
                        {"continuity_v", pieces.continuity_v}});
  }
  return surfaces;
}

std::string joined(const nlohmann::json& values) {
  std::string text;
  for (const auto& v : values) text += (text.empty() ? "" : " ") + v.dump();
  return text.empty() ? "-" : text;
}

}  // namespace

void run_patches_report(std::ostream& out, const std::string& path, bool json) {
  const auto start = std::chrono::steady_clock::now();
  // A free-form file is read once, for the set and for its surfaces.
  const std::optional<FreeformDocument> document =
      lower_extension(path) == ".obj" ? std::optional(read_obj_freeform(path)) : std::nullopt;
  const PatchSet set = document ? freeform_patch_set(*document) : read_patch_set(path);
  const PatchSetReport summary = report(set);
  double total_area = 0.0;
  double area_error = 0.0;
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    const double tolerance = 1e-10 * set.size() * set.size();
    const RationalBezierPatch* rational = set.rational(p);
    const SurfaceIntegral a = rational != nullptr ? area(*rational, tolerance) : area(set.control_nets()[p], tolerance);
    total_area += a.value;
    area_error += a.error_estimate;
  }
  const nlohmann::json surfaces = document ? surfaces_of(*document) : nlohmann::json();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (json) {
    nlohmann::json document = nlohmann::json::parse(to_json(summary));
    document["file"] = path;
    document["area"] = total_area;
    document["area_error_estimate"] = area_error;
    if (!surfaces.is_null()) document["surfaces"] = surfaces;
    out << document.dump(2) << "\n";
    return;
  }
  out << path << "\n";
  for (const auto& s : surfaces) {
    out << "surface '" << s["name"].get<std::string>() << "' (line " << s["line"] << "): "
        << (s["rational"].get<bool>() ? "rational " : "") << s["basis"].get<std::string>() << ", degrees "
        << s["degree"][0] << " x " << s["degree"][1] << ", " << s["control_points"][0] << " x "
        << s["control_points"][1] << " control points, " << s["spans"][0] << " x " << s["spans"][1]
        << " spans; continuity across u: " << joined(s["continuity_u"]) << ", across v: " << joined(s["continuity_v"])
        << "\n";
  }
  out << summary;
  out.precision(15);
  out << "  area: " << total_area << " (error estimate " << area_error << ")\n";
  out.precision(3);
  out << "  read and analysed in " << seconds * 1e3 << " ms\n";
}

}  // namespace patchwork::tools
