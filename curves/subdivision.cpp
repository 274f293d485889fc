#include "curves/subdivision.h"

#include "core/errors.h"
#include "curves/curve_checks.h"
#include "curves/dimensions.h"

namespace patchwork {

template <int Dim>
std::pair<BezierCurve<Dim>, BezierCurve<Dim>> split(const BezierCurve<Dim>& curve, double t) {
  detail::check_parameter("split", t);
  if (!(curve.a() < t && t < curve.b())) {
    throw InvalidInput(detail::message("split: t = ", t, " is not inside (", curve.a(), ", ", curve.b(), ")"));
  }
  const int n = curve.degree();
  const double s = curve.local_parameter(t);
  const double r = 1.0 - s;
  std::vector<Point<Dim>> work = curve.control_points();
  std::vector<Point<Dim>> left(static_cast<std::size_t>(n) + 1);
  std::vector<Point<Dim>> right(static_cast<std::size_t>(n) + 1);
  left[0] = work[0];
  right[n] = work[n];
  for (int k = 1; k <= n; ++k) {
    for (int i = 0; i + k <= n; ++i) work[i] = r * work[i] + s * work[i + 1];
    left[k] = work[0];
    right[n - k] = work[n - k];
  }
  return {BezierCurve<Dim>(std::move(left), curve.a(), t), BezierCurve<Dim>(std::move(right), t, curve.b())};
}

template <int Dim>
std::pair<BezierCurve<Dim>, BezierCurve<Dim>> halve(const BezierCurve<Dim>& curve) {
  return split(curve, 0.5 * (curve.a() + curve.b()));
}

template <int Dim>
BezierCurve<Dim> subcurve(const BezierCurve<Dim>& curve, double t0, double t1) {
  detail::check_parameter("subcurve", t0);
  detail::check_parameter("subcurve", t1);
  if (!(curve.a() <= t0 && t0 < t1 && t1 <= curve.b())) {
    throw InvalidInput(detail::message("subcurve: [", t0, ", ", t1, "] is not a non-empty part of [", curve.a(), ", ", curve.b(), "]"));
  }
  BezierCurve<Dim> piece = curve;
  if (t1 < curve.b()) piece = split(piece, t1).first;
  if (t0 > curve.a()) piece = split(piece, t0).second;
  return piece;
}

#define PATCHWORK_INSTANTIATE(D)                                                                  \
  template std::pair<BezierCurve<D>, BezierCurve<D>> split(const BezierCurve<D>&, double);        \
  template std::pair<BezierCurve<D>, BezierCurve<D>> halve(const BezierCurve<D>&);                \
  template BezierCurve<D> subcurve(const BezierCurve<D>&, double, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
