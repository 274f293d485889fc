#pragma once
// A-priori flatness bound: the distance between C on [a, b] and the polyline through
// C(t_0), ..., C(t_N) at N uniform steps is at most
//
//   n (n-1) / (8 N^2) * max_i |P_{i+1} - 2 P_i + P_{i-1}|
//
// since each piece deviates from its chord by at most h^2/8 max|C''| (h = 1/N in the local
// parameter) and |C''| <= n(n-1) max |second difference| by the convex hull property of the
// hodograph of the hodograph. The bound is in fact on the parametric distance |C(s) - L(s)|
// (L linear on each step), which bounds both one-sided Hausdorff distances. It is exact
// for a parabola (n = 2) at the midpoint of each step.

#include <cstdint>

#include "curves/bezier_curve.h"

namespace patchwork {

/// max_i |P_{i+1} - 2 P_i + P_{i-1}| (0 for n < 2).
template <int Dim>
double max_second_difference(const BezierCurve<Dim>& curve);

/// The bound above for `segments` uniform steps. \throws InvalidInput if segments < 1.
template <int Dim>
double flatness_bound(const BezierCurve<Dim>& curve, std::int64_t segments);

/// The fewest uniform segments N whose bound is <= tolerance (at least 1).
/// \throws InvalidInput if tolerance is not positive and finite, or N would exceed 2^31.
template <int Dim>
std::int64_t segments_for_tolerance(const BezierCurve<Dim>& curve, double tolerance);

}  // namespace patchwork
