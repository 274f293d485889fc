#include "report/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patchwork::performance {

std::vector<TradeoffPoint> lower_envelope(std::span<const TradeoffPoint> points) {
  std::vector<TradeoffPoint> sorted;
  for (const TradeoffPoint& p : points) {
    if (p.error > 0.0 && p.cost > 0.0 && std::isfinite(p.error) && std::isfinite(p.cost)) sorted.push_back(p);
  }
  std::sort(sorted.begin(), sorted.end(), [](const TradeoffPoint& a, const TradeoffPoint& b) {
    return a.error < b.error || (a.error == b.error && a.cost < b.cost);
  });
  std::vector<TradeoffPoint> envelope;
  double cheapest = std::numeric_limits<double>::infinity();
  for (const TradeoffPoint& p : sorted) {
    if (p.cost < cheapest) {
      envelope.push_back(p);
      cheapest = p.cost;
    }
  }
  return envelope;
}

std::optional<double> cost_at_error(std::span<const TradeoffPoint> points, double error) {
  const std::vector<TradeoffPoint> envelope = lower_envelope(points);
  double largest = 0.0;
  for (const TradeoffPoint& p : points) largest = std::max(largest, std::isfinite(p.error) ? p.error : 0.0);
  if (envelope.empty() || !(error >= envelope.front().error) || !(error <= largest)) return std::nullopt;
  // Beyond the envelope's last point (up to the largest error run) its run is the cheapest.
  if (error >= envelope.back().error) return envelope.back().cost;
  for (std::size_t k = 0; k + 1 < envelope.size(); ++k) {
    const TradeoffPoint& a = envelope[k];
    const TradeoffPoint& b = envelope[k + 1];
    if (error > b.error) continue;
    const double s = (std::log(error) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    return std::exp(std::log(a.cost) + s * (std::log(b.cost) - std::log(a.cost)));
  }
  return envelope.back().cost;
}

}  // namespace patchwork::performance
