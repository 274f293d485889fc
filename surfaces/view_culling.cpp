#include "surfaces/view_culling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.h"
#include "surfaces/bernstein_product.h"
#include "curves/bernstein.h"

namespace patchwork {
namespace {

struct CameraFrame {
  Vec3 eye;
  Vec3 forward;
  Vec3 right;
  Vec3 up;
  double tan_half_v;
  double tan_half_h;
};

CameraFrame frame(const Camera& camera) {
  validate(camera);
  CameraFrame f;
  f.eye = camera.eye;
  f.forward = (camera.target - camera.eye).normalized();
  f.right = f.forward.cross(camera.up).normalized();
  f.up = f.right.cross(f.forward);
  f.tan_half_v = std::tan(camera.fov_degrees * std::numbers::pi / 360.0);
  f.tan_half_h = f.tan_half_v * camera.width / camera.height;
  return f;
}

using detail::ScalarPatch;

}  // namespace

void validate(const Camera& camera) {
  if (!camera.eye.allFinite() || !camera.target.allFinite() || !camera.up.allFinite()) {
    throw InvalidInput("Camera: eye, target and up must be finite");
  }
  const Vec3 view = camera.target - camera.eye;
  if (view.norm() == 0.0) throw InvalidInput("Camera: eye and target coincide");
  if (view.normalized().cross(camera.up).norm() < 1e-9 * camera.up.norm() || camera.up.norm() == 0.0) {
    throw InvalidInput("Camera: up is parallel to the view direction");
  }
  if (!(camera.fov_degrees > 0.0 && camera.fov_degrees < 180.0)) {
    throw InvalidInput(detail::message("Camera: field of view ", camera.fov_degrees, " degrees is not in (0, 180)"));
  }
  if (camera.width < 1 || camera.height < 1) {
    throw InvalidInput(detail::message("Camera: image size ", camera.width, " x ", camera.height, " is empty"));
  }
}

double focal_length_pixels(const Camera& camera) {
  return 0.5 * camera.height / frame(camera).tan_half_v;
}

double nearest_depth(const BezierPatch3& patch, const Camera& camera) {
  const CameraFrame f = frame(camera);
  double depth = std::numeric_limits<double>::infinity();
  for (const Vec3& p : patch.control_points()) depth = std::min(depth, (p - f.eye).dot(f.forward));
  return depth;
}

bool outside_frustum(const BezierPatch3& patch, const Camera& camera) {
  const CameraFrame f = frame(camera);
  // Per plane, whether every control point is outside it: behind the eye, left, right, below, above.
  bool behind = true, left = true, right = true, below = true, above = true;
  for (const Vec3& p : patch.control_points()) {
    const Vec3 q = p - f.eye;
    const double z = q.dot(f.forward);
    const double x = q.dot(f.right);
    const double y = q.dot(f.up);
    behind = behind && z <= 0.0;
    left = left && x < -z * f.tan_half_h;
    right = right && x > z * f.tan_half_h;
    below = below && y < -z * f.tan_half_v;
    above = above && y > z * f.tan_half_v;
  }
  return behind || left || right || below || above;
}

std::vector<double> facing_coefficients(const BezierPatch3& patch, const Vec3& eye) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  if (n == 0 || m == 0) return {};
  // Per coordinate c: F_c - eye_c (n, m), F_u,c = n (P_i+1,j - P_ij) (n-1, m), F_v,c = m (P_i,j+1 - P_ij) (n, m-1).
  std::array<ScalarPatch, 3> F, Fu, Fv;
  for (int c = 0; c < 3; ++c) {
    F[c] = {n, m, {}};
    Fu[c] = {n - 1, m, {}};
    Fv[c] = {n, m - 1, {}};
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) {
        F[c].c.push_back(patch.control_point(i, j)[c] - eye[c]);
        if (i < n) Fu[c].c.push_back(n * (patch.control_point(i + 1, j)[c] - patch.control_point(i, j)[c]));
        if (j < m) Fv[c].c.push_back(m * (patch.control_point(i, j + 1)[c] - patch.control_point(i, j)[c]));
      }
    }
  }
  ScalarPatch g{0, 0, {}};
  for (int c = 0; c < 3; ++c) {
    // (F_u x F_v)_c = F_u,c1 F_v,c2 - F_u,c2 F_v,c1 with (c, c1, c2) cyclic.
    const int c1 = (c + 1) % 3;
    const int c2 = (c + 2) % 3;
    ScalarPatch normal_c = detail::multiply(Fu[c1], Fv[c2]);
    detail::add(normal_c, detail::multiply(Fu[c2], Fv[c1]), -1.0);
    detail::add(g, detail::multiply(F[c], normal_c), 1.0);
  }
  return g.c;
}

bool back_facing(const BezierPatch3& patch, const Vec3& eye) {
  const std::vector<double> g = facing_coefficients(patch, eye);
  if (g.empty()) return true;
  double largest = 0.0;
  for (double c : g) largest = std::max(largest, std::abs(c));
  // Rounding in the products is far below this margin; a coefficient that is zero or nearly so
  // (a patch seen edge-on) keeps the patch.
  return std::all_of(g.begin(), g.end(), [&](double c) { return c > 1e-12 * largest; });
}

}  // namespace patchwork
