#pragma once
// Intersections of a space curve with a patch or a patch set: every hit, each once, with a
// certified bound.
//
//   curve C(t), t in [a, b]        patch F(u, v), (u, v) in [0, 1]^2        G(t, u, v) = F(u, v) - C(t)
//
// Search. Triples (curve piece [t0, t1], patch piece [u0, u1] x [v0, v1]) are split in halves,
// the larger piece first (a patch piece along its longer parameter direction). A triple is dropped
// only when the control points' hulls are apart by more than eps along some unit axis (the
// coordinate axes, the patch piece's normal, across the curve's chord, the chord times the
// normal): the curve piece and the patch piece lie in those hulls (positive weights), so no hit is
// lost. eps = 64 (n + 1) u max |coordinate| (n the largest degree, u = 2^-53).
//
// Transversal hits. Krawczyk's test (queries/intersection_kernel.h) on G over the triple's box
// widened by 1/64 of its width on every side, with the interval Jacobian [F_u, F_v, -C'] from the
// hodographs: when K(X) lies inside X, G has exactly one zero in X. Newton's method on the 3x3
// system and further Krawczyk steps give the hit with
//
//   |t - t*| <= t_bound,  |u - u*| <= u_bound,  |v - v*| <= v_bound
//
// for the exact zero, tangential = false. The same floating-point caveat as for curves applies
// (intervals widened by a few units of rounding, not directed rounding).
//
// Tangential hits (the curve touching the surface, or lying in it): where the test cannot decide,
// triples are split until the curve piece is flat within eps, the patch piece is flat within eps
// (its control points in a slab of width eps about its plane) and the chord is parallel to that
// plane within a sine of 1e-4, or the pieces have been halved 44 times. Such triples whose boxes
// touch form one contact, reported once at the point of its boxes where |F(u, v) - C(t)| is
// smallest (Gauss-Newton; where that stalls, golden-section search on t of min_(u,v) |G|), if
// that is <= eps, with bounds covering all its boxes, and
// tangential = true: every (t', u', v') of the contact with |G| <= eps is within the bounds.
// A curve lying in the surface is one such contact, whose bounds span it.
//
// A hit within its bound (plus 1e-13) of the edge of [a, b] or of [0, 1]^2 is kept, its
// parameters clamped. In a patch set every patch is searched, and hits of different patches whose
// t intervals [t - t_bound, t + t_bound] meet are one hit (one point of the curve): a hit on an
// edge shared by two patches, or at a corner shared by four, is reported once, by the certified
// hit (else the closest; among equals the patch of the lowest index), with t_bound widened to
// cover both t intervals (u, v and their bounds are that patch's).

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_set.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// One point where a curve meets a surface.
struct CurveSurfaceHit {
  /// Parameter on the curve.
  double t;
  /// The patch (0 for a single patch; the index in a set).
  std::uint32_t patch;
  /// Parameters on the patch.
  double u;
  double v;
  /// curve(t).
  Vec3 point;
  /// The exact hit (or every point of the contact) has |t' - t| <= t_bound, ...
  double t_bound;
  double u_bound;
  double v_bound;
  /// |F(u, v) - C(t)| as evaluated.
  double distance;
  /// The curve touches the surface (see the file comment) rather than crossing it.
  bool tangential;
};

/// Every hit, ordered by t.
struct CurveSurfaceHits {
  std::vector<CurveSurfaceHit> hits;
  /// The rounding level eps used (file comment).
  double eps = 0.0;
};

/// The hits of a curve on a patch. \throws NumericalError if the search needs more than 2^21
/// triples of pieces.
CurveSurfaceHits intersect_curve_surface(const BezierCurve3& curve, const BezierPatch3& patch);
/// The hits of a rational curve on a rational patch. \throws NumericalError as above.
CurveSurfaceHits intersect_curve_surface(const RationalBezierCurve3& curve, const RationalBezierPatch& patch);
/// The hits of a curve on every patch of a set, one per point of the curve. \throws NumericalError.
CurveSurfaceHits intersect_curve_surface(const BezierCurve3& curve, const PatchSet& set);
/// The hits of a rational curve on a patch set. \throws NumericalError.
CurveSurfaceHits intersect_curve_surface(const RationalBezierCurve3& curve, const PatchSet& set);

namespace detail {

/// The hits on a patch set of the curve made of `pieces` end to end (each with its own interval).
/// \pre pieces is not empty.
CurveSurfaceHits intersect_pieces_with_set(const std::vector<RationalBezierCurve3>& pieces, const PatchSet& set);

}  // namespace detail
}  // namespace patchwork
