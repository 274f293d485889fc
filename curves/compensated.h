#pragma once
// Compensated de Casteljau (Graillat, Langlois & Louvet, "Algorithms for accurate, validated and
// fast polynomial evaluation", Japan J. Indust. Appl. Math. 26, 2009; error analysis of the
// Bernstein case by Jiang, Li, Cheng & Wang, J. Comput. Appl. Math. 233, 2010).
//
// Every de Casteljau step r*b_i + t*b_{i+1} is computed with the error-free transformations
// TwoSum and TwoProduct (an FMA), the rounding errors are propagated through a second de
// Casteljau scheme, and added back at the end. For s in [0, 1] the result satisfies
//
//   |res - p(s)| <= u |p(s)| + 2 gamma_{3n+2}^2  p~(s),   p~(s) = sum_i |b_i| B_i^n(s),
//
// with u = 2^-53 and gamma_k = k u / (1 - k u): as accurate as plain de Casteljau computed in
// twice the working precision, then rounded. Plain de Casteljau satisfies
// |res - p(s)| <= gamma_{3n} p~(s) (per level: 1 - s rounded, a product, a sum; gamma_{2n} when
// 1 - s is exact, e.g. for s in [1/2, 1] by Sterbenz's lemma) and stays the fast default.

#include "curves/bezier_curve.h"

namespace patchwork {

/// gamma_k = k u / (1 - k u) with u = 2^-53, the usual constant of rounding-error analysis.
double gamma_constant(int k);

/// A compensated value with a bound on |value - exact| per coordinate.
template <int Dim>
struct CompensatedPoint {
  Point<Dim> value;
  /// Per coordinate: computed bound on the error, from the theorem above evaluated at run time
  /// with p~(s) computed alongside (rounding of the bound itself accounted for). Valid for
  /// s in [0, 1]; the local parameter s = (t-a)/(b-a) is taken as computed.
  Point<Dim> error_bound;
};

/// C(t) by compensated de Casteljau. \throws InvalidInput if t is not finite.
template <int Dim>
CompensatedPoint<Dim> evaluate_compensated(const BezierCurve<Dim>& curve, double t);

/// Per coordinate p~(s) = sum_i |P_i| B_i^n(s), the magnitude that scales every error bound.
template <int Dim>
Point<Dim> absolute_value_sum(const BezierCurve<Dim>& curve, double t);

}  // namespace patchwork
