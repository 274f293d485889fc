#pragma once
// Rational tensor-product Bezier patches: control points P_ij with positive weights w_ij,
//
//   F(u, v) = sum_ij w_ij P_ij B_i^n(u) B_j^m(v) / sum_ij w_ij B_i^n(u) B_j^m(v),
//
// stored as the polynomial patch of homogeneous points (w P, w) (BezierPatch4), same index
// order as BezierPatch (P_ij at i + (n+1) j). Derivatives follow from H = w F by Leibniz's rule:
//   d^(a,b) F = (d^(a,b) H - sum_{(k,l) != (0,0)} C(a,k) C(b,l) d^(k,l) w d^(a-k,b-l) F) / w.
// Quadrics are exact: sphere_octant gives the unit sphere's octant to rounding.

#include <variant>
#include <vector>

#include "curves/rational_bezier_curve.h"
#include "surfaces/bezier_patch.h"

namespace patchwork {

class RationalBezierPatch {
 public:
  /// Patch of degrees (n, m) with control points and weights (same index order).
  /// \throws InvalidInput if counts differ, a value is not finite or a weight is not positive.
  RationalBezierPatch(int n, int m, const std::vector<Vec3>& control_points, const std::vector<double>& weights);
  /// From homogeneous control points (w P, w). \throws InvalidInput if a weight is not positive.
  explicit RationalBezierPatch(BezierPatch4 homogeneous);

  int degree_u() const noexcept { return homogeneous_.degree_u(); }
  int degree_v() const noexcept { return homogeneous_.degree_v(); }
  /// The homogeneous patch (w P, w).
  const BezierPatch4& homogeneous() const noexcept { return homogeneous_; }
  /// P_ij (homogeneous point divided by its weight).
  Vec3 control_point(int i, int j) const;
  /// w_ij.
  double weight(int i, int j) const { return homogeneous_.control_point(i, j)[3]; }
  /// The points P_ij as a polynomial patch (the surface lies in their convex hull).
  BezierPatch3 control_net() const;
  /// The weights w_ij, in the order of the control points.
  std::vector<double> weights() const;

  /// F(u, v). \throws InvalidInput if u or v is not finite.
  Vec3 evaluate(double u, double v) const;
  Vec3 operator()(double u, double v) const { return evaluate(u, v); }

 private:
  BezierPatch4 homogeneous_;
};

/// All partial derivatives of F with a + b <= order at (u, v).
PartialDerivatives<3> partial_derivatives(const RationalBezierPatch& patch, double u, double v, int order);

namespace detail {
/// The partial derivatives of F = H / w from those of the homogeneous H = (w F, w), by the
/// Leibniz rule of the file comment (shared with NURBS surfaces). \pre H.at(0, 0)[3] > 0.
PartialDerivatives<3> projected_partial_derivatives(const PartialDerivatives<4>& H);
}  // namespace detail

// The operations of BezierPatch, on the homogeneous net (exact for the rational surface: de
// Casteljau and degree elevation of H = (w P, w) are those of F, since F = H / w pointwise).

/// The pieces over [0,u] x [0,1] and [u,1] x [0,1], each reparametrised to [0,1]^2.
/// \throws InvalidInput unless 0 < u < 1.
std::pair<RationalBezierPatch, RationalBezierPatch> split_u(const RationalBezierPatch& patch, double u);
/// The pieces over [0,1] x [0,v] and [0,1] x [v,1]. \throws InvalidInput unless 0 < v < 1.
std::pair<RationalBezierPatch, RationalBezierPatch> split_v(const RationalBezierPatch& patch, double v);
/// The piece over [u0,u1] x [v0,v1], reparametrised to [0,1]^2.
/// \throws InvalidInput unless 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1.
RationalBezierPatch subpatch(const RationalBezierPatch& patch, double u0, double u1, double v0, double v1);
/// The same surface with degrees (n + times_u, m + times_v). \throws InvalidInput if negative.
RationalBezierPatch elevate_degree(const RationalBezierPatch& patch, int times_u, int times_v);
/// The curve v -> F(u, v) for fixed u.
RationalBezierCurve3 iso_curve_u(const RationalBezierPatch& patch, double u);
/// The curve u -> F(u, v) for fixed v.
RationalBezierCurve3 iso_curve_v(const RationalBezierPatch& patch, double v);
/// The boundary curve of an edge, in the direction of increasing u (v0, v1) or v (u0, u1).
RationalBezierCurve3 boundary_curve(const RationalBezierPatch& patch, PatchEdge edge);

/// The polynomial patch as a rational one (every weight 1).
RationalBezierPatch as_rational(const BezierPatch3& patch);

/// A patch of either kind (a PatchSet holds both).
using AnyBezierPatch = std::variant<BezierPatch3, RationalBezierPatch>;

/// The unit sphere's octant x, y, z >= 0 (scaled by radius, moved to center) as a degree (2,2)
/// rational patch: the quarter circle (1,0,0) -> (0,0,1) in the xz-plane, weights (1, 1/sqrt2, 1),
/// revolved through 90 degrees about z with the same weights. The row j = 2 collapses to the
/// pole (0, 0, radius); the normal F_u x F_v points outward.
RationalBezierPatch sphere_octant(const Vec3& center, double radius);

}  // namespace patchwork
