#pragma once
// Cost against error: what a method needs (triangles, seconds) to reach a measured error, read
// off its runs. The runs of one method are points (error, cost); the cost of an error level e is
// taken on the lower envelope, the least cost among runs with error <= e, interpolated linearly
// in log-log between the envelope's points:
//
//   cost                                   envelope points: sorted by error, each one cheaper
//    ^  *                                  than every run with a smaller error
//    |   '.
//    |     *---.                           between two of them: log cost linear in log error
//    |          '.
//    |            *          *  (dominated, ignored)
//    +-------------------------> error
//
// Beyond the envelope's last point, up to the largest error of any run, the cost is that of the
// last point (a cheaper run with a smaller error exists). Below the smallest error and above the
// largest there is no answer (no extrapolation).

#include <optional>
#include <span>
#include <vector>

namespace patchwork::performance {

struct TradeoffPoint {
  double error;
  double cost;
};

/// The envelope points (see the file comment), sorted by increasing error.
std::vector<TradeoffPoint> lower_envelope(std::span<const TradeoffPoint> points);

/// The cost at `error` on the envelope, or nullopt outside its error range.
std::optional<double> cost_at_error(std::span<const TradeoffPoint> points, double error);

}  // namespace patchwork::performance
