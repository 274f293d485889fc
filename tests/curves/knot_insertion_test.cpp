#include "curves/knot_insertion.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "tests/curves/bspline_exact_reference.h"
#include "tests/curves/bspline_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// max |C(u) - D(u)| at 257 equally spaced parameters and every breakpoint of either curve.
template <class Curve>
double sampled_distance(const Curve& C, const Curve& D) {
  std::vector<double> us = C.knot_vector().breakpoints();
  const std::vector<double> more = D.knot_vector().breakpoints();
  us.insert(us.end(), more.begin(), more.end());
  for (int i = 0; i <= 256; ++i) us.push_back(std::min(C.b(), C.a() + (C.b() - C.a()) * (i / 256.0)));
  double worst = 0.0;
  for (double u : us) worst = std::max(worst, (C.evaluate(u) - D.evaluate(u)).norm());
  return worst;
}

// A parameter strictly inside (a, b) where the knot can be inserted once more, if there is one.
double insertable_interior_parameter(const KnotVector& knots) {
  const double u = *rc::gen::weightedOneOf<double>(
      {{1, rc::gen::elementOf(knots.breakpoints())}, {3, curve_gen::coordinate(knots.a(), knots.b())}});
  RC_PRE(knots.a() < u && u < knots.b() && knots.multiplicity(u) < knots.degree());
  return u;
}

RC_GTEST_PROP(KnotInsertion, ControlPointsAreTheExactBlossoms, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const double u = *bspline_gen::parameter(curve.knot_vector());
  const int room = curve.degree() - curve.knot_vector().multiplicity(u);
  RC_PRE(room > 0);
  const int times = *rc::gen::inRange(1, room + 1);
  const BSplineCurve2 inserted = insert_knot(curve, u, times);
  RC_ASSERT(inserted.knot_vector().multiplicity(u) == curve.knot_vector().multiplicity(u) + times);
  RC_ASSERT(inserted.knot_vector().size() == curve.knot_vector().size() + times);
  RC_ASSERT(inserted.a() == curve.a());
  RC_ASSERT(inserted.b() == curve.b());
  const auto exact = exact_bspline::refined_points(curve, inserted.knot_vector());
  // Each new point is `times` levels of convex combinations of old ones.
  const double tolerance = 2.0 * gamma(3 * times + 3) * exact_bspline::scale(curve);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    RC_ASSERT(exact_bspline::distance<2>(inserted.control_points()[i], exact[i]) <= tolerance);
  }
  // The curve is unchanged: the rounded new points, evaluated exactly, at a rational parameter.
  const mpq_class t =
      mpq_class(curve.a()) + (mpq_class(curve.b()) - mpq_class(curve.a())) * *rc::gen::inRange(0, 8) / 7;
  RC_ASSERT(exact_bspline::distance<2>(exact_bspline::evaluate(inserted, t), exact_bspline::evaluate(curve, t)) <=
            tolerance);
}

RC_GTEST_PROP(KnotInsertion, RefinementKeepsTheCurve, ()) {
  const auto curve = *bspline_gen::bspline_curve<3>(1, 5);
  const auto extra = *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(*rc::gen::inRange(1, 7)),
                                                              curve_gen::coordinate(curve.a(), curve.b()));
  std::vector<double> all = extra;
  all.insert(all.end(), curve.knot_vector().knots().begin(), curve.knot_vector().knots().end());
  for (double u : extra) RC_PRE(static_cast<int>(std::count(all.begin(), all.end(), u)) <= curve.degree());
  const BSplineCurve3 refined = refine_knots(curve, extra);
  RC_ASSERT(refined.knot_vector().size() == curve.knot_vector().size() + static_cast<int>(extra.size()));
  RC_ASSERT(sampled_distance(curve, refined) <= 64.0 * eps * curve.degree() * exact_bspline::scale(curve));
}

RC_GTEST_PROP(KnotRemoval, InsertThenRemoveGivesTheOriginal, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5);
  const double u = insertable_interior_parameter(curve.knot_vector());
  const int times = *rc::gen::inRange(1, curve.degree() - curve.knot_vector().multiplicity(u) + 1);
  const BSplineCurve2 inserted = insert_knot(curve, u, times);
  const double tolerance = 1e-9 * exact_bspline::scale(curve);
  const auto removal = remove_knot(inserted, u, times, tolerance);
  RC_ASSERT(removal.removed == times);
  RC_ASSERT(removal.bound <= tolerance);
  RC_ASSERT(removal.curve.knot_vector() == curve.knot_vector());
  for (std::size_t i = 0; i < curve.control_points().size(); ++i) {
    RC_ASSERT((removal.curve.control_points()[i] - curve.control_points()[i]).norm() <= tolerance);
  }
  RC_ASSERT(sampled_distance(inserted, removal.curve) <= removal.bound);
}

RC_GTEST_PROP(KnotRemoval, BoundHoldsAndRemovalBeyondTheToleranceIsRefused, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 5, 4, 1);
  const std::vector<double> breakpoints = curve.knot_vector().breakpoints();
  const double u = breakpoints[static_cast<std::size_t>(*rc::gen::inRange<std::size_t>(1, breakpoints.size() - 1))];
  const int times = *rc::gen::inRange(1, curve.knot_vector().multiplicity(u) + 1);
  const auto unconditional = remove_knot(curve, u, times, std::numeric_limits<double>::infinity());
  RC_ASSERT(unconditional.removed == times);
  const double moved = sampled_distance(curve, unconditional.curve);
  RC_ASSERT(moved <= unconditional.bound);
  // A tolerance between 0 and twice the bound: accepted exactly when the bound allows it, and
  // always refused when the sampled change alone exceeds the tolerance.
  const double tolerance = unconditional.bound * *rc::gen::inRange(0, 201) / 100.0;
  const auto removal = remove_knot(curve, u, times, tolerance);
  RC_ASSERT(removal.bound <= tolerance);
  RC_ASSERT(sampled_distance(curve, removal.curve) <= removal.bound);
  if (unconditional.bound <= tolerance) RC_ASSERT(removal.removed == times);
  if (moved > tolerance) RC_ASSERT(removal.removed < times);
  if (removal.removed == 0) RC_ASSERT(removal.curve == curve);
}

