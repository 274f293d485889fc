#include "curves/composite_curve.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "curves/dimensions.h"

namespace patchwork {

template <int Dim>
CompositeCurve<Dim>::CompositeCurve(std::vector<BezierCurve<Dim>> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) throw InvalidInput("CompositeCurve: no segments");
  for (std::size_t i = 1; i < segments_.size(); ++i) {
    if (segments_[i].a() != segments_[i - 1].b()) {
      throw InvalidInput(detail::message("CompositeCurve: segment ", i, " starts at ", segments_[i].a(),
                                         " but segment ", i - 1, " ends at ", segments_[i - 1].b()));
    }
  }
}

template <int Dim>
std::size_t CompositeCurve<Dim>::segment_index(double t) const {
  if (!std::isfinite(t) || t < a() || t > b()) {
    throw InvalidInput(detail::message("CompositeCurve: t = ", t, " is outside [", a(), ", ", b(), "]"));
  }
  // The first segment whose end exceeds t; t = b() belongs to the last segment.
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                                   [](double value, const BezierCurve<Dim>& segment) { return value < segment.b(); });
  return it == segments_.end() ? segments_.size() - 1 : static_cast<std::size_t>(it - segments_.begin());
}

template <int Dim>
typename CompositeCurve<Dim>::Point CompositeCurve<Dim>::evaluate(double t) const {
  return segments_[segment_index(t)].evaluate(t);
}

template <int Dim>
typename CompositeCurve<Dim>::Point CompositeCurve<Dim>::derivative(double t, int k) const {
  return patchwork::derivative(segments_[segment_index(t)], t, k);
}

template <int Dim>
std::vector<Continuity> CompositeCurve<Dim>::continuity(int max_order, double relative_tolerance) const {
  std::vector<Continuity> joints;
  joints.reserve(segments_.size() - 1);
  for (std::size_t i = 1; i < segments_.size(); ++i) {
    joints.push_back(patchwork::continuity(segments_[i - 1], segments_[i], max_order, relative_tolerance));
  }
  return joints;
}

#define PATCHWORK_INSTANTIATE(D) template class CompositeCurve<D>;
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
