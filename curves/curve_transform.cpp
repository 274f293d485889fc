#include "curves/curve_transform.h"

#include <cstddef>
#include <string>
#include <utility>

#include "core/errors.h"

namespace patchwork {

namespace {

// "control point 7", or "control point (3, 1)" in a net of rows of row_length points.
std::string point_name(std::size_t k, int row_length) {
  if (row_length <= 0) return detail::message("control point ", k);
  const std::size_t row = static_cast<std::size_t>(row_length);
  return detail::message("control point (", k % row, ", ", k / row, ")");
}

}  // namespace

namespace detail {

template <int Dim>
std::vector<Point<Dim>> affine_points(const char* function, const std::vector<Point<Dim>>& points,
                                      const AffineMap<Dim>& map, int row_length) {
  check_finite_map(function, map.matrix());
  const Eigen::Matrix<double, Dim, Dim> A = map.linear();
  const Point<Dim> b = map.translation();
  std::vector<Point<Dim>> result(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    result[i] = A * points[i] + b;
    if (!result[i].allFinite())
      throw InvalidInput(message(function, ": ", point_name(i, row_length), " maps to a point that is not finite"));
  }
  return result;
}

template <int Dim>
std::vector<Point<Dim + 1>> projective_points(const char* function, const std::vector<Point<Dim + 1>>& points,
                                              const ProjectiveMap<Dim>& map, int row_length) {
  check_finite_map(function, map);
  std::vector<Point<Dim + 1>> result(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    result[i] = map * points[i];
    if (!result[i].allFinite())
      throw InvalidInput(message(function, ": ", point_name(i, row_length), " maps to a point that is not finite"));
  }
  // The sign of control point 0's new weight decides; every other must have it.
  const double first = result.front()[Dim];
  for (std::size_t i = 0; i < result.size(); ++i) {
    const double w = result[i][Dim];
    if (w == 0.0 || (w > 0.0) != (first > 0.0)) {
      throw InvalidInput(message(
          function, ": ", point_name(i, row_length), " maps to weight ", w, " (", point_name(0, row_length), " to ",
          first, "): the image may cross the plane at infinity, and has no form with positive weights"));
    }
  }
  if (first < 0.0) {
    for (Point<Dim + 1>& h : result) h = -h;
  }
  return result;
}

template <int Dim>
std::vector<Point<Dim + 1>> unit_weight_points(const std::vector<Point<Dim>>& points) {
  std::vector<Point<Dim + 1>> result(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) result[i] << points[i], 1.0;
  return result;
}

}  // namespace detail

namespace {

// Projective maps must be invertible (a singular one collapses the curve's space).
template <int Dim>
void check_invertible(const char* function, const ProjectiveMap<Dim>& map) {
  detail::check_finite_map(function, map);
  if (map.determinant() == 0.0) throw InvalidInput(detail::message(function, ": the matrix is singular"));
}

}  // namespace

template <int Dim>
ProjectiveMap<Dim> projective_matrix(const AffineMap<Dim>& map) {
  ProjectiveMap<Dim> M = ProjectiveMap<Dim>::Zero();
  M.template topLeftCorner<Dim, Dim>() = map.linear();
  M.template topRightCorner<Dim, 1>() = map.translation();
  M(Dim, Dim) = 1.0;
  return M;
}

template <int Dim>
BezierCurve<Dim> transform(const BezierCurve<Dim>& curve, const AffineMap<Dim>& map) {
  return BezierCurve<Dim>(detail::affine_points("transform", curve.control_points(), map), curve.a(), curve.b());
}

template <int Dim>
RationalBezierCurve<Dim> transform(const RationalBezierCurve<Dim>& curve, const AffineMap<Dim>& map) {
  detail::check_finite_map("transform", map.matrix());
  const BezierCurve<Dim + 1>& H = curve.homogeneous();
  // The last row of [A b; 0 1] is (0, ..., 0, 1): the weights come out exactly as they were.
  return RationalBezierCurve<Dim>(BezierCurve<Dim + 1>(
      detail::projective_points<Dim>("transform", H.control_points(), projective_matrix(map)), H.a(), H.b()));
}

template <int Dim>
BSplineCurve<Dim> transform(const BSplineCurve<Dim>& curve, const AffineMap<Dim>& map) {
  return BSplineCurve<Dim>(curve.knot_vector(), detail::affine_points("transform", curve.control_points(), map));
}

template <int Dim>
NurbsCurve<Dim> transform(const NurbsCurve<Dim>& curve, const AffineMap<Dim>& map) {
  detail::check_finite_map("transform", map.matrix());
  const BSplineCurve<Dim + 1>& H = curve.homogeneous();
  return NurbsCurve<Dim>(BSplineCurve<Dim + 1>(
      H.knot_vector(), detail::projective_points<Dim>("transform", H.control_points(), projective_matrix(map))));
}

template <int Dim>
RationalBezierCurve<Dim> projective_transform(const RationalBezierCurve<Dim>& curve, const ProjectiveMap<Dim>& map) {
  check_invertible<Dim>("projective_transform", map);
  const BezierCurve<Dim + 1>& H = curve.homogeneous();
  return RationalBezierCurve<Dim>(BezierCurve<Dim + 1>(
      detail::projective_points<Dim>("projective_transform", H.control_points(), map), H.a(), H.b()));
}

template <int Dim>
RationalBezierCurve<Dim> projective_transform(const BezierCurve<Dim>& curve, const ProjectiveMap<Dim>& map) {
  check_invertible<Dim>("projective_transform", map);
  const std::vector<Point<Dim + 1>> H = detail::unit_weight_points(curve.control_points());
  return RationalBezierCurve<Dim>(
      BezierCurve<Dim + 1>(detail::projective_points<Dim>("projective_transform", H, map), curve.a(), curve.b()));
}

template <int Dim>
NurbsCurve<Dim> projective_transform(const NurbsCurve<Dim>& curve, const ProjectiveMap<Dim>& map) {
  check_invertible<Dim>("projective_transform", map);
  const BSplineCurve<Dim + 1>& H = curve.homogeneous();
  return NurbsCurve<Dim>(BSplineCurve<Dim + 1>(
      H.knot_vector(), detail::projective_points<Dim>("projective_transform", H.control_points(), map)));
}

template <int Dim>
NurbsCurve<Dim> projective_transform(const BSplineCurve<Dim>& curve, const ProjectiveMap<Dim>& map) {
  check_invertible<Dim>("projective_transform", map);
  const std::vector<Point<Dim + 1>> H = detail::unit_weight_points(curve.control_points());
  return NurbsCurve<Dim>(
      BSplineCurve<Dim + 1>(curve.knot_vector(), detail::projective_points<Dim>("projective_transform", H, map)));
}

#define PATCHWORK_CURVE_TRANSFORM(Dim)                                                                                 \
  template std::vector<Point<Dim>> detail::affine_points(const char*, const std::vector<Point<Dim>>&,                  \
                                                         const AffineMap<Dim>&, int);                                  \
  template std::vector<Point<Dim + 1>> detail::projective_points<Dim>(const char*, const std::vector<Point<Dim + 1>>&, \
                                                                      const ProjectiveMap<Dim>&, int);                 \
  template std::vector<Point<Dim + 1>> detail::unit_weight_points(const std::vector<Point<Dim>>&);                     \
  template ProjectiveMap<Dim> projective_matrix(const AffineMap<Dim>&);                                                \
  template BezierCurve<Dim> transform(const BezierCurve<Dim>&, const AffineMap<Dim>&);                                 \
  template RationalBezierCurve<Dim> transform(const RationalBezierCurve<Dim>&, const AffineMap<Dim>&);                 \
  template BSplineCurve<Dim> transform(const BSplineCurve<Dim>&, const AffineMap<Dim>&);                               \
  template NurbsCurve<Dim> transform(const NurbsCurve<Dim>&, const AffineMap<Dim>&);                                   \
  template RationalBezierCurve<Dim> projective_transform(const RationalBezierCurve<Dim>&, const ProjectiveMap<Dim>&);  \
  template RationalBezierCurve<Dim> projective_transform(const BezierCurve<Dim>&, const ProjectiveMap<Dim>&);          \
  template NurbsCurve<Dim> projective_transform(const NurbsCurve<Dim>&, const ProjectiveMap<Dim>&);                    \
  template NurbsCurve<Dim> projective_transform(const BSplineCurve<Dim>&, const ProjectiveMap<Dim>&);

PATCHWORK_CURVE_TRANSFORM(2)
PATCHWORK_CURVE_TRANSFORM(3)

#undef PATCHWORK_CURVE_TRANSFORM

}  // namespace patchwork
