#pragma once
// Patch sets whose topology and normals are known in closed form, and RapidCheck generators for
// them, for the tessellator's property tests.
//
//   grid    one wavy height field cut into rows x columns patches (C0 joins): a disc
//   fan     k patches around a pole, each with its v1 edge collapsed to it; patch i's u1 edge is
//           patch i+1's u0 edge, the v0 edges are the one boundary loop: a disc
//
//                 pole (row j = m, one point)
//               /  i  \  i+1 /            u runs counter-clockwise seen from the side the
//              /______\_____/             normals point to, v from the rim to the pole
//               rim (row j = 0)
//
//   lens    two fans glued along their rims, the lower one turning the other way: a sphere with
//           two poles
//   cube    six bicubic faces over [-1, 1]^3, straight cube edges, the four inner control points
//           of each face pushed outward, every face's F_u x F_v pointing out: a sphere
//
// Every patch may then have its parameter square turned by quarter turns (the same surface and
// orientation, another edge meeting each neighbour, in another direction) and be degree-elevated
// in one direction (the same surface, edges of different degrees), and the set moved rigidly.
//
// The normals here are computed from the control net on their own (the hodographs in Bernstein
// form), not through surfaces/surface_normal.h, which the tests check.

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/types.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_set.h"
#include "tests/surfaces/patch_fixtures.h"

namespace patchwork::testing {

/// B_i^n(t) = C(n, i) t^i (1 - t)^(n - i), 0 outside 0 <= i <= n.
inline double bernstein_value(int n, int i, double t) {
  if (i < 0 || i > n) return 0.0;
  double binomial = 1.0;
  for (int k = 1; k <= i; ++k) binomial = binomial * (n - i + k) / k;
  return binomial * std::pow(t, i) * std::pow(1.0 - t, n - i);
}

/// F_u and F_v at (u, v) from the hodographs: F_u = n sum B_i^(n-1)(u) B_j^m(v) (P_(i+1)j - P_ij),
/// likewise F_v.
inline std::pair<Vec3, Vec3> net_derivatives(const BezierPatch3& patch, double u, double v) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const auto P = [&](int i, int j) -> const Vec3& { return patch.control_points()[i + (n + 1) * j]; };
  Vec3 du = Vec3::Zero(), dv = Vec3::Zero();
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      if (i < n) du += n * bernstein_value(n - 1, i, u) * bernstein_value(m, j, v) * (P(i + 1, j) - P(i, j));
      if (j < m) dv += m * bernstein_value(n, i, u) * bernstein_value(m - 1, j, v) * (P(i, j + 1) - P(i, j));
    }
  }
  return {du, dv};
}

/// F_u x F_v / |F_u x F_v| from the net (only where it does not vanish).
inline Vec3 net_unit_normal(const BezierPatch3& patch, double u, double v) {
  const auto [du, dv] = net_derivatives(patch, u, v);
  return du.cross(dv).normalized();
}

/// The patch over its parameter square turned a quarter counter-clockwise `turns` times:
/// G(u, v) = F(1 - v, u) once, an orientation-preserving reparametrisation (Jacobian
/// [[0, -1], [1, 0]], determinant 1); G has degrees (m, n) and Q_ab = P_(n-b) a. F's edge v1
/// becomes G's u1, v0 becomes u0, u0 becomes v1 and u1 becomes v0.
inline BezierPatch3 turned(BezierPatch3 patch, int turns) {
  for (int t = 0; t < ((turns % 4) + 4) % 4; ++t) {
    const int n = patch.degree_u();
    const int m = patch.degree_v();
    std::vector<Vec3> points;
    for (int b = 0; b <= n; ++b) {
      for (int a = 0; a <= m; ++a) points.push_back(patch.control_points()[(n - b) + (n + 1) * a]);
    }
    patch = BezierPatch3(m, n, std::move(points));
  }
  return patch;
}

/// The same surface with the degree in u (or v) raised by one: Q_i = (i / (n+1)) P_(i-1) +
/// (1 - i / (n+1)) P_i along that direction (Farin, Curves and Surfaces for CAGD, 5.1).
inline BezierPatch3 elevated_once(const BezierPatch3& patch, bool along_u) {
  if (!along_u) return turned(elevated_once(turned(patch, 1), true), 3);
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const auto P = [&](int i, int j) -> const Vec3& { return patch.control_points()[i + (n + 1) * j]; };
  std::vector<Vec3> points;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n + 1; ++i) {
      const double a = static_cast<double>(i) / (n + 1);
      if (i == 0) {
        points.push_back(P(0, j));
      } else if (i == n + 1) {
        points.push_back(P(n, j));
      } else {
        points.push_back(a * P(i - 1, j) + (1 - a) * P(i, j));
      }
    }
  }
  return BezierPatch3(n + 1, m, std::move(points));
}

