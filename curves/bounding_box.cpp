#include "curves/bounding_box.h"

#include "curves/bernstein.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

// Coordinate c of the points as Bernstein coefficients.
template <int Dim>
std::vector<double> coordinate(const std::vector<Point<Dim>>& points, int c) {
  std::vector<double> values(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) values[i] = points[i][c];
  return values;
}

// Extends the box by the curve at the local parameters `critical`. `unit` is the curve on
// [0, 1]: evaluating at s itself, not at t = a + s (b - a), keeps the rounding of t (up to
// ulp(a) / (b - a) in s) from moving the point off the extreme or out of [a, b].
template <int Dim, class Curve>
void add_points(const Curve& unit, const std::vector<double>& critical, Box<Dim>& box) {
  for (double s : critical) box.extend(unit.evaluate(s));
}

}  // namespace

template <int Dim>
Box<Dim> bounding_box(const BezierCurve<Dim>& curve) {
  Box<Dim> box(curve.control_points().front());
  box.extend(curve.control_points().back());
  const BezierCurve<Dim> unit = with_interval(curve, 0.0, 1.0);
  for (int c = 0; c < Dim; ++c) {
    const std::vector<double> x = coordinate<Dim>(curve.control_points(), c);
    add_points<Dim>(unit, bernstein_roots(bernstein_derivative_coefficients(x)), box);
  }
  return box;
}

template <int Dim>
Box<Dim> bounding_box(const RationalBezierCurve<Dim>& curve) {
  const auto& H = curve.homogeneous().control_points();
  Box<Dim> box(curve.control_point(0));
  box.extend(curve.control_point(curve.degree()));
  const std::vector<double> w = coordinate<Dim + 1>(H, Dim);
  const std::vector<double> dw = bernstein_derivative_coefficients(w);
  const RationalBezierCurve<Dim> unit(with_interval(curve.homogeneous(), 0.0, 1.0));
  for (int c = 0; c < Dim; ++c) {
    const std::vector<double> x = coordinate<Dim + 1>(H, c);
    // (x/w)' = (x' w - x w') / w^2: both products have degree 2n-1.
    std::vector<double> numerator = bernstein_product(bernstein_derivative_coefficients(x), w);
    const std::vector<double> second = bernstein_product(x, dw);
    for (std::size_t i = 0; i < numerator.size(); ++i) numerator[i] -= second[i];
    add_points<Dim>(unit, bernstein_roots(numerator), box);
  }
  return box;
}

template <int Dim>
Box<Dim> control_box(const BezierCurve<Dim>& curve) {
  Box<Dim> box(curve.control_points().front());
  for (const auto& p : curve.control_points()) box.extend(p);
  return box;
}

#define PATCHWORK_INSTANTIATE(D)                                  \
  template Box<D> bounding_box(const BezierCurve<D>&);            \
  template Box<D> control_box(const BezierCurve<D>&);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE
template Box<2> bounding_box(const RationalBezierCurve<2>&);
template Box<3> bounding_box(const RationalBezierCurve<3>&);

}  // namespace patchwork
