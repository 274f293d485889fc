#pragma once
// B-spline and NURBS curves (The NURBS Book, ch. 2-4):
//
//   C(u) = sum_{i=0}^{n} N_{i,p}(u) P_i                                 BSplineCurve
//   C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i,  w_i > 0     NurbsCurve
//
// on the valid range [a, b] = [u_p, u_{n+1}] of the knot vector (knot_vector.h: span
// convention, multiplicity and continuity). Evaluation outside [a, b] is refused (InvalidInput),
// unlike a Bezier curve's extrapolation: the basis does not sum to one there.
//
// On span s the curve is the polynomial with blossom (polar form) f(t_1, ..., t_p), computed by
// de Boor's algorithm with t_r at level r; de Boor's point is f(u, ..., u), and the piece's Bezier
// points on [u_s, u_{s+1}] are f(u_s^(p-j), u_{s+1}^j).
//
// A NurbsCurve is stored as the BSplineCurve of homogeneous points (w_i P_i, w_i) in dimension
// Dim + 1, as RationalBezierCurve is; derivatives follow from C = H/w by Leibniz's rule.
// Derivatives at an interior breakpoint are those of the span starting there (from the right),
// at b from the left.

#include <span>
#include <vector>

#include "core/types.h"
#include "curves/knot_vector.h"

namespace patchwork {

template <int Dim>
class BSplineCurve {
 public:
  using Point = patchwork::Point<Dim>;

  /// Curve of degree knots.degree() with control points P_0..P_n.
  /// \throws InvalidInput if the number of points is not knots.size() - p - 1 or a coordinate
  ///         is not finite.
  BSplineCurve(KnotVector knots, std::vector<Point> control_points);

  /// The degree p.
  int degree() const noexcept { return knots_.degree(); }
  /// The knot vector.
  const KnotVector& knot_vector() const noexcept { return knots_; }
  /// The control points P_0..P_n.
  const std::vector<Point>& control_points() const noexcept { return points_; }
  /// Start of the valid range, u_p.
  double a() const noexcept { return knots_.a(); }
  /// End of the valid range, u_{n+1}.
  double b() const noexcept { return knots_.b(); }

  /// C(u) by de Boor's algorithm. \throws InvalidInput if u is not finite or outside [a, b].
  Point evaluate(double u) const;
  /// C(u); same as evaluate.
  Point operator()(double u) const { return evaluate(u); }

  friend bool operator==(const BSplineCurve&, const BSplineCurve&) = default;

 private:
  KnotVector knots_;
  std::vector<Point> points_;
};

template <int Dim>
class NurbsCurve {
 public:
  using Point = patchwork::Point<Dim>;
  using Homogeneous = BSplineCurve<Dim + 1>;

  /// Curve with control points P_i and weights w_i.
  /// \throws InvalidInput if the sizes differ from knots.size() - p - 1, a value is not finite
  ///         or a weight is not positive.
  NurbsCurve(KnotVector knots, std::vector<Point> control_points, std::vector<double> weights);
  /// From homogeneous control points (w_i P_i, w_i). \throws InvalidInput if a weight is <= 0.
  explicit NurbsCurve(Homogeneous homogeneous);

  /// The degree p.
  int degree() const noexcept { return homogeneous_.degree(); }
  /// The knot vector.
  const KnotVector& knot_vector() const noexcept { return homogeneous_.knot_vector(); }
  /// The number of control points n + 1.
  int control_point_count() const noexcept { return knot_vector().control_point_count(); }
  /// The control point P_i (the homogeneous point divided by its weight).
  Point control_point(int i) const;
  /// The weight w_i.
  double weight(int i) const { return homogeneous_.control_points().at(static_cast<std::size_t>(i))[Dim]; }
  /// The curve of homogeneous points (w_i P_i, w_i).
  const Homogeneous& homogeneous() const noexcept { return homogeneous_; }
  /// Start of the valid range, u_p.
  double a() const noexcept { return homogeneous_.a(); }
  /// End of the valid range, u_{n+1}.
  double b() const noexcept { return homogeneous_.b(); }