/// k patches of degrees (n, m) around `pole` (see the file comment). `net` holds the rows
/// j = 0 .. m-1 of the whole ring, k n points a row, angular index s fastest; patch i takes
/// s = i n + a (a = 0 .. n, cyclic), or with `clockwise` s = (i + 1) n - a, so that its u runs
/// the other way round.
inline std::vector<BezierPatch3> polar_fan(int k, int n, int m, const std::vector<Vec3>& net, const Vec3& pole,
                                           bool clockwise = false) {
  const int ring = k * n;
  std::vector<BezierPatch3> patches;
  for (int i = 0; i < k; ++i) {
    std::vector<Vec3> points;
    for (int j = 0; j <= m; ++j) {
      for (int a = 0; a <= n; ++a) {
        const int s = (clockwise ? (i + 1) * n - a : i * n + a) % ring;
        points.push_back(j == m ? pole : net[s + ring * j]);
      }
    }
    patches.emplace_back(n, m, std::move(points));
  }
  return patches;
}

/// Two fans glued at the rim (see the file comment): the upper one around `top` over `upper`, the
/// lower one around `bottom` over `lower` with its rim row replaced by the upper's and its u running
/// clockwise, so that both face out.
inline std::vector<BezierPatch3> lens(int k, int n, int m, const std::vector<Vec3>& upper, std::vector<Vec3> lower,
                                      const Vec3& top, const Vec3& bottom) {
  std::copy(upper.begin(), upper.begin() + k * n, lower.begin());  // the common rim
  std::vector<BezierPatch3> patches = polar_fan(k, n, m, upper, top);
  for (BezierPatch3& patch : polar_fan(k, n, m, lower, bottom, true)) patches.push_back(std::move(patch));
  return patches;
}

/// The ring of a fan: row j (0 .. m-1) at radius (1 - j / m) times radius(s, j), angle
/// 2 pi s / (k n), height height(s, j).
template <class Radius, class Height>
std::vector<Vec3> fan_net(int k, int n, int m, const Radius& radius, const Height& height) {
  const int ring = k * n;
  std::vector<Vec3> net;
  for (int j = 0; j < m; ++j) {
    for (int s = 0; s < ring; ++s) {
      const double angle = 2 * std::numbers::pi * s / ring;
      const double r = (1.0 - static_cast<double>(j) / m) * radius(s, j);
      net.emplace_back(r * std::cos(angle), r * std::sin(angle), height(s, j));
    }
  }
  return net;
}

/// Six bicubic faces over [-1, 1]^3: face e (outward axis e, in-face axes a, b with a x b = e)
/// has P_ij = e + c_i a + c_j b, c = (-1, -1/3, 1/3, 1), its inner points pushed out by
/// bulge[4 f + ...] (face f, points (1,1), (2,1), (1,2), (2,2)). Shared edge points are the same
/// doubles on both sides (every coordinate is one of the c's or +-1).
inline std::vector<BezierPatch3> bulged_cube(const std::vector<double>& bulge) {
  const double c[4] = {-1.0, -1.0 / 3, 1.0 / 3, 1.0};
  std::vector<BezierPatch3> faces;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const double sign = f % 2 == 0 ? 1.0 : -1.0;
    const Vec3 e = sign * Vec3::Unit(axis);
    Vec3 a = Vec3::Unit((axis + 1) % 3);
    const Vec3 b = Vec3::Unit((axis + 2) % 3);
    if (sign < 0) a = -a;  // (-a) x b = -e
    std::vector<Vec3> points;
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) {
        Vec3 p = e + c[i] * a + c[j] * b;
        if (i % 3 != 0 && j % 3 != 0) p += bulge[4 * f + (i - 1) + 2 * (j - 1)] * e;
        points.push_back(p);
      }
    }
    faces.emplace_back(3, 3, std::move(points));
  }
  return faces;
}

