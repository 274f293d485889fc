#include "surfaces/patch_flatness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace patchwork {

namespace {

// A net of degrees (n, m), P_ij at i + (n + 1) j, raised by one degree in u (transposed: in v),
// written to `raised` ((n + 2)(m + 1) points; (n + 1)(m + 2) in v).
void raise_in_u(std::span<const Vec3> net, int n, int m, std::span<Vec3> raised) {
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n + 1; ++i) {
      const double a = static_cast<double>(i) / (n + 1);
      const Vec3 left = i > 0 ? net[static_cast<std::size_t>(i - 1 + (n + 1) * j)] : Vec3::Zero();
      const Vec3 right = i <= n ? net[static_cast<std::size_t>(i + (n + 1) * j)] : Vec3::Zero();
      raised[static_cast<std::size_t>(i + (n + 2) * j)] = a * left + (1.0 - a) * right;
    }
  }
}

void raise_in_v(std::span<const Vec3> net, int n, int m, std::span<Vec3> raised) {
  for (int j = 0; j <= m + 1; ++j) {
    const double a = static_cast<double>(j) / (m + 1);
    for (int i = 0; i <= n; ++i) {
      const Vec3 below = j > 0 ? net[static_cast<std::size_t>(i + (n + 1) * (j - 1))] : Vec3::Zero();
      const Vec3 above = j <= m ? net[static_cast<std::size_t>(i + (n + 1) * j)] : Vec3::Zero();
      raised[static_cast<std::size_t>(i + (n + 1) * j)] = a * below + (1.0 - a) * above;
    }
  }
}

// The norm and directional bounds of the patch with net `at(i, j)` of degrees (n, m).
template <class Net>
SecondDerivativeBounds bounds_of_net(const Net& net_at, int n, int m) {
  // One buffer: the net, then the nets of F_uu (n-2, m), F_uv (n-1, m-1) and F_vv (n, m-2) each
  // raised to (n, m), then two scratch nets for the raising.
  const auto count = static_cast<std::size_t>((n + 1) * (m + 1));
  std::vector<Vec3> buffer(6 * count);
  const std::span<Vec3> points(buffer.data(), count);
  const std::array<std::span<Vec3>, 3> h = {std::span<Vec3>(buffer.data() + count, count),
                                            std::span<Vec3>(buffer.data() + 2 * count, count),
                                            std::span<Vec3>(buffer.data() + 3 * count, count)};
  const std::span<Vec3> raw(buffer.data() + 4 * count, count);
  const std::span<Vec3> half(buffer.data() + 5 * count, count);
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) points[static_cast<std::size_t>(i + (n + 1) * j)] = net_at(i, j);
  }
  const auto at = [&](int i, int j) -> const Vec3& { return points[static_cast<std::size_t>(i + (n + 1) * j)]; };
  const std::array<bool, 3> present = {n >= 2, n >= 1 && m >= 1, m >= 2};
  double uu = 0.0, uv = 0.0, vv = 0.0;
  if (present[0]) {
    std::size_t k = 0;
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i + 2 <= n; ++i, ++k) {
        raw[k] = n * (n - 1.0) * (at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j));
        uu = std::max(uu, raw[k].norm());
      }
    }
    raise_in_u(raw, n - 2, m, half);
    raise_in_u(half, n - 1, m, h[0]);
  }
  if (present[1]) {
    std::size_t k = 0;
    for (int j = 0; j + 1 <= m; ++j) {
      for (int i = 0; i + 1 <= n; ++i, ++k) {
        raw[k] = static_cast<double>(n) * m * (at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j));
        uv = std::max(uv, raw[k].norm());
      }
    }
    raise_in_u(raw, n - 1, m - 1, half);
    raise_in_v(half, n, m - 1, h[1]);
  }
  if (present[2]) {
    std::size_t k = 0;
    for (int j = 0; j + 2 <= m; ++j) {
      for (int i = 0; i <= n; ++i, ++k) {
        raw[k] = m * (m - 1.0) * (at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j));
        vv = std::max(vv, raw[k].norm());
      }
    }
    raise_in_v(raw, n, m - 2, half);
    raise_in_v(half, n, m - 1, h[2]);
  }
  DirectionalBounds d{};
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      double high = 0.0;
      double low = 0.0;
      if (present[a] && present[b]) {
        high = -std::numeric_limits<double>::infinity();
        low = std::numeric_limits<double>::infinity();
        for (std::size_t c = 0; c < count; ++c) {
          const double g = h[a][c].dot(h[b][c]);
          high = std::max(high, g);
          low = std::min(low, g);
        }
      }
      d.gram_max[a][b] = d.gram_max[b][a] = high;
      d.gram_min[a][b] = d.gram_min[b][a] = low;
    }
  }
  // Third differences: F_uuu, F_uuv, F_uvv, F_vvv lie in the hulls of their scaled nets.
  d.third = {0.0, 0.0, 0.0, 0.0};
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      if (i + 3 <= n) {
        d.third[0] = std::max(d.third[0], n * (n - 1.0) * (n - 2.0) *
                                              (at(i + 3, j) - 3.0 * at(i + 2, j) + 3.0 * at(i + 1, j) - at(i, j)).norm());
      }
      if (i + 2 <= n && j + 1 <= m) {
        const Vec3 d2 = (at(i + 2, j + 1) - 2.0 * at(i + 1, j + 1) + at(i, j + 1)) -
                        (at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j));
        d.third[1] = std::max(d.third[1], n * (n - 1.0) * m * d2.norm());
      }
      if (i + 1 <= n && j + 2 <= m) {
        const Vec3 d2 = (at(i + 1, j + 2) - 2.0 * at(i + 1, j + 1) + at(i + 1, j)) -
                        (at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j));
        d.third[2] = std::max(d.third[2], n * m * (m - 1.0) * d2.norm());
      }
      if (j + 3 <= m) {
        d.third[3] = std::max(d.third[3], m * (m - 1.0) * (m - 2.0) *
                                              (at(i, j + 3) - 3.0 * at(i, j + 2) + 3.0 * at(i, j + 1) - at(i, j)).norm());
      }
    }
  }
  return {uu, uv, vv, d};
}

