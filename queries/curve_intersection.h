#pragma once
// Intersections of two curves: every point where they meet, each once, with a certified bound,
// and the parameter intervals where they coincide.
//
//   first  A(t), t in [a, b]        second  B(s), s in [c, d]        (polynomial or rational)
//
// Search. Pairs of pieces (A on [t0, t1], B on [s0, s1]) are split in halves, the larger piece
// first. A pair is dropped only when the pieces provably stay apart: each piece lies in the convex
// hull of its control points (queries/intersection_kernel.h), so the gap between the projections
// of the two control polygons onto any unit axis is a lower bound of |A(t) - B(s)| on the pair
// (axes: the coordinate axes, across each chord, and in 3D the chords' common normal); a pair
// whose bound exceeds tolerance + eps cannot hold an intersection.
// eps = 64 (n + 1) u max |coordinate| (u = 2^-53, n the larger degree) is the rounding level.
//
// Transversal intersections (2D). Krawczyk's test on F(t, s) = A(t) - B(s) over the pair's box,
// widened by 1/64 of its width on every side (so a root on a seam between pairs is inside some
// box): when K(X) lies inside X, F has exactly one zero in X. Newton's method finds it and
// further Krawczyk steps X <- K(X) n X shrink the box around it; the intersection reported has
//
//   |t - t*| <= t_bound,  |s - s*| <= s_bound       for the exact zero (t*, s*),
//
// tangential = false. The test runs in floating point with every interval widened by a few
// units of rounding (not directed rounding), so "certified" means: up to that widening.
//
// Tangential and other singular contacts (2D), and every contact in 3D. Where no test decides,
// pairs are split until both pieces are flat within eps (3D: max(eps, tolerance / 8): the control
// points within that of the chord) and no larger than max(2^-16 size, tolerance) (size: the
// diagonal of both curves' box) and, in 2D, their chords are parallel within a sine of 1e-4 (or a piece has been
// halved 44 times), or both pieces are within eps of a point (where A' or B' vanishes, at a
// repeated end control point or a cusp, curves met at an angle are neither certified nor
// parallel: rounding cannot tell more); such pairs are leaves. Leaves whose parameter boxes touch
// form one contact; it is reported once, at the (t, s) in its boxes where |A(t) - B(s)| is
// smallest (Gauss-Newton from the best leaf; where that stalls, as it can at a tangency where
// [A', -B'] has rank 1, golden-section search on t of min_s |A(t) - B(s)|), if that distance is
// <= tolerance + eps, with
// t_bound, s_bound covering every leaf box of the contact: every (t', s') of that contact with
// |A(t') - B(s')| <= tolerance + eps satisfies |t' - t| <= t_bound, |s' - s| <= s_bound.
// In 2D such a contact is tangential (the curves touch, or cross at an angle rounding cannot
// tell from touching: zero, one or two exact crossings may lie within the bounds). In 3D
// (tolerance > 0 given by the caller) a contact is tangential when the sine of the angle between
// A'(t) and B'(s) is at most sqrt(tolerance / size), size = the diagonal of the pair's box,
// the angle below which the contact's length is set by the curvature, not by the angle.
//
// Overlaps. Where a piece of one curve (at least max(size / 1024, 64 tolerance) long, or the whole
// curve if at least 64 tolerance long) lies on the other (its end points project onto the other
// curve within tolerance + 16 eps, and its control points agree within that with those of the
// other curve's piece between the projections, both in standard form w_0 = w_n = 1 and the lower
// degree elevated), the pair is one overlap, not points. Overlaps found on neighbouring pieces
// are merged, and each is continued to where one of the curves ends (two polynomial or rational
// curves that agree on an interval agree as far as both go). Points and contacts inside an
// overlap's parameter rectangle are not reported. Overlaps are found when the two
// parametrisations are related by a linear (polynomial) or Moebius (rational) map, as for a
// curve and its own piece; curves that coincide under another reparametrisation are reported
// as a tangential contact spanning the coincidence.
//
// An intersection within its bound of an end of a parameter interval is reported, its parameter
// clamped to the interval.

#include <vector>

#include "core/types.h"
#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {

/// One point where two curves meet.
template <int Dim>
struct CurveIntersection {
  /// Parameter on the first curve.
  double t;
  /// Parameter on the second curve.
  double s;
  /// first(t).
  Point<Dim> point;
  /// The exact intersection (or every point of the contact) has |t' - t| <= t_bound.
  double t_bound;
  /// ... and |s' - s| <= s_bound.
  double s_bound;
  /// |first(t) - second(s)| as evaluated.
  double distance;
  /// The curves touch (see the file comment) rather than cross.
  bool tangential;
};

/// Parameter intervals on which the two curves coincide: first([t0, t1]) = second between s0
/// and s1, with s0 the parameter matching t0 (s0 > s1 when the curves run opposite).
struct CurveOverlap {
  double t0;
  double t1;
  double s0;
  double s1;
};

/// Everything two curves have in common.
template <int Dim>
struct CurveIntersections {
  /// Isolated points, ordered by t.
  std::vector<CurveIntersection<Dim>> points;
  /// Overlaps, ordered by t0.
  std::vector<CurveOverlap> overlaps;
  /// The rounding level eps used (file comment).
  double eps = 0.0;
};

/// The intersections of two planar curves. \throws NumericalError if the search needs more
/// than 2^21 pairs of pieces (curves that coincide under a reparametrisation it does not detect).
CurveIntersections<2> intersect_curves(const BezierCurve2& first, const BezierCurve2& second);
/// The intersections of two planar rational curves. \throws NumericalError as above.
CurveIntersections<2> intersect_curves(const RationalBezierCurve2& first, const RationalBezierCurve2& second);

/// The points where two space curves come within `tolerance` (file comment).
/// \throws InvalidInput if tolerance is not finite and positive. \throws NumericalError as above.
CurveIntersections<3> intersect_curves(const BezierCurve3& first, const BezierCurve3& second, double tolerance);
/// The same for rational space curves.
CurveIntersections<3> intersect_curves(const RationalBezierCurve3& first, const RationalBezierCurve3& second,
                                       double tolerance);

/// The curve as a rational curve with every weight 1 (the same points for the same t).
template <int Dim>
RationalBezierCurve<Dim> as_rational(const BezierCurve<Dim>& curve);

namespace detail {

/// Adds x to `points`, or, where an answer's box [t -+ t_bound] x [s -+ s_bound] meets x's (within
/// the slacks), merges the two into one: in 2D the certified one (else the closer one), in 3D the
/// closer one, with bounds covering both boxes. For answers of neighbouring pieces.
template <int Dim>
void add_or_merge(std::vector<CurveIntersection<Dim>>& points, const CurveIntersection<Dim>& x, double t_slack,
                  double s_slack);

/// The search of the file comment on rational curves (tolerance 0 in 2D).
template <int Dim>
CurveIntersections<Dim> intersect_rational(const RationalBezierCurve<Dim>& first, const RationalBezierCurve<Dim>& second,
                                           double tolerance);

}  // namespace detail
}  // namespace patchwork
