#pragma once
// Knot vectors of B-spline curves of degree p (The NURBS Book, Piegl & Tiller, ch. 2):
//
//   U = {u_0 <= u_1 <= ... <= u_m},   m + 1 = (n + 1) + p + 1 for n + 1 control points
//
//   u_0 .. u_{p-1} | u_p ======== valid range ======== u_{n+1} | u_{n+2} .. u_m
//
// The curve is defined on the valid range [a, b] = [u_p, u_{n+1}]; knots outside it only shape
// the basis functions there. Span i is [u_i, u_{i+1}) with p <= i <= n; span(u) is the i with
// u_i <= u < u_{i+1}, and the right end u = b belongs to the last non-empty span (the largest
// i <= n with u_i < u_{i+1}), so evaluation at b is the left-sided limit.
//
// A knot value of multiplicity m inside (a, b) is a breakpoint where the curve is C^(p-m)
// (so m <= p there); at most p + 1 equal knots anywhere. Clamped: u_0 = ... = u_p and
// u_{n+1} = ... = u_m, so the curve starts at P_0 and ends at P_n.
//
// Periodic curves are stored unclamped: uniform knots and n + 1 = k + p control points of which
// the last p repeat the first p (periodic_knots gives the knots, bspline_curve.h's
// periodic_curve the curve); the curve then closes with C^(p-1) at a = b.

#include <vector>

namespace patchwork {

class KnotVector {
 public:
  /// Knots u_0..u_m for degree p.
  /// \throws InvalidInput if p < 0, there are fewer than 2(p + 1) knots, a knot is not finite,
  ///         the knots decrease, a value occurs more than p + 1 times (more than p inside the
  ///         valid range), or the valid range [u_p, u_{m-p}] is empty.
  KnotVector(int degree, std::vector<double> knots);

  /// The degree p.
  int degree() const noexcept { return p_; }
  /// The knots u_0..u_m.
  const std::vector<double>& knots() const noexcept { return knots_; }
  /// The knot u_i (unchecked).
  double operator[](int i) const noexcept { return knots_[static_cast<std::size_t>(i)]; }
  /// The number of knots m + 1.
  int size() const noexcept { return static_cast<int>(knots_.size()); }
  /// The number of control points n + 1 = m - p that these knots carry.
  int control_point_count() const noexcept { return size() - p_ - 1; }
  /// Start of the valid range, u_p.
  double a() const noexcept { return knots_[static_cast<std::size_t>(p_)]; }
  /// End of the valid range, u_{n+1}.
  double b() const noexcept { return knots_[static_cast<std::size_t>(control_point_count())]; }

  /// The span index i (p <= i <= n) with u_i <= u < u_{i+1}; u = b gives the last non-empty span.
  /// \throws InvalidInput if u is not finite or outside [a, b].
  int span(double u) const;
  /// How many knots equal u (0 if u is not a knot).
  int multiplicity(double u) const;
  /// The distinct knot values in [a, b], increasing: a, the interior breakpoints, b.
  std::vector<double> breakpoints() const;
  /// The continuity order p - m at each interior breakpoint (breakpoints()[1..size-2]).
  std::vector<int> breakpoint_continuity() const;
  /// Whether the first p + 1 and the last p + 1 knots are equal.
  bool is_clamped() const;

  friend bool operator==(const KnotVector&, const KnotVector&) = default;

 private:
  int p_;
  std::vector<double> knots_;
};

/// Clamped knots for `control_points` control points of degree p with equally spaced interior
/// knots on [a, b]: a (p + 1 times), a + (b - a) j / (n + 1 - p) for j = 1..n - p, b (p + 1 times).
/// \throws InvalidInput if p < 0, control_points < p + 1, or !(a < b).
KnotVector clamped_uniform_knots(int degree, int control_points, double a = 0.0, double b = 1.0);

/// Unclamped equally spaced knots u_i = a + (b - a)(i - p) / (n + 1 - p) (valid range [a, b]).
/// \throws InvalidInput if p < 0, control_points < p + 1, or !(a < b).
KnotVector uniform_knots(int degree, int control_points, double a = 0.0, double b = 1.0);

/// The knots of a periodic curve of degree p over a closed polygon of k points on [a, b]:
/// uniform_knots(p, k + p, a, b). \throws InvalidInput if k < 2 or as uniform_knots.
KnotVector periodic_knots(int degree, int polygon_points, double a = 0.0, double b = 1.0);

}  // namespace patchwork
