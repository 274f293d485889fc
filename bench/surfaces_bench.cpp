// Points (position + unit normal) per second for the teapot's bicubic patches on a uniform
// grid: precomputed Bernstein weights (evaluate_grid) against pointwise tensor de Casteljau
// (evaluate + two first derivatives + cross product).

#include <benchmark/benchmark.h>

#include <vector>

#include "io/bpt.h"
#include "surfaces/patch_grid.h"
#include "surfaces/surface_normal.h"

namespace {

const std::vector<patchwork::BezierPatch3>& teapot() {
  static const std::vector<patchwork::BezierPatch3> patches = patchwork::read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  return patches;
}

void grid_with_weights(benchmark::State& state) {
  const auto segments = static_cast<std::size_t>(state.range(0));
  const patchwork::PatchGridWeights weights = patchwork::PatchGridWeights::uniform(3, 3, segments, segments);
  for (auto _ : state) {
    for (const auto& patch : teapot()) benchmark::DoNotOptimize(patchwork::evaluate_grid(patch, weights));
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(teapot().size() * (segments + 1) * (segments + 1)));
}

// The same grid written into storage the caller keeps (GridSamplesView, as the tessellator
// does): the kernel without the allocation and page faults of fresh sample arrays.
void grid_into_storage(benchmark::State& state) {
  const auto segments = static_cast<std::size_t>(state.range(0));
  const patchwork::PatchGridWeights weights = patchwork::PatchGridWeights::uniform(3, 3, segments, segments);
  std::vector<patchwork::Vec3> points((segments + 1) * (segments + 1));
  std::vector<patchwork::Vec3> normals(points.size());
  for (auto _ : state) {
    for (const auto& patch : teapot()) {
      patchwork::evaluate_grid(patch, weights, {points, normals, {}});
      benchmark::DoNotOptimize(points.data());
    }
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(teapot().size() * (segments + 1) * (segments + 1)));
}

void grid_with_de_casteljau(benchmark::State& state) {
  const auto segments = static_cast<int>(state.range(0));
  std::vector<patchwork::Vec3> points((segments + 1) * (segments + 1));
  std::vector<patchwork::Vec3> normals(points.size());
  for (auto _ : state) {
    for (const auto& patch : teapot()) {
      for (int b = 0; b <= segments; ++b) {
        for (int a = 0; a <= segments; ++a) {
          const double u = static_cast<double>(a) / segments;
          const double v = static_cast<double>(b) / segments;
          points[a + (segments + 1) * b] = patch.evaluate(u, v);
          normals[a + (segments + 1) * b] = patchwork::unit_normal(patch, u, v);
        }
      }
      benchmark::DoNotOptimize(points.data());
      benchmark::DoNotOptimize(normals.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(teapot().size() * points.size()));
}

BENCHMARK(grid_with_weights)->Arg(8)->Arg(32)->Arg(128);
BENCHMARK(grid_into_storage)->Arg(8)->Arg(32)->Arg(128);
BENCHMARK(grid_with_de_casteljau)->Arg(8)->Arg(32)->Arg(128);

}  // namespace

BENCHMARK_MAIN();