/// What the welded mesh of a fixture must be.
struct PatchSetFixture {
  const char* kind;
  std::vector<BezierPatch3> patches;
  bool closed;
  Count euler;
  Count components;
  Count boundary_loops;
};

/// A wavy grid: rows x columns patches of degrees (n, m) cut from one net over a height field.
inline rc::Gen<PatchSetFixture> grid_fixture() {
  return rc::gen::exec([] {
    const int n = *rc::gen::inRange(1, 4);
    const int m = *rc::gen::inRange(1, 4);
    const int rows = *rc::gen::inRange(1, 3);
    const int columns = *rc::gen::inRange(1, 4);
    const int width = n * columns + 1;
    const int height = m * rows + 1;
    std::vector<Vec3> net;
    for (int j = 0; j < height; ++j) {
      for (int i = 0; i < width; ++i) {
        // Jitter under half the spacing: the net does not fold.
        net.emplace_back((i + *coordinate(-0.3, 0.3)) / n, (j + *coordinate(-0.3, 0.3)) / m, *coordinate(-0.7, 0.7));
      }
    }
    PatchSetFixture fixture{"grid", {}, false, 1, 1, 1};
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < columns; ++c) {
        std::vector<Vec3> points;
        for (int j = 0; j <= m; ++j) {
          for (int i = 0; i <= n; ++i) points.push_back(net[(c * n + i) + width * (r * m + j)]);
        }
        fixture.patches.emplace_back(n, m, std::move(points));
      }
    }
    return fixture;
  });
}

/// A fan's ring: radii in [0.6, 1.4], heights rising towards the pole (a dome) with noise.
inline std::vector<Vec3> random_fan_net(int k, int n, int m, double lift) {
  std::vector<double> radii, heights;
  for (int q = 0; q < k * n * m; ++q) {
    radii.push_back(*coordinate(0.6, 1.4));
    heights.push_back(*coordinate(-0.15, 0.15));
  }
  const int ring = k * n;
  return fan_net(
      k, n, m, [&](int s, int j) { return radii[s + ring * j]; },
      [&](int s, int j) { return j == 0 ? 0.0 : lift * static_cast<double>(j) / m + heights[s + ring * j]; });
}

/// A dome of k patches of degrees (n, m), m >= 2, around a pole A whose row m-1 lies in the tilted
/// plane through A with normal N = normalize(-t_x, -t_y, 1), at uneven radii (not symmetric about
/// A). F_v(u, 1) = m (A - R(u)) and F_uv(u, 1) run in that plane (R the row's curve), so the
/// limit normal at A is N for every patch and u; its sign: near A, F_u x F_v ~ (1 - v) m^2
/// R'(u) x (A - R(u)), and R winds counter-clockwise about N.
struct TiltedDome {
  std::vector<BezierPatch3> patches;
  Vec3 pole;
  Vec3 normal;
};

inline rc::Gen<TiltedDome> tilted_dome(int k, int n, int m) {
  return rc::gen::exec([=] {
    const Vec3 pole(0, 0, *coordinate(0.5, 1.5));
    const Vec2 tilt(*coordinate(-0.8, 0.8), *coordinate(0.2, 0.8));  // at least 0.19 rad from the axis
    std::vector<Vec3> net = random_fan_net(k, n, m, 0.8 * pole.z());
    for (int s = 0; s < k * n; ++s) {
      Vec3& q = net[s + k * n * (m - 1)];
      q.z() = pole.z() + tilt.dot(q.head<2>());
    }
    return TiltedDome{polar_fan(k, n, m, net, pole), pole, Vec3(-tilt.x(), -tilt.y(), 1).normalized()};
  });
}

/// Degrees (n, m) in 1..3 and a patch count k from 3 (2 when n >= 2: a patch of degree 1 along the
/// rim spanning half of it would be a chord through the pole) to max_k.
struct FanShape {
  int n, m, k;
};
inline rc::Gen<FanShape> fan_shape(int max_k) {
  return rc::gen::exec([max_k] {
    const int n = *rc::gen::inRange(1, 4);
    const int m = *rc::gen::inRange(1, 4);
    return FanShape{n, m, *rc::gen::inRange(n >= 2 ? 2 : 3, max_k + 1)};
  });
}

