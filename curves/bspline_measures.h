#pragma once
// Measures of B-spline and NURBS curves over their valid range [a, b], from the Bezier pieces
// (bspline_conversion.h): arc length as the sum over the pieces (arc_length.h), the tight box as
// the union of the pieces' tight boxes (bounding_box.h), and the control polygon's box.

#include "curves/arc_length.h"
#include "curves/bounding_box.h"
#include "curves/bspline_curve.h"

namespace patchwork {

/// Length of C([a, b]) to absolute `tolerance` (shared among the pieces by their count); the
/// estimate is the sum of the pieces' estimates.
template <int Dim>
ArcLength arc_length(const BSplineCurve<Dim>& curve, double tolerance = 1e-12);

/// Length of the rational curve on [a, b] to absolute `tolerance`.
template <int Dim>
ArcLength arc_length(const NurbsCurve<Dim>& curve, double tolerance = 1e-12);

/// The smallest axis-aligned box containing C([a, b]).
template <int Dim>
Box<Dim> bounding_box(const BSplineCurve<Dim>& curve);

/// The smallest axis-aligned box containing the rational curve on [a, b].
template <int Dim>
Box<Dim> bounding_box(const NurbsCurve<Dim>& curve);

/// The box of the control points (contains the curve on [a, b]: convex hull property).
template <int Dim>
Box<Dim> control_box(const BSplineCurve<Dim>& curve);

/// The box of the rational curve's control points P_i (contains the curve: positive weights).
template <int Dim>
Box<Dim> control_box(const NurbsCurve<Dim>& curve);

}  // namespace patchwork
