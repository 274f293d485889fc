#include "curves/composite_curve.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "curves/subdivision.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// Three segments on [0, 1.5], [1.5, 4.5], [4.5, 5]: a cubic, its C^1 continuation by
// Bemerkung 18 (Q_1 = (4,1) + (3/4)(3/1.5)(1,-2) = (5.5,-2)), and a line leaving at a kink.
CompositeCurve<2> three_segments() {
  return CompositeCurve<2>({BezierCurve2({Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)}, 0.0, 1.5),
                            BezierCurve2({Vec2(4, 1), Vec2(5.5, -2), Vec2(7, 0), Vec2(6, 3), Vec2(9, 9)}, 1.5, 4.5),
                            BezierCurve2({Vec2(9, 9), Vec2(9, 12)}, 4.5, 5.0)});
}

TEST(CompositeCurve, RangeAndSegmentLookup) {
  const CompositeCurve<2> curve = three_segments();
  EXPECT_EQ(curve.a(), 0.0);
  EXPECT_EQ(curve.b(), 5.0);
  EXPECT_EQ(curve.segments().size(), 3u);
  // A breakpoint belongs to the segment starting there; the end to the last segment.
  EXPECT_EQ(curve.segment_index(0.0), 0u);
  EXPECT_EQ(curve.segment_index(1.0), 0u);
  EXPECT_EQ(curve.segment_index(std::nextafter(1.5, 0.0)), 0u);
  EXPECT_EQ(curve.segment_index(1.5), 1u);
  EXPECT_EQ(curve.segment_index(4.5), 2u);
  EXPECT_EQ(curve.segment_index(5.0), 2u);
}

TEST(CompositeCurve, EvaluatesTheSegmentsAtBreakpointsAndInside) {
  const CompositeCurve<2> curve = three_segments();
  const auto& segments = curve.segments();
  // At a breakpoint (local s = 0) and at the end (s = 1) de Casteljau returns the control point
  // exactly.
  EXPECT_EQ(curve.evaluate(0.0), Vec2(0, 0));
  EXPECT_EQ(curve.evaluate(1.5), Vec2(4, 1));
  EXPECT_EQ(curve.evaluate(4.5), Vec2(9, 9));
  EXPECT_EQ(curve(5.0), Vec2(9, 12));
  // Inside: the line is (9, 9 + 3 (t - 4.5)/0.5), exact at these dyadic parameters.
  EXPECT_EQ(curve.evaluate(4.75), Vec2(9, 10.5));
  for (double t : {0.3, 1.0, 2.0, 3.3, 4.4, 4.9}) {
    const std::size_t i = t < 1.5 ? 0 : (t < 4.5 ? 1 : 2);
    EXPECT_EQ(curve.evaluate(t), segments[i].evaluate(t)) << "t=" << t;
    EXPECT_EQ(curve.derivative(t, 2), derivative(segments[i], t, 2)) << "t=" << t;
  }
  // Derivatives at a breakpoint are one-sided, from the segment starting there: at 4.5 the
  // line's C' = (0, 3)/0.5, exactly, not the quartic's.
  EXPECT_EQ(curve.derivative(4.5, 1), Vec2(0, 6));
  EXPECT_EQ(curve.derivative(4.5, 0), Vec2(9, 9));
  // At t = 1.5 the join is C^1: both sides give C' = 3 (1,-2) / 1.5 = (2, -4) up to rounding of
  // the factor n/(b-a) (a few ulps of |C'| ~ 4.5).
  EXPECT_LT((curve.derivative(1.5, 1) - Vec2(2, -4)).norm(), 8 * eps * 4.5);
  EXPECT_LT((derivative(segments[0], 1.5, 1) - Vec2(2, -4)).norm(), 8 * eps * 4.5);
}

TEST(CompositeCurve, ContinuityAtEveryJoint) {
  const CompositeCurve<2> curve = three_segments();
  const std::vector<Continuity> joints = curve.continuity(3);
  ASSERT_EQ(joints.size(), 2u);
  EXPECT_EQ(joints[0].ck, 1);  // Bemerkung 18
  EXPECT_TRUE(joints[0].g1);
  EXPECT_EQ(joints[1].ck, 0);  // the quartic arrives along (3, 6), the line leaves along (0, 3)
  EXPECT_FALSE(joints[1].g1);
  // A segment may start away from where the previous one ended in space (only the parameter
  // intervals must be contiguous): the joint reports the gap.
  const CompositeCurve<2> gapped(
      {BezierCurve2({Vec2(0, 0), Vec2(1, 0)}, 0.0, 1.0), BezierCurve2({Vec2(1, 0.75), Vec2(2, 0)}, 1.0, 2.0)});
  const std::vector<Continuity> gap = gapped.continuity(2);
  ASSERT_EQ(gap.size(), 1u);
  EXPECT_EQ(gap[0].ck, -1);
  EXPECT_EQ(gap[0].gap, 0.75);
  // One segment has no joints.
  EXPECT_TRUE(CompositeCurve<2>({BezierCurve2({Vec2(0, 0), Vec2(1, 0)})}).continuity(2).empty());
}

