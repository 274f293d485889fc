#include "curves/bspline_conversion.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "curves/composite_curve.h"
#include "curves/continuity.h"
#include "tests/curves/bspline_exact_reference.h"
#include "tests/curves/bspline_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

RC_GTEST_PROP(BezierExtraction, PiecesJoinWithTheContinuityOfTheKnots, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const CompositeCurve<2> composite = to_composite(curve);
  const std::vector<double> breakpoints = curve.knot_vector().breakpoints();
  RC_ASSERT(composite.segments().size() + 1 == breakpoints.size());
  for (std::size_t i = 0; i < composite.segments().size(); ++i) {
    RC_ASSERT(composite.segments()[i].a() == breakpoints[i]);
    RC_ASSERT(composite.segments()[i].b() == breakpoints[i + 1]);
  }
  // Random control points: the join is C^(p-m) and (generically) not one order smoother.
  const std::vector<int> expected = curve.knot_vector().breakpoint_continuity();
  const std::vector<Continuity> joins = composite.continuity(curve.degree());
  RC_ASSERT(joins.size() == expected.size());
  for (std::size_t i = 0; i < joins.size(); ++i) RC_ASSERT(joins[i].ck == expected[i]);
}

RC_GTEST_PROP(BezierExtraction, RationalPiecesEvaluateAsTheCurve, ()) {
  const auto curve = *bspline_gen::nurbs_curve<3>(1, 5);
  const auto pieces = bezier_pieces(curve);
  double largest = 0.0;
  for (int i = 0; i < curve.control_point_count(); ++i) largest = std::max(largest, curve.control_point(i).norm());
  for (const auto& piece : pieces) {
    for (int j = 0; j <= 8; ++j) {
      const double u = std::min(piece.b(), piece.a() + (piece.b() - piece.a()) * j / 8.0);
      RC_ASSERT((piece.evaluate(u) - curve.evaluate(u)).norm() <= 1e-12 * largest);
    }
  }
}

RC_GTEST_PROP(BezierJoin, CompositeBackToTheSameBSpline, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  RC_PRE(curve.knot_vector().is_clamped());
  const BSplineCurve2 back = to_bspline(to_composite(curve));
  RC_ASSERT(back.knot_vector() == curve.knot_vector());
  for (std::size_t i = 0; i < curve.control_points().size(); ++i) {
    RC_ASSERT((back.control_points()[i] - curve.control_points()[i]).norm() <= 1e-9 * exact_bspline::scale(curve));
  }
}

RC_GTEST_PROP(BezierJoin, CkJoinedPiecesGiveMultiplicityDegreeMinusK, ()) {
  const int p = *rc::gen::inRange(1, 6);
  const int count = *rc::gen::inRange(2, 5);
  std::vector<BezierCurve2> segments;
  std::vector<int> orders;
  double start = 0.0;
  for (int i = 0; i < count; ++i) {
    const double length = *rc::gen::inRange(1, 9) / 8.0;
    std::vector<Vec2> P = *curve_gen::control_points<2>(p);
    if (i > 0) {
      // The next segment continues the previous one with C^k (Bemerkung 18 generalised).
      const int k = *rc::gen::inRange(0, p);
      const std::vector<Vec2> head = continue_ck(segments.back(), k, p, length);
      std::copy(head.begin(), head.end(), P.begin());
      orders.push_back(k);
    }
    segments.emplace_back(std::move(P), start, start + length);
    start += length;
  }
  const CompositeCurve<2> composite(segments);
  const BSplineCurve2 curve = to_bspline(composite);
  RC_ASSERT(curve.degree() == p);
  RC_ASSERT(curve.knot_vector().breakpoint_continuity() == orders);
  double scale = 0.0;
  for (const auto& segment : segments) {
    for (const auto& q : segment.control_points()) scale = std::max(scale, q.norm());
  }
  for (const auto& segment : segments) {
    for (int j = 0; j <= 8; ++j) {
      const double t = std::min(segment.b(), segment.a() + (segment.b() - segment.a()) * j / 8.0);
      RC_ASSERT((curve.evaluate(t) - segment.evaluate(t)).norm() <= 1e-8 * scale);
    }
  }
}

TEST(BezierJoin, SegmentsOfLowerDegreeAreElevatedAndGapsRefused) {
  const BezierCurve2 line({Vec2(0, 0), Vec2(1, 0)}, 0.0, 1.0);
  const BezierCurve2 quadratic({Vec2(1, 0), Vec2(2, 0), Vec2(2, 1)}, 1.0, 2.0);
  const BSplineCurve2 joined = to_bspline(CompositeCurve<2>({line, quadratic}));
  EXPECT_EQ(joined.degree(), 2);
  // The line at speed 1 meets the quadratic at speed 2: C^0 only, a double knot.
  EXPECT_EQ(joined.knot_vector().multiplicity(1.0), 2);
  EXPECT_NEAR((joined.evaluate(0.5) - Vec2(0.5, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((joined.evaluate(1.5) - quadratic.evaluate(1.5)).norm(), 0.0, 1e-15);
  const BezierCurve2 apart({Vec2(5, 5), Vec2(6, 5), Vec2(6, 6)}, 1.0, 2.0);
  expect_invalid_input([&] { (void)to_bspline(CompositeCurve<2>({line, apart})); }, "do not meet");
}

}  // namespace
}  // namespace patchwork
