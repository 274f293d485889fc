// Modeling queries on the teapot: closest points per second (one thread) and rays per second
// (one and two threads, every hit of each ray), against a prepared PatchBvh. The rays run from a
// ring of eyes around the teapot towards points inside its box; the closest-point queries are
// points in a box twice the teapot's, some near the surface.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "io/bpt.h"
#include "queries/closest_point.h"
#include "queries/patch_bvh.h"
#include "queries/ray_cast.h"

namespace {

using patchwork::Vec3;

const patchwork::PatchSet& teapot() {
  static const patchwork::PatchSet set(patchwork::read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  return set;
}

const patchwork::PatchBvh& teapot_bvh() {
  static const patchwork::PatchBvh bvh(teapot());
  return bvh;
}

// A deterministic sequence in [0, 1) (the fractional parts of k times the golden ratio's inverse
// and its square's), so that every run asks the same questions.
double sequence(std::size_t k, double step) { return std::fmod(0.5 + static_cast<double>(k) * step, 1.0); }

std::vector<Vec3> query_points(std::size_t count) {
  std::vector<Vec3> points;
  for (std::size_t k = 0; k < count; ++k)
    points.emplace_back(-7 + 14 * sequence(k, 0.6180339887), -4 + 8 * sequence(k, 0.3819660113),
                        -1.5 + 6.5 * sequence(k, 0.7548776662));
  return points;
}

struct Ray {
  Vec3 origin, direction;
};

std::vector<Ray> rays(std::size_t count) {
  std::vector<Ray> out;
  for (std::size_t k = 0; k < count; ++k) {
    const double phi = 2 * M_PI * sequence(k, 0.6180339887);
    const Vec3 eye(8 * std::cos(phi), 8 * std::sin(phi), -1 + 6 * sequence(k, 0.3819660113));
    const Vec3 target(-3 + 6.4 * sequence(k, 0.5698402910), -2 + 4 * sequence(k, 0.4302530), 3.2 * sequence(k, 0.7548776662));
    out.push_back({eye, target - eye});
  }
  return out;
}

void closest_point_teapot(benchmark::State& state) {
  const std::vector<Vec3> points = query_points(1024);
  const patchwork::PatchBvh& bvh = teapot_bvh();
  std::size_t k = 0;
  std::int64_t pieces = 0;
  for (auto _ : state) {
    const auto result = patchwork::closest_point(bvh, points[k++ % points.size()]);
    pieces += result.pieces;
    benchmark::DoNotOptimize(result.distance);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["pieces_per_query"] = static_cast<double>(pieces) / static_cast<double>(state.iterations());
}

void ray_cast_teapot(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const std::vector<Ray> batch = rays(8192);
  const patchwork::PatchBvh bvh(teapot(), static_cast<int>(state.range(1)));
  std::vector<std::size_t> hit_counts(batch.size());
  std::vector<std::int64_t> pieces(batch.size());
  for (auto _ : state) {
    patchwork::parallel_for(batch.size(), threads, [&](std::size_t k) {
      const patchwork::RayHits result = patchwork::ray_cast(bvh, batch[k].origin, batch[k].direction);
      hit_counts[k] = result.hits.size();
      pieces[k] = result.pieces;
    });
    benchmark::DoNotOptimize(hit_counts.data());
  }
  std::size_t hits = 0;
  for (std::size_t h : hit_counts) hits += h;
  std::int64_t examined = 0;
  for (std::int64_t p : pieces) examined += p;
  state.counters["pieces_per_ray"] = static_cast<double>(examined) / static_cast<double>(batch.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch.size()));
  state.counters["hits_per_ray"] = static_cast<double>(hits) / static_cast<double>(batch.size());
}

void build_bvh_teapot(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(patchwork::PatchBvh(teapot()).nodes().size());
}

}  // namespace

BENCHMARK(closest_point_teapot)->Unit(benchmark::kMicrosecond);
BENCHMARK(ray_cast_teapot)->Args({1, 4})->Args({1, 8})->Args({1, 16})->Args({2, 8})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(build_bvh_teapot)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
