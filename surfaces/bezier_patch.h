#pragma once
// Tensor-product Bezier patches (seed Def 60) of any degrees (n, m).
//
//   F(u, v) = sum_{i=0}^{n} sum_{j=0}^{m} B_i^n(u) B_j^m(v) P_ij,   (u, v) in [0,1]^2
//
// Control points are stored with the first index fastest, P_ij at i + (n+1) j, as in the BPT
// format (data/README.md), so u runs along a stored row and v across rows:
//
//        v ^   P_0m ---- P_1m ---- ... ---- P_nm        edge v = 1 (row j = m)
//          |    |                            |
//          |   ...                          ...
//          |    |                            |
//          |   P_00 ---- P_10 ---- ... ---- P_n0        edge v = 0 (row j = 0)
//          +---------------------------------------> u
//         edge u = 0 (column i = 0)       edge u = 1 (column i = n)
//
// The normal is F_u x F_v (Def 32); on the teapot it points out of the pot. Dim is 3 for
// ordinary patches and 4 for the homogeneous points (w P, w) of rational patches.

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "core/types.h"
#include "curves/bernstein.h"
#include "curves/bezier_curve.h"

namespace patchwork {

/// The four boundary edges of a patch, in counter-clockwise order around the (u, v) square.
enum class PatchEdge { v0 = 0, u1 = 1, v1 = 2, u0 = 3 };

template <int Dim>
class BezierPatch {
 public:
  using Point = patchwork::Point<Dim>;

  /// Patch of degrees (n, m) with (n+1)(m+1) control points, P_ij at index i + (n+1) j.
  /// \throws InvalidInput if a degree is negative, the count does not match, or a coordinate is
  ///         not finite.
  BezierPatch(int n, int m, std::vector<Point> control_points);

  /// Degree n in u.
  int degree_u() const noexcept { return n_; }
  /// Degree m in v.
  int degree_v() const noexcept { return m_; }
  /// All control points, P_ij at i + (n+1) j.
  const std::vector<Point>& control_points() const noexcept { return points_; }
  /// P_ij. \pre 0 <= i <= n, 0 <= j <= m.
  const Point& control_point(int i, int j) const noexcept {
    return points_[static_cast<std::size_t>(i + (n_ + 1) * j)];
  }

  /// F(u, v) by tensor de Casteljau (rows in u, then the results in v).
  /// \throws InvalidInput if u or v is not finite.
  Point evaluate(double u, double v) const;
  Point operator()(double u, double v) const { return evaluate(u, v); }

  friend bool operator==(const BezierPatch&, const BezierPatch&) = default;

 private:
  int n_;
  int m_;
  std::vector<Point> points_;
};

using BezierPatch3 = BezierPatch<3>;
using BezierPatch4 = BezierPatch<4>;

/// The mixed partial derivative d^(ku+kv) F / du^ku dv^kv at (u, v) (zero beyond the degrees).
/// \throws InvalidInput if ku or kv is negative or u, v are not finite.
template <int Dim>
Point<Dim> derivative(const BezierPatch<Dim>& patch, double u, double v, int ku, int kv);

/// All partial derivatives d^(a+b)F/du^a dv^b with a + b <= order at one point.
template <int Dim>
class PartialDerivatives {
 public:
  explicit PartialDerivatives(int order) : order_(order), values_(static_cast<std::size_t>((order + 1) * (order + 1))) {}
  /// The highest total order held.
  int order() const noexcept { return order_; }
  /// d^(a+b)F/du^a dv^b. \pre a + b <= order().
  Point<Dim>& at(int a, int b) noexcept { return values_[static_cast<std::size_t>(a + (order_ + 1) * b)]; }
  const Point<Dim>& at(int a, int b) const noexcept { return values_[static_cast<std::size_t>(a + (order_ + 1) * b)]; }

 private:
  int order_;
  std::vector<Point<Dim>> values_;
};

/// All partial derivatives with a + b <= order at (u, v). \throws InvalidInput if order < 0.
template <int Dim>
PartialDerivatives<Dim> partial_derivatives(const BezierPatch<Dim>& patch, double u, double v, int order);

/// The patch split at u into the pieces over [0,u] x [0,1] and [u,1] x [0,1], each
/// reparametrised to [0,1]^2. \throws InvalidInput unless 0 < u < 1.
template <int Dim>
std::pair<BezierPatch<Dim>, BezierPatch<Dim>> split_u(const BezierPatch<Dim>& patch, double u);

/// The patch split at v (see split_u). \throws InvalidInput unless 0 < v < 1.
template <int Dim>
std::pair<BezierPatch<Dim>, BezierPatch<Dim>> split_v(const BezierPatch<Dim>& patch, double v);

/// The piece over [u0,u1] x [v0,v1], reparametrised to [0,1]^2.
/// \throws InvalidInput unless 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1.
template <int Dim>
BezierPatch<Dim> subpatch(const BezierPatch<Dim>& patch, double u0, double u1, double v0, double v1);

/// The same surface with degrees (n + times_u, m + times_v). \throws InvalidInput if negative.
template <int Dim>
BezierPatch<Dim> elevate_degree(const BezierPatch<Dim>& patch, int times_u, int times_v);

/// The curve v -> F(u, v) for fixed u (degree m, on [0,1]).
template <int Dim>
BezierCurve<Dim> iso_curve_u(const BezierPatch<Dim>& patch, double u);

/// The curve u -> F(u, v) for fixed v (degree n, on [0,1]).
template <int Dim>
BezierCurve<Dim> iso_curve_v(const BezierPatch<Dim>& patch, double v);

/// The boundary curve of an edge, in the direction of increasing u (edges v0, v1) or v (edges
/// u0, u1): its control points are the edge's row or column of the net.
template <int Dim>
BezierCurve<Dim> boundary_curve(const BezierPatch<Dim>& patch, PatchEdge edge);

/// The control points of the k-th row (k = 0 at the edge) counted from `edge` into the patch,
/// in the direction of boundary_curve(edge): the rows that decide cross-boundary derivatives.
/// \pre 0 <= k <= the degree across the edge.
template <int Dim>
std::vector<Point<Dim>> row_from_edge(const BezierPatch<Dim>& patch, PatchEdge edge, int k);

}  // namespace patchwork
