// The flatness bound on the teapot (the smaller of the Filip-Magedson-Markot norm bound and the
// directional bound): it must hold (measured <= bound) and must not be loose by more than a small
// factor, since the tessellator's triangle count rests on it.

#include <gtest/gtest.h>

#include "io/bpt.h"
#include "surfaces/patch_flatness.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork {
namespace {


TEST(TeapotFlatness, BoundHoldsAndIsWithinTheDocumentedFactorOfTheMeasuredDistance) {
  const std::vector<BezierPatch3> patches = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  double loosest = 0.0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const SecondDerivativeBounds M = second_derivative_bounds(patches[k]);
    const GridSize grid = grid_for_tolerance(M, 1e-2);
    const double bound = flatness_bound(M, 1.0 / grid.segments_u, 1.0 / grid.segments_v);
    const double measured = testing::measured_distance(patches[k], grid.segments_u, grid.segments_v, 6);
    EXPECT_LE(bound, 1e-2) << "patch " << k;
    EXPECT_LE(measured, bound) << "patch " << k;
    // Sampling finds a lower bound of the true distance, so this ratio is an upper bound.
    EXPECT_LE(bound, 3.0 * measured) << "patch " << k;
    loosest = std::max(loosest, bound / measured);
  }
  std::cout << "teapot at tolerance 1e-2: the flatness bound is at most " << loosest << " x the measured distance\n";
  // README and docs/surfaces.md quote 1.67x: the figure is held here, not only the loose 3x.
  EXPECT_LE(loosest, 1.675);
}

}  // namespace
}  // namespace patchwork
