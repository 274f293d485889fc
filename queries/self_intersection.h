#pragma once
// Self-intersections of one curve: the pairs t < s with C(t) = C(s) (2D), or |C(t) - C(s)| within
// a tolerance (3D), each once, with the bounds of queries/curve_intersection.h.
//
// Method. [a, b] is split in halves until every piece is monotone in some direction v: the
// hodograph's numerator N(t) = H'_xyz(t) w(t) - H_xyz(t) w'(t) (C' = N / w^2, Bernstein
// coefficients N_i by products, for a polynomial curve just H') has v . N_i >= 10^-3 |N_i| for
// every i with N_i != 0, v the normalised sum of the unit N_i (a piece whose N_i all vanish is a
// point, and is kept whole). Then v . C increases on the piece,
// so the piece cannot meet itself. Pieces halved 40 times without passing the test (a cusp,
// where C' = 0 and the direction turns round) are kept as they are.
// Every pair of pieces i < j is intersected (intersect_curves on the pieces, which keep the
// global parameter); an answer of a pair whose parameters are as close as the pieces' shared end
// allows, s - t <= t_bound + s_bound + 4 w (w = (b - a) / 2^40), is the pieces meeting at that
// end and is dropped. So loops smaller than that in parameter are not reported, and neither is a
// cusp: its branches meet only at the cusp point itself, which is no crossing. Answers found on
// both sides of a seam (bounds overlapping) are reported once.
//
// A closed curve (C(a) = C(b) within tolerance + eps) meets itself where it closes: an answer at
// t = a, s = b (within its bounds) is that closing and is dropped.
//
// Overlaps: a curve that runs back over itself (C(t) = C(s) on a whole interval, e.g. a
// degenerate cubic retracing a line) gives overlaps with t0 < t1 and s0 > s1.

#include <vector>

#include "queries/curve_intersection.h"

namespace patchwork {

/// The self-intersections of a planar curve. \throws NumericalError as intersect_curves.
CurveIntersections<2> self_intersections(const BezierCurve2& curve);
/// The self-intersections of a planar rational curve.
CurveIntersections<2> self_intersections(const RationalBezierCurve2& curve);

/// The pairs t < s where the space curve comes within `tolerance` of itself (away from t = s).
/// \throws InvalidInput if tolerance is not finite and positive.
CurveIntersections<3> self_intersections(const BezierCurve3& curve, double tolerance);
/// The same for a rational space curve.
CurveIntersections<3> self_intersections(const RationalBezierCurve3& curve, double tolerance);

namespace detail {

/// The self-intersections of the curve made of `pieces` end to end (each keeping its own
/// parameter interval, in order): every piece split into monotone pieces, every pair intersected.
template <int Dim>
CurveIntersections<Dim> self_intersections_of_pieces(const std::vector<RationalBezierCurve<Dim>>& pieces, double tolerance);

}  // namespace detail
}  // namespace patchwork
