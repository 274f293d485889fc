#pragma once
// Arc length (seed Def 31): L = int_{t0}^{t1} |C'(t)| dt by adaptive Gauss-Legendre quadrature.
//
// On each interval a 10-point rule on the whole is compared with the rule on both halves; the
// halves are accepted when 16 times their difference is below the interval's share of the
// tolerance (the factor covers the slow convergence near an unresolved near-cusp), and the
// difference is kept as the error estimate (it estimates the error of the coarser value).
// Where |C'| has a kink (a cusp), the bisection concentrates there. A difference at the rounding
// level of the integrand (64 eps times its mean magnitude; for curves, the rounding bound of
// evaluating |C'| from the control points) is accepted too: a tolerance below that level is not
// reachable, and error_estimate then exceeds the tolerance.
//
// The estimate cannot see a kink that lies before the first (or after the last) Gauss node of an
// interval and of both its halves: the rules then agree on the smooth continuation. So the arc
// length functions first cut [t0, t1] at the critical points of the speed (roots of (|C'|^2)',
// which include every cusp C' = 0), putting each kink at the end of a piece where |C'| is
// analytic; the tolerance is shared among the pieces by length. integrate_adaptive itself takes
// f as given: a kink of f should be an end of [t0, t1].

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
