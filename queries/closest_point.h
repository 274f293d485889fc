#pragma once
// The closest point of a curve, a patch or a patch set to a point q: the global minimum of
// |C(t) - q| or |F(u, v) - q|, with a certified interval for the distance.
//
// Branch and bound over pieces (de Casteljau halving; a patch piece is halved across the direction
// in which its control polygons are longer, so that the wedges at a pole are cut across the pole
// and their number does not double with every level, queries/net_piece.h). Each piece lies in the convex hull of its control points, so the
// distance from q to a box around them (for curves a cylinder about the chord, for patches a box
// in the frame of the corners) is a lower bound for every point of the piece; the bound is
// second order (a piece of size h is within O(h^2) of flat), so only O(1) pieces per level stay
// near a simple minimum. Every piece's end points or corners are surface points and give upper
// bounds; Newton from the surviving pieces' centres finishes the minimum:
//
//   curves:  t <- t - g/g',  g = C'.(C - q),  g' = C''.(C - q) + |C'|^2,
//   patches: (u,v) <- (u,v) - H^-1 grad,  grad = (F_u.(F-q), F_v.(F-q)),
//            H = [F_u.F_u + F_uu.(F-q), F_u.F_v + F_uv.(F-q); ., F_v.F_v + F_vv.(F-q)],
//
// clamped to the domain (on an edge the search goes on along it). The search stops when the
// smallest lower bound of any piece left is within the requested gap of the best distance found:
//
//   lower_bound <= true distance <= distance,    distance - lower_bound <= gap,
//
// or when the budget of pieces runs out, with a wider interval that still holds. Near the medial
// axis (a point near a sphere's centre) nearly every piece is nearly as near, and the budget is
// what bounds the work.
//
// Several feet: when Newton finds two foot points at least `separation` apart (relative to the
// size of the geometry) whose distances differ by at most 4 gaps, the distance is attained more
// than once (a point on the medial axis: the centre of a
// circle or sphere, a point between two symmetric parts); one foot is returned.

#include <cstdint>

#include "core/types.h"
#include "curves/bezier_curve.h"
#include "curves/bspline_curve.h"
#include "curves/rational_bezier_curve.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_set.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

class PatchBvh;

/// How closely a closest-point search certifies its answer.
struct ClosestPointOptions {
  /// The certified interval's width, relative to the size: the diagonal of the box of the
  /// geometry's control points and the query point.
  double relative_gap = 1e-12;
  /// Foot points closer than this (relative to the size) are one foot.
  double relative_separation = 1e-6;
  /// Pieces examined at most; past it the interval is wider than asked (still certified).
  std::int64_t max_pieces = 20'000;
};

/// The closest point of a curve.
template <int Dim>
struct CurveClosestPoint {
  /// |C(t) - q| at the returned foot (the upper end of the certified interval).
  double distance = 0.0;
  /// The lower end of the certified interval: no point of the curve is nearer.
  double lower_bound = 0.0;
  /// The foot point C(t).
  Point<Dim> point;
  /// Its parameter (the curve's own, in [a, b]).
  double t = 0.0;
  /// Another foot at least the separation away is as near, within the interval.
  bool attained_more_than_once = false;
  /// Pieces examined.
  std::int64_t pieces = 0;
};

/// The closest point of a surface (a patch, or a patch of a set).
struct SurfaceClosestPoint {
  /// |F(u, v) - q| at the returned foot (the upper end of the certified interval).
  double distance = 0.0;
  /// The lower end of the certified interval: no point of the surface is nearer.
  double lower_bound = 0.0;
  /// The foot point F(u, v).
  Vec3 point = Vec3::Zero();
  /// The patch of the foot (0 for a single patch).
  std::uint32_t patch = 0;
  double u = 0.0;
  double v = 0.0;
  /// Another foot at least the separation away is as near, within the interval.
  bool attained_more_than_once = false;
  /// Pieces examined.
  std::int64_t pieces = 0;
};

/// The closest point of a Bezier curve to q. \throws InvalidInput if q is not finite.
template <int Dim>
CurveClosestPoint<Dim> closest_point(const BezierCurve<Dim>& curve, const Point<Dim>& q,
                                     const ClosestPointOptions& options = {});
/// The closest point of a rational Bezier curve to q. \throws InvalidInput if q is not finite.
template <int Dim>
CurveClosestPoint<Dim> closest_point(const RationalBezierCurve<Dim>& curve, const Point<Dim>& q,
                                     const ClosestPointOptions& options = {});
/// The closest point of a B-spline curve to q (over its Bezier pieces; t in the curve's own
/// parameter). \throws InvalidInput if q is not finite.
template <int Dim>
CurveClosestPoint<Dim> closest_point(const BSplineCurve<Dim>& curve, const Point<Dim>& q,
                                     const ClosestPointOptions& options = {});
/// The closest point of a NURBS curve to q. \throws InvalidInput if q is not finite.
template <int Dim>
CurveClosestPoint<Dim> closest_point(const NurbsCurve<Dim>& curve, const Point<Dim>& q,
                                     const ClosestPointOptions& options = {});

/// The closest point of a patch to q. \throws InvalidInput if q is not finite.
SurfaceClosestPoint closest_point(const BezierPatch3& patch, const Vec3& q, const ClosestPointOptions& options = {});
/// The closest point of a rational patch to q. \throws InvalidInput if q is not finite.
SurfaceClosestPoint closest_point(const RationalBezierPatch& patch, const Vec3& q,
                                  const ClosestPointOptions& options = {});
/// The closest point of a patch set to q (builds its PatchBvh; keep one for many queries).
/// \throws InvalidInput if q is not finite.
SurfaceClosestPoint closest_point(const PatchSet& set, const Vec3& q, const ClosestPointOptions& options = {});
/// The closest point of the patch set of a PatchBvh to q. \throws InvalidInput if q is not finite.
SurfaceClosestPoint closest_point(const PatchBvh& bvh, const Vec3& q, const ClosestPointOptions& options = {});

}  // namespace patchwork
