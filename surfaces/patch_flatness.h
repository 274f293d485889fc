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
//
// The directional bound. Norms add F_uu, F_uv and F_vv as if they pointed the same way; where
// they do not (F_uv along the surface and F_uu across it, as on a surface of revolution; F_uu
// and F_vv opposite, as on a saddle) a tighter bound follows from the vectors themselves. By
// Taylor at x with a third-order remainder, for a triangle p_k and barycentric weights lambda_k
// of x, d_k = p_k - x:
//
//   |F(x) - L(x)| <= (1/2) |m_1 F_uu(x) + m_2 F_uv(x) + m_3 F_vv(x)| + (1/6) sum_k lambda_k |D^3 F [d_k]^3|,
//   m = (sum lambda_k d_ku^2, 2 sum lambda_k d_ku d_kv, sum lambda_k d_kv^2),
//
// where m_1 <= du^2 / 4, |m_2| <= du dv / 2, m_3 <= dv^2 / 4 (the variance and covariance of the
// vertices' coordinates under lambda; du, dv the triangle's extents), and m_2 >= 0 when the
// vertices are ordered alike in u and v (as in every grid triangle). The first term is at most
// max over the box of m of |sum m_i H_i(y)|: convex in m, so attained at a corner of the box, and
// bounded through the Gram matrices of the nets of H_i raised to one degree (convex hull).
//
// The cell bound. The remainder above ignores that on a grid triangle the cubic moments vanish
// where the quadratic ones peak (the diagonal's midpoint). Expanded to fourth order instead,
//   |F(x) - L(x)| <= (1/2) |sum_i m_i H_i(x)| + (1/6) sum_j c_j |mu_j| |T_j| + R_4,
// with the exact third moments mu_j of x (polynomials in its position), and the maximum of the
// first two terms together is taken over boxes of a graded partition of each triangle (fine
// near s = t = 1/2), with the moments' exact ranges over each box. R_4 comes from fourth
// differences of the net. It costs some 30 times the quick bounds, so grid_for_tolerance
// searches with those and then asks the cell bound only about grids with fewer cells.
//
// flatness_bound is the smallest of the norm, directional and cell bounds.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "surfaces/bezier_patch.h"

