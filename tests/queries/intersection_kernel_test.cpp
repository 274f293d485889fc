// The kernel the intersection queries stand on: pieces by blossoming (also past the curve's
// interval), derivative enclosures that contain every sampled derivative, and touching groups.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "queries/intersection_kernel.h"

namespace intersection_kernel_test {
namespace {

using namespace patchwork;

// A rational cubic with coordinates on a grid of 1/8 and weights 1..4, on [0, 1].
RationalBezierCurve2 rational_cubic() {
  const auto v = *rc::gen::container<std::vector<int>>(8, rc::gen::inRange(-16, 17));
  const auto w = *rc::gen::container<std::vector<int>>(4, rc::gen::inRange(1, 5));
  std::vector<Vec2> points;
  for (int i = 0; i < 4; ++i) points.emplace_back(v[2 * i] / 8.0, v[2 * i + 1] / 8.0);
  return RationalBezierCurve2(points, std::vector<double>(w.begin(), w.end()));
}

RC_GTEST_PROP(IntersectionKernel, PieceEvaluatesToTheCurveAndEnclosesItsDerivative, ()) {
  const RationalBezierCurve2 curve = rational_cubic();
  const double t0 = *rc::gen::inRange(-2, 60) / 64.0;
  const double t1 = t0 + *rc::gen::inRange(1, 8) / 64.0;
  const detail::CurvePiece<2> piece = detail::curve_piece(curve, t0, t1);
  RC_PRE(piece.valid);
  const RationalBezierCurve2 as_curve(BezierCurve<3>(piece.H, t0, t1));
  const auto enclosure = detail::derivative_enclosure(piece);
  for (int k = 0; k <= 16; ++k) {
    const double t = t0 + (t1 - t0) * k / 16.0;
    RC_ASSERT((as_curve.evaluate(t) - curve.evaluate(t)).norm() <= 1e-12);
    RC_ASSERT(piece.box.exteriorDistance(curve.evaluate(t)) <= 1e-12);
    const Vec2 d = derivative(curve, t, 1);
    for (int c = 0; c < 2; ++c) {
      RC_ASSERT(enclosure[c].lo <= d[c] + 1e-12 * (1 + std::abs(d[c])));
      RC_ASSERT(d[c] <= enclosure[c].hi + 1e-12 * (1 + std::abs(d[c])));
    }
    // The piece lies within `flatness` of its chord.
    RC_ASSERT(detail::segment_distance<2>(curve.evaluate(t), piece.P.front(), piece.P.back()) <= piece.flatness + 1e-12);
  }
}

TEST(IntersectionKernel, TouchingGroupsChainThroughSharedSides) {
  using detail::Interval;
  const std::vector<std::array<Interval, 2>> boxes{
      {Interval{0, 1}, Interval{0, 1}}, {Interval{1, 2}, Interval{1, 2}},  // corner to corner
      {Interval{3, 4}, Interval{0, 1}},                                    // apart
      {Interval{2, 3}, Interval{5, 6}}, {Interval{2.5, 3.5}, Interval{5.5, 7}}};
  const auto groups = detail::touching_groups<2>(boxes, 0.0);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0], (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(groups[1], (std::vector<std::size_t>{2}));
  EXPECT_EQ(groups[2], (std::vector<std::size_t>{3, 4}));
}

}  // namespace
}  // namespace intersection_kernel_test
