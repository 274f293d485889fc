// The half-plane test on a piece's plane-distance nets (queries/ray_piece_nets.h) never drops a
// piece with a zero, and drops pieces whose points lie in a half-plane that no axis bounds.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include "queries/ray_piece_nets.h"

namespace ray_piece_nets_test {
namespace {

using namespace patchwork;
using detail::ray_nets::FixedScalarNets;

double coordinate() { return *rc::gen::inRange(-1000000, 1000000) / 1e5; }

// Bicubic Bernstein basis value i at x.
double basis(int i, double x) {
  const double binomial[4] = {1, 3, 3, 1};
  return binomial[i] * std::pow(x, i) * std::pow(1 - x, 3 - i);
}

// Nets of (g_1, g_2) with a common zero at (s, t) in the piece (inside, on an edge, at a corner): random nets less their values
// there (the basis sums to 1, so subtracting a constant from every coefficient subtracts it from
// the function). Points drawn near a line or a half-plane, to make the cone narrow.
RC_GTEST_PROP(RayPieceNets, NeverDropsAPieceWithAZero, ()) {
  FixedScalarNets<3, 3> nets;
  // The zero inside, or on an edge or at a corner (where the origin is on the points' hull).
  const auto parameter = [] { return *rc::gen::oneOf(rc::gen::just(0.0), rc::gen::just(1.0), rc::gen::map(rc::gen::inRange(0, 1001), [](int i) { return i / 1000.0; })); };
  const double s = parameter(), t = parameter();
  const double slope = coordinate(), spread = *rc::gen::element(1e-6, 1e-2, 1.0, 100.0);
  for (std::size_t k = 0; k < 16; ++k) {
    nets.g[0][k] = coordinate();
    nets.g[1][k] = slope * nets.g[0][k] + spread * coordinate();
  }
  for (auto& g : nets.g) {
    double value = 0.0;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) value += basis(i, s) * basis(j, t) * g[static_cast<std::size_t>(i + 4 * j)];
    for (double& c : g) c -= value;
  }
  // The subtraction and the sum round by far less than this.
  nets.margin = 1e-10;
  RC_ASSERT(!detail::ray_nets::hull_misses_origin(nets));
}

// The nets' margin is what keeps a piece whose exact nets touch the half-plane's boundary: exact
// nets with a common zero at (1/2, 0) on the edge t = 0, whose row there lies on a line through
// the origin (g_1 = 0, g_2 = 2s - 1, rotated by a random angle) and whose other rows lie beyond
// it, moved off the line by margin / 2 (as rounding may move them). The computed points are then
// all strictly in a half-plane, by less than the margin: kept. (The test without its margin
// drops the piece.)
RC_GTEST_PROP(RayPieceNets, KeepsAZeroOnTheHalfPlanesBoundaryWithinTheMargin, ()) {
  FixedScalarNets<3, 3> nets;
  nets.margin = *rc::gen::element(1e-12, 1e-8, 1e-4);
  const double angle = *rc::gen::inRange(0, 6284) / 1000.0;
  const double c = std::cos(angle), s = std::sin(angle);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      // Before the rotation: x = 0 on the edge row, beyond the line elsewhere; y anything.
      const double x = j == 0 ? 0.0 : j * (0.5 + std::abs(coordinate()));
      const double y = j == 0 ? -1.0 + 2.0 * i / 3.0 : coordinate();
      // Off the line by half the margin (the line's normal is (c, s) after the rotation).
      const double moved = x + 0.5 * nets.margin;
      const auto k = static_cast<std::size_t>(i + 4 * j);
      nets.g[0][k] = c * moved - s * y;
      nets.g[1][k] = s * moved + c * y;
    }
  }
  RC_ASSERT(!detail::ray_nets::hull_misses_origin(nets));
}

TEST(RayPieceNets, DropsAPieceMissedObliquely) {
  // Points with x + y >= 1 but both signs in x and in y: no axis separates them from the origin.
  FixedScalarNets<3, 3> nets;
  for (std::size_t k = 0; k < 16; ++k) {
    const double x = -2.0 + 0.3 * static_cast<double>(k);
    nets.g[0][k] = x;
    nets.g[1][k] = 1.0 - x + 0.05 * static_cast<double>(k % 3);
  }
  nets.margin = 1e-12;
  EXPECT_FALSE(detail::ray_nets::one_sign(nets.g[0], nets.margin));
  EXPECT_FALSE(detail::ray_nets::one_sign(nets.g[1], nets.margin));
  EXPECT_TRUE(detail::ray_nets::hull_misses_origin(nets));
  // The origin on the hull's edge (one point at 0): kept.
  nets.g[0][5] = nets.g[1][5] = 0.0;
  EXPECT_FALSE(detail::ray_nets::hull_misses_origin(nets));
}

}  // namespace
}  // namespace ray_piece_nets_test
