#pragma once
// Normals of Bezier patches (seed Def 32): n = F_u x F_v, and a unit normal that is defined
// everywhere, also where F_u x F_v vanishes.
//
// Where it vanishes (a collapsed edge such as the teapot's lid top, a collapsed corner), the
// unit normal is the limit of n / |n| approaching (u, v) from inside the square along the
// direction d towards its centre (1/2, 1/2): with N(s) = n(u + s d_u, v + s d_v),
//   N^(k)(0) = sum_j C(k,j) D^j F_u x D^(k-j) F_v,   D = d_u d/du + d_v d/dv,
// and the first N^(k) that does not vanish gives the direction (s > 0, so its sign is kept).
// At a collapsed edge this limit is the same for every inward direction; at a true cone point
// it depends on d, and the one towards the centre is returned.

#include "core/types.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// F_u x F_v at (u, v), not normalised (zero where the parametrisation degenerates).
Vec3 normal(const BezierPatch3& patch, double u, double v);
/// F_u x F_v of a rational patch.
Vec3 normal(const RationalBezierPatch& patch, double u, double v);

/// The unit normal at (u, v), the limit normal where F_u x F_v vanishes.
/// \throws NumericalError only for a patch that is degenerate everywhere near (u, v) (a point or
///         a curve), which has no normal.
Vec3 unit_normal(const BezierPatch3& patch, double u, double v);
/// The unit normal of a rational patch (limit normal at collapsed edges, e.g. a sphere's pole).
Vec3 unit_normal(const RationalBezierPatch& patch, double u, double v);

/// The unit direction of F_u (along_u) or F_v at (u, v); where that derivative vanishes (a
/// collapsed edge), the limit of its direction approaching from inside towards (1/2, 1/2), as
/// for unit_normal. \throws NumericalError if every derivative along the direction vanishes.
Vec3 unit_derivative_direction(const BezierPatch3& patch, double u, double v, bool along_u);
/// unit_derivative_direction of a rational patch.
Vec3 unit_derivative_direction(const RationalBezierPatch& patch, double u, double v, bool along_u);

/// The unit tangent along increasing u in the tangent plane of `unit_normal`, with w = +1 or -1
/// the sign of (normal x tangent) . F_v (the glTF TANGENT convention; +1 for a regular patch).
Vec4 unit_tangent(const BezierPatch3& patch, double u, double v, const Vec3& unit_normal);
/// unit_tangent of a rational patch.
Vec4 unit_tangent(const RationalBezierPatch& patch, double u, double v, const Vec3& unit_normal);

namespace detail {

/// When F_u x F_v counts as vanishing (|F_u x F_v| <= normal) and a first derivative or a
/// tangent's part (<= derivative), for degrees (n, m) and a net in `box` (docs/surfaces.md):
/// relative to the net's size s (its box diagonal), and never below the rounding of the
/// derivatives' sums, which grows with the net's distance R from the origin: a derivative taken
/// from the control points carries about 4 d (d + 1) eps R of noise (d = max(n, m)) even where it
/// vanishes exactly. A rational patch (F = H / w, weights w_max / w_min = weight_ratio apart)
/// has three such terms in its quotient rule, each up to weight_ratio larger, and derivatives up
/// to weight_ratio larger. `normal` and `derivative` hold for the whole patch (the grid kernels'
/// test, which sends doubtful samples to the limit normal); first_normal_vanishes and
/// limit_unit_normal judge each point by its own derivatives' sizes.
struct DegeneracyThresholds {
  double normal;      // |F_u x F_v| below it vanishes anywhere on the patch
  double derivative;  // |F_u| (a tangent's part) below it vanishes
  double relative;    // 1e-12 n m s^2: the part relative to the net's size
  double noise;       // the rounding of one first derivative, 4 d (d + 1) eps R (times 3 w_max / w_min)
};
DegeneracyThresholds degeneracy_thresholds(int n, int m, const Eigen::AlignedBox3d& box, bool rational = false,
                                           double weight_ratio = 1.0);
/// degeneracy_thresholds of a patch's net.
DegeneracyThresholds degeneracy_thresholds(const BezierPatch3& patch);
/// degeneracy_thresholds of a rational patch's net of points P_ij and its weights.
DegeneracyThresholds degeneracy_thresholds(const RationalBezierPatch& patch);

/// Whether F_u x F_v vanishes at a point with these first derivatives: below the net-relative
/// part or below the rounding it can carry there, 2 noise (|F_u| + |F_v|).
bool first_normal_vanishes(const Vec3& du, const Vec3& dv, const DegeneracyThresholds& thresholds);

/// unit_normal(patch, u, v) with the patch's degeneracy_thresholds found by the caller (once for
/// many points of one patch): the same value, bit for bit.
Vec3 unit_normal(const BezierPatch3& patch, double u, double v, const DegeneracyThresholds& thresholds);

/// The limit unit normal from a derivative table of order >= 1 (see the file comment), judged by
/// the patch's degeneracy_thresholds; n and m its degrees.
Vec3 limit_unit_normal(const PartialDerivatives<3>& derivatives, double u, double v,
                       const DegeneracyThresholds& thresholds, int n, int m);

/// unit_normal where the caller has found F_u x F_v vanishing (a grid sample at a pole): the
/// limit normal without evaluating the first-order normal again; unit_normal's value there.
/// \throws NumericalError as unit_normal.
Vec3 degenerate_unit_normal(const BezierPatch3& patch, double u, double v);
/// degenerate_unit_normal of a rational patch.
Vec3 degenerate_unit_normal(const RationalBezierPatch& patch, double u, double v);

}  // namespace detail
}  // namespace patchwork
