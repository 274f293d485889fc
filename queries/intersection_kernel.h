#pragma once
// Internal (patchwork::detail): what the intersection queries share.
//
// Intervals. [lo, hi] with the arithmetic of interval analysis; every result is widened outward
// by 4 u (|lo| + |hi|) (u = 2^-53), which covers the rounding of the operation without
// switching the rounding mode.
//
// Pieces. A curve piece on [t0, t1] holds the homogeneous control points (w_i P_i, w_i) of the
// curve reparametrised to [t0, t1] by blossoming,
//
//   H_i = h(t0^(n-i), t1^i),   i = 0..n        (h the blossom of the homogeneous curve),
//
// which works for [t0, t1] inside or a little outside the curve's interval (the polynomial
// continued): the Krawczyk test below runs on boxes that reach past a piece's seam. The curve on
// the piece lies in the convex hull of the projected points P_i = H_i,xyz / w_i (the weights are
// positive), so the box of the P_i contains it, and its distance to the chord segment P_0 P_n
// is at most flatness = max_i dist(P_i, [P_0, P_n]) (the distance to a convex set is convex).
//
// Derivative enclosures. C = H / w gives C' = (H'_xyz - w' C) / w; with H' and w' enclosed by
// the boxes of the hodograph's control points n (H_{i+1} - H_i) / (t1 - t0), C by the box of the
// P_i and w by [min w_i, max w_i] > 0, interval arithmetic encloses C' over the piece. Patches
// likewise: F_u = (H_u,xyz - w_u F) / w with the hodograph net in u.
//
// Krawczyk's test (Krawczyk 1969; Moore, Kearfott, Cloud, "Introduction to Interval Analysis",
// SIAM 2009, sec. 8.2) for G(x) = 0 on a box X with midpoint m, an interval matrix J containing
// G'(X) and a point matrix Y ~ G'(m)^-1:
//
//   K(X) = m - Y G(m) + (I - Y J)(X - m).
//
// K(X) inside the interior of X: G has exactly one zero in X, and it lies in K(X).
// K(X) disjoint from X: G has no zero in X.

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/types.h"
#include "curves/rational_bezier_curve.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork::detail {

struct Interval {
  double lo;
  double hi;
  double mid() const { return 0.5 * (lo + hi); }
  double width() const { return hi - lo; }
};

Interval operator+(Interval x, Interval y);
Interval operator-(Interval x, Interval y);
Interval operator*(Interval x, Interval y);
/// x / y for y > 0 throughout. \pre y.lo > 0.
Interval divide_positive(Interval x, Interval y);
/// The point value v as an interval [v, v].
inline Interval point_interval(double v) { return {v, v}; }

/// The homogeneous control points of the curve with points P on [a, b], reparametrised to
/// [t0, t1] (any t0 != t1, also outside [a, b]) by the blossom (file comment).
template <int D>
std::vector<Point<D>> reparametrized(const std::vector<Point<D>>& P, double a, double b, double t0, double t1);

/// The homogeneous net of a patch with degrees (n, m) reparametrised to [u0,u1] x [v0,v1]
/// (reparametrized on every row, then on every column).
std::vector<Vec4> reparametrized_net(const std::vector<Vec4>& net, int n, int m, double u0, double u1, double v0,
                                     double v1);

/// One piece of a (rational) curve: see the file comment.
template <int Dim>
struct CurvePiece {
  double t0;
  double t1;
  std::vector<Point<Dim + 1>> H;
  std::vector<Point<Dim>> P;
  Eigen::AlignedBox<double, Dim> box;
  double flatness;
  /// Every weight of the piece is positive (false far outside the curve's interval).
  bool valid;
};

/// The piece of `curve` on [t0, t1].
template <int Dim>
CurvePiece<Dim> curve_piece(const RationalBezierCurve<Dim>& curve, double t0, double t1);

/// Per coordinate, an interval containing C'(t) for every t of the piece. \pre piece.valid.
template <int Dim>
std::array<Interval, Dim> derivative_enclosure(const CurvePiece<Dim>& piece);

/// C(t) and C'(t).
template <int Dim>
std::pair<Point<Dim>, Point<Dim>> point_and_derivative(const RationalBezierCurve<Dim>& curve, double t);

/// C(t), C'(t) and C''(t).
template <int Dim>
std::array<Point<Dim>, 3> point_and_derivatives(const RationalBezierCurve<Dim>& curve, double t);

/// Distance from q to the segment [p0, p1].
template <int Dim>
double segment_distance(const Point<Dim>& q, const Point<Dim>& p0, const Point<Dim>& p1);

/// The closest points of the segments [p0, p1] and [q0, q1]: parameters (alpha, beta) in [0, 1]^2.
template <int Dim>
std::pair<double, double> segment_closest(const Point<Dim>& p0, const Point<Dim>& p1, const Point<Dim>& q0,
                                          const Point<Dim>& q1);

/// The outcome of Krawczyk's test.
enum class KrawczykOutcome { no_zero, unique_zero, unknown };

/// Krawczyk's test for G on X (file comment): G(m) is known within +-g_error per coordinate,
/// J encloses G' on X (row i, column j: dG_i/dx_j). Writes K(X) into `image`.
template <int N>
KrawczykOutcome krawczyk(const std::array<Interval, N>& X, const Eigen::Matrix<double, N, 1>& m,
                         const Eigen::Matrix<double, N, 1>& g, double g_error,
                         const std::array<std::array<Interval, N>, N>& J, const Eigen::Matrix<double, N, N>& Y,
                         std::array<Interval, N>& image);

/// The groups of boxes that touch (closed boxes meeting, with `margin` added on every side),
/// connected through chains of touching boxes: each group as indices into `boxes`.
template <int N>
std::vector<std::vector<std::size_t>> touching_groups(const std::vector<std::array<Interval, N>>& boxes, double margin);

/// Golden-section search for a minimum of value(t) on [lo, hi]: 80 steps, then both ends;
/// `value` keeps the best it has seen (and whatever it carries from one call to the next).
template <class Value>
void golden_section(double lo, double hi, Value&& value) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  const double a = lo, b = hi;
  for (int iteration = 0; iteration < 80 && hi > lo; ++iteration) {
    const double t1 = hi - ratio * (hi - lo), t2 = lo + ratio * (hi - lo);
    if (value(t1) <= value(t2)) {
      hi = t2;
    } else {
      lo = t1;
    }
  }
  value(a);
  value(b);
}

/// The rounding level of coordinates up to `scale` in magnitude after work of degree n:
/// 64 (n + 1) u scale, u = 2^-53.
double rounding_level(double scale, int n);

}  // namespace patchwork::detail
