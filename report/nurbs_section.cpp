#include "report/nurbs_section.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "report/format.h"
#include "report/tradeoff.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"

#ifdef PATCHWORK_HAVE_OCCT
#include "report/occt_peer.h"
#endif

namespace patchwork::performance {
namespace {

constexpr double kSphereRadius = 1.0;
constexpr double kTorusMajor = 2.0;
constexpr double kTorusMinor = 0.5;
// (3 sqrt 3 / 2): an equilateral triangle's area over e / kappa at sagitta e (header).
constexpr double kIdealAreaFactor = 2.598076211353316;

double sphere_distance(const Vec3& x) { return std::abs(x.norm() - kSphereRadius); }

double torus_distance(const Vec3& x) {
  const double rho = std::hypot(x.x(), x.y());
  return std::abs(std::hypot(rho - kTorusMajor, x.z()) - kTorusMinor);
}

// The largest distance on one triangle's barycentric lattice of order k.
double triangle_distance(const ExactShape& shape, const Vec3& a, const Vec3& b, const Vec3& c, int k) {
  double largest = 0.0;
  for (int i = 0; i <= k; ++i) {
    for (int j = 0; i + j <= k; ++j) {
      const Vec3 x = (static_cast<double>(i) * a + static_cast<double>(j) * b + static_cast<double>(k - i - j) * c) / k;
      largest = std::max(largest, shape.distance(x));
    }
  }
  return largest;
}

// A run's distance is the meter's mesh -> surface side; the other side is bounded by it (header).
void set_distance(Run& run, double distance) { run.distance.mesh_to_surface.distance = distance; }

struct Meter {
  int lattice;
  int refine;
};

std::vector<Run> patchwork_nurbs_runs(const ExactShape& shape, const std::vector<double>& tolerances, int repeats,
                                      const Meter& meter) {
  const PatchSet set(bezier_patches(shape.surface).patches);
  std::vector<Run> runs;
  for (const double tolerance : tolerances) {
    TessellationOptions options;
    options.tolerance = tolerance;
    options.threads = 1;
    const Tessellation result = tessellate(set, options);
    Run run;
    run.setting = text("%g", tolerance);
    run.triangles = result.mesh.triangle_count();
    run.vertices = result.mesh.vertex_count();
    run.error_bound = result.error_bound;
    run.own_error = result.measured_error;
    // Timed as a user calls it: render-ready output, no self-measurement.
    options.measure = false;
    run.seconds = median_seconds(repeats, [&] { tessellate(set, options); }).first;
    set_distance(
        run, mesh_to_surface_distance(shape, result.mesh.positions, result.mesh.indices, meter.lattice, meter.refine));
    runs.push_back(std::move(run));
  }
  return runs;
}

// Open CASCADE at absolute linear deflections; empty with `why` set without it.
std::vector<Run> occt_nurbs_runs(const ExactShape& shape, const std::vector<double>& deflections,
                                 double angular_deflection, int repeats, const Meter& meter, std::string& why) {
#ifdef PATCHWORK_HAVE_OCCT
  std::vector<Run> runs;
  for (const double deflection : deflections) {
    const OcctRun occt =
        timed_enough([&](int n) { return occt_tessellate(shape.surface, deflection, angular_deflection, n); }, repeats);
    Run run;
    run.setting = text("%g", deflection);
    run.triangles = occt.mesh.triangle_count();
    run.vertices = occt.mesh.positions.size();
    run.seconds = occt.seconds_median;
    set_distance(run,
                 mesh_to_surface_distance(shape, occt.mesh.positions, occt.mesh.indices, meter.lattice, meter.refine));
    runs.push_back(std::move(run));
  }
  why = "Open CASCADE " + occt_version();
  return runs;
#else
  static_cast<void>(shape), static_cast<void>(deflections), static_cast<void>(angular_deflection);
  static_cast<void>(repeats), static_cast<void>(meter);
  why = kWithoutOcct;
  return {};
#endif
}

// Columns: measured distance, triangles, seconds.
void write_data(const std::filesystem::path& folder, const std::string& name, const std::vector<Run>& runs) {
  std::ostringstream out;
  out << "# " << name << ": distance triangles seconds\n";
  for (const Run& run : runs) {
    out << text("%.9g", run.distance.hausdorff()) << " " << run.triangles << " " << text("%.9g", run.seconds) << "\n";
  }
  write_file_atomically(folder / (name + ".dat"), out.str());
}

std::string ratio(double a, double b) { return text("%.2f", a / b); }

// The smallest and largest of some ratios, printed "1.60-2.40", "1.60" or (none) "-".
struct Span {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  void add(double x) {
    low = std::min(low, x);
    high = std::max(high, x);
  }
  std::string str() const {
    if (low > high) return "-";
    return low == high ? text("%.2f", low) : text("%.2f", low) + "-" + text("%.2f", high);
  }
};

// One sentence from a shape's rows: the counts against the ideal, the peer against patchwork.
std::string summary(const ExactShape& shape, const std::vector<Run>& ours, const std::vector<Run>& theirs) {
  Span our_ideal, their_ideal, triangles, seconds;
  for (const Run& run : ours) {
    our_ideal.add(static_cast<double>(run.triangles) / ideal_uniform_triangles(shape, run.distance.hausdorff()));
  }
  int matched = 0;
  for (const Run& run : theirs) {
    const double e = run.distance.hausdorff();
    their_ideal.add(static_cast<double>(run.triangles) / ideal_uniform_triangles(shape, e));
    const std::optional<double> t = cost_at_error(tradeoff(ours, 1.0, false), e);
    const std::optional<double> s = cost_at_error(tradeoff(ours, 1.0, true), e);
    if (t && s) {
      triangles.add(static_cast<double>(run.triangles) / *t);
      seconds.add(run.seconds / *s);
      ++matched;
    }
  }
  std::ostringstream out;
  out << "- The " << shape.name << ": patchwork's triangles are " << our_ideal.str()
      << " x the ideal uniform count at their measured distance";
  if (!theirs.empty()) {
    out << ", Open CASCADE's " << their_ideal.str() << " x; at equal measured distance (" << matched
        << " of its rows in patchwork's range) Open CASCADE has " << triangles.str()
        << " x patchwork's triangles and takes " << seconds.str() << " x its time";
  }
  return out.str() + ".\n";
}

std::string shape_tables(const ExactShape& shape, const std::vector<Run>& ours, const std::vector<Run>& theirs) {
  std::ostringstream out;
  const NurbsBezierPatches pieces = bezier_patches(shape.surface);
  out << "**The " << shape.name << "** (" << pieces.spans_u << " x " << pieces.spans_v
      << " rational Bezier pieces), patchwork (`--tolerance e`, absolute):\n\n"
      << "| tolerance | triangles | vertices | ms | a-priori bound | own e_par | measured | ideal uniform | "
         "triangles / ideal |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const Run& run : ours) {
    const double ideal = ideal_uniform_triangles(shape, run.distance.hausdorff());
    out << "| " << run.setting << " | " << count(run.triangles) << " | " << count(run.vertices) << " | "
        << text("%.3g", 1e3 * run.seconds) << " | " << text("%.3g", run.error_bound) << " | "
        << text("%.3g", run.own_error) << " | " << text("%.3g", run.distance.hausdorff()) << " | "
        << count(static_cast<std::size_t>(std::lround(ideal))) << " | "
        << ratio(static_cast<double>(run.triangles), ideal) << " |\n";
  }
  if (theirs.empty()) return out.str() + "\n";
  out << "\nOpen CASCADE (linear deflection, absolute) and patchwork at the same measured distance (patchwork's"
      << " triangles and time interpolated on its rows above, `report/tradeoff.h`):\n\n"
      << "| deflection | triangles | ms | measured | ideal uniform | triangles / ideal | patchwork triangles | "
         "patchwork ms | triangles / patchwork's | time / patchwork's |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Run& run : theirs) {
    const double ideal = ideal_uniform_triangles(shape, run.distance.hausdorff());
    const std::optional<double> triangles = cost_at_error(tradeoff(ours, 1.0, false), run.distance.hausdorff());
    const std::optional<double> seconds = cost_at_error(tradeoff(ours, 1.0, true), run.distance.hausdorff());
    out << "| " << run.setting << " | " << count(run.triangles) << " | " << text("%.3g", 1e3 * run.seconds) << " | "
        << text("%.3g", run.distance.hausdorff()) << " | " << count(static_cast<std::size_t>(std::lround(ideal)))
        << " | " << ratio(static_cast<double>(run.triangles), ideal) << " | "
        << (triangles ? count(static_cast<std::size_t>(std::lround(*triangles))) : "out of range") << " | "
        << (seconds ? text("%.3g", 1e3 * *seconds) : "out of range") << " | "
        << (triangles ? ratio(static_cast<double>(run.triangles), *triangles) : "-") << " | "
        << (seconds ? ratio(run.seconds, *seconds) : "-") << " |\n";
  }
  return out.str() + "\n";
}

}  // namespace