namespace patchwork {

/// What the second derivatives H = (F_uu, F_uv, F_vv) are as vectors, and bounds on the third.
struct DirectionalBounds {
  /// For weights w and every point y of the domain,
  ///   |w_0 F_uu(y) + w_1 F_uv(y) + w_2 F_vv(y)|^2 <= sum_ij w_i w_j G_ij,
  /// G_ij = gram_max[i][j] where w_i w_j >= 0 and gram_min[i][j] where w_i w_j < 0: the extreme
  /// Gram entries over the control points of the three nets raised to degree (n, m).
  std::array<std::array<double, 3>, 3> gram_max;
  std::array<std::array<double, 3>, 3> gram_min;
  /// Bounds on |F_uuu|, |F_uuv|, |F_uvv|, |F_vvv| (third differences of the net).
  std::array<double, 4> third;
  /// Bounds on |F_uuuu|, |F_uuuv|, |F_uuvv|, |F_uvvv|, |F_vvvv| (fourth differences).
  std::array<double, 5> fourth;
};

/// The second-derivative bounds of a patch.
struct SecondDerivativeBounds {
  double uu;
  double uv;
  double vv;
  /// The directional bounds, when known (surfaces from other sources give only the norms).
  std::optional<DirectionalBounds> directions = std::nullopt;
};

/// Bounds over the union of the domains of a and b (the larger of each; directions only if both
/// have them).
SecondDerivativeBounds merged_bounds(const SecondDerivativeBounds& a, const SecondDerivativeBounds& b);

/// Bounds over the union of the domains of all of `bounds` (merged_bounds of them all).
/// \pre bounds is not empty.
SecondDerivativeBounds merged_bounds(const std::vector<SecondDerivativeBounds>& bounds);

/// The bounds in the parameters of a sub-domain `size` times as wide in u and v (chain rule:
/// second derivatives times size^2, their Gram entries times size^4, third derivatives times
/// size^3, fourth times size^4). \pre size > 0.
SecondDerivativeBounds scaled_bounds(const SecondDerivativeBounds& bounds, double size);

/// M_uu, M_uv, M_vv of the patch (zero where a degree is too low), with its directional bounds.
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

/// The bound for parameter steps du, dv on the grid's triangles (each cell split along its
/// (i, j)-(i+1, j+1) diagonal): the smallest of the norm bound, the directional bound and the cell
/// bound (patch_flatness.cpp: the quadratic and cubic Taylor terms together, maximised over boxes
/// of each triangle, with a fourth-order remainder; some 30 times the cost of the other two).
/// When the norm or directional bound is already <= `good_enough`, that one is returned without
/// the cell bound. \throws InvalidInput unless both steps are in (0, 1].
double flatness_bound(const SecondDerivativeBounds& bounds, double du, double dv, double good_enough = 0.0);

/// The bound on |F - L| over one triangle of parameter points p0, p1, p2 (any shape), L linear on
/// it: |F - L| <= (1/2) sum_k lambda_k q(p_k - x) with q(d) = M_uu d_u^2 + 2 M_uv |d_u d_v| +
/// M_vv d_v^2 (Taylor at x, lambda the barycentric weights of x); q(d) <= d^T A d with
/// A = diag(M_uu + s M_uv, M_vv + M_uv / s) for any s > 0, and then the maximum over the triangle
/// is r^2 / 2 with r the radius of its smallest enclosing circle in the metric of A. With
/// s = `aspect` (= dv/du of a grid) a grid triangle gets the norm part of flatness_bound(du, dv)
/// exactly. With directions, the directional bound of the triangle where it is smaller.
double triangle_flatness_bound(const SecondDerivativeBounds& bounds, const Vec2& p0, const Vec2& p1, const Vec2& p2,
                               double aspect = 1.0);

/// A bound on |F - L| over triangle p0 p1 p2 that is at most `target` where that can be shown:
/// where triangle_flatness_bound exceeds it, the triangle is split at its edge midpoints, and on
/// each part |F - L| <= |F - L'| + max |F - L| over the part's corners (L' the part's linear
/// interpolant: L - L' is linear, so largest at a corner, where L' = F), the first term bounded
/// the same way, up to `depth` levels. It costs three evaluations of `surface` per split (the
/// corners' deviations are exact samples), and tends to the true maximum as the parts shrink.
double refined_triangle_flatness_bound(const SecondDerivativeBounds& bounds,
                                       const std::function<Vec3(const Vec2&)>& surface, const Vec2& p0, const Vec2& p1,
                                       const Vec2& p2, double aspect, double target, int depth = 3);

/// max |F(u,v) - L(u,v)| over the triangulated nu x nv grid (each cell split along its diagonal
/// from (u_a, v_b) to (u_a+1, v_b+1)), sampled at the points of a `samples`-step barycentric
/// lattice per triangle: the measured counterpart of flatness_bound (a lower bound of the true
/// distance). \throws InvalidInput unless nu, nv, samples >= 1.
double sampled_grid_distance(const BezierPatch3& patch, std::int64_t nu, std::int64_t nv, int samples);

namespace detail {
/// The fourth-order Taylor remainder of the cell bound at steps (du, dv) with fourth-derivative
/// bounds f (DirectionalBounds::fourth), as {c_1, c_3}: (1/24) sum_k lambda_k |D^4 F [d_k]^4| <=
/// c_1 m_1 + c_3 m_3 with m the normalised second moments (sum_k lambda_k (d_ku/du)^2 and
/// (d_kv/dv)^2) of any point of a grid triangle (exposed for a test against brute force).
std::array<double, 2> fourth_order_coefficients(const std::array<double, 5>& f, double du, double dv);
}  // namespace detail

/// A grid of segments_u x segments_v cells.
struct GridSize {
  std::int64_t segments_u;
  std::int64_t segments_v;
};

/// The grid with the fewest cells, at least min_segments per side, whose bound is <= tolerance
/// (ties under the quick bounds: the more even grid). Searched with the norm and directional
/// bounds, then for fewer cells under the cell bound (up to 64 x 64 cells); the fewest assumes
/// the bound falls as either rate grows, which the tests check against brute force.
/// \throws InvalidInput if the tolerance is not positive and finite, min_segments is not in
///         [1, 2^20], or a side would need more than 2^20 segments.
GridSize grid_for_tolerance(const SecondDerivativeBounds& bounds, double tolerance, std::int64_t min_segments = 1);

/// What grid_for_tolerance has learnt about one set of bounds, for asking again at another
/// tolerance (a renderer's next frame): the cell bounds of the grids it tried (each exact, or a
/// value the bound is known to exceed, where the test stopped early), and its last answers. It
/// holds for the bounds it was first used with, and for no other.
struct GridSearchMemo {
  struct CellBound {
    std::int64_t nu, nv;
    double value;
    /// value is the cell bound itself; else the bound is at least value.
    bool exact;
  };
  /// At most most_cell_bounds of them (the first asked for; later grids are computed each
  /// time), so that a camera whose tolerances drift for ever does not grow the memo for ever.
  std::vector<CellBound> cell_bounds;
  static constexpr std::size_t most_cell_bounds = 64;
  struct Answer {
    double tolerance;
    std::int64_t min_segments;
    GridSize grid;
  };
  /// The last two answers, newest first (a tolerance that alternates between two values hits).
  std::vector<Answer> answers;
};

/// flatness_bound(bounds, 1 / nu, 1 / nv, good_enough), the same value, with the cell bound taken
/// from `memo` where it holds it whole, and kept there where it is computed.
/// \pre memo was only used with these bounds; nu, nv >= 1.
double flatness_bound(const SecondDerivativeBounds& bounds, std::int64_t nu, std::int64_t nv, double good_enough,
                      GridSearchMemo& memo);

/// grid_for_tolerance(bounds, tolerance, min_segments), answered from `memo` where it can and
/// adding to it: the same grid as without a memo (it keeps values, not guesses), with the cell
/// bounds of grids tried before not computed again. \pre memo was only used with these bounds.
GridSize grid_for_tolerance(const SecondDerivativeBounds& bounds, double tolerance, std::int64_t min_segments,
                            GridSearchMemo& memo);

}  // namespace patchwork