TEST(CompositeCurve, RejectsBadInput) {
  EXPECT_THROW(CompositeCurve<2>(std::vector<BezierCurve2>{}), InvalidInput);
  const BezierCurve2 first({Vec2(0, 0), Vec2(1, 0)}, 0.0, 1.0);
  // A gap, an overlap, one ulp apart, and a segment out of order.
  EXPECT_THROW(CompositeCurve<2>({first, BezierCurve2({Vec2(1, 0), Vec2(2, 0)}, 1.1, 2.0)}), InvalidInput);
  EXPECT_THROW(CompositeCurve<2>({first, BezierCurve2({Vec2(1, 0), Vec2(2, 0)}, 0.9, 2.0)}), InvalidInput);
  EXPECT_THROW(CompositeCurve<2>({first, BezierCurve2({Vec2(1, 0), Vec2(2, 0)}, std::nextafter(1.0, 2.0), 2.0)}),
               InvalidInput);
  EXPECT_THROW(CompositeCurve<2>({first, BezierCurve2({Vec2(1, 0), Vec2(2, 0)}, -1.0, 0.0)}), InvalidInput);

  const CompositeCurve<2> curve = three_segments();
  EXPECT_THROW(curve.evaluate(std::nextafter(0.0, -1.0)), InvalidInput);
  EXPECT_THROW(curve.evaluate(std::nextafter(5.0, 6.0)), InvalidInput);
  EXPECT_THROW(curve.evaluate(-1.0), InvalidInput);
  EXPECT_THROW(curve.evaluate(std::nan("")), InvalidInput);
  EXPECT_THROW(curve.evaluate(std::numeric_limits<double>::infinity()), InvalidInput);
  EXPECT_THROW(curve.segment_index(7.0), InvalidInput);
  EXPECT_THROW(curve.derivative(6.0, 1), InvalidInput);
  EXPECT_THROW(curve.derivative(1.0, -1), InvalidInput);
  EXPECT_THROW(curve.continuity(-1), InvalidInput);
}

RC_GTEST_PROP(CompositeCurve, PiecesOfOneCurveReproduceItAndJoinSmoothly, ()) {
  // Cut one curve at sorted random parameters: the composite evaluates like the curve, picks
  // the segment whose interval holds t, and every joint is C^(n+1) (one polynomial).
  const int n = *rc::gen::inRange(1, 9);
  std::vector<Vec3> P(static_cast<std::size_t>(n) + 1);
  double magnitude = 0.0;
  for (auto& p : P) {
    p = Vec3(random_unit(), random_unit(), random_unit()) * 2.0 - Vec3::Ones();
    magnitude = std::max(magnitude, p.norm());
  }
  const BezierCurve3 curve(P, -1.0, 3.0);
  std::vector<int> cuts = *rc::gen::unique<std::vector<int>>(rc::gen::inRange(1, 400));
  std::sort(cuts.begin(), cuts.end());
  if (cuts.size() > 6) cuts.resize(6);
  std::vector<BezierCurve3> segments;
  BezierCurve3 rest = curve;
  for (int cut : cuts) {
    auto [left, right] = split(rest, -1.0 + cut / 100.0);
    segments.push_back(std::move(left));
    rest = std::move(right);
  }
  segments.push_back(rest);
  const CompositeCurve<3> composite(segments);
  RC_ASSERT(composite.a() == -1.0 && composite.b() == 3.0);
  for (int i = 0; i <= 40; ++i) {
    const double t = -1.0 + 0.1 * i;
    const double clamped = std::min(t, 3.0);
    const std::size_t index = composite.segment_index(clamped);
    const auto& segment = composite.segments()[index];
    RC_ASSERT(segment.a() <= clamped);
    RC_ASSERT(clamped < segment.b() || (index + 1 == segments.size() && clamped == segment.b()));
    // Up to 6 splits and two evaluations, each a de Casteljau run with error <= gamma_{2n} max|P|
    // (convex combinations do not amplify earlier errors): 8 * 2n eps max|P|, doubled for room.
    RC_ASSERT((composite.evaluate(clamped) - curve.evaluate(clamped)).norm() <= 32.0 * n * eps * magnitude);
  }
  for (const Continuity& joint : composite.continuity(n + 1)) {
    RC_ASSERT(joint.ck == n + 1);
  }
}

}  // namespace
}  // namespace patchwork
