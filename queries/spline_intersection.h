#pragma once
// Intersections of B-spline and NURBS curves, through their Bezier pieces (bspline_conversion.h):
// every pair of pieces is searched as in queries/curve_intersection.h (the pieces keep the
// curve's parameter), and the answers are joined:
//   - points of different piece pairs whose parameter boxes [t -+ t_bound] x [s -+ s_bound] meet
//     are one point (an intersection at a breakpoint is found from both pieces there);
//   - overlaps of neighbouring pieces that continue one another are one overlap;
//   - points inside an overlap's parameter rectangle are dropped.
// Self-intersections split every piece into monotone pieces (queries/self_intersection.h), so
// pieces meeting at a breakpoint are neighbours like any others. A curve against a patch set goes
// piece by piece, one hit per point of the curve (queries/curve_surface_intersection.h).

#include "curves/bspline_curve.h"
#include "queries/curve_intersection.h"
#include "queries/curve_surface_intersection.h"
#include "surfaces/patch_set.h"

namespace patchwork {

/// The intersections of two planar B-spline curves. \throws NumericalError as intersect_curves.
CurveIntersections<2> intersect_curves(const BSplineCurve2& first, const BSplineCurve2& second);
/// The intersections of two planar NURBS curves. \throws NumericalError as intersect_curves.
CurveIntersections<2> intersect_curves(const NurbsCurve2& first, const NurbsCurve2& second);
/// Where two space B-spline curves come within `tolerance`.
/// \throws InvalidInput if tolerance is not finite and positive.
CurveIntersections<3> intersect_curves(const BSplineCurve3& first, const BSplineCurve3& second, double tolerance);
/// Where two space NURBS curves come within `tolerance`.
/// \throws InvalidInput if tolerance is not finite and positive.
CurveIntersections<3> intersect_curves(const NurbsCurve3& first, const NurbsCurve3& second, double tolerance);

/// The self-intersections of a planar B-spline curve.
CurveIntersections<2> self_intersections(const BSplineCurve2& curve);
/// The self-intersections of a planar NURBS curve.
CurveIntersections<2> self_intersections(const NurbsCurve2& curve);

/// The pairs t < s where a space B-spline curve comes within `tolerance` of itself.
/// \throws InvalidInput if tolerance is not finite and positive.
CurveIntersections<3> self_intersections(const BSplineCurve3& curve, double tolerance);
/// The same for a space NURBS curve. \throws InvalidInput if tolerance is not finite and positive.
CurveIntersections<3> self_intersections(const NurbsCurve3& curve, double tolerance);

/// The hits of a B-spline curve on a patch set. \throws NumericalError as intersect_curve_surface.
CurveSurfaceHits intersect_curve_surface(const BSplineCurve3& curve, const PatchSet& set);
/// The hits of a NURBS curve on a patch set. \throws NumericalError as intersect_curve_surface.
CurveSurfaceHits intersect_curve_surface(const NurbsCurve3& curve, const PatchSet& set);

}  // namespace patchwork
