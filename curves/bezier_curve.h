#pragma once
// Bezier curves of any degree n >= 0 (seed Def 57, Satz 21, Satz 22).
//
//   C(t) = sum_{i=0}^{n} B_i^n(s) P_i,   s = (t - a) / (b - a),   t in [a, b]
//
//   P_0 ---- P_1 ---- ... ---- P_n        C(a) = P_0, C(b) = P_n
//
// A curve owns its parameter interval [a, b] (default [0, 1]); every operation speaks in that
// global parameter t, so a piece split off at t keeps evaluating to the same points for the
// same t. Derivatives are with respect to t (chain rule of Satz 21: a factor 1/(b-a) per order).
// Evaluating outside [a, b] extrapolates the polynomial (allowed, but unstable far out).

#include <span>
#include <vector>

#include "core/types.h"
#include "curves/bernstein.h"

namespace patchwork {

template <int Dim>
class BezierCurve {
 public:
  using Point = patchwork::Point<Dim>;

  /// Curve with control points P_0..P_n on [a, b].
  /// \throws InvalidInput if there is no control point, a coordinate or a or b is not finite,
  ///         or !(a < b).
  explicit BezierCurve(std::vector<Point> control_points, double a = 0.0, double b = 1.0);

  /// The degree n (number of control points - 1).
  int degree() const noexcept { return static_cast<int>(points_.size()) - 1; }
  /// The control points P_0..P_n.
  const std::vector<Point>& control_points() const noexcept { return points_; }
  /// Start of the parameter interval.
  double a() const noexcept { return a_; }
  /// End of the parameter interval.
  double b() const noexcept { return b_; }
  /// The local parameter s = (t - a) / (b - a).
  double local_parameter(double t) const noexcept { return (t - a_) / (b_ - a_); }

  /// C(t) by de Casteljau (Satz 22). \throws InvalidInput if t is not finite.
  Point evaluate(double t) const;
  /// C(t); same as evaluate.
  Point operator()(double t) const { return evaluate(t); }

  friend bool operator==(const BezierCurve&, const BezierCurve&) = default;

 private:
  std::vector<Point> points_;
  double a_;
  double b_;
};

using BezierCurve1 = BezierCurve<1>;
using BezierCurve2 = BezierCurve<2>;
using BezierCurve3 = BezierCurve<3>;
using BezierCurve4 = BezierCurve<4>;

/// The same control points on another interval [a, b]. \throws InvalidInput if !(a < b).
template <int Dim>
BezierCurve<Dim> with_interval(const BezierCurve<Dim>& curve, double a, double b);

/// The hodograph C'(t) as a curve of degree n-1 on [a, b]: control points n (P_{i+1} - P_i)/(b-a)
/// (Satz 21). A degree-0 curve gives the zero curve of degree 0.
template <int Dim>
BezierCurve<Dim> derivative_curve(const BezierCurve<Dim>& curve);

/// The k-th derivative d^k C / dt^k at t (k = 0 is the point; zero for k > n).
/// \throws InvalidInput if k < 0 or t is not finite.
template <int Dim>
Point<Dim> derivative(const BezierCurve<Dim>& curve, double t, int k);

/// C(t), C'(t), ..., C^(k)(t) in one pass (de Casteljau down to degree k, then differences).
/// \throws InvalidInput if k < 0 or t is not finite.
template <int Dim>
std::vector<Point<Dim>> derivatives(const BezierCurve<Dim>& curve, double t, int k);

/// Unit tangent at t. Where C'(t) vanishes (a cusp, or P_0 = P_1 at an end) this is the limit
/// direction from the first non-vanishing derivative C^(k): taken from the right at t < b, from
/// the left at t = b. \throws NumericalError if every derivative vanishes (a point curve).
template <int Dim>
Point<Dim> tangent(const BezierCurve<Dim>& curve, double t);

/// Curvature |C'|^2|C''|^2 - (C'.C'')^2)^(1/2) / |C'|^3 at t (|C' x C''|/|C'|^3 in 3D), >= 0.
/// \throws NumericalError if C'(t) = 0, where curvature is not defined by this formula.
template <int Dim>
double curvature(const BezierCurve<Dim>& curve, double t);

/// C(t) at many parameters t (global, in [a, b]), sharing one Bernstein table.
template <int Dim>
std::vector<Point<Dim>> evaluate_many(const BezierCurve<Dim>& curve, std::span<const double> ts);

/// C at the table's parameters, which are LOCAL parameters s in [0, 1]: the fast path when many
/// curves of one degree are evaluated at the same parameters. \throws InvalidInput on a degree
/// mismatch.
template <int Dim>
std::vector<Point<Dim>> evaluate(const BezierCurve<Dim>& curve, const BernsteinTable& table);

}  // namespace patchwork