// The directional bound (file comment) for a triangle of parameter extents du, dv; `mixed` is
// the sign of m_2 when known (+1 or -1), else 0.
double directional_bound(const DirectionalBounds& d, double du, double dv, int mixed) {
  const double m0 = du * du / 4.0;
  const double m1 = du * dv / 2.0;
  const double m2 = dv * dv / 4.0;
  // Terms w_a w_b G_ab of sum_ab w_a w_b G_ab that do not depend on the sign of w_1 = +-m1.
  const double t00 = m0 * m0 * d.gram_max[0][0];
  const double t11 = m1 * m1 * d.gram_max[1][1];
  const double t22 = m2 * m2 * d.gram_max[2][2];
  const double t02 = m0 * m2 * d.gram_max[0][2];
  double q = std::max({t00, t11, t22, t00 + t22 + 2.0 * t02});
  for (int sign : {1, -1}) {
    if (mixed != 0 && sign != mixed) continue;
    const double t01 = m0 * m1 * (sign > 0 ? d.gram_max[0][1] : -d.gram_min[0][1]);
    const double t12 = m1 * m2 * (sign > 0 ? d.gram_max[1][2] : -d.gram_min[1][2]);
    // The corners of the box of m with m_1 in use (each other m_i zero or at its extreme).
    q = std::max({q, t00 + t11 + 2.0 * t01, t11 + t22 + 2.0 * t12, t00 + t11 + t22 + 2.0 * (t01 + t02 + t12)});
  }
  // sum_k lambda_k |d_ku|^3 <= du^3 / 8 on any triangle (|x - mean|^3 is convex: the extreme
  // distribution on an interval puts half its weight at each end), and by a^2 b <= (2a^3 + b^3)/3
  // the mixed third-order terms split into pure ones.
  const std::array<double, 4>& t = d.third;
  const double third = ((t[0] + 2.0 * t[1] + t[2]) * du * du * du + (t[1] + 2.0 * t[2] + t[3]) * dv * dv * dv) / 48.0;
  return 0.5 * std::sqrt(q) + third;
}

}  // namespace

SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch) {
  return bounds_of_net([&](int i, int j) -> const Vec3& { return patch.control_point(i, j); }, patch.degree_u(),
                       patch.degree_v());
}

SecondDerivativeBounds merged_bounds(const SecondDerivativeBounds& a, const SecondDerivativeBounds& b) {
  SecondDerivativeBounds merged{std::max(a.uu, b.uu), std::max(a.uv, b.uv), std::max(a.vv, b.vv)};
  if (a.directions && b.directions) {
    DirectionalBounds d = *a.directions;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        d.gram_max[i][j] = std::max(d.gram_max[i][j], b.directions->gram_max[i][j]);
        d.gram_min[i][j] = std::min(d.gram_min[i][j], b.directions->gram_min[i][j]);
      }
    }
    for (int k = 0; k < 4; ++k) d.third[k] = std::max(d.third[k], b.directions->third[k]);
    merged.directions = d;
  }
  return merged;
}

SecondDerivativeBounds scaled_bounds(const SecondDerivativeBounds& bounds, double size) {
  const double s2 = size * size;
  SecondDerivativeBounds scaled{s2 * bounds.uu, s2 * bounds.uv, s2 * bounds.vv};
  if (bounds.directions) {
    DirectionalBounds d = *bounds.directions;
    for (auto* gram : {&d.gram_max, &d.gram_min}) {
      for (auto& row : *gram) {
        for (double& g : row) g *= s2 * s2;
      }
    }
    for (double& t : d.third) t *= s2 * size;
    scaled.directions = d;
  }
  return scaled;
}

namespace {

// The control points of a degree-n Bezier segment over [t0, t1] are linear in the whole curve's:
// Q_i = sum_k S(i, k) P_k, Q_i the blossom at (t0 x (n - i), t1 x i). Each column of S is that
// blossom of the k-th unit control polygon, by de Casteljau steps at those parameters.
Eigen::MatrixXd segment_matrix(int n, double t0, double t1) {
  Eigen::MatrixXd S(n + 1, n + 1);
  std::vector<double> work(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    for (int i = 0; i <= n; ++i) {
      std::fill(work.begin(), work.end(), 0.0);
      work[static_cast<std::size_t>(k)] = 1.0;
      for (int step = 0; step < n; ++step) {
        const double t = step < n - i ? t0 : t1;
        for (int j = 0; j + step < n; ++j) work[j] = (1.0 - t) * work[j] + t * work[j + 1];
      }
      S(i, k) = work[0];
    }
  }
  return S;
}

}  // namespace

std::vector<SecondDerivativeBounds> piece_second_derivative_bounds(const BezierPatch3& patch, int pieces) {
  if (pieces < 1 || pieces > 64) {
    throw InvalidInput(detail::message("second_derivative_bounds: ", pieces, " pieces is not in [1, 64]"));
  }
  if (pieces == 1) return {second_derivative_bounds(patch)};
  // The net of piece (a, b) is S_a P S_b^T per coordinate (segment matrices in u and v): the same
  // points as de Casteljau sub-patches, without building a patch per piece.
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  std::array<Eigen::MatrixXd, 3> net;
  for (int c = 0; c < 3; ++c) {
    net[c].resize(n + 1, m + 1);
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) net[c](i, j) = patch.control_point(i, j)[c];
    }
  }
  std::vector<Eigen::MatrixXd> su;
  std::vector<Eigen::MatrixXd> sv;
  for (int a = 0; a < pieces; ++a) {
    su.push_back(segment_matrix(n, static_cast<double>(a) / pieces, static_cast<double>(a + 1) / pieces));
    sv.push_back(segment_matrix(m, static_cast<double>(a) / pieces, static_cast<double>(a + 1) / pieces).transpose());
  }
  std::vector<SecondDerivativeBounds> bounds(static_cast<std::size_t>(pieces) * static_cast<std::size_t>(pieces));
  std::array<Eigen::MatrixXd, 3> row;
  std::array<Eigen::MatrixXd, 3> piece;
  for (int b = 0; b < pieces; ++b) {
    for (int c = 0; c < 3; ++c) row[c].noalias() = net[c] * sv[static_cast<std::size_t>(b)];
    for (int a = 0; a < pieces; ++a) {
      for (int c = 0; c < 3; ++c) piece[c].noalias() = su[static_cast<std::size_t>(a)] * row[c];
      const auto at = [&](int i, int j) { return Vec3(piece[0](i, j), piece[1](i, j), piece[2](i, j)); };
      // The piece's own bounds, then in the patch's parameters (a domain `pieces` times as wide).
      bounds[static_cast<std::size_t>(a + pieces * b)] = scaled_bounds(bounds_of_net(at, n, m), pieces);
    }
  }
  return bounds;
}

SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch, int pieces) {
  const std::vector<SecondDerivativeBounds> all = piece_second_derivative_bounds(patch, pieces);
  SecondDerivativeBounds M = all.front();
  for (const SecondDerivativeBounds& piece : all) M = merged_bounds(M, piece);
  return M;
}

double flatness_bound(const SecondDerivativeBounds& M, double du, double dv) {
  if (!(du > 0.0 && du <= 1.0 && dv > 0.0 && dv <= 1.0)) {
    throw InvalidInput(detail::message("flatness_bound: steps (", du, ", ", dv, ") are not in (0, 1]"));
  }
  const double norms = (M.uu * du * du + 2.0 * M.uv * du * dv + M.vv * dv * dv) / 8.0;
  // Grid triangles have their vertices ordered alike in u and v: m_2 >= 0.
  return M.directions ? std::min(norms, directional_bound(*M.directions, du, dv, 1)) : norms;
}

double triangle_flatness_bound(const SecondDerivativeBounds& M, const Vec2& p0, const Vec2& p1, const Vec2& p2,
                               double aspect) {
  const double s = aspect > 0.0 && std::isfinite(aspect) ? aspect : 1.0;
  const Vec2 scale(std::sqrt(M.uu + s * M.uv), std::sqrt(M.vv + M.uv / s));
  const Vec2 a = p0.cwiseProduct(scale);
  const Vec2 b = p1.cwiseProduct(scale);
  const Vec2 c = p2.cwiseProduct(scale);
  // Smallest enclosing circle of a triangle: half its longest side if the angle opposite is not
  // acute, else the circumcircle, r = |ab| |bc| |ca| / (4 area).
  const double ab = (b - a).squaredNorm();
  const double bc = (c - b).squaredNorm();
  const double ca = (a - c).squaredNorm();
  const double longest = std::max({ab, bc, ca});
  double r2 = longest / 4.0;
  if (2.0 * longest < ab + bc + ca) {  // acute: the longest side squared is below the sum of the others
    const double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (cross != 0.0) r2 = ab * bc * ca / (4.0 * cross * cross);
  }
  const double norms = r2 / 2.0;
  if (!M.directions) return norms;
  const Vec2 low = p0.cwiseMin(p1).cwiseMin(p2);
  const Vec2 high = p0.cwiseMax(p1).cwiseMax(p2);
  // The covariance of u and v under any weights has the sign that all vertex pairs share.
  int positive = 0;
  int negative = 0;
  for (const auto& [x, y] : {std::pair{&p0, &p1}, std::pair{&p1, &p2}, std::pair{&p2, &p0}}) {
    const double product = (x->x() - y->x()) * (x->y() - y->y());
    positive += product > 0.0;
    negative += product < 0.0;
  }
  const int mixed = negative == 0 ? 1 : positive == 0 ? -1 : 0;
  return std::min(norms, directional_bound(*M.directions, high.x() - low.x(), high.y() - low.y(), mixed));
}