  /// C(u) = H_xyz(u) / w(u). \throws InvalidInput if u is not finite or outside [a, b].
  Point evaluate(double u) const;
  /// C(u); same as evaluate.
  Point operator()(double u) const { return evaluate(u); }

  friend bool operator==(const NurbsCurve&, const NurbsCurve&) = default;

 private:
  Homogeneous homogeneous_;
};

using BSplineCurve2 = BSplineCurve<2>;
using BSplineCurve3 = BSplineCurve<3>;
using NurbsCurve2 = NurbsCurve<2>;
using NurbsCurve3 = NurbsCurve<3>;

/// The blossom f(t_1, ..., t_p) of the polynomial piece on span s (de Boor with t_r at level r).
/// \throws InvalidInput unless s is a non-empty span in [p, n] and arguments has p finite values.
template <int Dim>
Point<Dim> blossom(const BSplineCurve<Dim>& curve, int span, std::span<const double> arguments);

/// d^k C / du^k at u (zero for k > p), from the basis function derivatives (A2.3, A3.2).
/// \throws InvalidInput if k < 0 or u is not in [a, b].
template <int Dim>
Point<Dim> derivative(const BSplineCurve<Dim>& curve, double u, int k);

/// C(u), C'(u), ..., C^(k)(u). \throws InvalidInput if k < 0 or u is not in [a, b].
template <int Dim>
std::vector<Point<Dim>> derivatives(const BSplineCurve<Dim>& curve, double u, int k);

/// The derivative C' as a B-spline of degree p - 1 on u_1..u_{m-1} with control points
/// p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}) (eq. 3.4; 0 where the knot gap is zero). A degree-0
/// curve gives the zero curve of degree 0 on the same knots.
/// \throws InvalidInput if an interior knot has multiplicity p (C' jumps there, which a knot
///         vector of degree p - 1 cannot carry; derivative() gives the one-sided values).
template <int Dim>
BSplineCurve<Dim> derivative_curve(const BSplineCurve<Dim>& curve);

/// Unit tangent at u: that of the span's Bezier piece (limit direction where C' vanishes, from
/// the right at a breakpoint, from the left at b). \throws NumericalError on a point piece.
template <int Dim>
Point<Dim> tangent(const BSplineCurve<Dim>& curve, double u);

/// d^k C / du^k of the rational curve at u (Leibniz on C = H / w).
/// \throws InvalidInput if k < 0 or u is not in [a, b].
template <int Dim>
Point<Dim> derivative(const NurbsCurve<Dim>& curve, double u, int k);

/// C(u), C'(u), ..., C^(k)(u) of the rational curve.
template <int Dim>
std::vector<Point<Dim>> derivatives(const NurbsCurve<Dim>& curve, double u, int k);

/// Unit tangent of the rational curve at u (as for BSplineCurve).
template <int Dim>
Point<Dim> tangent(const NurbsCurve<Dim>& curve, double u);

/// The closed curve of degree p over the closed polygon Q_0..Q_{k-1} (Q_0 not repeated at the
/// end): control points Q_0..Q_{k-1}, Q_0..Q_{p-1} on periodic_knots(p, k, a, b); C(a) = C(b)
/// with C^(p-1) there. \throws InvalidInput as periodic_knots, or if a point is not finite.
template <int Dim>
BSplineCurve<Dim> periodic_curve(int degree, const std::vector<Point<Dim>>& polygon, double a = 0.0, double b = 1.0);

/// The closed rational curve over the polygon with weights (wrapped as the points).
template <int Dim>
NurbsCurve<Dim> periodic_curve(int degree, const std::vector<Point<Dim>>& polygon, const std::vector<double>& weights,
                               double a = 0.0, double b = 1.0);

}  // namespace patchwork
