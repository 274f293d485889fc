#pragma once
// The Python curve classes: one class per kind of curve (BezierCurve, RationalBezierCurve,
// NurbsCurve), each holding a planar or a space curve, chosen by the shape of its control points
// ((n, 2) or (n, 3)). The C++ types are templates over the dimension; Python has one class.

#include <variant>

#include "curves/bezier_curve.h"
#include "curves/bspline_curve.h"
#include "curves/rational_bezier_curve.h"
#include "python/arrays.h"

namespace patchwork::python {

/// A curve of kind Curve in 2D or 3D.
template <template <int> class Curve>
struct AnyDimCurve {
  std::variant<Curve<2>, Curve<3>> curve;
  /// 2 or 3.
  int dimension() const noexcept { return curve.index() == 0 ? 2 : 3; }
  friend bool operator==(const AnyDimCurve&, const AnyDimCurve&) = default;
};

using AnyBezierCurve = AnyDimCurve<BezierCurve>;
using AnyRationalCurve = AnyDimCurve<RationalBezierCurve>;
using AnyNurbsCurve = AnyDimCurve<NurbsCurve>;

/// make(points) with the points of `array` as Point<2> or Point<3> by its shape, wrapped.
/// \throws InvalidInput naming control_points unless the shape is (n, 2) or (n, 3).
template <template <int> class Curve, class Make>
AnyDimCurve<Curve> make_curve(const DoubleArray& array, Make&& make) {
  if (array.ndim() == 2 && array.shape(1) == 2) return {make(points_from<2>(array, "control_points"))};
  if (array.ndim() == 2 && array.shape(1) == 3) return {make(points_from<3>(array, "control_points"))};
  throw InvalidInput(detail::message("control_points: expected an array of shape (n, 2) or (n, 3), got ",
                                     shape_text(array)));
}

/// The two curves' C++ values when they have the same dimension: f(first, second).
/// \throws InvalidInput naming both dimensions otherwise.
template <template <int> class A, template <int> class B, class F>
auto visit_same_dimension(const AnyDimCurve<A>& first, const AnyDimCurve<B>& second, F&& f) {
  if (first.dimension() != second.dimension()) {
    throw InvalidInput(detail::message("the curves must have the same dimension, got ", first.dimension(), " and ",
                                       second.dimension()));
  }
  if (first.dimension() == 2) return f(std::get<0>(first.curve), std::get<0>(second.curve));
  return f(std::get<1>(first.curve), std::get<1>(second.curve));
}

/// The dimension of a C++ curve type.
template <class Curve>
inline constexpr int dimension_of = Curve::Point::RowsAtCompileTime;

/// The dimension of a point type (Point<Dim>).
template <class Point>
inline constexpr int point_dimension = Point::RowsAtCompileTime;

}  // namespace patchwork::python
