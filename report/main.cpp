// patchwork_report: writes docs/performance.md, the speed-vs-error report (scripts/report).
//
//   patchwork_report --out FILE.md --data DIR [--quick] [--bench-dir DIR] [--commit TEXT]
//                    [--source-dir DIR]
//
// Every number in the file is measured by this run; DIR receives the data files, the gnuplot
// script and the plots (PNG, when gnuplot is installed). The run fails (exit 1) if one of
// patchwork's rows has a measured error above its own a-priori bound. --quick runs a few rows
// with a coarser meter: the test suite's check that the pipeline works.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/bpt.h"
#include "report/benchmark_json.h"
#include "report/format.h"
#include "report/hard_cases.h"
#include "report/nurbs_section.h"
#include "report/report_section.h"
#include "report/scale_section.h"
#include "report/teapot_runs.h"
#include "report/tradeoff.h"
#include "surfaces/tessellator.h"

namespace patchwork::performance {
namespace {

namespace fs = std::filesystem;

struct Arguments {
  fs::path out;
  fs::path data;
  fs::path bench_dir;
  fs::path source_dir = PATCHWORK_SOURCE_DIR;
  std::string commit = "unknown";
  bool quick = false;
};

std::string optional_text(const char* format, double value) { return std::isnan(value) ? "-" : text(format, value); }

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string model = "unknown CPU";
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores";
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return buffer;
}

// ---------------------------------------------------------------------------------------------
// Sections 1-4: the teapot runs, their tables, plots and ratios.

struct Method {
  std::string name;
  std::string note;  // version, or why it is missing
  std::vector<Run> runs;
};

std::string run_table(const std::vector<Run>& runs, double diagonal, bool patchwork) {
  std::ostringstream out;
  out << "| setting | triangles | vertices | ms (1 thread) |" << (patchwork ? " ms (2 threads) | a-priori bound |" : "")
      << (patchwork ? " own e_par |" : "") << " Hausdorff | surface→mesh | mesh→surface |\n";
  out << "|---|---|---|---|" << (patchwork ? "---|---|---|" : "") << "---|---|---|\n";
  for (const Run& run : runs) {
    out << "| " << run.setting << " | " << count(run.triangles) << " | " << count(run.vertices) << " | "
        << optional_text("%.3g", 1e3 * run.seconds) << " |";
    if (patchwork) {
      out << " " << optional_text("%.3g", 1e3 * run.seconds_two_threads) << " | "
          << text("%.3g", run.error_bound / diagonal) << " | " << text("%.3g", run.own_error / diagonal) << " |";
    }
    out << " " << text("%.3g", run.distance.hausdorff() / diagonal) << " | "
        << text("%.3g", run.distance.surface_to_mesh.distance / diagonal) << " | "
        << text("%.3g", run.distance.mesh_to_surface.distance / diagonal) << " |\n";
  }
  return out.str();
}

std::string data_file_name(const std::string& method) {
  std::string name;
  for (char c : method) name += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
  return name + ".dat";
}

// Columns: relative Hausdorff distance, triangles, seconds (one thread).
void write_data(const fs::path& folder, const Method& method, double diagonal) {
  std::ostringstream out;
  out << "# " << method.name << ": relative_hausdorff triangles seconds\n";
  for (const Run& run : method.runs) {
    out << text("%.9g", run.distance.hausdorff() / diagonal) << " " << run.triangles << " " << text("%.9g", run.seconds)
        << "\n";
  }
  write_file_atomically(folder / data_file_name(method.name), out.str());
}

std::string plots(const std::vector<Method>& methods) {
  std::ostringstream out;
  const auto plot = [&](const char* file, const char* xlabel, int column) {
    out << "set terminal pngcairo size 900,600 font ',11'\nset output '" << file << "'\n"
        << "set logscale xy\nset grid\nset key top right\nset format y '10^{%L}'\n"
        << "set xlabel '" << xlabel << "'\nset ylabel 'measured error (two-sided Hausdorff / box diagonal)'\nplot ";
    bool first = true;
    for (const Method& method : methods) {
      if (method.runs.empty()) continue;
      out << (first ? "" : ", ") << "'" << data_file_name(method.name) << "' using " << column
          << ":1 with linespoints title '" << method.name << "'";
      first = false;
    }
    out << "\n";
  };
  plot("error_vs_triangles.png", "triangles", 2);
  plot("error_vs_time.png", "seconds (tessellation alone, one thread)", 3);
  return out.str();
}

struct Ratios {
  std::string markdown;
  std::vector<std::string> missed;
};

Ratios ratio_table(const std::vector<Method>& methods, const std::vector<double>& levels, double diagonal) {
  // methods[0] is patchwork adaptive, the reference.
  std::ostringstream out;
  out << "| error | method | triangles | ms | triangles / patchwork's | time / patchwork's "
         "|\n|---|---|---|---|---|---|\n";
  Ratios ratios;
  for (double level : levels) {
    const auto ours_triangles = cost_at_error(tradeoff(methods[0].runs, diagonal, false), level);
    const auto ours_seconds = cost_at_error(tradeoff(methods[0].runs, diagonal, true), level);
    for (const Method& method : methods) {
      if (method.runs.empty()) continue;
      const auto triangles = cost_at_error(tradeoff(method.runs, diagonal, false), level);
      const auto seconds = cost_at_error(tradeoff(method.runs, diagonal, true), level);
      out << "| " << text("%g", level) << " | " << method.name << " | "
          << (triangles ? count(static_cast<std::size_t>(std::lround(*triangles))) : "out of range") << " | "
          << (seconds ? text("%.3g", 1e3 * *seconds) : "out of range") << " | ";
      const bool reference = &method == &methods[0];
      if (reference || !triangles || !ours_triangles) {
        out << (reference ? "1" : "-") << " | ";
      } else {
        out << text("%.2f", *triangles / *ours_triangles) << " | ";
        if (*triangles <= *ours_triangles)
          ratios.missed.push_back("fewer triangles than " + method.name + " at " + text("%g", level));
      }
      if (reference || !seconds || !ours_seconds) {
        out << (reference ? "1" : "-") << " |\n";
      } else {
        out << text("%.2f", *seconds / *ours_seconds) << " |\n";
        if (method.name.rfind("patchwork", 0) != 0 && *seconds < 10.0 * *ours_seconds) {
          ratios.missed.push_back("10x less time than " + method.name + " at " + text("%g", level));
        }
      }
    }
  }
  ratios.markdown = out.str();
  return ratios;
}

// Why the goals that were missed were missed, from the runs themselves.
std::string why_missed(const Ratios& ratios, const std::vector<Method>& methods) {
  const auto missed = [&](const std::string& what) {
    return std::any_of(ratios.missed.begin(), ratios.missed.end(),
                       [&](const std::string& m) { return m.find(what) != std::string::npos; });
  };
  std::ostringstream out;
  const Run& coarsest = methods[0].runs.front();
  const Run& finest_uniform = methods[1].runs.back();
  if (missed("less time than") && !methods[2].runs.empty()) {
    const Run& theirs = methods[2].runs.back();
    out << "Why not 10x less time everywhere: patchwork's time has a fixed part, the rigorous rates (second-derivative"
        << " bounds from the nets of 16 sub-patches per patch, the tight box a relative tolerance needs, the bound of"
        << " every stitched triangle): " << coarsest.setting << " takes " << text("%.3g", 1e3 * coarsest.seconds)
        << " ms for " << count(coarsest.triangles) << " triangles, which is most of the time at coarse levels. Per"
        << " vertex patchwork and three.js both evaluate Bernstein sums on a"
        << " grid; patchwork also welds, writes exact normals at the poles and reorders for the vertex cache, and"
        << " is "
        << text("%.2g", (theirs.seconds / static_cast<double>(theirs.vertices)) /
                            (finest_uniform.seconds / static_cast<double>(finest_uniform.vertices)))
        << "x three.js's speed per vertex at " << finest_uniform.setting << " (interiors evaluated straight into"
        << " the output by a vectorised kernel, section 5). Fewer triangles at equal error do not make up a factor"
        << " of 10 on that: at fine levels the time is the evaluation and writing of every vertex, at coarse ones"
        << " the fixed part above.\n\n";
  }
  if (missed("fewer triangles than Open CASCADE")) {
    out << "Why not fewer triangles than Open CASCADE everywhere: at coarse levels BRepMesh places nodes where each"
        << " face bends, while patchwork gives every patch one uniform grid (stitched to its neighbours' rates); a"
        << " patch whose curvature varies needs its worst part's rate everywhere. Patches are split 2 x 2 or 4 x 4"
        << " only where the a-priori count says that saves triangles, all patches alike, which at coarse levels it"
        << " does not.\n\n";
  }
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Section 5: throughput against the machine's write bandwidth.

double write_bandwidth(std::size_t bytes, bool use_memset) {
  std::vector<char> buffer(bytes, 1);  // touched once: the pages exist before the timing
  double best = 0.0;
  for (int r = 0; r < 5; ++r) {
    const auto start = std::chrono::steady_clock::now();
    if (use_memset) {
      std::memset(buffer.data(), r, bytes);
    } else {
      auto* words = reinterpret_cast<double*>(buffer.data());
      const std::size_t n = bytes / sizeof(double);
      for (std::size_t k = 0; k < n; ++k) words[k] = static_cast<double>(r);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    volatile char sink = buffer[bytes / 2];
    static_cast<void>(sink);
    best = std::max(best, static_cast<double>(bytes) / seconds);
  }
  return best;
}

std::string throughput_section(const PatchSet& teapot, bool quick) {
  const int n = quick ? 64 : 256;
  const int repeats = quick ? 1 : 5;
  std::ostringstream out;
  out << "## 5. Throughput\n\nThe teapot at N = " << n << " per patch (uniform), position + normal + UV, no"
      << " self-measurement, no vertex-cache reordering (as `bench/tessellator_bench`); median of " << repeats
      << " runs. *Reused*: into one `Tessellation` whose arrays keep their storage from run to run (after one"
      << " warm-up run), the steady state of a caller that tessellates again and again; *fresh*: a new one each"
      << " run, so every run also pays for new memory (page faults, the kernel zeroing pages). The ceiling beside"
      << " it is this machine's write bandwidth, measured now on a warm buffer, divided by the bytes a vertex"
      << " occupies in the output (`RenderMesh`: position, normal in doubles, UV: 64 bytes; with its share of the"
      << " indices, position ids and triangle patches, about 100; the glTF file stores 32).\n\n"
      << "| threads | output | vertices | ms | vertices/s |\n|---|---|---|---|---|\n";
  for (int threads : {1, 2}) {
    for (const bool reuse : {true, false}) {
      TessellationOptions options;
      options.segments = n;
      options.threads = threads;
      options.measure = false;
      options.optimize = false;
      Tessellation result;
      if (reuse) tessellate(teapot, options, result);
      std::vector<double> seconds;
      for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        if (reuse) {
          tessellate(teapot, options, result);
        } else {
          result = tessellate(teapot, options);
        }
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      std::sort(seconds.begin(), seconds.end());
      const double median = seconds[seconds.size() / 2];
      const std::size_t vertices = result.mesh.vertex_count();
      out << "| " << threads << " | " << (reuse ? "reused" : "fresh") << " | " << count(vertices) << " | "
          << text("%.4g", 1e3 * median) << " | " << text("%.3g", static_cast<double>(vertices) / median) << " |\n";
    }
  }
  const std::size_t bytes = (quick ? 32u : 256u) << 20;
  const double memset_bandwidth = write_bandwidth(bytes, true);
  const double store_bandwidth = write_bandwidth(bytes, false);
  out << "\n| write test (" << (bytes >> 20) << " MiB, best of 5, one thread) | GB/s | vertices/s at 64 B | at 32 B |\n"
      << "|---|---|---|---|\n";
  for (const auto& [name, bandwidth] :
       {std::pair{"memset", memset_bandwidth}, std::pair{"store loop (doubles)", store_bandwidth}}) {
    out << "| " << name << " | " << text("%.3g", bandwidth / 1e9) << " | " << text("%.3g", bandwidth / 64) << " | "
        << text("%.3g", bandwidth / 32) << " |\n";
  }
  out << "\n";
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Section 7: subdivision and topology throughput from the benchmarks of the meshes and
// subdivision issues (Google Benchmark, JSON output).

std::string benchmark_tables(const fs::path& bench_dir, const fs::path& data);

// Section 7, or a line saying why it failed (the rest of the report stands without it).
std::string benchmark_section(const fs::path& bench_dir, const fs::path& data) {
  try {
    return benchmark_tables(bench_dir, data);
  } catch (const std::exception& error) {
    return "## 7. Subdivision and topology against OpenMesh and CGAL\n\nFailed: " + std::string(error.what()) + "\n\n";
  }
}

std::string benchmark_tables(const fs::path& bench_dir, const fs::path& data) {
  std::ostringstream out;
  out << "## 7. Subdivision and topology against OpenMesh and CGAL\n\n";
  if (bench_dir.empty()) {
    out << "Not run: no `--bench-dir` (the quick mode in the test suite builds no benchmarks).\n\n";
    return out.str();
  }
  const auto meshes = run_benchmark(bench_dir / "meshes_bench", data / "meshes_bench.json");
  const auto subdivision = run_benchmark(bench_dir / "subdivision_bench", data / "subdivision_bench.json");
  if (meshes) {
    const auto seconds = cpu_seconds(*meshes);
    out << "Building the half-edge structure and the whole topology report (χ, genus, components, boundary loops,"
        << " orientability, manifoldness) of a 1M-triangle torus (`bench/meshes_bench`), CPU seconds per run:\n\n"
        << "| library | seconds | time / patchwork's |\n|---|---|---|\n";
    const auto reference = seconds.find("patchwork_halfedge_and_analyze");
    if (reference == seconds.end()) throw NumericalError("meshes_bench has no patchwork_halfedge_and_analyze");
    const double ours = reference->second;
    for (const auto& [name, key] : {std::pair{"patchwork", "patchwork_halfedge_and_analyze"},
                                    std::pair{"OpenMesh", "openmesh_build_and_topology"},
                                    std::pair{"CGAL Surface_mesh", "cgal_build_and_topology"}}) {
      if (!seconds.count(key)) continue;
      out << "| " << name << " | " << text("%.3g", seconds.at(key)) << " | " << text("%.2f", seconds.at(key) / ours)
          << " |\n";
    }
    out << "\n";
  } else {
    out << "`meshes_bench` did not run (not built, or it failed).\n\n";
  }
  if (subdivision) {
    const auto seconds = cpu_seconds(*subdivision);
    out << "Uniform subdivision of a quad torus (`bench/subdivision_bench`; both sides' outputs are checked equal"
        << " there), CPU seconds per run:\n\n| scheme/level | patchwork | OpenMesh | OpenMesh / patchwork "
           "|\n|---|---|---|---|\n";
    for (const auto& [name, value] : seconds) {
      const auto slash = name.find("/patchwork_refine/");
      if (slash == std::string::npos) continue;
      const std::string scheme = name.substr(0, slash);
      const std::string level = name.substr(slash + std::strlen("/patchwork_refine/"));
      const auto theirs = seconds.find(scheme + "/openmesh_subdivide/" + level);
      if (theirs == seconds.end()) continue;
      out << "| " << scheme << " " << level << " | " << text("%.3g", value) << " | " << text("%.3g", theirs->second)
          << " | " << text("%.2f", theirs->second / value) << " |\n";
    }
    out << "\n";
  } else {
    out << "`subdivision_bench` did not run (not built, or it failed).\n\n";
  }
  return out.str();
}

// ---------------------------------------------------------------------------------------------

Arguments parse_arguments(int argc, char** argv) {
  Arguments arguments;
  for (int k = 1; k < argc; ++k) {
    const std::string flag = argv[k];
    const auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw InvalidInput("patchwork_report: " + flag + " needs a value");
      return argv[++k];
    };
    if (flag == "--out")
      arguments.out = value();
    else if (flag == "--data")
      arguments.data = value();
    else if (flag == "--bench-dir")
      arguments.bench_dir = value();
    else if (flag == "--source-dir")
      arguments.source_dir = value();
    else if (flag == "--commit")
      arguments.commit = value();
    else if (flag == "--quick")
      arguments.quick = true;
    else
      throw InvalidInput("patchwork_report: unknown argument " + flag);
  }
  if (arguments.out.empty() || arguments.data.empty())
    throw InvalidInput("patchwork_report: --out and --data are required");
  return arguments;
}

int run(const Arguments& arguments) {
  const auto started = std::chrono::steady_clock::now();
  const bool quick = arguments.quick;
  fs::create_directories(arguments.data);
  const PatchSet teapot(read_bpt(arguments.source_dir / "data/teapot.bpt"));
  const double diagonal = surface_pieces(teapot).diagonal;

  RunSettings settings;
  settings.repeats = quick ? 2 : 7;
  if (quick) {
    settings.meter.grid_segments = 16;
    settings.meter.lattice = 3;
    settings.meter.refine = 8;
  }
  const std::vector<double> tolerances =
      quick ? std::vector<double>{1e-1, 1e-2, 1e-3}
            : std::vector<double>{1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
  const std::vector<int> segments =
      quick ? std::vector<int>{2, 4, 8} : std::vector<int>{2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128};
  const std::vector<double> deflections =
      quick ? std::vector<double>{1e-1, 1e-2}
            : std::vector<double>{1e-1, 5e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4};
  // Loose enough that the linear deflection governs (from 2 pi up no angle test of BRepMesh fires;
  // 10 and 10^6 give the same meshes); and OCCT's default.
  const double loose_angle = 10.0;
  const double default_angle = 0.5;

  std::cerr << "patchwork_report: patchwork runs\n";
  const std::vector<Run> ours = patchwork_runs(teapot, tolerances, segments, settings);
  std::vector<Method> methods(5);
  methods[0].name = "patchwork adaptive";
  methods[1].name = "patchwork uniform";
  for (const Run& run : ours) (run.method == methods[0].name ? methods[0] : methods[1]).runs.push_back(run);
  std::cerr << "patchwork_report: three.js runs\n";
  methods[2].name = "three.js";
  // three.js's meshes are scratch (tens of MB at N = 128), not report data.
  const fs::path scratch = fs::temp_directory_path() / ("patchwork_report_threejs_" + std::to_string(::getpid()));
  methods[2].runs = threejs_runs(teapot, arguments.source_dir, scratch, segments, settings, methods[2].note);
  fs::remove_all(scratch);
  std::cerr << "patchwork_report: Open CASCADE runs\n";
  methods[3].name = "Open CASCADE";
  methods[3].runs = occt_runs(teapot, deflections, loose_angle, methods[3].name, settings, methods[3].note);
  methods[4].name = "Open CASCADE 0.5 rad";
  methods[4].runs = occt_runs(teapot, deflections, default_angle, methods[4].name, settings, methods[4].note);

  // The check the quick mode exists for: the meter never finds more than patchwork's bound.
  std::vector<std::string> violations;
  for (const Run& run : ours) {
    if (!(run.distance.hausdorff() <= run.error_bound) || !(run.own_error <= run.error_bound)) {
      violations.push_back(run.method + " " + run.setting + ": measured " + text("%.6g", run.distance.hausdorff()) +
                           " (own " + text("%.6g", run.own_error) + ") above the bound " +
                           text("%.6g", run.error_bound));
    }
  }

  for (const Method& method : methods) {
    if (!method.runs.empty()) write_data(arguments.data, method, diagonal);
  }
  const std::vector<double> levels = {1e-2, 1e-3, 1e-4};
  const Ratios ratios = ratio_table(methods, levels, diagonal);

  std::cerr << "patchwork_report: throughput, hard cases, benchmarks\n";
  const std::string throughput = throughput_section(teapot, quick);
  const ReportSection hard_cases = hard_case_section(arguments.data, quick);
  const std::string benchmarks = benchmark_section(arguments.bench_dir, arguments.data);
  std::cerr << "patchwork_report: NURBS sphere and torus\n";
  const NurbsSection nurbs = nurbs_section(arguments.data, quick);
  std::cerr << "patchwork_report: scale and the per-frame path\n";
  const fs::path cli = arguments.bench_dir.empty() ? fs::path() : arguments.bench_dir.parent_path() / "tools/patchwork";
  const ReportSection scale = scale_section(arguments.bench_dir, cli, arguments.source_dir, arguments.data);

  const std::string gnuplot = plots(methods) + hard_cases.gnuplot + scale.gnuplot;
  write_file_atomically(arguments.data / "plots.gp", gnuplot);
  const bool plotted =
      std::system(("cd '" + arguments.data.string() + "' && gnuplot plots.gp > plots.log 2>&1").c_str()) == 0;

  const std::string images = arguments.data.filename().string();
  std::ostringstream md;
  md << "# Speed against error\n\n"
     << "Written by `scripts/report` (`report/main.cpp`)" << (quick ? " in its quick mode" : "") << " on " << today()
     << ", commit " << arguments.commit << ", on " << machine() << ". Every number below is measured by that run;"
     << " none is typed by hand. Errors are fractions of the teapot's box diagonal (" << text("%.5g", diagonal)
     << "); times are the tessellation alone, one thread unless a column says otherwise, median of " << settings.repeats
     << " runs after a warm-up (patchwork's: of as many more as fit in a quarter second, up to 200).\n\n";
  md << "## At 10^-3 of the diagonal\n\nInterpolated on each method's runs at equal measured error (section 4):\n\n";
  {
    md << "| method | triangles | ms |\n|---|---|---|\n";
    for (const Method& method : methods) {
      if (method.runs.empty() || method.name == "patchwork uniform") continue;
      const auto triangles = cost_at_error(tradeoff(method.runs, diagonal, false), 1e-3);
      const auto seconds = cost_at_error(tradeoff(method.runs, diagonal, true), 1e-3);
      md << "| " << method.name << " | "
         << (triangles ? count(static_cast<std::size_t>(std::lround(*triangles))) : "out of range") << " | "
         << (seconds ? text("%.3g", 1e3 * *seconds) : "out of range") << " |\n";
      if (method.name != "patchwork adaptive") continue;
      // The same meshes through a PreparedSurface made once (surfaces/prepared_surface.h).
      std::vector<TradeoffPoint> prepared = tradeoff(method.runs, diagonal, true);
      for (std::size_t k = 0; k < prepared.size(); ++k) prepared[k].cost = method.runs[k].seconds_prepared;
      const auto prepared_seconds = cost_at_error(prepared, 1e-3);
      md << "| patchwork adaptive, prepared surface (the per-frame call) | "
         << (triangles ? count(static_cast<std::size_t>(std::lround(*triangles))) : "out of range") << " | "
         << (prepared_seconds ? text("%.3g", 1e3 * *prepared_seconds) : "out of range") << " |\n";
    }
    md << "\n";
  }
  md << "## 1. The teapot: patchwork\n\n"
     << "The measured error is the two-sided Hausdorff distance between the mesh and the exact patches,"
     << " measured by `measure/hausdorff.h` from the geometry alone (dense surface samples against the mesh in"
     << " CGAL's AABB tree; mesh samples against the surface, refined by Newton steps in (u, v); the largest of"
     << " each side refined further). It is validated on closed forms in `tests/measure/hausdorff_test.cpp`."
     << " patchwork's own numbers are beside it: the a-priori bound its rates guarantee and `e_par`, its"
     << " sampled |S(u,v) - L(u,v)|, which bounds the Hausdorff distance from above.\n\n";
  md << "Adaptive (`--relative-tolerance r`):\n\n" << run_table(methods[0].runs, diagonal, true) << "\n";
  md << "Uniform (`--segments N`, N x N per patch):\n\n" << run_table(methods[1].runs, diagonal, true) << "\n";
  md << (violations.empty() ? "On every row the measured error is within the a-priori bound.\n\n"
                            : "**Rows whose measured error exceeds the bound:**\n\n");
  for (const std::string& v : violations) md << "- " << v << "\n";
  md << "## 2. The peers, same teapot, same meter\n\n";
  md << "**three.js** `TeapotGeometry` (bottom, lid, body on; fitLid, blinn off) run by node, its output mapped back"
     << " to the teapot's coordinates (`report/threejs/teapot.mjs`); timed in node around the constructor. "
     << (methods[2].runs.empty() ? "Not run: " : "") << methods[2].note << ".\n\n";
  if (!methods[2].runs.empty()) md << run_table(methods[2].runs, diagonal, false) << "\n";
  md << "**Open CASCADE** `BRepMesh_IncrementalMesh` on one `Geom_BezierSurface` face per patch "
        "(`report/occt_peer.cpp`),"
     << " absolute linear deflection (the setting), not in parallel, angular deflection " << text("%g", loose_angle)
     << " rad (loose, so that the linear one governs) and the default " << text("%g", default_angle) << " rad. "
     << (methods[3].runs.empty() ? "Not run: " : "") << methods[3].note << ".\n\n";
  if (!methods[3].runs.empty()) {
    md << "Angular " << text("%g", loose_angle) << " rad:\n\n" << run_table(methods[3].runs, diagonal, false) << "\n";
    md << "Angular " << text("%g", default_angle) << " rad:\n\n" << run_table(methods[4].runs, diagonal, false) << "\n";
  }
  md << "## 3. Plots\n\n";
  if (plotted) {
    md << "![measured error against triangles](" << images << "/error_vs_triangles.png)\n\n"
       << "![measured error against time](" << images << "/error_vs_time.png)\n\n";
  } else {
    md << "Not drawn: gnuplot is not installed or failed (`" << images << "/plots.gp`).\n\n";
  }
  md << "## 4. Ratios at equal measured error\n\n"
     << "Each method's triangles and time at the error level, interpolated in log-log on its runs' lower envelope"
     << " (`report/tradeoff.h`), divided by patchwork adaptive's. Goals: fewer triangles than every peer at every"
     << " level, at least 10x less time than each peer.\n\n"
     << ratios.markdown << "\n";
  if (ratios.missed.empty()) {
    md << "Every goal is met at every level where both curves reach it.\n\n";
  } else {
    md << "Not met:\n\n";
    for (const std::string& m : ratios.missed) md << "- " << m << "\n";
    md << "\n" << why_missed(ratios, methods);
  }
  md << throughput << hard_cases.markdown << "\n" << benchmarks << nurbs.section.markdown << scale.markdown;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  md << "---\nThis run took " << text("%.0f", seconds) << " s.\n";
  write_file_atomically(arguments.out, md.str());
  std::cerr << "patchwork_report: wrote " << arguments.out << " in " << text("%.0f", seconds) << " s\n";
  for (const std::string& v : violations) std::cerr << "patchwork_report: " << v << "\n";
  for (const std::string& v : nurbs.violations) std::cerr << "patchwork_report: " << v << "\n";
  return violations.empty() && nurbs.violations.empty() ? 0 : 1;
}

}  // namespace
}  // namespace patchwork::performance

int main(int argc, char** argv) {
  try {
    return patchwork::performance::run(patchwork::performance::parse_arguments(argc, argv));
  } catch (const std::exception& error) {
    std::cerr << "patchwork_report: " << error.what() << "\n";
    return 1;
  }
}
