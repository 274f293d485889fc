#pragma once
// Second-derivative bounds of rational Bezier patches, for the flatness bound
// (surfaces/patch_flatness.h) and so the tessellator's guarantee.
//
// F = G / w with G(u, v) = sum_ij w_ij (P_ij - c) B_i^n(u) B_j^m(v) (the homogeneous patch
// moved by any point c; F_uu and the rest do not depend on c) and w = sum_ij w_ij B_i^n B_j^m > 0.
// Differentiating F = G / w by the quotient rule, the second derivatives have polynomial
// numerators over w^3:
//   w^3 F_uu = w (G_uu w - G w_uu) - 2 w_u (G_u w - G w_u),
//   w^3 F_uv = w (G_uv w + G_u w_v - G_v w_u - G w_uv) - 2 w_v (G_u w - G w_u),
//   w^3 F_vv = w (G_vv w - G w_vv) - 2 w_v (G_v w - G w_v),
// of degrees (3n - 2, 3m), (3n - 1, 3m - 1), (3n, 3m - 2). Their Bernstein coefficients
// (vectors) are computed from the nets by products in the Bernstein basis
// (surfaces/bernstein_product.h), and by the convex hull property
//   sup |F_uu| <= max_k |N_uu,k| / min_k (w^3)_k,
// with (w^3)_k the coefficients of w^3 at degrees (3n, 3m) (all positive), and likewise for
// uv and vv: rigorous, and with all weights equal exactly the polynomial norm bounds of
// second_derivative_bounds(BezierPatch3) (the numerators are then w^3 times F_uu's net). The
// quotient-rule route through the homogeneous form and a lower bound on the weight function is
// that of Zheng & Sederberg ("Estimating tessellation parameter intervals for rational curves
// and surfaces", ACM TOG 19(1), 2000); bounding the whole numerator at once, instead of each of
// its terms by the triangle inequality, keeps the cancellation between them (on the sphere's
// octant the termwise bound was 1.6 times this one at 16 pieces). c is the centre of the box of
// the P_ij, which keeps the rounding of the products small.
//
// On sub-patches the nets tighten (the weights' spread and R shrink with the domain), so the
// pieces form bounds each piece on its own part and scales it back by the chain rule
// (F_uu = k^2 F_ss on a piece 1/k wide), as second_derivative_bounds(BezierPatch3, pieces) does.
// Only the norms are known (SecondDerivativeBounds::directions stays empty).

#include <vector>

#include "surfaces/patch_flatness.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// M_uu, M_uv, M_vv of a rational patch over [0,1]^2 (see the file comment).
SecondDerivativeBounds second_derivative_bounds(const RationalBezierPatch& patch);

/// The bounds of each of the pieces x pieces sub-patches (de Casteljau on the homogeneous net) on
/// its own part of [0,1]^2, in the patch's parameters, piece (a, b) at a + pieces * b.
/// \throws InvalidInput unless 1 <= pieces <= 64.
std::vector<SecondDerivativeBounds> piece_second_derivative_bounds(const RationalBezierPatch& patch, int pieces);

/// The largest of piece_second_derivative_bounds(patch, pieces).
/// \throws InvalidInput unless 1 <= pieces <= 64.
SecondDerivativeBounds second_derivative_bounds(const RationalBezierPatch& patch, int pieces);

}  // namespace patchwork
