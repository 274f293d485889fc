#pragma once
// Knot insertion, refinement and removal (The NURBS Book, ch. 5): the same curve on more knots,
// and fewer knots where the curve allows it within a guaranteed bound.
//
// Insertion of u (u_k <= u < u_{k+1}, multiplicity s) by Boehm's algorithm (A5.1), repeated:
//
//   Q_i = alpha_i P_i + (1 - alpha_i) P_{i-1},  alpha_i = (u - u_i) / (u_{i+p} - u_i),  k-p+1 <= i <= k-s
//
// Removal of an interior knot solves these relations backwards from both ends (Tiller 1992,
// A5.8); one equation is left over, which is exact only if the curve is C^(p-s+1) at u. The
// bound: re-inserting the knot into the candidate gives control points R_i on the old knots,
// and since the B-splines are non-negative and sum to one,
//
//   |C(u) - C'(u)| = |sum_i N_i(u) (P_i - R_i)| <= d = max_i |P_i - R_i|   (+ rounding)
//
// (Tiller, "Knot-removal algorithms for NURBS curves and surfaces", CAD 24(8), 1992; The NURBS
// Book eq. 5.30). For a NURBS curve d is taken on the homogeneous points, and
// C - C' = ((H - H')_xyz + C (w' - w)) / w' gives |C - C'| <= d (1 + max_i |P_i|) / min_i w'_i
// (Piegl & Tiller eq. 5.31). A removal is made only when this bound is <= the tolerance.

#include <span>

#include "curves/bspline_curve.h"

namespace patchwork {

/// The curve with u inserted `times` more times (Boehm, A5.1); the same curve on more knots.
/// \throws InvalidInput if u is not in [a, b], times < 0, or the multiplicity would exceed p.
template <int Dim>
BSplineCurve<Dim> insert_knot(const BSplineCurve<Dim>& curve, double u, int times = 1);

/// The rational curve with u inserted `times` more times (on the homogeneous points).
template <int Dim>
NurbsCurve<Dim> insert_knot(const NurbsCurve<Dim>& curve, double u, int times = 1);

/// The curve with every value of `knots` inserted once (a value given twice, twice): repeated
/// Boehm insertion in increasing order. \throws InvalidInput as insert_knot.
template <int Dim>
BSplineCurve<Dim> refine_knots(const BSplineCurve<Dim>& curve, std::span<const double> knots);

/// The rational curve refined by `knots`.
template <int Dim>
NurbsCurve<Dim> refine_knots(const NurbsCurve<Dim>& curve, std::span<const double> knots);

/// The result of remove_knot: the curve with the knot removed `removed` times (0: unchanged), and
/// a guaranteed bound on max_u |C(u) - C'(u)| for that curve (0 when nothing was removed).
template <class Curve>
struct KnotRemoval {
  Curve curve;
  int removed;
  double bound;
};

/// Removes the interior knot u t times for the largest t <= `times` whose bound on the curve's
/// total change is <= tolerance (t = 0, the curve unchanged, if there is none).
/// \throws InvalidInput if u is not a knot inside (a, b), times < 1 or above its multiplicity,
///         or tolerance is negative or NaN (+infinity removes unconditionally).
template <int Dim>
KnotRemoval<BSplineCurve<Dim>> remove_knot(const BSplineCurve<Dim>& curve, double u, int times, double tolerance);

/// Removes the interior knot u of a rational curve (bound of eq. 5.31; a removal that would make
/// a weight <= 0 is refused).
template <int Dim>
KnotRemoval<NurbsCurve<Dim>> remove_knot(const NurbsCurve<Dim>& curve, double u, int times, double tolerance);

}  // namespace patchwork
