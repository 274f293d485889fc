#include "tools/patches_command.h"

#include <chrono>
#include <nlohmann/json.hpp>
#include <ostream>

#include "io/bpt.h"
#include "surfaces/patch_set.h"
#include "surfaces/surface_integrals.h"

namespace patchwork::tools {

void run_patches_report(std::ostream& out, const std::string& path, bool json) {
  const auto start = std::chrono::steady_clock::now();
  const PatchSet set(read_bpt(path));
  const PatchSetReport summary = report(set);
  double total_area = 0.0;
  double area_error = 0.0;
  for (const BezierPatch3& patch : set.patches()) {
    const SurfaceIntegral a = area(patch, 1e-10 * set.size() * set.size());
    total_area += a.value;
    area_error += a.error_estimate;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (json) {
    nlohmann::json document = nlohmann::json::parse(to_json(summary));
    document["file"] = path;
    document["area"] = total_area;
    document["area_error_estimate"] = area_error;
    out << document.dump(2) << "\n";
    return;
  }
  out << path << "\n" << summary;
  out.precision(15);
  out << "  area: " << total_area << " (error estimate " << area_error << ")\n";
  out.precision(3);
  out << "  read and analysed in " << seconds * 1e3 << " ms\n";
}

}  // namespace patchwork::tools
