#pragma once
// Arc length (seed Def 31): L = int_{t0}^{t1} |C'(t)| dt by adaptive Gauss-Legendre quadrature.
//
// On each interval a 10-point rule on the whole is compared with the rule on both halves; the
// halves are accepted when they differ by less than the interval's share of the tolerance, and
// the difference is kept as the error estimate (conservative: it estimates the error of the
// coarser value). Where |C'| has a kink (a cusp), the bisection concentrates there.

#include <functional>

#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {

/// A length and an estimate of |length - exact|.
struct ArcLength {
  double length;
  double error_estimate;
};

/// int_{t0}^{t1} f(t) dt by adaptive Gauss-Legendre to absolute `tolerance`.
/// \throws InvalidInput if the tolerance is not positive or the limits are not finite;
///         NumericalError if 50 bisection levels do not reach the tolerance.
ArcLength integrate_adaptive(const std::function<double(double)>& f, double t0, double t1,
                             double tolerance);

/// Length of the whole curve to absolute `tolerance`.
template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double tolerance = 1e-12);

/// Length of the piece on [t0, t1] (a <= t0 <= t1 <= b).
template <int Dim>
ArcLength arc_length(const BezierCurve<Dim>& curve, double t0, double t1, double tolerance);

/// Length of the whole rational curve to absolute `tolerance`.
template <int Dim>
ArcLength arc_length(const RationalBezierCurve<Dim>& curve, double tolerance = 1e-12);

}  // namespace patchwork