std::vector<ExactShape> exact_shapes() {
  constexpr double pi = std::numbers::pi;
  return {
      {"sphere", nurbs_sphere(Vec3::Zero(), kSphereRadius), &sphere_distance, 4 * pi * kSphereRadius * kSphereRadius,
       1 / kSphereRadius},
      {"torus", nurbs_torus(Vec3::Zero(), kTorusMajor, kTorusMinor), &torus_distance,
       4 * pi * pi * kTorusMajor * kTorusMinor, std::max(1 / kTorusMinor, 1 / (kTorusMajor - kTorusMinor))},
  };
}

double ideal_uniform_triangles(const ExactShape& shape, double e) {
  return shape.area * shape.max_curvature / (kIdealAreaFactor * e);
}

double mesh_to_surface_distance(const ExactShape& shape, const std::vector<Vec3>& positions,
                                const std::vector<std::uint32_t>& indices, int lattice, int refine) {
  if (lattice < 1)
    throw InvalidInput(patchwork::detail::message("mesh_to_surface_distance: lattice ", lattice, " < 1"));
  for (const std::uint32_t index : indices) {
    if (index >= positions.size()) {
      throw InvalidInput(patchwork::detail::message("mesh_to_surface_distance: index ", index, " with ",
                                                    positions.size(), " positions"));
    }
  }
  const std::size_t triangles = indices.size() / 3;
  const auto corner = [&](std::size_t t, int k) -> const Vec3& { return positions[indices[3 * t + k]]; };
  std::vector<std::pair<double, std::size_t>> coarse(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    coarse[t] = {triangle_distance(shape, corner(t, 0), corner(t, 1), corner(t, 2), lattice), t};
  }
  const std::size_t fine = std::min(triangles, static_cast<std::size_t>(std::max(refine, 0)));
  std::partial_sort(coarse.begin(), coarse.begin() + static_cast<std::ptrdiff_t>(fine), coarse.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  double largest = 0.0;
  for (std::size_t k = 0; k < triangles; ++k) largest = std::max(largest, coarse[k].first);
  for (std::size_t k = 0; k < fine; ++k) {
    const std::size_t t = coarse[k].second;
    largest = std::max(largest, triangle_distance(shape, corner(t, 0), corner(t, 1), corner(t, 2), 64));
  }
  return largest;
}

NurbsSection nurbs_section(const std::filesystem::path& data_dir, bool quick) {
  const int repeats = quick ? 2 : 7;
  const Meter meter{quick ? 4 : 8, quick ? 8 : 64};
  const std::vector<double> tolerances =
      quick ? std::vector<double>{1e-2, 1e-3} : std::vector<double>{3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
  const std::vector<double> deflections =
      quick ? std::vector<double>{1e-2, 3e-3} : std::vector<double>{3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
  // As for the teapot: loose enough that the linear deflection governs.
  const double loose_angle = 10.0;

  NurbsSection result;
  std::ostringstream out;
  std::string why;
  std::ostringstream tables;
  std::ostringstream summaries;
  for (const ExactShape& shape : exact_shapes()) {
    const std::vector<Run> ours = patchwork_nurbs_runs(shape, tolerances, repeats, meter);
    const std::vector<Run> theirs = occt_nurbs_runs(shape, deflections, loose_angle, repeats, meter, why);
    write_data(data_dir, "nurbs_" + shape.name + "_patchwork", ours);
    if (!theirs.empty()) write_data(data_dir, "nurbs_" + shape.name + "_open_cascade", theirs);
    for (const Run& run : ours) {
      if (!(run.distance.hausdorff() <= run.error_bound)) {
        result.violations.push_back("NURBS " + shape.name + " tolerance " + run.setting + ": measured " +
                                    text("%.6g", run.distance.hausdorff()) + " above the bound " +
                                    text("%.6g", run.error_bound));
      }
    }
    tables << shape_tables(shape, ours, theirs);
    summaries << summary(shape, ours, theirs);
  }
  out << "## 8. NURBS: the exact sphere and torus against Open CASCADE\n\n"
      << "The unit sphere and the torus with radii 2 and 1/2 of `surfaces/nurbs_shapes.h` (rational quadratic)."
      << " patchwork tessellates their Bezier extraction as one `PatchSet` of"
      << " rational patches; **Open CASCADE** meshes one face on the same surface as a `Geom_BSplineSurface`"
      << " (`BRepBuilderAPI_MakeFace`, `BRepMesh_IncrementalMesh`, absolute linear deflection, angular deflection "
      << text("%g", loose_angle) << " rad, not in parallel; `report/occt_peer.cpp`). "
      << (why.empty() ? "" : why + ". ") << "Distances are in model units. *Measured* is the largest distance of the"
      << " mesh to the exact surface, in closed form (|x| - 1 for the sphere), sampled on a barycentric lattice of"
      << " order " << meter.lattice << " in every triangle and of order 64 in the " << meter.refine << " worst: a lower"
      << " bound of the mesh's distance to the surface, which for a closed mesh wrapping the surface once is the"
      << " two-sided Hausdorff distance (`report/nurbs_section.h`; closedness is tested for patchwork's meshes at 1e-3"
      << " and Open CASCADE's at deflections 1e-2 and 1e-3, not on every row). Times are the tessellation alone, one"
      << " thread, median of at least " << repeats << " runs after a warm-up, except that an Open CASCADE run of"
      << " over a second is timed once, cold (its largest ratios come from those rows).\n\n"
      << "*Ideal uniform* is the count of equilateral triangles of one size, with their corners on the surface, at"
      << " the measured distance as sagitta e where the surface bends most: area * kappa_max / (2.598 e), for the"
      << " sphere 4 pi R / (2.598 e), for the torus 4 pi^2 R r max(1/r, 1/(R - r)) / (2.598 e) = 8 pi^2 / (2.598 e)"
      << " (`report/nurbs_section.h` derives it). On the torus triangles stretched along its flatter parallels"
      << " can go below it.\n\n"
      << "From the rows below (ratios measured side by side in this run):\n\n"
      << summaries.str() << "\n"
      << tables.str()
      << (result.violations.empty() ? "On every patchwork row the measured distance is within the a-priori bound.\n\n"
                                    : "**Rows whose measured distance exceeds the bound:**\n\n");
  for (const std::string& v : result.violations) out << "- " << v << "\n";
  result.section.markdown = out.str();
  return result;
}

}  // namespace patchwork::performance
