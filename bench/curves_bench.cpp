// Points per second for Bezier curve evaluation: de Casteljau, compensated de Casteljau, and
// batch evaluation with a Bernstein table reused across calls, for cubic and degree-10 curves.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "curves/bezier_curve.h"
#include "curves/compensated.h"

namespace {

using patchwork::BezierCurve3;
using patchwork::Vec3;

constexpr int points_per_iteration = 1024;

// A fixed, non-degenerate curve of the given degree (a helix-like control polygon).
BezierCurve3 make_curve(int degree) {
  std::vector<Vec3> points;
  for (int i = 0; i <= degree; ++i) points.emplace_back(std::cos(1.3 * i), std::sin(0.7 * i), 0.25 * i);
  return BezierCurve3(std::move(points));
}

std::vector<double> parameters() {
  std::vector<double> ts(points_per_iteration);
  for (int k = 0; k < points_per_iteration; ++k) ts[k] = (k + 0.5) / points_per_iteration;
  return ts;
}

void de_casteljau(benchmark::State& state) {
  const BezierCurve3 curve = make_curve(static_cast<int>(state.range(0)));
  const std::vector<double> ts = parameters();
  for (auto _ : state) {
    for (double t : ts) benchmark::DoNotOptimize(curve.evaluate(t));
  }
  state.SetItemsProcessed(state.iterations() * points_per_iteration);
}

void compensated(benchmark::State& state) {
  const BezierCurve3 curve = make_curve(static_cast<int>(state.range(0)));
  const std::vector<double> ts = parameters();
  for (auto _ : state) {
    for (double t : ts) benchmark::DoNotOptimize(patchwork::evaluate_compensated(curve, t));
  }
  state.SetItemsProcessed(state.iterations() * points_per_iteration);
}

void batch_with_table(benchmark::State& state) {
  const BezierCurve3 curve = make_curve(static_cast<int>(state.range(0)));
  const std::vector<double> ts = parameters();
  const patchwork::BernsteinTable table(curve.degree(), ts);  // built once, reused
  for (auto _ : state) benchmark::DoNotOptimize(patchwork::evaluate(curve, table));
  state.SetItemsProcessed(state.iterations() * points_per_iteration);
}

void batch_building_table(benchmark::State& state) {
  const BezierCurve3 curve = make_curve(static_cast<int>(state.range(0)));
  const std::vector<double> ts = parameters();
  for (auto _ : state) benchmark::DoNotOptimize(patchwork::evaluate_many(curve, ts));
  state.SetItemsProcessed(state.iterations() * points_per_iteration);
}

BENCHMARK(de_casteljau)->Arg(3)->Arg(10);
BENCHMARK(compensated)->Arg(3)->Arg(10);
BENCHMARK(batch_with_table)->Arg(3)->Arg(10);
BENCHMARK(batch_building_table)->Arg(3)->Arg(10);

}  // namespace

BENCHMARK_MAIN();
