#pragma once
// B-splines and piecewise Bezier curves, both ways, and degree elevation through the pieces.
//
//   knots  a=u_p      u_{p+1}      ...      b=u_{n+1}
//   pieces [---- 0 ----][---- 1 ----] ... [-- N-1 --]     one Bezier piece per non-empty span
//
// Extraction: the piece on span s = [u_s, u_{s+1}] has the Bezier points
// b_j = f_s(u_s^(p-j), u_{s+1}^j) (blossoms, bspline_curve.h) and keeps the global parameter, as
// split Bezier curves do; pieces meet with C^(p-m) at a breakpoint of multiplicity m.
// Joining: Bezier pieces of degree p on contiguous intervals that meet with C^k become the
// B-spline with the breakpoint of multiplicity p - k: first all breakpoints p times (the C^0
// form: the pieces' points, shared end points once), then each knot removed k times, which is
// exact (up to rounding) because the pieces join C^k.

#include <vector>

#include "curves/bezier_curve.h"
#include "curves/bspline_curve.h"
#include "curves/composite_curve.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {

/// The Bezier piece of span s on [u_s, u_{s+1}].
/// \throws InvalidInput unless s is a non-empty span in [p, n].
template <int Dim>
BezierCurve<Dim> bezier_piece(const BSplineCurve<Dim>& curve, int span);

/// The rational Bezier piece of span s (the homogeneous piece).
template <int Dim>
RationalBezierCurve<Dim> bezier_piece(const NurbsCurve<Dim>& curve, int span);

/// The Bezier pieces of every non-empty span in [a, b], in order.
template <int Dim>
std::vector<BezierCurve<Dim>> bezier_pieces(const BSplineCurve<Dim>& curve);

/// The rational Bezier pieces of every non-empty span in [a, b], in order.
template <int Dim>
std::vector<RationalBezierCurve<Dim>> bezier_pieces(const NurbsCurve<Dim>& curve);

/// The pieces as a CompositeCurve on the same parameter.
template <int Dim>
CompositeCurve<Dim> to_composite(const BSplineCurve<Dim>& curve);

/// The B-spline of the composite curve: every segment elevated to the highest degree p
/// (at least 1); at joint i the continuity k_i = continuity(segment i, segment i+1, p - 1,
/// relative_tolerance).ck gives the knot multiplicity p - k_i. Where two segments meet within the
/// tolerance but not exactly, the first segment's end point is kept.
/// \throws InvalidInput if two segments do not meet (no C^0 join).
template <int Dim>
BSplineCurve<Dim> to_bspline(const CompositeCurve<Dim>& curve, double relative_tolerance = 1e-10);

/// The same curve with degree p + times: each Bezier piece elevated, rejoined with every
/// interior multiplicity raised by `times` (the continuity is unchanged). The result is clamped on
/// [a, b]: an unclamped curve's knots outside [a, b] are not kept.
/// \throws InvalidInput if times < 0.
template <int Dim>
BSplineCurve<Dim> elevate_degree(const BSplineCurve<Dim>& curve, int times = 1);

/// The same rational curve with degree p + times (on the homogeneous points).
template <int Dim>
NurbsCurve<Dim> elevate_degree(const NurbsCurve<Dim>& curve, int times = 1);

/// The NURBS curve of rational Bezier pieces of one degree p >= 1 joined end to end, on [0, 1]
/// with piece i on [i/n, (i+1)/n] and interior knots of multiplicity p (C^0 in the parameter;
/// each piece's homogeneous points scaled so the joints agree, the curve of each piece
/// unchanged). circle_arc's pieces give an exact NURBS arc this way.
/// \throws InvalidInput if there is no piece, the degrees differ or are 0, or a piece does not
///         start where the previous one ends (within 1e-12 max(1, |end|)).
template <int Dim>
NurbsCurve<Dim> join_rational_pieces(const std::vector<RationalBezierCurve<Dim>>& pieces);

}  // namespace patchwork
