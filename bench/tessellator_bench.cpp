// The tessellator's targets (issue "The tessellator, glTF output and the patchwork CLI"):
//   - the teapot end to end at 1e-3 of the box diagonal (tessellate, weld, glb bytes), < 5 ms;
//   - throughput in vertices (position + normal + UV) per second at large rates (N >= 256),
//     1 thread and 2 threads;
//   - before the timings, a table: triangles, a-priori bound and measured error against the
//     smallest per-patch grid whose measured error meets the tolerance (the reference for the
//     a-priori rates), and uniform grids.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <vector>

#include "io/bpt.h"
#include "io/gltf.h"
#include "surfaces/patch_flatness.h"
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
