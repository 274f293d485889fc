#include "curves/flatness.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "curves/degree.h"
#include "tests/curves/curve_generators.h"
#include "tests/support/rounding.h"

namespace patchwork {
namespace {

using namespace testing;

// Largest parametric distance |C(s) - L(s)| found at `samples` fractions of each of N uniform
// steps, L the chord of the step; evaluated in the local parameter s = k/N + f/N.
template <int Dim>
double measured_deviation(const BezierCurve<Dim>& curve, std::int64_t N, const std::vector<double>& fractions) {
  const BezierCurve<Dim> unit = with_interval(curve, 0.0, 1.0);
  double worst = 0.0;
  for (std::int64_t k = 0; k < N; ++k) {
    const double s0 = static_cast<double>(k) / static_cast<double>(N);
    const double s1 = static_cast<double>(k + 1) / static_cast<double>(N);
    const Point<Dim> c0 = unit.evaluate(s0);
    const Point<Dim> c1 = unit.evaluate(s1);
    for (double f : fractions) {
      const Point<Dim> chord = (1.0 - f) * c0 + f * c1;
      worst = std::max(worst, (unit.evaluate(s0 + f * (s1 - s0)) - chord).norm());
    }
  }
  return worst;
}

TEST(Flatness, BoundFollowsClosedForm) {
  // Second differences (1, -1) and (-1, 3): the largest norm is sqrt(10); the bound for N steps
  // is 3*2/8 sqrt(10) / N^2.
  const BezierCurve2 curve({Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 7)}, -2.0, 7.0);
  EXPECT_EQ(max_second_difference(curve), std::sqrt(10.0));
  EXPECT_DOUBLE_EQ(flatness_bound(curve, 1), 0.75 * std::sqrt(10.0));
  EXPECT_DOUBLE_EQ(flatness_bound(curve, 3), 0.75 * std::sqrt(10.0) / 9.0);
  EXPECT_EQ(max_second_difference(BezierCurve2({Vec2(1, 1)})), 0.0);
  EXPECT_EQ(max_second_difference(BezierCurve2({Vec2(1, 1), Vec2(5, -2)})), 0.0);
}

RC_GTEST_PROP(Flatness, MaxSecondDifferenceMatchesExactNorms, ()) {
  const auto curve = *curve_gen::bezier_curve<3>(0, 12);
  const auto& P = curve.control_points();
  mpq_class largest = 0;
  for (std::size_t i = 1; i + 1 < P.size(); ++i) {
    mpq_class squared = 0;
    for (int c = 0; c < 3; ++c) {
      const mpq_class d = mpq_class(P[i + 1][c]) - 2 * mpq_class(P[i][c]) + mpq_class(P[i - 1][c]);
      squared += d * d;
    }
    largest = std::max(largest, squared);
  }
  const double expected = std::sqrt(largest.get_d());
  // P_{i+1} - 2 P_i + P_{i-1} is rounded twice on the scale 4M per coordinate, the norm adds a
  // few relative roundings.
  const double tolerance = 2 * 4 * kUnit * max_abs<3>(P) * std::sqrt(3.0) + 8 * kUnit * expected;
  RC_ASSERT(std::abs(max_second_difference(curve) - expected) <= tolerance);
  const int n = curve.degree();
  const std::int64_t N = *rc::gen::inRange<std::int64_t>(1, 1000);
  const double closed_form = n * (n - 1.0) / (8.0 * static_cast<double>(N * N)) * max_second_difference(curve);
  RC_ASSERT(std::abs(flatness_bound(curve, N) - closed_form) <= 4 * kUnit * closed_form);
}

RC_GTEST_PROP(Flatness, BoundIsAttainedForParabolaAtStepMidpoints, ()) {
  // For n = 2, C - L = -(s - s_k)(s_{k+1} - s)/2 C'' with C'' = 2 Delta^2 P constant: at the
  // midpoint of every step the distance is exactly h^2/8 |C''| = |Delta^2 P| / (4 N^2).
  const auto curve = *curve_gen::bezier_curve_on_interval<3>(2, 2);
  const std::int64_t N = *rc::gen::inRange<std::int64_t>(1, 65);
  const double bound = flatness_bound(curve, N);
  const BezierCurve3 unit = with_interval(curve, 0.0, 1.0);
  // Three evaluations (gamma_4 M each), the chord midpoint and the rounded step ends (moving
  // L by |C'| u <= 4 M u): 32 u M covers them and the bound's own rounding.
  const double tolerance = 32 * kUnit * max_abs<3>(curve.control_points());
  for (std::int64_t k = 0; k < N; ++k) {
    const double s0 = static_cast<double>(k) / static_cast<double>(N);
    const double s1 = static_cast<double>(k + 1) / static_cast<double>(N);
    const Vec3 chord_midpoint = 0.5 * (unit.evaluate(s0) + unit.evaluate(s1));
    const double distance = (unit.evaluate(0.5 * (s0 + s1)) - chord_midpoint).norm();
    RC_ASSERT(std::abs(distance - bound) <= tolerance);
  }
  // Elsewhere in a step the distance is smaller: 4 f (1-f) times the bound at fraction f.
  RC_ASSERT(measured_deviation<3>(curve, N, {0.25}) <= 0.75 * bound + tolerance);
}

RC_GTEST_PROP(Flatness, BoundHoldsForRandomCurves, ()) {
  const auto curve = *curve_gen::bezier_curve_on_interval<2>(0, 12);
  const std::int64_t N = *rc::gen::inRange<std::int64_t>(1, 21);
  const double f = *curve_gen::coordinate(0.0, 1.0);
  const int n = curve.degree();
  // Three evaluations (gamma_{2n} M each), the chord, and rounded step ends (|C'| u <= 2n M u).
  const double tolerance = 16 * (n + 1) * kUnit * max_abs<2>(curve.control_points());
  const double bound = flatness_bound(curve, N);
  RC_ASSERT(measured_deviation<2>(curve, N, {0.5, 0.1, 0.9, f}) <= bound + tolerance);
  // The bound is a property of the control points only, not of the interval.
  RC_ASSERT(flatness_bound(with_interval(curve, 0.0, 1.0), N) == bound);
}

RC_GTEST_PROP(Flatness, SegmentsForToleranceIsTheSmallestCount, ()) {
  const auto curve = *curve_gen::bezier_curve<3>(0, 12);
  const double tolerance = std::pow(10.0, *curve_gen::coordinate(-6.0, 1.0));
  const std::int64_t N = segments_for_tolerance(curve, tolerance);
  RC_ASSERT(N >= 1);
  RC_ASSERT(flatness_bound(curve, N) <= tolerance);
  // (RC_ASSERT does not short-circuit ||: evaluate the bound for N - 1 only when it exists.)
  const bool one_fewer_fails = N == 1 || flatness_bound(curve, N - 1) > tolerance;
  RC_ASSERT(one_fewer_fails);
}

RC_GTEST_PROP(Flatness, SegmentsForExactBoundGiveBackTheCount, ()) {
  // tolerance = bound(K) exactly: K meets it and K - 1 does not (the bound falls strictly with N
  // here), so the answer is K. sqrt and ceil on a rounded quotient must not overshoot to K + 1.
  const auto curve = *curve_gen::bezier_curve<2>(2, 12);
  RC_PRE(max_second_difference(curve) > 0.0);
  const std::int64_t K = *rc::gen::inRange<std::int64_t>(1, 1000001);
  const double tolerance = flatness_bound(curve, K);
  RC_ASSERT(segments_for_tolerance(curve, tolerance) == K);
}

TEST(Flatness, StraightCurvesNeedOneSegment) {
  // Zero second differences: a point, a segment, and that segment as a quintic (uniformly
  // spaced collinear integer points, the degree-elevated segment).
  const BezierCurve2 line({Vec2(0, 0), Vec2(5, 10)});
  const BezierCurve2 quintic({Vec2(0, 0), Vec2(1, 2), Vec2(2, 4), Vec2(3, 6), Vec2(4, 8), Vec2(5, 10)});
  for (const BezierCurve2& curve : {BezierCurve2({Vec2(3, 4)}), line, quintic}) {
    EXPECT_EQ(flatness_bound(curve, 1), 0.0);
    EXPECT_EQ(segments_for_tolerance(curve, 1e-300), 1);
    EXPECT_EQ(segments_for_tolerance(curve, 1e300), 1);
  }
}

TEST(Flatness, SegmentsForParabolaClosedForm) {
  // (t, t^2): Delta^2 P = (0, 1), bound(N) = 1/(4 N^2). Tolerance 1e-4 needs N >= 50.
  const BezierCurve2 parabola({Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 1)});
  EXPECT_EQ(segments_for_tolerance(parabola, 1e-4), 50);
  EXPECT_EQ(segments_for_tolerance(parabola, 0.99e-4), 51);
  EXPECT_EQ(segments_for_tolerance(parabola, 0.25), 1);
  EXPECT_EQ(segments_for_tolerance(parabola, 0.2), 2);
}