RC_GTEST_PROP(KnotRemoval, RationalBoundHolds, ()) {
  const auto curve = *bspline_gen::nurbs_curve<2>(1, 4, 4, 1);
  const std::vector<double> breakpoints = curve.knot_vector().breakpoints();
  const double u = breakpoints[static_cast<std::size_t>(*rc::gen::inRange<std::size_t>(1, breakpoints.size() - 1))];
  const auto removal = remove_knot(curve, u, 1, std::numeric_limits<double>::infinity());
  if (removal.removed == 1) {
    RC_ASSERT(sampled_distance(curve, removal.curve) <= removal.bound);
  } else {
    RC_ASSERT(removal.curve == curve);  // refused only for a weight <= 0
  }
  // Insert and remove again: the rational curve comes back within the bound.
  const double v = insertable_interior_parameter(curve.knot_vector());
  const auto inserted = insert_knot(curve, v, 1);
  RC_ASSERT(sampled_distance(curve, inserted) <= 1e-12 * 64.0 * exact_bspline::scale(curve.homogeneous()));
  const auto back = remove_knot(inserted, v, 1, 1e-9 * exact_bspline::scale(curve.homogeneous()));
  RC_ASSERT(back.removed == 1);
  RC_ASSERT(back.curve.knot_vector() == curve.knot_vector());
  RC_ASSERT(sampled_distance(inserted, back.curve) <= back.bound);
}

RC_GTEST_PROP(DegreeElevation, SameCurveOneDegreeHigherSameContinuity, ()) {
  const auto curve = *bspline_gen::bspline_curve<2>(1, 4, 4);
  const int times = *rc::gen::inRange(1, 3);
  const BSplineCurve2 elevated = elevate_degree(curve, times);
  RC_ASSERT(elevated.degree() == curve.degree() + times);
  RC_ASSERT(elevated.a() == curve.a());
  RC_ASSERT(elevated.b() == curve.b());
  RC_ASSERT(elevated.knot_vector().is_clamped());
  RC_ASSERT(elevated.knot_vector().breakpoints() == curve.knot_vector().breakpoints());
  RC_ASSERT(elevated.knot_vector().breakpoint_continuity() == curve.knot_vector().breakpoint_continuity());
  RC_ASSERT(sampled_distance(curve, elevated) <= 1e-10 * exact_bspline::scale(curve));
}

TEST(KnotInsertion, BadInputIsRefused) {
  const BSplineCurve2 curve(KnotVector(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}),
                            {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0, 2)});
  expect_invalid_input([&] { (void)insert_knot(curve, 1.5); }, "outside the valid range");
  expect_invalid_input([&] { (void)insert_knot(curve, 0.5); }, "would exceed the degree 2");
  expect_invalid_input([&] { (void)insert_knot(curve, 0.25, -1); }, "negative");
  expect_invalid_input([&] { (void)refine_knots(curve, std::vector<double>{0.25, 0.25, 0.25}); }, "would exceed");
  expect_invalid_input([&] { (void)remove_knot(curve, 0.25, 1, 1.0); }, "not a knot inside");
  expect_invalid_input([&] { (void)remove_knot(curve, 0.0, 1, 1.0); }, "not a knot inside");
  expect_invalid_input([&] { (void)remove_knot(curve, 0.5, 3, 1.0); }, "times = 3 is not in [1, 2]");
  expect_invalid_input([&] { (void)remove_knot(curve, 0.5, 1, -1.0); }, "negative or NaN");
  EXPECT_EQ(insert_knot(curve, 0.25, 0), curve);
}

}  // namespace
}  // namespace patchwork

namespace patchwork {
namespace {

RC_GTEST_PROP(NurbsCurve, RefinementAndElevationKeepTheCurve, ()) {
  const auto curve = *bspline_gen::nurbs_curve<3>(1, 4, 4);
  const auto extra = *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(*rc::gen::inRange(1, 5)),
                                                              curve_gen::coordinate(curve.a(), curve.b()));
  for (double u : extra) RC_PRE(curve.knot_vector().multiplicity(u) == 0);
  RC_PRE(std::adjacent_find(extra.begin(), extra.end()) == extra.end());
  const double scale = testing::max_norm(curve.homogeneous().control_points());
  const auto refined = refine_knots(curve, extra);
  RC_ASSERT(refined.knot_vector().size() == curve.knot_vector().size() + static_cast<int>(extra.size()));
  RC_ASSERT(sampled_distance(curve, refined) <= 1e-12 * scale);
  const auto elevated = elevate_degree(curve, 1);
  RC_ASSERT(elevated.degree() == curve.degree() + 1);
  RC_ASSERT(elevated.knot_vector().breakpoint_continuity() == curve.knot_vector().breakpoint_continuity());
  RC_ASSERT(sampled_distance(curve, elevated) <= 1e-10 * scale);
}

}  // namespace
}  // namespace patchwork
