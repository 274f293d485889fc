#include "queries/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "curves/bernstein.h"
#include "queries/intersection_kernel.h"
#include "queries/query_arguments.h"

namespace patchwork {
namespace {

constexpr int max_depth = 40;

// Whether the piece's hodograph numerator lies in an open half-space cone (file comment).
template <int Dim>
bool monotone(const std::vector<Point<Dim + 1>>& H) {
  const int n = static_cast<int>(H.size()) - 1;
  if (n == 0) return true;
  std::vector<double> w(H.size()), dw(static_cast<std::size_t>(n)), coordinate(H.size()), d_coordinate(static_cast<std::size_t>(n));
  for (int i = 0; i <= n; ++i) w[i] = H[i][Dim];
  for (int i = 0; i < n; ++i) dw[i] = n * (H[i + 1][Dim] - H[i][Dim]);
  std::vector<Point<Dim>> N;
  for (int c = 0; c < Dim; ++c) {
    for (int i = 0; i <= n; ++i) coordinate[i] = H[i][c];
    for (int i = 0; i < n; ++i) d_coordinate[i] = n * (H[i + 1][c] - H[i][c]);
    const auto first = bernstein_product(d_coordinate, w);
    const auto second = bernstein_product(coordinate, dw);
    N.resize(first.size());
    for (std::size_t k = 0; k < first.size(); ++k) N[k][c] = first[k] - second[k];
  }
  Point<Dim> v = Point<Dim>::Zero();
  for (const auto& direction : N) {
    if (direction.norm() > 0.0) v += direction.normalized();
  }
  if (std::all_of(N.begin(), N.end(), [](const Point<Dim>& direction) { return direction.norm() == 0.0; })) return true;  // a point
  if (!(v.norm() > 0.0)) return false;
  v.normalize();
  for (const auto& direction : N) {
    if (direction.norm() > 0.0 && !(v.dot(direction) >= 1e-3 * direction.norm())) return false;
  }
  return true;
}

template <int Dim>
void monotone_pieces(const RationalBezierCurve<Dim>& curve, double t0, double t1, int depth,
                     std::vector<RationalBezierCurve<Dim>>& pieces) {
  const auto H = detail::reparametrized(curve.homogeneous().control_points(), curve.a(), curve.b(), t0, t1);
  const double middle = 0.5 * (t0 + t1);
  if (depth >= max_depth || monotone<Dim>(H) || !(t0 < middle && middle < t1)) {
    pieces.emplace_back(BezierCurve<Dim + 1>(H, t0, t1));
    return;
  }
  monotone_pieces(curve, t0, middle, depth + 1, pieces);
  monotone_pieces(curve, middle, t1, depth + 1, pieces);
}

}  // namespace

namespace detail {

template <int Dim>
CurveIntersections<Dim> self_intersections_of_pieces(const std::vector<RationalBezierCurve<Dim>>& curve_pieces, double tolerance) {
  std::vector<RationalBezierCurve<Dim>> pieces;
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& curve : curve_pieces) {
    monotone_pieces(curve, curve.a(), curve.b(), 0, pieces);
    shortest = std::min(shortest, std::ldexp(curve.b() - curve.a(), -max_depth));
  }
  CurveIntersections<Dim> result;
  // A closed curve's start and end meet where it closes, which is no crossing.
  const RationalBezierCurve<Dim>& first = curve_pieces.front();
  const RationalBezierCurve<Dim>& last = curve_pieces.back();
  const double a = first.a(), b = last.b();
  double scale = 0.0;
  for (const auto& curve : curve_pieces) {
    for (int i = 0; i <= curve.degree(); ++i) scale = std::max(scale, curve.control_point(i).cwiseAbs().maxCoeff());
  }
  const bool closed = (first.evaluate(a) - last.evaluate(b)).norm() <= tolerance + detail::rounding_level(scale, 1);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      CurveIntersections<Dim> pair = detail::intersect_rational(pieces[i], pieces[j], tolerance);
      result.eps = std::max(result.eps, pair.eps);
      for (const CurveIntersection<Dim>& x : pair.points) {
        if (x.s - x.t <= x.t_bound + x.s_bound + 4.0 * shortest) continue;  // the pieces' shared end
        if (closed && x.t - a <= x.t_bound + 4.0 * shortest && b - x.s <= x.s_bound + 4.0 * shortest) continue;
        detail::add_or_merge(result.points, x, shortest, shortest);
      }
      result.overlaps.insert(result.overlaps.end(), pair.overlaps.begin(), pair.overlaps.end());
    }
  }
  std::sort(result.points.begin(), result.points.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  // Overlaps of neighbouring pieces that continue one another.
  std::sort(result.overlaps.begin(), result.overlaps.end(), [](const CurveOverlap& x, const CurveOverlap& y) { return x.t0 < y.t0; });
  std::vector<CurveOverlap> merged;
  for (const CurveOverlap& o : result.overlaps) {
    if (!merged.empty() && o.t0 <= merged.back().t1 + shortest && std::abs(o.s0 - merged.back().s1) <= shortest) {
      merged.back().t1 = o.t1, merged.back().s1 = o.s1;
    } else {
      merged.push_back(o);
    }
  }
  result.overlaps = std::move(merged);
  return result;
}

template CurveIntersections<2> self_intersections_of_pieces(const std::vector<RationalBezierCurve<2>>&, double);
template CurveIntersections<3> self_intersections_of_pieces(const std::vector<RationalBezierCurve<3>>&, double);

}  // namespace detail

namespace {

template <int Dim>
CurveIntersections<Dim> self_intersections_of(const RationalBezierCurve<Dim>& curve, double tolerance) {
  return detail::self_intersections_of_pieces(std::vector<RationalBezierCurve<Dim>>{curve}, tolerance);
}

}  // namespace

CurveIntersections<2> self_intersections(const BezierCurve2& curve) { return self_intersections_of(as_rational(curve), 0.0); }

CurveIntersections<2> self_intersections(const RationalBezierCurve2& curve) { return self_intersections_of(curve, 0.0); }

CurveIntersections<3> self_intersections(const BezierCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return self_intersections_of(as_rational(curve), tolerance);
}

CurveIntersections<3> self_intersections(const RationalBezierCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return self_intersections_of(curve, tolerance);
}

}  // namespace patchwork
