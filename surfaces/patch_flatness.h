#pragma once
// The a-priori flatness bound of Filip, Magedson & Markot (1986, "Surface algorithms using
// bounds on derivatives", CAGD 3): on a uniform grid of parameter steps (du, dv), triangulated,
// the distance between F and its piecewise-linear interpolant is at most
//
//   (1/8) (M_uu du^2 + 2 M_uv du dv + M_vv dv^2),
//
// with M_uu >= sup |F_uu|, M_uv >= sup |F_uv|, M_vv >= sup |F_vv| taken from the net's second
// differences (convex hull property of the differenced nets):
//   M_uu = n(n-1) max |P_{i+2,j} - 2 P_{i+1,j} + P_ij|
//   M_uv = n m    max |P_{i+1,j+1} - P_{i+1,j} - P_{i,j+1} + P_ij|
//   M_vv = m(m-1) max |P_{i,j+2} - 2 P_{i,j+1} + P_ij|
// The bound is on the parametric distance |F(u,v) - L(u,v)| (L linear on each triangle), which
// bounds both one-sided Hausdorff distances. The tessellator's guarantee rests on it.

#include <cstdint>
#include <vector>

#include "surfaces/bezier_patch.h"

namespace patchwork {

/// The second-derivative bounds of a patch.
struct SecondDerivativeBounds {
  double uu;
  double uv;
  double vv;
};

/// M_uu, M_uv, M_vv of the patch (zero where a degree is too low).
SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch);

/// Tighter bounds from the nets of the pieces x pieces sub-patches (de Casteljau): each piece's
/// net bounds its own derivatives, and by the chain rule F_uu = (pieces)^2 F_ss of a piece, so
/// the largest piece bound times pieces^2 bounds the whole patch. As pieces grows this tends to
/// the true sup |F_uu| (and likewise uv, vv); on the teapot 4 pieces save 18% of the triangles.
/// \throws InvalidInput unless 1 <= pieces <= 64.
SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch, int pieces);

/// The bounds of each of the pieces x pieces sub-patches on its own part of [0,1]^2, in the
/// patch's parameters (the sub-net's bounds times pieces^2), piece (a, b) at a + pieces * b:
/// second_derivative_bounds(patch, pieces) is their largest.
/// \throws InvalidInput unless 1 <= pieces <= 64.
std::vector<SecondDerivativeBounds> piece_second_derivative_bounds(const BezierPatch3& patch, int pieces);

/// The bound for parameter steps du, dv. \throws InvalidInput unless both are in (0, 1].
double flatness_bound(const SecondDerivativeBounds& bounds, double du, double dv);

/// The bound on |F - L| over one triangle of parameter points p0, p1, p2 (any shape), L linear on
/// it: |F - L| <= (1/2) sum_k lambda_k q(p_k - x) with q(d) = M_uu d_u^2 + 2 M_uv |d_u d_v| +
/// M_vv d_v^2 (Taylor at x, lambda the barycentric weights of x); q(d) <= d^T A d with
/// A = diag(M_uu + s M_uv, M_vv + M_uv / s) for any s > 0, and then the maximum over the triangle
/// is r^2 / 2 with r the radius of its smallest enclosing circle in the metric of A. With
/// s = `aspect` (= dv/du of a grid) a grid triangle gets flatness_bound(du, dv) exactly.
double triangle_flatness_bound(const SecondDerivativeBounds& bounds, const Vec2& p0, const Vec2& p1, const Vec2& p2,
                               double aspect = 1.0);

/// max |F(u,v) - L(u,v)| over the triangulated nu x nv grid (each cell split along its diagonal
/// from (u_a, v_b) to (u_a+1, v_b+1)), sampled at the points of a `samples`-step barycentric
/// lattice per triangle: the measured counterpart of flatness_bound (a lower bound of the true
/// distance). \throws InvalidInput unless nu, nv, samples >= 1.
double sampled_grid_distance(const BezierPatch3& patch, std::int64_t nu, std::int64_t nv, int samples);

/// A grid of segments_u x segments_v cells.
struct GridSize {
  std::int64_t segments_u;
  std::int64_t segments_v;
};

/// The grid with the fewest cells whose bound is <= tolerance (ties: the more even grid).
/// \throws InvalidInput if the tolerance is not positive and finite, or a side would need more
///         than 2^20 segments.
GridSize grid_for_tolerance(const SecondDerivativeBounds& bounds, double tolerance);

}  // namespace patchwork
