#pragma once
// How two patches join along an edge they share: the gap, C^k across it and G^1 (surfaces/
// patch_set.h finds the shared edges). Patches of either kind: a join that involves a rational
// patch is judged on the homogeneous patches H = (w P, w), the second scaled by the ratio s of
// the two edges' weights at the edge's start, so that equal edges have equal homogeneous rows.
// Where s H2 joins H1 with C^k, so do the surfaces F = H / w (F is the projection of H, and
// derivatives of F up to order k are functions of those of H up to order k); the converse
// fails (a join can be C^k with homogeneous nets that are not), so for rational joins ck is a
// lower bound. G^1 is sampled on the (rational) unit normals.
//
// The gap of rational edges. With a's weights w_i and b's w'_i, r_i = w'_i / w_i and
// e = max r / min r - 1 (0 when proportional), a point of b is sum mu_i Q_i and the matching
// point of a sum lambda_i P_i, with lambda_i = w_i B_i / sum_j w_j B_j and mu_i likewise; then
// mu_i / lambda_i lies in [1 / (1 + e), 1 + e], so sum |mu_i - lambda_i| <= e, and
//   |A(t) - B(t)| <= max_i |P_i - Q_i| + e max_i |Q_i - Q_0|,
// the bound `gap` reports (the first term alone for polynomial edges).

#include <vector>

#include "surfaces/bezier_patch.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// How two patches join along a shared edge.
struct EdgeContinuity {
  /// A bound on the distance between the two boundary curves at equal parameters: the largest
  /// distance between corresponding control points (polynomial edges), plus the weights' term
  /// of the file comment where an edge is rational.
  double gap;
  /// The highest k <= the degrees across the edge for which the join is C^k (cross-boundary
  /// derivatives of orders 0..k agree, each patch in its own parameters on [0,1]^2); -1 if the
  /// control points of the edge differ by more than the tolerance.
  int ck;
  /// The normals agree along the edge (to 1e-7 rad) at 4 max(n, m) + 1 sample points.
  bool g1;
  /// The largest angle between the two unit normals at the samples, radians.
  double max_normal_angle;
};

/// The first k+1 rows R_0 (the edge itself) .. R_k of a neighbour patch of degree
/// `degree_across` across `edge` that joins `patch` with C^k there. The neighbour is
/// parametrised with u along boundary_curve(patch, edge) and v leaving `patch`, its rows
/// indexed by v (row j = its control points P_0j .. P_nj): rows k+1 .. degree_across are free.
/// Each column is continued with the curve rule of Bemerkung 18 (continue_ck).
/// \throws InvalidInput if k < 0 or k > degree_across.
std::vector<std::vector<Vec3>> continue_across(const BezierPatch3& patch, PatchEdge edge, int k, int degree_across);

/// Continuity of two patches along edges that coincide (first's edge, second's edge, reversed
/// as in SharedEdge), judged with `relative_tolerance` of the control-point scale.
EdgeContinuity edge_continuity(const BezierPatch3& first, PatchEdge first_edge, const BezierPatch3& second,
                               PatchEdge second_edge, bool reversed, double relative_tolerance = 1e-9);

/// edge_continuity for patches of either kind (see the file comment for rational joins).
EdgeContinuity edge_continuity(const AnyBezierPatch& first, PatchEdge first_edge, const AnyBezierPatch& second,
                               PatchEdge second_edge, bool reversed, double relative_tolerance = 1e-9);

namespace detail {
/// How two edges' homogeneous rows (same degree, b read backwards when reversed) agree: the
/// largest distance of their points P_i = H_i / w_i, the spread e of their weight ratios, and
/// the bound on the curves' distance that they give (the file comment).
struct EdgeAgreement {
  /// max_i |P_i - Q_i|.
  double points;
  /// e = max r / min r - 1 of the weight ratios r_i = w'_i / w_i.
  double weights;
  /// points + e max_i |Q_i - Q_0|: the curves' distance at equal parameters is at most this.
  double gap;
};
/// \pre a.size() == b.size(), every weight positive.
EdgeAgreement edge_agreement(const std::vector<Vec4>& a, const std::vector<Vec4>& b, bool reversed);
}  // namespace detail

}  // namespace patchwork
