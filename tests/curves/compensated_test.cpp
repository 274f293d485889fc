#include "curves/compensated.h"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/errors.h"
#include "tests/curves/exact_reference.h"

namespace patchwork {
namespace {

// The parameters the issue names, plus a few generic ones. 1e-12 and 1 - 1e-12 are not
// representable: the double nearest to them IS the parameter, and the reference uses it exactly.
const std::vector<double> kSpecialParameters = {0.0, 1e-12, 0.5, 1.0 - 1e-12, 1.0, 0.1, 1.0 / 3.0, 0.9};

std::vector<double> random_coefficients(std::mt19937_64& random, int n, double lo, double hi) {
  std::uniform_real_distribution<double> uniform(lo, hi);
  std::vector<double> c(static_cast<std::size_t>(n) + 1);
  for (double& v : c) v = uniform(random);
  return c;
}

// A double in [0, 1] with all 52 fraction bits random.
rc::Gen<double> unit_double() {
  return rc::gen::map(rc::gen::pair(rc::gen::inRange<std::int64_t>(0, (std::int64_t{1} << 26) + 1),
                                    rc::gen::inRange<std::int64_t>(0, std::int64_t{1} << 26)),
                      [](const std::pair<std::int64_t, std::int64_t>& bits) {
                        const double x = std::ldexp(static_cast<double>((bits.first << 26) + bits.second), -52);
                        return std::min(x, 1.0);
                      });
}

// A coefficient sign * m * 2^e with m in [0, 1] full precision and e in [-20, 20]: mixed scales
// and signs, so that cancellation (|p| << p~) is common.
rc::Gen<double> coefficient() {
  return rc::gen::map(rc::gen::tuple(unit_double(), rc::gen::inRange(-20, 21), rc::gen::arbitrary<bool>()),
                      [](const std::tuple<double, int, bool>& v) {
                        const double magnitude = std::ldexp(std::get<0>(v), std::get<1>(v));
                        return std::get<2>(v) ? -magnitude : magnitude;
                      });
}

rc::Gen<double> parameter() { return rc::gen::oneOf(rc::gen::elementOf(kSpecialParameters), unit_double()); }

std::vector<Point<1>> as_points(const std::vector<double>& c) {
  std::vector<Point<1>> points;
  for (double v : c) points.push_back(Point<1>(v));
  return points;
}

TEST(CompensatedDeCasteljau, WithinBothBoundsForDegrees1To40) {
  std::mt19937_64 random(20261123);
  for (int n = 1; n <= 40; ++n) {
    // Mixed signs (cancellation) and, twice, all positive (p~ = |p|).
    const std::vector<std::vector<double>> polynomials = {random_coefficients(random, n, -1.0, 1.0),
                                                          random_coefficients(random, n, -1.0, 1.0),
                                                          random_coefficients(random, n, 1.0, 2.0)};
    for (const std::vector<double>& c : polynomials) {
      for (double t : kSpecialParameters) {
        const exact::EvaluationErrors e = exact::measure_errors(c, t);
        EXPECT_TRUE(exact::within_bounds(e)) << "n=" << n << " t=" << t;
      }
    }
  }
}

TEST(CompensatedDeCasteljau, FaithfulWhenThereIsNoCancellation) {
  // With all b_i > 0, p~ = |p| and the theorem gives |res - p| <= (u + 2 gamma_{3n+2}^2) |p|,
  // which is below one ulp of p (u|p| < ulp(p), and 2 gamma^2 |p| < 1e-11 ulp for n <= 40):
  // the result is one of the two doubles around p.
  std::mt19937_64 random(7);
  for (int n = 1; n <= 40; ++n) {
    const std::vector<double> c = random_coefficients(random, n, 0.5, 3.0);
    for (double t : kSpecialParameters) {
      const exact::EvaluationErrors e = exact::measure_errors(c, t);
      EXPECT_LT(e.compensated, mpq_class(exact::ulp(exact::nearest_double(e.exact))))
          << "n=" << n << " t=" << t << " error " << exact::in_ulps(e.compensated, e.exact) << " ulp";
    }
  }
}

RC_GTEST_PROP(CompensatedDeCasteljau, BoundsHoldForRandomPolynomials, ()) {
  const int n = *rc::gen::inRange(0, 41);
  const std::vector<double> c =
      *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(n) + 1, coefficient());
  const double t = *parameter();
  RC_ASSERT(exact::within_bounds(exact::measure_errors(c, t)));
}

RC_GTEST_PROP(CompensatedDeCasteljau, EachCoordinateIsTheScalarEvaluation, ()) {
  // The 3D evaluation reads coordinates with a stride; each must equal, bit for bit, the scalar
  // evaluation of that coordinate's polynomial (same operations on the same numbers).
  const int n = *rc::gen::inRange(0, 41);
  std::vector<Point<3>> points(static_cast<std::size_t>(n) + 1);
  for (Point<3>& p : points) p = Point<3>(*coefficient(), *coefficient(), *coefficient());
  const double t = *parameter();
  const CompensatedPoint<3> result = evaluate_compensated(BezierCurve<3>(points), t);
  for (int k = 0; k < 3; ++k) {
    std::vector<double> c;
    for (const Point<3>& p : points) c.push_back(p[k]);
    const CompensatedPoint<1> scalar = evaluate_compensated(BezierCurve<1>(as_points(c)), t);
    RC_ASSERT(result.value[k] == scalar.value[0]);
    RC_ASSERT(result.error_bound[k] == scalar.error_bound[0]);
    RC_ASSERT(exact::within_bounds(exact::measure_errors(c, t)));
  }
}

TEST(CompensatedDeCasteljau, ExactAtTheEnds) {
  // At s = 0 and s = 1 every de Casteljau step is 1*b_i + 0*b_{i+1} (or the mirror): exact.
  std::mt19937_64 random(11);
  for (int n : {0, 1, 3, 7, 20, 40}) {
    const std::vector<double> c = random_coefficients(random, n, -5.0, 5.0);
    for (const auto& [a, b] : {std::pair{0.0, 1.0}, std::pair{-3.0, 5.0}}) {
      const BezierCurve<1> curve(as_points(c), a, b);
      EXPECT_EQ(evaluate_compensated(curve, a).value[0], c.front()) << "n=" << n;
      EXPECT_EQ(evaluate_compensated(curve, b).value[0], c.back()) << "n=" << n;
    }
  }
}

TEST(CompensatedDeCasteljau, GlobalParameterMapsToTheLocalOne) {
  // On [2, 6] the parameter t = 2 + 4 s is exact for these s, and so is s = (t - 2) / 4: the
  // evaluation must be the one of the same points on [0, 1] at s, bit for bit.
  std::mt19937_64 random(13);
  const std::vector<double> c = random_coefficients(random, 12, -1.0, 1.0);
  const BezierCurve<1> unit(as_points(c));
  const BezierCurve<1> shifted(as_points(c), 2.0, 6.0);
  for (double s : {0.0, 0.125, 0.3125, 0.5, 0.9375, 1.0}) {
    const CompensatedPoint<1> expected = evaluate_compensated(unit, s);
    const CompensatedPoint<1> got = evaluate_compensated(shifted, 2.0 + 4.0 * s);
    EXPECT_EQ(got.value[0], expected.value[0]) << "s=" << s;
    EXPECT_EQ(got.error_bound[0], expected.error_bound[0]) << "s=" << s;
  }
}

TEST(CompensatedDeCasteljau, RejectsNonFiniteParameter) {
  const BezierCurve<1> curve(as_points({1.0, 2.0, 3.0}));
  EXPECT_THROW(evaluate_compensated(curve, std::nan("")), InvalidInput);
  EXPECT_THROW(evaluate_compensated(curve, std::numeric_limits<double>::infinity()), InvalidInput);
}

TEST(AbsoluteValueSum, MatchesExactMagnitude) {
  // de Casteljau on non-negative numbers: on each of the n levels the rounded 1 - t, a product
  // and a sum touch every term, all terms non-negative, so the relative error is at most
  // (1 + u)^(3n) - 1 <= gamma_{3n}; gamma_{2n} where 1 - t is exact. (evaluate_compensated's
  // error_bound relies on the lower side of this.)
  std::mt19937_64 random(17);
  for (int n = 0; n <= 40; n += 5) {
    const std::vector<double> c = random_coefficients(random, n, -1.0, 1.0);
    const BezierCurve<1> curve(as_points(c));
    for (double t : kSpecialParameters) {
      const mpq_class exact_sum = exact::absolute_value_sum(c, t);
      const mpq_class error = abs(mpq_class(absolute_value_sum(curve, t)[0]) - exact_sum);
      const bool exact_complement = mpq_class(1.0 - t) == 1 - mpq_class(t);
      EXPECT_LE(error, exact::gamma(exact_complement ? 2 * n : 3 * n) * exact_sum) << "n=" << n << " t=" << t;
    }
  }
}

TEST(GammaConstant, MatchesDefinition) {
  // k u is exact; 1 - k u and the quotient are rounded once each: relative error <= gamma_2.
  for (int k : {0, 1, 2, 3, 80, 122, 1000, 1 << 20}) {
    const mpq_class expected = exact::gamma(k);
    EXPECT_LE(abs(mpq_class(gamma_constant(k)) - expected), exact::gamma(2) * expected) << "k=" << k;
  }
}

}  // namespace
}  // namespace patchwork