double sampled_grid_distance(const BezierPatch3& patch, std::int64_t nu, std::int64_t nv, int samples) {
  if (nu < 1 || nv < 1 || samples < 1) {
    throw InvalidInput(detail::message("sampled_grid_distance: grid ", nu, " x ", nv, " with ", samples, " samples"));
  }
  double result = 0.0;
  for (std::int64_t b = 0; b < nv; ++b) {
    for (std::int64_t a = 0; a < nu; ++a) {
      const double u0 = static_cast<double>(a) / nu, u1 = static_cast<double>(a + 1) / nu;
      const double v0 = static_cast<double>(b) / nv, v1 = static_cast<double>(b + 1) / nv;
      const Vec3 p00 = patch.evaluate(u0, v0), p10 = patch.evaluate(u1, v0);
      const Vec3 p01 = patch.evaluate(u0, v1), p11 = patch.evaluate(u1, v1);
      for (int s = 0; s <= samples; ++s) {
        for (int t = 0; s + t <= samples; ++t) {
          const double x = static_cast<double>(s) / samples, y = static_cast<double>(t) / samples;
          // Lower triangle (p00, p10, p11): (u, v) = (u0 + (x + y) du, v0 + y dv).
          const Vec3 lower = (1 - x - y) * p00 + x * p10 + y * p11;
          result = std::max(result, (patch.evaluate(u0 + (x + y) * (u1 - u0), v0 + y * (v1 - v0)) - lower).norm());
          // Upper triangle (p00, p11, p01): (u, v) = (u0 + x du, v0 + (x + y) dv).
          const Vec3 upper = (1 - x - y) * p00 + x * p11 + y * p01;
          result = std::max(result, (patch.evaluate(u0 + x * (u1 - u0), v0 + (x + y) * (v1 - v0)) - upper).norm());
        }
      }
    }
  }
  return result;
}

GridSize grid_for_tolerance(const SecondDerivativeBounds& M, double tolerance, std::int64_t min_segments) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("grid_for_tolerance: tolerance ", tolerance, " is not positive and finite"));
  }
  constexpr std::int64_t limit = std::int64_t{1} << 20;
  if (min_segments < 1 || min_segments > limit) {
    throw InvalidInput(detail::message("grid_for_tolerance: at least ", min_segments, " segments is not in [1, 2^20]"));
  }
  // The bound falls as either rate grows (both the norm and the directional bound do), so the
  // smallest rates are found by bisection and the fewest cells by one walk along N_u.
  const auto meets = [&](std::int64_t nu, std::int64_t nv) {
    return flatness_bound(M, 1.0 / static_cast<double>(nu), 1.0 / static_cast<double>(nv)) <= tolerance;
  };
  if (!meets(limit, limit)) {
    throw InvalidInput(
        detail::message("grid_for_tolerance: tolerance ", tolerance, " needs more than 2^20 segments per side"));
  }
  // The smallest x in [min_segments, high] with ok(x), given ok(high): doubling from there, then
  // bisection (the answers are small next to 2^20, and each test is a bound).
  const auto smallest = [min_segments](std::int64_t high, const auto& ok) {
    std::int64_t low = min_segments;
    for (std::int64_t step = min_segments; step < high; step *= 2) {
      if (ok(step)) {
        high = step;
        break;
      }
      low = step + 1;
    }
    while (low < high) {
      const std::int64_t mid = low + (high - low) / 2;
      if (ok(mid)) {
        high = mid;
      } else {
        low = mid + 1;
      }
    }
    return high;
  };
  const std::int64_t first = smallest(limit, [&](std::int64_t nu) { return meets(nu, limit); });
  // N_v cannot drop below what it needs at the finest N_u; once it is there, larger N_u only costs.
  const std::int64_t floor_v = smallest(limit, [&](std::int64_t nv) { return meets(limit, nv); });
  GridSize best{-1, -1};
  std::int64_t nv = limit;  // meets(nu, nv) holds for every nu >= first
  for (std::int64_t nu = first; nu <= limit; ++nu) {
    if (nv > min_segments && meets(nu, nv - 1)) {
      nv = smallest(nv - 1, [&](std::int64_t v) { return meets(nu, v); });
    }
    const bool better = best.segments_u < 0 || nu * nv < best.segments_u * best.segments_v ||
                        (nu * nv == best.segments_u * best.segments_v &&
                         std::abs(nu - nv) < std::abs(best.segments_u - best.segments_v));
    if (better) best = {nu, nv};
    if (nv <= floor_v || nu >= best.segments_u * best.segments_v) break;
  }
  return best;
}

}  // namespace patchwork
