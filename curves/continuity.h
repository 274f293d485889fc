#pragma once
// Continuity of two curves where they meet (seed Def 58, Bemerkung 18).
//
// `first` ends at t = first.b(), `second` starts at t = second.a(). The join is C^k when the
// derivatives of order 0..k with respect to each curve's own parameter agree there (with the
// chain rule of Def 57, so for two curves on [0,1] this is Def 58 verbatim). Derivatives at an
// end are exact finite differences of the control points:
//
//   C^(j)(b) = n!/(n-j)! / (b-a)^j * Delta^j P_{n-j},   Delta^j P_i = sum_l (-1)^(j-l) C(j,l) P_{i+l}
//
// and "agree" means |difference| <= relative_tolerance * s_j, where the scale
// s_j = max over both curves of n!/(n-j)!/h^j * 2^j * max_i |P_i| (each curve with its own n,
// h = b - a and P_i) bounds the rounding in forming the differences: two joins that are equal in
// exact arithmetic are reported equal, also for control points far from the origin.
// G^1: C^0 and the limit tangents point the same way.

#include <vector>

#include "curves/bezier_curve.h"

namespace patchwork {

/// What a join achieves.
struct Continuity {
  /// The highest k <= max_order with a C^k join; -1 when the ends do not even meet (no C^0).
  int ck;
  /// C^0 and equal unit tangent directions (limit tangents where C' vanishes).
  bool g1;
  /// |first(b) - second(a)|.
  double gap;
};

/// How `first` (at its end) and `second` (at its start) join, up to order max_order.
/// \throws InvalidInput if max_order < 0 or relative_tolerance is negative or not finite.
template <int Dim>
Continuity continuity(const BezierCurve<Dim>& first, const BezierCurve<Dim>& second, int max_order,
                      double relative_tolerance = 1e-10);

/// The first k+1 control points Q_0..Q_k of a curve of degree m on an interval of length
/// `length` that joins `curve` (at its end) with C^k; the remaining m-k points are free.
/// Solved order by order from Delta^j Q_0 = (m-j)!/m! * length^j * C^(j)(b); k = 1 is
/// Bemerkung 18: Q_1 = Q_0 + (n/m) (length/(b-a)) (P_n - P_{n-1}).
/// \throws InvalidInput if k < 0, k > m, or length is not positive and finite.
template <int Dim>
std::vector<Point<Dim>> continue_ck(const BezierCurve<Dim>& curve, int k, int m, double length);

}  // namespace patchwork
