#include "curves/flatness.h"

#include <cmath>

#include "core/errors.h"
#include "curves/dimensions.h"

namespace patchwork {

template <int Dim>
double max_second_difference(const BezierCurve<Dim>& curve) {
  const auto& P = curve.control_points();
  double result = 0.0;
  for (std::size_t i = 1; i + 1 < P.size(); ++i) result = std::max(result, (P[i + 1] - 2.0 * P[i] + P[i - 1]).norm());
  return result;
}

template <int Dim>
double flatness_bound(const BezierCurve<Dim>& curve, std::int64_t segments) {
  if (segments < 1) throw InvalidInput(detail::message("flatness_bound: ", segments, " segments"));
  const double n = curve.degree();
  const double N = static_cast<double>(segments);
  return n * (n - 1.0) / (8.0 * N * N) * max_second_difference(curve);
}

template <int Dim>
std::int64_t segments_for_tolerance(const BezierCurve<Dim>& curve, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("segments_for_tolerance: tolerance ", tolerance, " is not positive and finite"));
  }
  const double n = curve.degree();
  const double needed = std::ceil(std::sqrt(n * (n - 1.0) * max_second_difference(curve) / (8.0 * tolerance)));
  if (!(needed <= 2147483648.0)) {
    throw InvalidInput(detail::message("segments_for_tolerance: tolerance ", tolerance, " needs ", needed, " segments (more than 2^31)"));
  }
  std::int64_t segments = std::max<std::int64_t>(1, static_cast<std::int64_t>(needed));
  // sqrt and ceil work on a rounded quotient and may land one off either way: step until the
  // count meets the bound and one fewer does not.
  while (flatness_bound(curve, segments) > tolerance) ++segments;
  while (segments > 1 && flatness_bound(curve, segments - 1) <= tolerance) --segments;
  if (segments > (std::int64_t{1} << 31)) {
    throw InvalidInput(detail::message("segments_for_tolerance: tolerance ", tolerance, " needs ", segments, " segments (more than 2^31)"));
  }
  return segments;
}

#define PATCHWORK_INSTANTIATE(D)                                                   \
  template double max_second_difference(const BezierCurve<D>&);                    \
  template double flatness_bound(const BezierCurve<D>&, std::int64_t);             \
  template std::int64_t segments_for_tolerance(const BezierCurve<D>&, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
