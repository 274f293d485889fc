#pragma once
// What a camera sees of a triangle mesh, by casting one ray through the centre of every pixel:
// the distance to the nearest triangle hit (either side), or infinity. A test-only renderer that
// shares nothing with the tessellator's culling (surfaces/view_culling.h), so the two can be
// compared: a culled mesh must show every pixel the whole mesh shows.
//
// Camera space as in view_culling.h: d = (target - eye) / |target - eye|, r = d x up, t = r x d;
// pixel (i, j), i to the right and j down, is the ray eye + s (d + x r + y t) with
// x = (i + 1/2 - width/2) / f, y = (height/2 - j - 1/2) / f, f the focal length in pixels.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "meshes/render_mesh.h"
#include "surfaces/view_culling.h"

namespace patchwork::testing {

/// The nearest hit distance per pixel, row by row (infinity where the ray hits nothing).
inline std::vector<double> ray_cast(const RenderMesh& mesh, const Camera& camera) {
  const Vec3 d = (camera.target - camera.eye).normalized();
  const Vec3 r = d.cross(camera.up).normalized();
  const Vec3 t = r.cross(d);
  const double f = focal_length_pixels(camera);
  const int w = camera.width;
  const int h = camera.height;
  std::vector<double> depth(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                            std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
    const Vec3& a = mesh.positions[mesh.indices[3 * k]];
    const Vec3& b = mesh.positions[mesh.indices[3 * k + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * k + 2]];
    // The pixels the triangle can cover: its projected box (every corner in front of the eye).
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    bool in_front = true;
    for (const Vec3* p : {&a, &b, &c}) {
      const Vec3 q = *p - camera.eye;
      const double z = q.dot(d);
      if (!(z > 0.0)) in_front = false;
      const double px = 0.5 * w + f * q.dot(r) / z;
      const double py = 0.5 * h - f * q.dot(t) / z;
      x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
    }
    if (!in_front) continue;
    const int i0 = std::max(0, static_cast<int>(std::floor(x0 - 1)));
    const int i1 = std::min(w - 1, static_cast<int>(std::ceil(x1 + 1)));
    const int j0 = std::max(0, static_cast<int>(std::floor(y0 - 1)));
    const int j1 = std::min(h - 1, static_cast<int>(std::ceil(y1 + 1)));
    const Vec3 e1 = b - a;
    const Vec3 e2 = c - a;
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        // Moeller-Trumbore, both sides.
        const Vec3 ray = d + ((i + 0.5 - 0.5 * w) / f) * r + ((0.5 * h - j - 0.5) / f) * t;
        const Vec3 pv = ray.cross(e2);
        const double det = e1.dot(pv);
        if (det == 0.0) continue;
        const Vec3 tv = camera.eye - a;
        const double u = tv.dot(pv) / det;
        if (u < 0.0 || u > 1.0) continue;
        const Vec3 qv = tv.cross(e1);
        const double v = ray.dot(qv) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double s = e2.dot(qv) / det;
        if (!(s > 0.0)) continue;
        double& nearest = depth[static_cast<std::size_t>(i) + static_cast<std::size_t>(w) * static_cast<std::size_t>(j)];
        nearest = std::min(nearest, s * ray.norm());
      }
    }
  }
  return depth;
}

/// Pixels that `whole` shows and `part` does not (background where the whole mesh has a surface).
inline std::size_t pixels_lost(const std::vector<double>& whole, const std::vector<double>& part) {
  std::size_t lost = 0;
  for (std::size_t k = 0; k < whole.size(); ++k) lost += std::isfinite(whole[k]) && !std::isfinite(part[k]);
  return lost;
}

}  // namespace patchwork::testing
