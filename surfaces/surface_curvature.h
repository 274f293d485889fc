#pragma once
// Curvature of a surface F(u, v) at a point: Gaussian and mean curvature, the principal
// curvatures and their directions, from the fundamental forms (do Carmo, ch. 3):
//
//   n = F_u x F_v / |F_u x F_v|                       the unit normal (that of surface_normal.h)
//   E = F_u.F_u   F = F_u.F_v   G = F_v.F_v           first fundamental form I
//   L = F_uu.n    M = F_uv.n    N = F_vv.n            second fundamental form II
//   K = (L N - M^2) / (E G - F^2)                     Gaussian curvature = k1 k2
//   H = (E N - 2 F M + G L) / (2 (E G - F^2))         mean curvature = (k1 + k2) / 2
//
// Sign convention: a normal curvature II(t, t) / I(t, t) is positive where the surface bends
// towards n. A sphere of radius r with the outward normal (sphere_octant, nurbs_sphere) has
// k1 = k2 = H = -1/r and K = 1/r^2; with the inward normal, +1/r. K does not depend on the side
// of n; H, k1, k2 change sign with it (and k1, k2 exchange).
//
// The principal curvatures k1 >= k2 are the eigenvalues of the shape operator, written in the
// orthonormal frame e1 = F_u / |F_u|, e2 = n x e1 of the tangent plane as the symmetric matrix
// R^(-T) II R^(-1) with R = [e1 e2]^T [F_u F_v]; their unit eigenvectors, taken to 3D, are the
// principal directions d1, d2, chosen with d1 x d2 = n. At an umbilic (k1 = k2: every tangent
// direction is principal) the directions are the frame e1, e2, and `umbilic` says so; the test is
// k1 - k2 <= 1e-8 (|k1| + |k2| + 1 / size), size the diagonal of the control points' box.
//
// Where F_u x F_v vanishes (detail::first_normal_vanishes: below 1e-12 max(n m, 1) size^2 or
// its rounding far from the origin, as surface_normal.h judges it) the formulas divide by zero.
// At a pole, a boundary edge whose control points coincide (the teapot's lid and bottom, a
// sphere's poles), the curvature is computed from the curves that leave the pole across the edge:
// each curve c(t) = F(s, t) (or F(t, s)) through the pole is regular there (c' = F_v != 0), and
// by Meusnier's theorem its normal curvature
//
//   k_n(s) = c''.n / |c'|^2 = II(T, T),   T = c' / |c'|, n the limit normal of surface_normal.h,
//
// is the second fundamental form in its direction T, wherever the surface is twice
// differentiable at the pole. II, a symmetric form a x^2 + 2 b x y + c y^2 on the tangent plane,
// is fitted to k_n at 9 curves (s evenly over the edge) by least squares; `pole_residual` is the
// largest |k_n(s) - II(T, T)| left: rounding on a surface that is C^2 at the pole (a sphere, a
// surface of revolution), larger where the curves' curvatures are not those of any quadratic
// form, so the surface is not C^2 there and has no curvature (the teapot's approximate circles;
// the caller judges). The pole is refused (defined = false) where a curve's tangent leaves the
// tangent plane (a cone point) or the curves' directions do not span it.
// At other points where F_u x F_v vanishes (a collapsed corner, a fold) nothing is computed.
//
//        v ^   pole: row j = m collapsed          the curves v -> F(s, v) meet at the pole,
//          |   * * * * *                          each in its direction T(s) of the tangent plane
//          |   |  |  |  |
//          |   P_00 ... P_n0
//          +--------------> u

#include "core/types.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// The curvature of a surface at a point (file comment for the conventions).
struct SurfaceCurvature {
  /// The values below were computed; false where F_u x F_v vanishes away from a pole or a pole is
  /// refused (then every number is NaN).
  bool defined = false;
  /// Gaussian curvature K = k1 k2.
  double gaussian = 0.0;
  /// Mean curvature H = (k1 + k2) / 2, positive where the surface bends towards the normal.
  double mean = 0.0;
  /// Principal curvatures, k1 >= k2.
  double k1 = 0.0;
  double k2 = 0.0;
  /// Unit principal directions in the tangent plane, d1 x d2 = normal.
  Vec3 d1 = Vec3::Zero();
  Vec3 d2 = Vec3::Zero();
  /// The unit normal n of the convention.
  Vec3 normal = Vec3::Zero();
  /// k1 = k2 (within the file comment's tolerance): d1, d2 are any orthonormal pair (e1, e2).
  bool umbilic = false;
  /// Computed at a pole from the curves through it.
  bool at_pole = false;
  /// At a pole, the largest |k_n - II(T, T)| of the fit (0 elsewhere).
  double pole_residual = 0.0;
};

/// The curvature of a polynomial patch at (u, v). \throws InvalidInput if u or v is not finite.
SurfaceCurvature curvature(const BezierPatch3& patch, double u, double v);
/// The curvature of a rational patch at (u, v). \throws InvalidInput if u or v is not finite.
SurfaceCurvature curvature(const RationalBezierPatch& patch, double u, double v);
/// The curvature of a NURBS surface at (u, v) (one-sided at a breakpoint, as partial_derivatives);
/// poles are recognised on edges where the knot vector is clamped.
/// \throws InvalidInput if (u, v) is not finite or outside the domain.
SurfaceCurvature curvature(const NurbsSurface& surface, double u, double v);

namespace detail {
/// The curvature at a regular point from F_u, F_v, F_uu, F_uv, F_vv (derivatives of order <= 2);
/// `size` scales the umbilic test. \pre F_u x F_v != 0.
SurfaceCurvature regular_curvature(const PartialDerivatives<3>& F, double size);
}  // namespace detail

}  // namespace patchwork
