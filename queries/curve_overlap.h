#pragma once
// Internal (patchwork::detail): overlaps of two curves, for curve_intersection.cpp.
//
// A piece of curve X on [x0, x1] lies on curve Y when its end points project onto Y, at y0 and
// y1, within `match`, and the piece of Y between y0 and y1 (reversed when y0 > y1) has the same
// control points within `match` once both are in standard form (weights scaled by rho^i with
// rho = (w_0 / w_n)^(1/n) and divided by w_0, so w_0 = w_n = 1: the form is unique under Moebius
// reparametrisation) and the lower degree is elevated to the higher.

#include <optional>
#include <utility>
#include <vector>

#include "curves/rational_bezier_curve.h"
#include "queries/curve_intersection.h"
#include "queries/intersection_kernel.h"

namespace patchwork::detail {

/// The parameter of the point of `curve` closest to q, by Newton from the best of samples of
/// [s0, s1], clamped to the curve's interval; and the distance there.
template <int Dim>
std::pair<double, double> project_onto(const RationalBezierCurve<Dim>& curve, const Point<Dim>& q, double s0, double s1);

/// The parameters (y0, y1) on `other` where `piece` (of some curve) lies on `other`, if it does;
/// `hint` is the piece of `other` to start the projections from.
template <int Dim>
std::optional<std::pair<double, double>> lies_on(const CurvePiece<Dim>& piece, const RationalBezierCurve<Dim>& other,
                                                 const CurvePiece<Dim>& hint, double match);

/// Merges overlaps that touch: same direction, t intervals meeting within t_margin and s intervals
/// within s_margin. Sorted by t0.
std::vector<CurveOverlap> merge_touching(std::vector<CurveOverlap> overlaps, double t_margin, double s_margin);

/// The overlap `found` continued on both sides to where the first or the second curve ends, if
/// the continued pieces still lie on each other: two curves that coincide on an interval (the
/// same curve under a reparametrisation) coincide until one of them ends, while two that merely
/// run within `match` of each other (a crossing at a tiny angle) part before. Nothing if they do.
template <int Dim>
std::optional<CurveOverlap> whole_overlap(const CurveOverlap& found, const RationalBezierCurve<Dim>& first,
                                          const RationalBezierCurve<Dim>& second, double match);

/// Merges overlaps that touch (same direction, t and s intervals meeting) and continues each to
/// where the first or the second curve ends. Sorted by t0.
template <int Dim>
std::vector<CurveOverlap> merged_overlaps(std::vector<CurveOverlap> overlaps, const RationalBezierCurve<Dim>& first,
                                          const RationalBezierCurve<Dim>& second, double match);

}  // namespace patchwork::detail
