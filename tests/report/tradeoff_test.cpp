// Cost at equal error: the envelope and the log-log interpolation against closed forms.

#include "report/tradeoff.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace patchwork::performance {
namespace {

TEST(Tradeoff, InterpolatesAPowerLawExactly) {
  // cost = 5 error^-1/2, sampled at decades: log-log linear, so any level in range is exact.
  std::vector<TradeoffPoint> points;
  for (double e : {1e-1, 1e-2, 1e-3, 1e-4}) points.push_back({e, 5 / std::sqrt(e)});
  for (double e : {3e-2, 1e-3, 2.5e-4, 1e-4, 1e-1}) {
    EXPECT_NEAR(*cost_at_error(points, e), 5 / std::sqrt(e), 1e-12 * (5 / std::sqrt(e))) << e;
  }
}

TEST(Tradeoff, RefusesToExtrapolate) {
  const std::vector<TradeoffPoint> points = {{1e-2, 10}, {1e-3, 100}};
  EXPECT_FALSE(cost_at_error(points, 2e-2));
  EXPECT_FALSE(cost_at_error(points, 5e-4));
  EXPECT_FALSE(cost_at_error(std::vector<TradeoffPoint>{}, 1e-3));
}

TEST(Tradeoff, IgnoresDominatedRuns) {
  // The run (1e-2, 500) costs more than one with a smaller error: it is not on the envelope.
  const std::vector<TradeoffPoint> points = {{1e-1, 10}, {1e-2, 500}, {1e-3, 100}, {5e-3, 200}};
  const std::vector<TradeoffPoint> envelope = lower_envelope(points);
  ASSERT_EQ(envelope.size(), 2u);
  EXPECT_EQ(envelope[0].error, 1e-3);
  EXPECT_EQ(envelope[1].error, 1e-1);
  // Between (1e-3, 100) and (1e-1, 10): the geometric middle 1e-2 costs sqrt(100 * 10).
  EXPECT_NEAR(*cost_at_error(points, 1e-2), std::sqrt(1000.0), 1e-9);
}

TEST(Tradeoff, BeyondTheEnvelopeTheCheaperRunServes) {
  // (1e-2, 15) is dominated by (5e-3, 13): up to error 1e-2 the cheaper run is the answer.
  const std::vector<TradeoffPoint> points = {{1e-3, 100}, {5e-3, 13}, {1e-2, 15}};
  EXPECT_EQ(*cost_at_error(points, 8e-3), 13.0);
  EXPECT_EQ(*cost_at_error(points, 1e-2), 13.0);
  EXPECT_FALSE(cost_at_error(points, 1.1e-2));
}

}  // namespace
}  // namespace patchwork::performance
