#pragma once
// Splitting Bezier curves by the de Casteljau triangle (Satz 22, Def 59).
//
//   split at t:  P_0 = b_0^0      b_0^1 ...  b_0^n = C(t) = b_0^n ...  b_{n-1}^1   b_n^0 = P_n
//                \_____ left curve on [a, t] ______/ \______ right curve on [t, b] _____/
//
// Both pieces keep the global parameter: left(t') = C(t') for t' in [a, t], right likewise.

#include <utility>

#include "curves/bezier_curve.h"

namespace patchwork {

/// The two pieces of `curve` on [a, t] and [t, b]. \throws InvalidInput unless a < t < b.
template <int Dim>
std::pair<BezierCurve<Dim>, BezierCurve<Dim>> split(const BezierCurve<Dim>& curve, double t);

/// Def 59's halving: split at the midpoint of [a, b]; the halves join C^n.
template <int Dim>
std::pair<BezierCurve<Dim>, BezierCurve<Dim>> halve(const BezierCurve<Dim>& curve);

/// The piece of `curve` on [t0, t1]. \throws InvalidInput unless a <= t0 < t1 <= b.
template <int Dim>
BezierCurve<Dim> subcurve(const BezierCurve<Dim>& curve, double t0, double t1);

}  // namespace patchwork
