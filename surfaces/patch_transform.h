#pragma once
// Affine and projective maps of patches, NURBS surfaces and patch sets, exact on the control
// points (curves/curve_transform.h gives the rules):
//
//   affine      x -> A x + b:   P'_ij = A P_ij + b, weights unchanged
//   projective  M (4 x 4):      h'_ij = M h_ij on the homogeneous points h = (w P, w); every new
//                               weight > 0: the image; every one < 0: -M h_ij, the same surface;
//                               else InvalidInput naming control point (i, j) (the image may
//                               cross the plane at infinity)
//
// Orientation. The derivatives map by the linear part, F'_u = A F_u, F'_v = A F_v, so
//
//   F'_u x F'_v = (A F_u) x (A F_v) = det(A) A^(-T) (F_u x F_v):
//
// a map with det(A) < 0 (a mirror) turns every normal to the other side of the surface; the
// outward normals of a closed set become inward. A projective map x -> (A x + b) / (c.x + d) has
// the Jacobian determinant det(M) / (c.x + d)^4, so det(M) < 0 reverses the orientation (the sign
// of c.x + d does not matter). A singular map (det = 0) flattens the surface: InvalidInput.
//
// A patch set's transform reports orientation_reversed = (det < 0), and with
// TransformOrientation::keep reverses every patch's u direction as well, F''(u, v) = F'(1 - u, v)
// (P''_ij = P'_(n-i)j), so that the normals keep their side. Reversing u in every patch keeps shared edges consistent:
// edges u0 and u1 exchange their names, and v0, v1 run the other way, which a shared edge's
// `reversed` flag records, so each pair still walks its edge in opposite directions.
//
//   u reversed:   v1: P'_n m <-- P'_0 m        u0 <-> u1
//                 v0: P'_n 0 <-- P'_0 0
//
// The set's shared edges are given to the new set as known joins with their C^k (affine and
// projective maps keep the C^k of the homogeneous nets, and reversing u keeps cross-boundary
// derivatives measured into each patch): the adjacency is the set's, edge for edge, not searched
// again; collapsed and open edges and T-junctions are found again from the mapped points.

#include <Eigen/Geometry>

#include "surfaces/bezier_patch.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/patch_set.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// The image A F + b: control points A P_ij + b.
/// \throws InvalidInput if the map has an entry that is not finite, det(A) = 0, or an image
///         point overflows.
BezierPatch3 transform(const BezierPatch3& patch, const Eigen::Affine3d& map);
/// The image of a rational patch: homogeneous points (w (A P + b), w), weights unchanged.
/// \throws InvalidInput as for a polynomial patch.
RationalBezierPatch transform(const RationalBezierPatch& patch, const Eigen::Affine3d& map);
/// The image of a NURBS surface: control points A P_ij + b, same knots and weights.
/// \throws InvalidInput as for a patch.
NurbsSurface transform(const NurbsSurface& surface, const Eigen::Affine3d& map);

/// The projective image of a rational patch (homogeneous points M h_ij, negated if every new
/// weight is negative). \throws InvalidInput if M has an entry that is not finite, det(M) = 0, or
/// the new weights are not all of one sign, naming the first control point (i, j) that differs.
RationalBezierPatch projective_transform(const RationalBezierPatch& patch, const Eigen::Matrix4d& map);
/// The projective image of a polynomial patch (weights 1), a rational patch.
/// \throws InvalidInput as for a rational patch.
RationalBezierPatch projective_transform(const BezierPatch3& patch, const Eigen::Matrix4d& map);
/// The projective image of a NURBS surface (same knots). \throws InvalidInput as for a patch.
NurbsSurface projective_transform(const NurbsSurface& surface, const Eigen::Matrix4d& map);

/// The same surface with u running the other way: P'_ij = P_(n-i)j, F'(u, v) = F(1 - u, v),
/// so F'_u x F'_v = -(F_u x F_v) at mirrored parameters.
BezierPatch3 reverse_u(const BezierPatch3& patch);
/// reverse_u of a rational patch (weights move with their points).
RationalBezierPatch reverse_u(const RationalBezierPatch& patch);

/// What a patch set's transform does with the orientation of a mirror (det < 0).
enum class TransformOrientation {
  /// The patches are the mapped patches; a mirror turns the normals to the other side.
  follow_map,
  /// Where the map is a mirror, every patch's u is reversed too, so the normals keep their side.
  keep,
};

/// A mapped patch set and what the map did to its orientation.
struct TransformedPatchSet {
  PatchSet set;
  /// det < 0: the map alone turns F_u x F_v to the other side of the surface.
  bool orientation_reversed;
  /// Every patch's u was reversed (orientation_reversed and TransformOrientation::keep), so
  /// patch p's (u, v) is the mapped patch's (1 - u, v) and its edges u0 and u1 are exchanged.
  bool u_reversed;
};

/// Every patch mapped by the affine map (of its kind), the shared edges kept (file comment).
/// \throws InvalidInput as for a patch, or if the mapped shared edges no longer agree within
///         twice the set's relative tolerance of the new size (a map far from conformal).
TransformedPatchSet transform(const PatchSet& set, const Eigen::Affine3d& map,
                              TransformOrientation orientation = TransformOrientation::follow_map);
/// Every patch mapped projectively (polynomial patches become rational), the shared edges kept.
/// \throws InvalidInput as for a patch (naming the patch), or as the affine form.
TransformedPatchSet projective_transform(const PatchSet& set, const Eigen::Matrix4d& map,
                                         TransformOrientation orientation = TransformOrientation::follow_map);

}  // namespace patchwork
