#pragma once
// Quadrics as rational Bezier patches for tests, built independently of the library's shapes
// from the quarter circle (cos a, sin a), (cos a - sin a, sin a + cos a), (-sin a, cos a) with
// weights 1, 1/sqrt2, 1: the unit sphere from 8 octants, the torus from 16 patches.

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "surfaces/rational_bezier_patch.h"

namespace patchwork::testing {

/// The patches as a PatchSet's input.
inline std::vector<AnyBezierPatch> as_any(const std::vector<RationalBezierPatch>& patches) {
  return {patches.begin(), patches.end()};
}

/// The control points (x, y) and weights of the unit circle's quarter from angle a.
inline std::array<std::pair<Vec2, double>, 3> quarter_circle(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {{{Vec2(c, s), 1.0}, {Vec2(c - s, s + c), std::sqrt(0.5)}, {Vec2(-s, c), 1.0}}};
}

/// The patch with u and v exchanged (P'_ij = P_ji): the normal F_u x F_v turns round.
inline RationalBezierPatch transposed(const RationalBezierPatch& patch) {
  const int n = patch.degree_u(), m = patch.degree_v();
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= m; ++j) {
      points.push_back(patch.control_point(i, j));
      weights.push_back(patch.weight(i, j));
    }
  }
  return RationalBezierPatch(m, n, points, weights);
}

/// The unit sphere as the 8 octants x, y, z = +-, each with the outward normal.
inline std::vector<RationalBezierPatch> unit_sphere_octants() {
  const RationalBezierPatch octant = sphere_octant(Vec3::Zero(), 1.0);
  std::vector<RationalBezierPatch> result;
  for (int k = 0; k < 8; ++k) {
    const Vec3 sign((k & 1) ? -1.0 : 1.0, (k & 2) ? -1.0 : 1.0, (k & 4) ? -1.0 : 1.0);
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int j = 0; j <= 2; ++j) {
      for (int i = 0; i <= 2; ++i) {
        points.push_back(octant.control_point(i, j).cwiseProduct(sign));
        weights.push_back(octant.weight(i, j));
      }
    }
    const RationalBezierPatch mirrored(2, 2, points, weights);
    // An odd number of mirrors turns the normal inward; exchanging u and v turns it back.
    result.push_back(sign.prod() < 0 ? transposed(mirrored) : mirrored);
  }
  return result;
}

/// The torus of radii R (of the centre circle, about z) and r, as 4 x 4 biquadratic patches:
/// P_ij = ((R + r c_j) M_i, r s_j) with weight w_i w_j, M_i the major circle's quarter and
/// (c_j, s_j) the minor one's.
inline std::vector<RationalBezierPatch> torus_patches(double R, double r) {
  std::vector<RationalBezierPatch> result;
  for (int major = 0; major < 4; ++major) {
    const auto M = quarter_circle(major * std::numbers::pi / 2);
    for (int minor = 0; minor < 4; ++minor) {
      const auto C = quarter_circle(minor * std::numbers::pi / 2);
      std::vector<Vec3> points;
      std::vector<double> weights;
      for (int j = 0; j <= 2; ++j) {
        for (int i = 0; i <= 2; ++i) {
          const double radius = R + r * C[j].first.x();
          points.emplace_back(radius * M[i].first.x(), radius * M[i].first.y(), r * C[j].first.y());
          weights.push_back(M[i].second * C[j].second);
        }
      }
      result.emplace_back(2, 2, points, weights);
    }
  }
  return result;
}

/// The closed wedge {x, y >= 0, x^2 + y^2 <= radius^2, 0 <= z <= height} moved by `offset`, as
/// a mixed shell with outward normals: the curved side and the two quarter-disk caps rational
/// (degrees (2, 1), a cap's centre row collapsed), the two flat sides polynomial.
inline std::vector<AnyBezierPatch> wedge(double radius, double height, const Vec3& offset) {
  const auto arc = quarter_circle(0.0);
  const auto rational = [&](const std::function<Vec3(int, int)>& point) {
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int j = 0; j <= 1; ++j) {
      for (int i = 0; i <= 2; ++i) {
        points.push_back(offset + point(i, j));
        weights.push_back(arc[i].second);
      }
    }
    return RationalBezierPatch(2, 1, points, weights);
  };
  const auto rim = [&](int i, double z) { return Vec3(radius * arc[i].first.x(), radius * arc[i].first.y(), z); };
  const auto flat = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return BezierPatch3(1, 1, {offset + a, offset + b, offset + c, offset + d});
  };
  const double r = radius, h = height;
  return {
      rational([&](int i, int j) { return rim(i, h * j); }),                         // curved: u along the arc, v up
      rational([&](int i, int j) { return j == 0 ? Vec3(0, 0, 0) : rim(i, 0.0); }),  // bottom: centre to rim
      rational([&](int i, int j) { return j == 0 ? rim(i, h) : Vec3(0, 0, h); }),    // top: rim to centre
      flat(Vec3(0, 0, 0), Vec3(r, 0, 0), Vec3(0, 0, h), Vec3(r, 0, h)),              // y = 0: u along x, v up
      flat(Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(0, r, 0), Vec3(0, r, h)),              // x = 0: u up, v along y
  };
}

/// Distance from p to the torus of radii R and r about z.
inline double torus_distance(const Vec3& p, double R, double r) {
  return std::abs(std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r);
}

/// The torus's outward unit normal at (or nearest to) p.
inline Vec3 torus_normal(const Vec3& p, double R) {
  const double rho = std::hypot(p.x(), p.y());
  const Vec3 centre(R * p.x() / rho, R * p.y() / rho, 0.0);
  return (p - centre).normalized();
}

}  // namespace patchwork::testing
