#include "queries/spline_intersection.h"

#include <algorithm>
#include <cmath>

#include "curves/bspline_conversion.h"
#include "queries/curve_overlap.h"
#include "queries/query_arguments.h"
#include "queries/self_intersection.h"

namespace patchwork {
namespace {

template <int Dim>
std::vector<RationalBezierCurve<Dim>> rational_pieces(const BSplineCurve<Dim>& curve) {
  std::vector<RationalBezierCurve<Dim>> result;
  for (const BezierCurve<Dim>& piece : bezier_pieces(curve)) result.push_back(as_rational(piece));
  return result;
}

template <int Dim>
std::vector<RationalBezierCurve<Dim>> rational_pieces(const NurbsCurve<Dim>& curve) {
  return bezier_pieces(curve);
}

template <int Dim>
CurveIntersections<Dim> intersect_pieces(const std::vector<RationalBezierCurve<Dim>>& first,
                                         const std::vector<RationalBezierCurve<Dim>>& second, double tolerance) {
  const double t_slack = 1e-13 * (first.back().b() - first.front().a());
  const double s_slack = 1e-13 * (second.back().b() - second.front().a());
  CurveIntersections<Dim> result;
  std::vector<CurveOverlap> overlaps;
  for (const auto& a : first) {
    for (const auto& b : second) {
      CurveIntersections<Dim> pair = detail::intersect_rational(a, b, tolerance);
      result.eps = std::max(result.eps, pair.eps);
      for (const CurveIntersection<Dim>& x : pair.points) {
        detail::add_or_merge(result.points, x, t_slack, s_slack);
      }
      overlaps.insert(overlaps.end(), pair.overlaps.begin(), pair.overlaps.end());
    }
  }
  result.overlaps = detail::merge_touching(std::move(overlaps), t_slack, s_slack);
  std::erase_if(result.points, [&](const CurveIntersection<Dim>& x) {
    return std::any_of(result.overlaps.begin(), result.overlaps.end(), [&](const CurveOverlap& o) {
      return o.t0 - x.t_bound - t_slack <= x.t && x.t <= o.t1 + x.t_bound + t_slack &&
             std::min(o.s0, o.s1) - x.s_bound - s_slack <= x.s && x.s <= std::max(o.s0, o.s1) + x.s_bound + s_slack;
    });
  });
  std::sort(result.points.begin(), result.points.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  return result;
}

}  // namespace

CurveIntersections<2> intersect_curves(const BSplineCurve2& first, const BSplineCurve2& second) {
  return intersect_pieces(rational_pieces(first), rational_pieces(second), 0.0);
}

CurveIntersections<2> intersect_curves(const NurbsCurve2& first, const NurbsCurve2& second) {
  return intersect_pieces(rational_pieces(first), rational_pieces(second), 0.0);
}

CurveIntersections<3> intersect_curves(const BSplineCurve3& first, const BSplineCurve3& second, double tolerance) {
  require_positive(tolerance, "intersect_curves", "tolerance");
  return intersect_pieces(rational_pieces(first), rational_pieces(second), tolerance);
}

CurveIntersections<3> intersect_curves(const NurbsCurve3& first, const NurbsCurve3& second, double tolerance) {
  require_positive(tolerance, "intersect_curves", "tolerance");
  return intersect_pieces(rational_pieces(first), rational_pieces(second), tolerance);
}

CurveIntersections<2> self_intersections(const BSplineCurve2& curve) {
  return detail::self_intersections_of_pieces(rational_pieces(curve), 0.0);
}

CurveIntersections<2> self_intersections(const NurbsCurve2& curve) {
  return detail::self_intersections_of_pieces(rational_pieces(curve), 0.0);
}

CurveIntersections<3> self_intersections(const BSplineCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return detail::self_intersections_of_pieces(rational_pieces(curve), tolerance);
}

CurveIntersections<3> self_intersections(const NurbsCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return detail::self_intersections_of_pieces(rational_pieces(curve), tolerance);
}

CurveSurfaceHits intersect_curve_surface(const BSplineCurve3& curve, const PatchSet& set) {
  return detail::intersect_pieces_with_set(rational_pieces(curve), set);
}

CurveSurfaceHits intersect_curve_surface(const NurbsCurve3& curve, const PatchSet& set) {
  return detail::intersect_pieces_with_set(rational_pieces(curve), set);
}

}  // namespace patchwork
