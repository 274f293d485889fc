// The Filip-Magedson-Markot bound on the teapot: it must hold (measured <= bound) and must not
// be loose by more than a small factor, since the tessellator's triangle count rests on it.

#include <gtest/gtest.h>

#include "io/bpt.h"
#include "surfaces/patch_flatness.h"

namespace patchwork {
namespace {

// max |F - L| over the triangulated grid, sampled at 6 x 6 barycentric points per triangle
// (cells split along the diagonal from (u_a, v_b) to (u_a+1, v_b+1)).
double measured_distance(const BezierPatch3& patch, std::int64_t nu, std::int64_t nv) {
  constexpr int samples = 6;
  double result = 0.0;
  for (std::int64_t b = 0; b < nv; ++b) {
    for (std::int64_t a = 0; a < nu; ++a) {
      const double u0 = static_cast<double>(a) / nu, u1 = static_cast<double>(a + 1) / nu;
      const double v0 = static_cast<double>(b) / nv, v1 = static_cast<double>(b + 1) / nv;
      const Vec3 p00 = patch.evaluate(u0, v0), p10 = patch.evaluate(u1, v0);
      const Vec3 p01 = patch.evaluate(u0, v1), p11 = patch.evaluate(u1, v1);
      for (int s = 0; s <= samples; ++s) {
        for (int t = 0; s + t <= samples; ++t) {
          const double x = static_cast<double>(s) / samples, y = static_cast<double>(t) / samples;
          const Vec3 lower = (1 - x - y) * p00 + x * p10 + y * p11;
          result = std::max(result, (patch.evaluate(u0 + (x + y) * (u1 - u0), v0 + y * (v1 - v0)) - lower).norm());
          const Vec3 upper = (1 - x - y) * p00 + x * p11 + y * p01;
          result = std::max(result, (patch.evaluate(u0 + x * (u1 - u0), v0 + (x + y) * (v1 - v0)) - upper).norm());
        }
      }
    }
  }
  return result;
}

TEST(TeapotFlatness, BoundHoldsAndIsWithinThreeTimesTheMeasuredDistance) {
  const std::vector<BezierPatch3> patches = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  double loosest = 0.0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const SecondDerivativeBounds M = second_derivative_bounds(patches[k]);
    const GridSize grid = grid_for_tolerance(M, 1e-2);
    const double bound = flatness_bound(M, 1.0 / grid.segments_u, 1.0 / grid.segments_v);
    const double measured = measured_distance(patches[k], grid.segments_u, grid.segments_v);
    EXPECT_LE(bound, 1e-2) << "patch " << k;
    EXPECT_LE(measured, bound) << "patch " << k;
    // Sampling finds a lower bound of the true distance, so this ratio is an upper bound.
    EXPECT_LE(bound, 3.0 * measured) << "patch " << k;
    loosest = std::max(loosest, bound / measured);
  }
  std::cout << "teapot at tolerance 1e-2: the FMM bound is at most " << loosest << " x the measured distance\n";
}

}  // namespace
}  // namespace patchwork
