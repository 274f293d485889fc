#pragma once
// Tight axis-aligned bounding boxes: per coordinate, the extremes lie at the interval's ends or
// at roots of that coordinate's derivative (bernstein_roots). The control polygon's box
// contains the curve too (convex hull property) but is generally larger.

#include <Eigen/Geometry>

#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {

template <int Dim>
using Box = Eigen::AlignedBox<double, Dim>;

/// The smallest axis-aligned box containing C([a, b]).
template <int Dim>
Box<Dim> bounding_box(const BezierCurve<Dim>& curve);

/// The smallest axis-aligned box containing the rational curve on [a, b] (extremes at roots of
/// the numerator X'w - Xw' of each coordinate's derivative).
template <int Dim>
Box<Dim> bounding_box(const RationalBezierCurve<Dim>& curve);

/// The box of the control points (contains the curve; cheap, not tight).
template <int Dim>
Box<Dim> control_box(const BezierCurve<Dim>& curve);

}  // namespace patchwork