/// A fan of up to 5 patches.
inline rc::Gen<PatchSetFixture> fan_fixture() {
  return rc::gen::exec([] {
    const auto [n, m, k] = *fan_shape(5);
    const Vec3 pole(0, 0, *coordinate(0.5, 1.5));
    return PatchSetFixture{"fan", polar_fan(k, n, m, random_fan_net(k, n, m, pole.z() * 0.8), pole), false, 1, 1, 1};
  });
}

/// Two fans glued at the rim, the lower one running clockwise (so both face out).
inline rc::Gen<PatchSetFixture> lens_fixture() {
  return rc::gen::exec([] {
    const auto [n, m, k] = *fan_shape(4);
    const Vec3 top(0, 0, *coordinate(0.5, 1.5));
    const Vec3 bottom(0, 0, -*coordinate(0.5, 1.5));
    const std::vector<Vec3> upper = random_fan_net(k, n, m, top.z() * 0.8);
    const std::vector<Vec3> lower = random_fan_net(k, n, m, bottom.z() * 0.8);
    return PatchSetFixture{"lens", lens(k, n, m, upper, lower, top, bottom), true, 2, 1, 0};
  });
}

/// The bulged cube with inner points pushed out by 0 to 0.6.
inline rc::Gen<PatchSetFixture> cube_fixture() {
  return rc::gen::exec([] {
    std::vector<double> bulge;
    for (int q = 0; q < 24; ++q) bulge.push_back(*coordinate(0.0, 0.6));
    return PatchSetFixture{"cube", bulged_cube(bulge), true, 2, 1, 0};
  });
}

/// Every patch turned by 0 to 3 quarter turns, and by chance elevated once in u or v; the set moved by a
/// rigid motion.
inline rc::Gen<PatchSetFixture> reparametrised(rc::Gen<PatchSetFixture> base) {
  return rc::gen::exec([base] {
    PatchSetFixture fixture = *base;
    const Eigen::Isometry3d motion = *random_rigid_motion();
    for (BezierPatch3& patch : fixture.patches) {
      patch = turned(patch, *rc::gen::inRange(0, 4));
      const int elevation = *rc::gen::inRange(0, 4);  // 0, 1: none; 2: in u; 3: in v
      if (elevation >= 2) patch = elevated_once(patch, elevation == 2);
      patch = transformed(patch, Eigen::Affine3d(motion));
    }
    return fixture;
  });
}

/// Any of the fixtures, reparametrised; sometimes two of them side by side (far apart), whose
/// counts add up.
inline rc::Gen<PatchSetFixture> any_patch_set() {
  const auto one = [] {
    return reparametrised(rc::gen::oneOf(grid_fixture(), fan_fixture(), lens_fixture(), cube_fixture()));
  };
  return rc::gen::exec([one] {
    PatchSetFixture fixture = *one();
    if (*rc::gen::inRange(0, 4) == 0) {
      PatchSetFixture other = *one();
      const Eigen::Affine3d away(Eigen::Translation3d(40, 0, 0));
      for (const BezierPatch3& patch : other.patches) fixture.patches.push_back(transformed(patch, away));
      fixture.closed = fixture.closed && other.closed;
      fixture.euler += other.euler;
      fixture.components += other.components;
      fixture.boundary_loops += other.boundary_loops;
      fixture.kind = "two sets";
    }
    return fixture;
  });
}

/// A fixed set of mixed degrees with poles and turned patches (no randomness): the lens of four
/// patches of degrees (3, 2) a side, every other patch elevated in u or v and turned.
inline std::vector<BezierPatch3> mixed_degree_lens() {
  const int k = 4, n = 3, m = 2;
  const auto radius = [](int s, int j) { return 1.0 + 0.3 * std::sin(1.7 * s + 2.3 * j); };
  std::vector<BezierPatch3> patches =
      lens(k, n, m, fan_net(k, n, m, radius, [](int s, int j) { return j == 0 ? 0.0 : 0.6 + 0.2 * std::cos(0.9 * s); }),
           fan_net(k, n, m, radius, [](int s, int j) { return j == 0 ? 0.0 : -0.5 - 0.2 * std::sin(1.3 * s); }),
           Vec3(0, 0, 1.1), Vec3(0, 0, -0.9));
  for (std::size_t p = 0; p < patches.size(); p += 2) patches[p] = turned(elevated_once(patches[p], p % 4 == 0), 1 + p % 3);
  return patches;
}

}  // namespace patchwork::testing
