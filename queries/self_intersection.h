#pragma once
// Self-intersections of one curve: the pairs t < s with C(t) = C(s) (2D), or |C(t) - C(s)| within
// a tolerance (3D), each once, with the bounds of queries/curve_intersection.h.
//
// Curves on a line. When every control point lies within eps of the line through the first
// control point and the one farthest from it (eps = 64 (n + 1) u max |coordinate|, u = 2^-53;
// not for a curve within eps of a point), the curve is solved along the line. With
// p(t) = u . (C(t) - origin) its position (u the unit direction), each piece is cut where p
// turns back, at the roots of u . N (N the hodograph's numerator below, p' = u . N / w^2) found
// by Bernstein subdivision (curves/bernstein.h), into runs on which p is monotone; neighbouring
// intervals where p moves the same way, or by no more than eps, are one run. Two runs meet where
// their ranges of p do: an overlap where the ranges share more than max(eps, 64 tolerance), its
// ends where p reaches the end of one run's range (a parameter within eps of a run's end in p is
// that end, so the turning point t* where two neighbouring runs meet ends both: t1 = s1 = t*),
// found on the other run by bisection; else a contact (tangential, bounds over the parameters
// within tolerance + eps of the other range) where the ranges come within tolerance + eps, unless
// it is the runs' shared end, the curve's closing or a corner of an overlap's rectangle. This is
// how a cubic retraces itself (a curve C = D o phi with deg phi > 1 (Lueroth); for a cubic D is
// a line), under a reparametrisation that is not Moebius, which the search of
// queries/curve_intersection.h would see as one long contact.
//
// Other curves. [a, b] is split until every piece is monotone in some direction v: the
// hodograph's numerator N(t) = H'_xyz(t) w(t) - H_xyz(t) w'(t) (C' = N / w^2, Bernstein
// coefficients N_i by products, for a polynomial curve just H') has v . N_i >= 10^-3 |N_i| for
// every i with |N_i| > noise, v the normalised sum of those unit N_i (a piece with none is a
// point, and is kept whole). noise = 64 n^2 u max |H_xyz| max w bounds the rounding of the N_i
// (n levels of de Casteljau for the piece, differences and products), so such an N_i has no
// certain direction: it is the zero of C' at a repeated end control point or at a cusp where the
// piece was cut. Then v . C increases on the piece but for a retreat of at most
// 2 noise (t1 - t0) / ((2n - 1) min w^2) per such coefficient (each B_i of degree 2n - 2
// integrates to (t1 - t0) / (2n - 1)), so the piece cannot meet itself but in a loop of about
// that size, within rounding. A piece that fails is cut where |N| is smallest (33 samples, then
// golden-section search), when |N| there is at most noise / 8 and the place lies in the middle
// 62/64 of the piece: a cusp, where C' = 0 and the direction turns round (halving reaches it only
// at a dyadic t; the pieces of depth 40 around it met in points and tiny overlaps); else it is
// halved. Pieces cut 40 times without
// passing the test (a near-cusp whose hodograph misses zero by more than rounding) are kept as
// they are.
// Every pair of pieces i < j whose boxes of control points come within tolerance + eps of each
// other (the pairs farther apart are those intersect_curves drops at its first test) is
// intersected (intersect_curves on the pieces, which keep the
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
// degenerate cubic retracing a line) gives overlaps with t0 < t1 and s0 > s1; where it folds at
// t*, the overlap of the two sides ends at t1 = s1 = t*. A curve that runs forward again over
// what it retraced gives overlaps with s0 < s1 as well.

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
