// The tessellator's targets (issue "The tessellator, glTF output and the patchwork CLI"):
//   - the teapot end to end at 1e-3 of the box diagonal (tessellate, weld, glb bytes), < 5 ms;
//   - throughput in vertices (position + normal + UV) per second at large rates (N >= 256),
//     1 thread and 2 threads;
//   - before the timings, a table: triangles, a-priori bound and measured error against the
//     smallest per-patch grid whose measured error meets the tolerance (the reference for the
//     a-priori rates), and uniform grids.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/scene.h"
#include "io/bpt.h"
#include "io/gltf.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator.h"

namespace {

using namespace patchwork;

const PatchSet& teapot() {
  static const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  return set;
}

void teapot_end_to_end(benchmark::State& state) {
  TessellationOptions options;
  options.relative_tolerance = 1e-3;
  options.threads = static_cast<int>(state.range(0));
  options.measure = false;
  GltfOptions gltf;
  gltf.double_sided = !teapot().open_edges().empty();
  std::size_t triangles = 0;
  for (auto _ : state) {
    const Tessellation result = tessellate(teapot(), options);
    benchmark::DoNotOptimize(format_gltf(result.mesh, GltfFormat::glb, gltf));
    triangles = result.mesh.triangle_count();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(teapot_end_to_end)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The per-frame call: the teapot at a relative tolerance of range(0) * 1e-4, one thread, no
// measuring, into one Tessellation reused from frame to frame. range(1): 0 the plain call on the
// set (prepares every time); 1 a PreparedSurface made once, the same tolerance every frame (the
// last frame's plan reused); 2 the prepared surface with the tolerance alternating between
// range(0) * 1e-4 and 1.01 times that (every frame plans afresh, as with a moving camera).
void teapot_per_frame(benchmark::State& state) {
  const double tolerance = static_cast<double>(state.range(0)) * 1e-4;
  const int mode = static_cast<int>(state.range(1));
  TessellationOptions options;
  options.relative_tolerance = tolerance;
  options.threads = 1;
  options.measure = false;
  const PreparedSurface prepared(teapot());
  Tessellation result;
  std::size_t triangles = 0;
  bool odd = false;
  for (auto _ : state) {
    if (mode == 0) {
      tessellate(teapot(), options, result);
    } else {
      if (mode == 2) options.relative_tolerance = odd ? 1.01 * tolerance : tolerance;
      odd = !odd;
      tessellate(prepared, options, result);
    }
    triangles = result.mesh.triangle_count();
    benchmark::DoNotOptimize(result.mesh.positions.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(teapot_per_frame)
    ->ArgNames({"tol_1e-4", "mode"})
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({10, 2})
    ->Args({100, 0})
    ->Args({100, 1})
    ->Args({100, 2})
    ->Unit(benchmark::kMicrosecond);

// The per-frame view-dependent re-tessellation of a scene of range(0) rotated teapots
// (bench/scene.h) from a camera circling over it, prepared once, 2 threads, half a pixel on a
// 1920 x 1080 screen, frustum and back-face culling (automatic: the teapot is open, so only
// the frustum culls), into one Tessellation reused from frame to frame. Every frame moves the
// camera by 1 degree, so every frame plans afresh.
void scene_camera_frames(benchmark::State& state) {
  const auto copies = static_cast<std::size_t>(state.range(0));
  static std::vector<BezierPatch3> patches;
  static std::size_t made = 0;
  if (made != copies) patches = bench::rotated_copies(teapot().patches(), copies), made = copies;
  const PatchSet set(patches);
  const PreparedSurface prepared(set);
  const Eigen::AlignedBox3d box = bounding_box(set, 1e-6 * set.size());
  const Vec3 centre = box.center();
  const double radius = 0.35 * box.diagonal().norm();
  TessellationOptions options;
  options.threads = 2;
  options.measure = false;
  options.pixel_tolerance = 0.5;
  Tessellation result;
  int frame = 0;
  std::int64_t triangles = 0;
  std::int64_t culled = 0;
  for (auto _ : state) {
    const double angle = frame++ * 3.14159265358979323846 / 180.0;
    const Vec3 eye = centre + Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.25 * radius);
    options.camera = Camera{eye, centre, Vec3::UnitZ(), 60.0, 1920, 1080};
    tessellate(prepared, options, result);
    triangles += static_cast<std::int64_t>(result.mesh.triangle_count());
    culled += static_cast<std::int64_t>(result.culled_patches);
  }
  state.counters["patches"] = static_cast<double>(set.count());
  state.counters["triangles_per_frame"] = static_cast<double>(triangles) / static_cast<double>(frame);
  state.counters["culled_per_frame"] = static_cast<double>(culled) / static_cast<double>(frame);
}
BENCHMARK(scene_camera_frames)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

// Uniform N x N grids (N = range(0)) on range(1) threads, into one Tessellation whose arrays are
// reused from run to run (range(2) = 1: the steady state of a caller that tessellates again and
// again) or a fresh one each run (range(2) = 0: every run pays for new memory, page faults and
// the kernel's zeroing included).
void teapot_uniform_throughput(benchmark::State& state) {
  TessellationOptions options;
  options.segments = static_cast<int>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  options.measure = false;
  options.optimize = false;
  const bool reuse = state.range(2) == 1;
  Tessellation result;
  std::size_t vertices = 0;
  for (auto _ : state) {
    if (reuse) {
      tessellate(teapot(), options, result);
    } else {
      result = tessellate(teapot(), options);
    }
    vertices = result.mesh.vertex_count();
    benchmark::DoNotOptimize(result.mesh.positions.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(vertices));
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(teapot_uniform_throughput)
    ->ArgNames({"N", "threads", "reuse"})
    ->Args({256, 1, 1})
    ->Args({256, 2, 1})
    ->Args({256, 1, 0})
    ->Args({256, 2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The meter's cost beside the tessellation's: the teapot at the absolute tolerance 0.0082 (about
// 1e-3 of its box diagonal) on one thread into a reused Tessellation, with the measured error
// (range(0) = 1) and without it (0). Every iteration times both parts (Tessellation's
// tessellation_seconds and measure_seconds), so the ratio comes from the same runs.
void teapot_measure(benchmark::State& state) {
  TessellationOptions options;
  options.tolerance = 0.0082;
  options.threads = 1;
  options.measure = state.range(0) == 1;
  Tessellation result;
  double tessellation = 0.0;
  double measure = 0.0;
  for (auto _ : state) {
    tessellate(teapot(), options, result);
    tessellation += result.tessellation_seconds;
    measure += result.measure_seconds;
    benchmark::DoNotOptimize(result.measured_error);
  }
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["tessellation_ms"] = 1e3 * tessellation / iterations;
  state.counters["measure_ms"] = 1e3 * measure / iterations;
  state.counters["measure/tessellation"] = measure / tessellation;
  state.counters["triangles"] = static_cast<double>(result.mesh.triangle_count());
}
BENCHMARK(teapot_measure)->ArgName("measure")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The smallest per-patch grid (fewest cells) whose sampled distance meets eps: what the a-priori
// rates are compared with.
std::int64_t reference_triangles(double eps) {
  std::int64_t total = 0;
  for (const BezierPatch3& patch : teapot().patches()) {
    std::int64_t best = std::int64_t{1} << 40;
    for (int nu = 1; nu <= 64; ++nu) {
      for (int nv = 1; nv <= 64 && nu * nv < best; ++nv) {
        if (sampled_grid_distance(patch, nu, nv, 4) <= eps) {
          best = static_cast<std::int64_t>(nu) * nv;
          break;
        }
      }
    }
    total += 2 * best;
  }
  return total;
}

void print_table() {
  std::printf("teapot: tolerance (relative to the box diagonal) -> triangles, bound, measured error\n");
  std::printf("%-22s %10s %12s %12s %12s %14s\n", "mode", "triangles", "tolerance", "bound", "measured", "reference");
  for (double r : {1e-2, 1e-3, 1e-4}) {
    TessellationOptions options;
    options.relative_tolerance = r;
    const Tessellation result = tessellate(teapot(), options);
    const std::int64_t reference = r >= 1e-3 ? reference_triangles(result.tolerance) : 0;
    std::printf("adaptive %-13g %10zu %12.4g %12.4g %12.4g %14lld\n", r, result.mesh.triangle_count(), result.tolerance,
                result.error_bound, result.measured_error, static_cast<long long>(reference));
  }
  for (int n : {8, 16, 32}) {
    TessellationOptions options;
    options.segments = n;
    const Tessellation result = tessellate(teapot(), options);
    std::printf("uniform %-14d %10zu %12s %12.4g %12.4g %14s\n", n, result.mesh.triangle_count(), "-",
                result.error_bound, result.measured_error, "-");
  }
  std::printf("(reference: smallest per-patch grids whose sampled error meets the tolerance, no welding)\n\n");
}

}  // namespace

int main(int argc, char** argv) {
  print_table();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
