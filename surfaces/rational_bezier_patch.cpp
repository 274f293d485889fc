#include "surfaces/rational_bezier_patch.h"

#include <cmath>

#include "core/errors.h"

namespace patchwork {
namespace {

BezierPatch4 homogenize(int n, int m, const std::vector<Vec3>& points, const std::vector<double>& weights) {
  if (points.size() != weights.size()) {
    throw InvalidInput(detail::message("RationalBezierPatch: ", points.size(), " control points but ", weights.size(), " weights"));
  }
  std::vector<Vec4> homogeneous(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!std::isfinite(weights[k]) || !(weights[k] > 0.0)) {
      throw InvalidInput(detail::message("RationalBezierPatch: weight ", k, " = ", weights[k], " is not positive and finite"));
    }
    homogeneous[k] << weights[k] * points[k], weights[k];
  }
  return BezierPatch4(n, m, std::move(homogeneous));
}

const BezierPatch4& checked(const BezierPatch4& homogeneous) {
  const auto& H = homogeneous.control_points();
  for (std::size_t k = 0; k < H.size(); ++k) {
    if (!(H[k][3] > 0.0)) throw InvalidInput(detail::message("RationalBezierPatch: weight ", k, " = ", H[k][3], " is not positive"));
  }
  return homogeneous;
}

}  // namespace

RationalBezierPatch::RationalBezierPatch(int n, int m, const std::vector<Vec3>& control_points,
                                         const std::vector<double>& weights)
    : homogeneous_(homogenize(n, m, control_points, weights)) {}

RationalBezierPatch::RationalBezierPatch(BezierPatch4 homogeneous) : homogeneous_(checked(homogeneous)) {}

Vec3 RationalBezierPatch::control_point(int i, int j) const {
  const Vec4& h = homogeneous_.control_point(i, j);
  return h.head<3>() / h[3];
}

BezierPatch3 RationalBezierPatch::control_net() const {
  std::vector<Vec3> points;
  points.reserve(homogeneous_.control_points().size());
  for (const Vec4& h : homogeneous_.control_points()) points.push_back(h.head<3>() / h[3]);
  return BezierPatch3(degree_u(), degree_v(), std::move(points));
}

std::vector<double> RationalBezierPatch::weights() const {
  std::vector<double> result;
  result.reserve(homogeneous_.control_points().size());
  for (const Vec4& h : homogeneous_.control_points()) result.push_back(h[3]);
  return result;
}

RationalBezierPatch as_rational(const BezierPatch3& patch) {
  return RationalBezierPatch(patch.degree_u(), patch.degree_v(), patch.control_points(),
                             std::vector<double>(patch.control_points().size(), 1.0));
}

Vec3 RationalBezierPatch::evaluate(double u, double v) const {
  const Vec4 h = homogeneous_.evaluate(u, v);
  return h.head<3>() / h[3];
}

PartialDerivatives<3> partial_derivatives(const RationalBezierPatch& patch, double u, double v, int order) {
  return detail::projected_partial_derivatives(partial_derivatives(patch.homogeneous(), u, v, order));
}

namespace detail {

PartialDerivatives<3> projected_partial_derivatives(const PartialDerivatives<4>& H) {
  const int order = H.order();
  PartialDerivatives<3> F(order);
  const double w = H.at(0, 0)[3];
  // Increasing total order: every F term on the right is already known.
  for (int total = 0; total <= order; ++total) {
    for (int a = 0; a <= total; ++a) {
      const int b = total - a;
      Vec3 numerator = H.at(a, b).head<3>();
      for (int k = 0; k <= a; ++k) {
        for (int l = 0; l <= b; ++l) {
          if (k == 0 && l == 0) continue;
          numerator -= binomial(a, k) * binomial(b, l) * H.at(k, l)[3] * F.at(a - k, b - l);
        }
      }
      F.at(a, b) = numerator / w;
    }
  }
  return F;
}

}  // namespace detail

std::pair<RationalBezierPatch, RationalBezierPatch> split_u(const RationalBezierPatch& patch, double u) {
  auto [a, b] = split_u(patch.homogeneous(), u);
  return {RationalBezierPatch(std::move(a)), RationalBezierPatch(std::move(b))};
}

std::pair<RationalBezierPatch, RationalBezierPatch> split_v(const RationalBezierPatch& patch, double v) {
  auto [a, b] = split_v(patch.homogeneous(), v);
  return {RationalBezierPatch(std::move(a)), RationalBezierPatch(std::move(b))};
}

RationalBezierPatch subpatch(const RationalBezierPatch& patch, double u0, double u1, double v0, double v1) {
  return RationalBezierPatch(subpatch(patch.homogeneous(), u0, u1, v0, v1));
}

RationalBezierPatch elevate_degree(const RationalBezierPatch& patch, int times_u, int times_v) {
  return RationalBezierPatch(elevate_degree(patch.homogeneous(), times_u, times_v));
}

RationalBezierCurve3 iso_curve_u(const RationalBezierPatch& patch, double u) {
  return RationalBezierCurve3(iso_curve_u(patch.homogeneous(), u));
}

RationalBezierCurve3 iso_curve_v(const RationalBezierPatch& patch, double v) {
  return RationalBezierCurve3(iso_curve_v(patch.homogeneous(), v));
}

RationalBezierCurve3 boundary_curve(const RationalBezierPatch& patch, PatchEdge edge) {
  return RationalBezierCurve3(boundary_curve(patch.homogeneous(), edge));
}

RationalBezierPatch sphere_octant(const Vec3& center, double radius) {
  if (!center.allFinite() || !std::isfinite(radius) || !(radius > 0.0)) {
    throw InvalidInput(detail::message("sphere_octant: radius ", radius, " is not positive, or the centre is not finite"));
  }
  const double s = std::sqrt(0.5);
  // Profile (r_j, z_j) from the equator to the pole, and the revolution's unit-circle arc (c_i, s_i).
  const double profile_r[3] = {1.0, 1.0, 0.0};
  const double profile_z[3] = {0.0, 1.0, 1.0};
  const double arc_x[3] = {1.0, 1.0, 0.0};
  const double arc_y[3] = {0.0, 1.0, 1.0};
  const double w[3] = {1.0, s, 1.0};
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) {
      points.push_back(center + radius * Vec3(profile_r[j] * arc_x[i], profile_r[j] * arc_y[i], profile_z[j]));
      weights.push_back(w[i] * w[j]);
    }
  }
  return RationalBezierPatch(2, 2, points, weights);
}

}  // namespace patchwork
