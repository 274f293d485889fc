#include "report/scale_section.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "report/benchmark_json.h"
#include "report/format.h"

namespace patchwork::performance {
namespace {

namespace fs = std::filesystem;

// One teapot's tolerance: 10^-3 of its tight box diagonal (8.2049), absolute, so that every
// scene is tessellated like its one teapot.
constexpr double scene_tolerance = 0.0082;
// Timed runs per scene (medians; three times as many for the scenes of a few milliseconds).
constexpr int scene_repeats = 3;

struct SceneRow {
  int copies = 0;
  std::size_t patches = 0;
  std::size_t triangles = 0;
  double glb_bytes = 0.0;
  double seconds = 0.0;       // whole process, median
  double peak_bytes = 0.0;    // peak resident set, median
  double tessellation = 0.0;  // the CLI's tessellation_seconds, in the measured run
  double measuring = 0.0;     // its measure_seconds
};

// The path in single quotes for the shell (appended piecewise: GCC 12 warns falsely about
// operator+ on a char and a string here, -Wrestrict).
std::string quoted(const fs::path& path) {
  std::string quoted = "'";
  quoted += path.string();
  quoted += '\'';
  return quoted;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// Runs `command` under GNU time; its peak resident bytes.
double peak_bytes(const std::string& command, const fs::path& scratch) {
  const fs::path times = scratch / "time.txt";
  const std::string line = "/usr/bin/time -f '%M' -o " + quoted(times) + " " + command;
  if (std::system(line.c_str()) != 0) throw NumericalError("scale section: failed: " + command);
  std::ifstream in(times);
  double kilobytes = 0.0;
  if (!(in >> kilobytes)) throw NumericalError("scale section: no GNU time output for " + command);
  return 1024.0 * kilobytes;
}

// Wall seconds of `command` run through the shell (std::system), less the shell's own start:
// the median of `repeats` runs of each (GNU time prints hundredths, too coarse for one teapot).
double wall_seconds(const std::string& command, int repeats) {
  const auto run = [](const std::string& line) {
    const auto start = std::chrono::steady_clock::now();
    if (std::system(line.c_str()) != 0) throw NumericalError("scale section: failed: " + line);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<double> seconds;
  std::vector<double> shell;
  for (int r = 0; r < repeats; ++r) {
    seconds.push_back(run(command));
    shell.push_back(run(":"));
  }
  return std::max(median(seconds) - median(shell), 0.0);
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

SceneRow scene_row(int copies, const fs::path& bench_dir, const fs::path& cli, const fs::path& source_dir,
                   const fs::path& scratch) {
  SceneRow row;
  row.copies = copies;
  const fs::path scene = scratch / ("scene_" + std::to_string(copies) + ".bpt");
  const fs::path glb = scratch / ("scene_" + std::to_string(copies) + ".glb");
  const fs::path summary = scratch / "summary.json";
  const std::string make = quoted(bench_dir / "make_scene") + " " + quoted(source_dir / "data/teapot.bpt") + " " +
                           std::to_string(copies) + " " + quoted(scene);
  if (std::system(make.c_str()) != 0) throw NumericalError("scale section: make_scene failed");
  const std::string tessellate = quoted(cli) + " tessellate " + quoted(scene) + " -o " + quoted(glb) + " --tolerance " +
                                 text("%g", scene_tolerance) + " --threads 2 --json";
  const std::string unmeasured_run = tessellate + " --no-measure > " + quoted(summary);
  row.seconds = wall_seconds(unmeasured_run, copies <= 16 ? 3 * scene_repeats : scene_repeats);
  row.peak_bytes = peak_bytes(unmeasured_run, scratch);
  const nlohmann::json unmeasured = read_json(summary);
  row.patches = unmeasured.at("patches").get<std::size_t>();
  row.triangles = unmeasured.at("triangles").get<std::size_t>();
  row.glb_bytes = static_cast<double>(fs::file_size(glb));
  if (std::system((tessellate + " > " + quoted(summary)).c_str()) != 0) {
    throw NumericalError("scale section: failed: " + tessellate);
  }
  const nlohmann::json measured = read_json(summary);
  row.tessellation = measured.at("tessellation_seconds").get<double>();
  row.measuring = measured.at("measure_seconds").get<double>();
  fs::remove(scene);
  fs::remove(glb);
  return row;
}

std::string scene_table(const std::vector<SceneRow>& rows) {
  std::ostringstream out;
  out << "| teapots | patches | triangles | glb MB | whole process s | peak MB | peak / glb | us / triangle | "
         "bytes / triangle | tessellating s | measuring s |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SceneRow& r : rows) {
    const double triangles = static_cast<double>(r.triangles);
    out << "| " << r.copies << " | " << count(r.patches) << " | " << count(r.triangles) << " | "
        << text("%.1f", r.glb_bytes / 1e6) << " | " << text("%.3g", r.seconds) << " | "
        << text("%.0f", r.peak_bytes / 1e6) << " | " << text("%.2f", r.peak_bytes / r.glb_bytes) << " | "
        << text("%.3g", 1e6 * r.seconds / triangles) << " | " << text("%.0f", r.peak_bytes / triangles) << " | "
        << text("%.3g", r.tessellation) << " | " << text("%.3g", r.measuring) << " |\n";
  }
  return out.str();
}

// The log-log plot of time and peak memory against patches, with lines of slope 1 through the
// 16-teapot row (the one-teapot process is mostly start-up).
std::string scale_plot(const std::vector<SceneRow>& rows, const fs::path& data) {
  std::ofstream file(data / "scale.dat");
  file << "# patches seconds peak_MB\n";
  for (const SceneRow& r : rows) file << r.patches << " " << r.seconds << " " << r.peak_bytes / 1e6 << "\n";
  const SceneRow& anchor = rows.size() > 1 ? rows[1] : rows[0];
  std::ostringstream gp;
  gp << "set terminal pngcairo size 900,600 font ',11'\nset output 'scale.png'\n"
     << "set logscale xy\nset xrange [" << rows.front().patches / 2 << ":" << rows.back().patches * 2 << "]\n"
     << "set yrange [" << rows.front().seconds / 4 << ":" << rows.back().seconds * 4 << "]\n"
     << "set y2range [" << rows.front().peak_bytes / 4e6 << ":" << rows.back().peak_bytes * 4 / 1e6 << "]\n"
     << "set xlabel 'patches'\nset ylabel 'seconds'\nset y2label 'peak memory, MB'\n"
     << "set logscale y2\nset ytics nomirror\nset y2tics\nset key left top\nset grid\n"
     << "plot 'scale.dat' using 1:2 with linespoints title 'whole process, seconds', "
     << "x * " << anchor.seconds / static_cast<double>(anchor.patches) << " with lines dt 2 title 'linear (seconds)', "
     << "'scale.dat' using 1:3 axes x1y2 with linespoints title 'peak memory, MB', "
     << "x * " << anchor.peak_bytes / 1e6 / static_cast<double>(anchor.patches)
     << " axes x1y2 with lines dt 3 title 'linear (MB)'\n";
  return gp.str();
}

std::string per_frame_table(const fs::path& bench_dir, const fs::path& data) {
  const auto results = run_benchmark(bench_dir / "tessellator_bench", data / "tessellator_bench.json",
                                     "--benchmark_filter='teapot_per_frame|scene_camera_frames'");
  if (!results) return "`tessellator_bench` did not run (not built, or it failed).\n\n";
  const auto cpu = cpu_seconds(*results);
  const auto wall = benchmark_seconds(*results, "real_time");
  std::map<std::string, double> triangles;
  std::map<std::string, double> culled;
  for (const nlohmann::json& b : results->at("benchmarks")) {
    const std::string name = registered_name(b.at("name").get<std::string>());
    if (b.contains("triangles")) triangles[name] = b.at("triangles").get<double>();
    if (b.contains("triangles_per_frame")) triangles[name] = b.at("triangles_per_frame").get<double>();
    if (b.contains("culled_per_frame")) culled[name] = b.at("culled_per_frame").get<double>();
  }
  std::ostringstream out;
  out << "The teapot, one thread, no measuring, one `Tessellation` reused from call to call (`teapot_per_frame`):"
      << " the plain call `tessellate(set, options, result)`, which prepares the set every time, against a"
      << " `PreparedSurface` made once, at one tolerance every frame and at a tolerance alternating by 1%"
      << " (every frame plans afresh):\n\n"
      << "| relative tolerance | triangles | plain ms | prepared ms | prepared, alternating ms | plain / prepared "
         "|\n|---|---|---|---|---|---|\n";
  for (const char* tolerance : {"10", "100"}) {
    const std::string base = std::string("teapot_per_frame/tol_1e-4:") + tolerance + "/mode:";
    if (!cpu.count(base + "0") || !cpu.count(base + "1") || !cpu.count(base + "2")) continue;
    out << "| " << (std::string(tolerance) == "10" ? "1e-3" : "1e-2") << " | "
        << count(static_cast<std::size_t>(triangles[base + "0"])) << " | " << text("%.3g", 1e3 * cpu.at(base + "0"))
        << " | " << text("%.3g", 1e3 * cpu.at(base + "1")) << " | " << text("%.3g", 1e3 * cpu.at(base + "2")) << " | "
        << text("%.2f", cpu.at(base + "0") / cpu.at(base + "1")) << " |\n";
  }
  const std::string scene = "scene_camera_frames/1024";
  if (wall.count(scene)) {
    out << "\nThe 1,024-teapot scene (32,768 patches), prepared once, re-tessellated frame after frame from a camera"
        << " circling over it (1 degree a frame, half a pixel on a 1920 x 1080 screen, 60 degrees of view,"
        << " frustum culling), 2 threads (`scene_camera_frames`): " << text("%.3g", 1e3 * wall.at(scene))
        << " ms a frame (wall clock) for " << count(static_cast<std::size_t>(triangles[scene])) << " triangles, "
        << count(static_cast<std::size_t>(culled[scene])) << " patches culled.\n\n";
  }
  return out.str();
}

}  // namespace

ReportSection scale_section(const fs::path& bench_dir, const fs::path& cli, const fs::path& source_dir,
                            const fs::path& data) {
  ReportSection section;
  std::ostringstream md;
  md << "## 9. Scale and the per-frame path\n\n";
  if (bench_dir.empty()) {
    md << "Not run: no `--bench-dir` (the quick mode in the test suite builds no benchmarks).\n\n";
    section.markdown = md.str();
    return section;
  }
  const fs::path scratch = fs::temp_directory_path() / ("patchwork_report_scale_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  try {
    std::vector<SceneRow> rows;
    for (const int copies : {1, 16, 256, 1024}) rows.push_back(scene_row(copies, bench_dir, cli, source_dir, scratch));
    fs::remove_all(scratch);
    md << "Scenes of rotated teapots that never touch (`bench/make_scene`), tessellated by the CLI as a user runs it:"
       << " `patchwork tessellate SCENE.bpt -o SCENE.glb --tolerance " << text("%g", scene_tolerance)
       << " --no-measure --threads 2` (10^-3 of one teapot's diagonal), whole process: the wall time the median of "
       << scene_repeats << " runs (" << 3 * scene_repeats << " for 1 and 16 teapots) less the median start of the shell"
       << " that runs them, the peak resident memory by GNU time; the last two columns from one more run with"
       << " the meter on (the CLI's `tessellation_seconds` and `measure_seconds`).\n\n"
       << scene_table(rows) << "\n";
    const SceneRow& one = rows.front();
    const SceneRow& many = rows.back();
    const auto per_triangle = [](const SceneRow& r, double value) { return value / static_cast<double>(r.triangles); };
    md << "From 1 to " << many.copies << " teapots the time per triangle changes by a factor "
       << text("%.2f", per_triangle(many, many.seconds) / per_triangle(one, one.seconds)) << " (16 to " << many.copies
       << ": " << text("%.2f", per_triangle(many, many.seconds) / per_triangle(rows[1], rows[1].seconds))
       << ") and the peak memory per triangle by "
       << text("%.2f", per_triangle(many, many.peak_bytes) / per_triangle(one, one.peak_bytes)) << " (16 to "
       << many.copies << ": "
       << text("%.2f", per_triangle(many, many.peak_bytes) / per_triangle(rows[1], rows[1].peak_bytes))
       << "; the one-teapot process is mostly start-up and the loaded program). The " << many.copies
       << "-teapot run takes " << text("%.3g", many.seconds) << " s and a peak of "
       << text("%.2f", many.peak_bytes / many.glb_bytes) << " times its glb's size.\n\n";
    md << "![time and peak memory against patches](performance/scale.png)\n\n";
    section.gnuplot = scale_plot(rows, data);
  } catch (const std::exception& error) {
    fs::remove_all(scratch);
    md << "Failed: " << error.what() << "\n\n";
  }
  md << per_frame_table(bench_dir, data);
  section.markdown = md.str();
  return section;
}

}  // namespace patchwork::performance
