#pragma once
// Rational Bezier curves: control points P_i with positive weights w_i,
//
//   C(t) = sum_i w_i P_i B_i^n(s) / sum_i w_i B_i^n(s),   s = (t - a)/(b - a).
//
// Stored as the polynomial curve of homogeneous points (w_i P_i, w_i) in dimension Dim + 1, so
// splitting and degree elevation are those of BezierCurve, and derivatives follow from
// C = H/w by Leibniz's rule: C^(k) = (H^(k) - sum_{j=1}^{k} C(k,j) w^(j) C^(k-j)) / w.
// Conic sections are exact: circle_arc gives circles to the last bit of the weights.

#include <span>
#include <vector>

#include "curves/bezier_curve.h"

namespace patchwork {

template <int Dim>
class RationalBezierCurve {
 public:
  using Point = patchwork::Point<Dim>;
  using Homogeneous = BezierCurve<Dim + 1>;

  /// Curve with control points P_i and weights w_i on [a, b].
  /// \throws InvalidInput if the sizes differ, nothing is given, a value is not finite, a weight
  ///         is not positive, or !(a < b).
  RationalBezierCurve(std::vector<Point> control_points, std::vector<double> weights,
                      double a = 0.0, double b = 1.0);
  /// From homogeneous control points (w_i P_i, w_i). \throws InvalidInput if a weight is <= 0.
  explicit RationalBezierCurve(Homogeneous homogeneous);

  /// The degree n.
  int degree() const noexcept { return homogeneous_.degree(); }
  double a() const noexcept { return homogeneous_.a(); }
  double b() const noexcept { return homogeneous_.b(); }
  /// The control point P_i (the homogeneous point divided by its weight).
  Point control_point(int i) const;
  /// The weight w_i.
  double weight(int i) const { return homogeneous_.control_points().at(i)[Dim]; }
  /// The curve of homogeneous points (w_i P_i, w_i).
  const Homogeneous& homogeneous() const noexcept { return homogeneous_; }

  /// C(t). \throws InvalidInput if t is not finite.
  Point evaluate(double t) const;
  Point operator()(double t) const { return evaluate(t); }

  friend bool operator==(const RationalBezierCurve&, const RationalBezierCurve&) = default;

 private:
  Homogeneous homogeneous_;
};

using RationalBezierCurve2 = RationalBezierCurve<2>;
using RationalBezierCurve3 = RationalBezierCurve<3>;

/// The k-th derivative of C at t. \throws InvalidInput if k < 0 or t is not finite.
template <int Dim>
Point<Dim> derivative(const RationalBezierCurve<Dim>& curve, double t, int k);

/// Unit tangent at t (limit direction where C' vanishes, as for BezierCurve).
template <int Dim>
Point<Dim> tangent(const RationalBezierCurve<Dim>& curve, double t);

/// Curvature at t. \throws NumericalError if C'(t) = 0.
template <int Dim>
double curvature(const RationalBezierCurve<Dim>& curve, double t);

/// The pieces on [a, t] and [t, b]. \throws InvalidInput unless a < t < b.
template <int Dim>
std::pair<RationalBezierCurve<Dim>, RationalBezierCurve<Dim>> split(
    const RationalBezierCurve<Dim>& curve, double t);

/// The same curve with degree n + times. \throws InvalidInput if times < 0.
template <int Dim>
RationalBezierCurve<Dim> elevate_degree(const RationalBezierCurve<Dim>& curve, int times = 1);

/// An exact circular arc of `radius` about `center` in the plane spanned by the orthonormal
/// axes x_axis, y_axis, from angle `start` to `end` (radians, counter-clockwise from x_axis
/// towards y_axis when end > start): quadratic pieces of at most 90 degrees, weights
/// (1, cos(phi/2), 1) for a piece of sweep phi, each on [0, 1].
/// \throws InvalidInput if radius <= 0, start == end, |end - start| > 2 pi, or the axes are not
///         orthonormal (to 1e-12).
template <int Dim>
std::vector<RationalBezierCurve<Dim>> circle_arc(const Point<Dim>& center, const Point<Dim>& x_axis,
                                                 const Point<Dim>& y_axis, double radius,
                                                 double start, double end);

/// The 2D arc about `center` from angle `start` to `end` (see the general form).
std::vector<RationalBezierCurve<2>> circle_arc(const Vec2& center, double radius, double start,
                                               double end);

}  // namespace patchwork
