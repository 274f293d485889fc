#pragma once
// Degree elevation (exact: the same polynomial, written with one more control point) and
// least-squares degree reduction (an approximation, returned with its exact maximum error).
//
// Elevation n -> n+1:  Q_i = (i/(n+1)) P_{i-1} + (1 - i/(n+1)) P_i,  i = 0..n+1.
// Reduction n -> m minimises the continuous L2 distance  int_0^1 |C(s) - R(s)|^2 ds  through the
// Bernstein Gram matrices  G^{mn}_{ki} = C(m,k) C(n,i) / ((m+n+1) C(m+n, k+i)).

#include "curves/bezier_curve.h"

namespace patchwork {

/// The same curve written with degree n + times. \throws InvalidInput if times < 0.
template <int Dim>
BezierCurve<Dim> elevate_degree(const BezierCurve<Dim>& curve, int times = 1);

/// Whether a reduced curve must keep the original end points (C^0-preserving reduction).
enum class EndPoints { free, interpolate };

/// A reduced curve and max_{t in [a,b]} |C(t) - R(t)|, found from the roots of d/dt |C - R|^2.
template <int Dim>
struct DegreeReduction {
  BezierCurve<Dim> curve;
  double max_error;
};

/// Least-squares reduction to degree m < n (or m = n, which returns the curve and error 0).
/// \throws InvalidInput if m < 0, m > n, or m < 1 with EndPoints::interpolate.
template <int Dim>
DegreeReduction<Dim> reduce_degree(const BezierCurve<Dim>& curve, int m,
                                   EndPoints end_points = EndPoints::free);

}  // namespace patchwork