TEST(Flatness, RejectsBadInput) {
  const BezierCurve2 parabola({Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 1)});
  expect_invalid_input([&] { flatness_bound(parabola, 0); }, "flatness_bound");
  expect_invalid_input([&] { flatness_bound(parabola, -3); }, "flatness_bound");
  expect_invalid_input([&] { segments_for_tolerance(parabola, 0.0); }, "segments_for_tolerance");
  expect_invalid_input([&] { segments_for_tolerance(parabola, -1.0); }, "segments_for_tolerance");
  expect_invalid_input([&] { segments_for_tolerance(parabola, std::numeric_limits<double>::quiet_NaN()); },
                       "segments_for_tolerance");
  expect_invalid_input([&] { segments_for_tolerance(parabola, std::numeric_limits<double>::infinity()); },
                       "segments_for_tolerance");
  // 1/(4 N^2) <= 1e-20 needs N = 5e9 > 2^31.
  expect_invalid_input([&] { segments_for_tolerance(parabola, 1e-20); }, "2^31");
  // Just below the bound for 2^31 segments: 2^31 + 1 would be needed, one too many.
  const std::int64_t limit = std::int64_t{1} << 31;
  EXPECT_EQ(segments_for_tolerance(parabola, flatness_bound(parabola, limit)), limit);
  expect_invalid_input([&] { segments_for_tolerance(parabola, std::nextafter(flatness_bound(parabola, limit), 0.0)); },
                       "2^31");
}

}  // namespace
}  // namespace patchwork
