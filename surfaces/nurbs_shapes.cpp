#include "surfaces/nurbs_shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {
namespace {

void check_direction(const Vec3& d, const char* what) {
  if (!d.allFinite() || !(d.norm() > 0.0)) throw InvalidInput(detail::message(what, " is zero or not finite"));
}

void check_positive(double x, const char* what) {
  if (!std::isfinite(x) || !(x > 0.0)) throw InvalidInput(detail::message(what, " ", x, " is not positive and finite"));
}

}  // namespace

NurbsCurve<3> nurbs_circle_arc(const Vec3& center, const Vec3& x_axis, const Vec3& y_axis, double radius, double start,
                               double end) {
  return join_rational_pieces(circle_arc<3>(center, x_axis, y_axis, radius, start, end));
}

NurbsSurface revolve(const NurbsCurve<3>& profile, const Vec3& axis_point, const Vec3& axis, double angle) {
  check_direction(axis, "revolve: the axis");
  if (!axis_point.allFinite()) throw InvalidInput("revolve: the axis point is not finite");
  if (!(angle > 0.0 && angle <= 2 * std::numbers::pi)) {
    throw InvalidInput(detail::message("revolve: angle ", angle, " is not in (0, 2 pi]"));
  }
  const Vec3 A = axis.normalized();
  // The unit arc in the plane (1, 0), (0, 1): its points give each row's arc.
  const NurbsCurve<2> arc = join_rational_pieces(circle_arc(Vec2(0, 0), 1.0, 0.0, angle));
  const int count_u = arc.control_point_count();
  const int count_v = profile.control_point_count();
  std::vector<Vec3> points(static_cast<std::size_t>(count_u) * static_cast<std::size_t>(count_v));
  std::vector<double> weights(points.size());
  // A profile point within rounding of the axis (a circle's cos(pi/2) = 6e-17) is on it: its row
  // collapses to one point, a pole.
  double reach = 0.0;
  for (int j = 0; j < count_v; ++j) reach = std::max(reach, (profile.control_point(j) - axis_point).norm());
  for (int j = 0; j < count_v; ++j) {
    const Vec3 P = profile.control_point(j);
    const Vec3 O = axis_point + (P - axis_point).dot(A) * A;
    const double distance = (P - O).norm();
    const double r = distance <= 1e-14 * reach ? 0.0 : distance;
    // On the axis any X serves: every point of the row is O.
    const Vec3 X = r > 0.0 ? Vec3((P - O) / r) : A.unitOrthogonal();
    const Vec3 Y = A.cross(X);
    for (int i = 0; i < count_u; ++i) {
      const Vec2 q = arc.control_point(i);
      const auto k = static_cast<std::size_t>(i + count_u * j);
      points[k] = r > 0.0 ? Vec3(O + r * (q.x() * X + q.y() * Y)) : O;
      weights[k] = arc.weight(i) * profile.weight(j);
    }
  }
  return NurbsSurface(arc.knot_vector(), profile.knot_vector(), points, weights);
}

NurbsSurface extrude(const NurbsCurve<3>& profile, const Vec3& direction) {
  check_direction(direction, "extrude: the direction");
  const int count_u = profile.control_point_count();
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i < count_u; ++i) {
      points.push_back(profile.control_point(i) + j * direction);
      weights.push_back(profile.weight(i));
    }
  }
  return NurbsSurface(profile.knot_vector(), KnotVector(1, {0, 0, 1, 1}), points, weights);
}

NurbsSurface nurbs_sphere(const Vec3& center, double radius) {
  check_positive(radius, "nurbs_sphere: radius");
  const double half = std::numbers::pi / 2;
  return revolve(nurbs_circle_arc(center, Vec3::UnitX(), Vec3::UnitZ(), radius, -half, half), center, Vec3::UnitZ(),
                 2 * std::numbers::pi);
}

NurbsSurface nurbs_torus(const Vec3& center, double major, double minor) {
  check_positive(minor, "nurbs_torus: minor radius");
  if (!(major > minor) || !std::isfinite(major)) {
    throw InvalidInput(
        detail::message("nurbs_torus: major radius ", major, " is not finite and above the minor ", minor));
  }
  const NurbsCurve<3> circle =
      nurbs_circle_arc(center + major * Vec3::UnitX(), Vec3::UnitX(), Vec3::UnitZ(), minor, 0.0, 2 * std::numbers::pi);
  return revolve(circle, center, Vec3::UnitZ(), 2 * std::numbers::pi);
}

NurbsSurface nurbs_cylinder(const Vec3& center, double radius, double height) {
  check_positive(radius, "nurbs_cylinder: radius");
  check_positive(height, "nurbs_cylinder: height");
  return extrude(nurbs_circle_arc(center, Vec3::UnitX(), Vec3::UnitY(), radius, 0.0, 2 * std::numbers::pi),
                 height * Vec3::UnitZ());
}

NurbsSurface nurbs_cone(const Vec3& center, double radius, double height) {
  check_positive(radius, "nurbs_cone: radius");
  check_positive(height, "nurbs_cone: height");
  const NurbsCurve<3> side(KnotVector(1, {0, 0, 1, 1}),
                           {center + radius * Vec3::UnitX(), center + height * Vec3::UnitZ()}, {1.0, 1.0});
  return revolve(side, center, Vec3::UnitZ(), 2 * std::numbers::pi);
}

}  // namespace patchwork
