#include "surfaces/patch_flatness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/errors.h"

namespace patchwork {

SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  double uu = 0.0;
  double uv = 0.0;
  double vv = 0.0;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      const Vec3& p = patch.control_point(i, j);
      if (i + 2 <= n)
        uu = std::max(uu, (patch.control_point(i + 2, j) - 2.0 * patch.control_point(i + 1, j) + p).norm());
      if (j + 2 <= m)
        vv = std::max(vv, (patch.control_point(i, j + 2) - 2.0 * patch.control_point(i, j + 1) + p).norm());
      if (i + 1 <= n && j + 1 <= m) {
        uv = std::max(
            uv, (patch.control_point(i + 1, j + 1) - patch.control_point(i + 1, j) - patch.control_point(i, j + 1) + p)
                    .norm());
      }
    }
  }
  return {n * (n - 1.0) * uu, static_cast<double>(n) * m * uv, m * (m - 1.0) * vv};
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
  const double scale = static_cast<double>(pieces) * pieces;
  std::array<Eigen::MatrixXd, 3> row;
  std::array<Eigen::MatrixXd, 3> piece;
  for (int b = 0; b < pieces; ++b) {
    for (int c = 0; c < 3; ++c) row[c].noalias() = net[c] * sv[static_cast<std::size_t>(b)];
    for (int a = 0; a < pieces; ++a) {
      for (int c = 0; c < 3; ++c) piece[c].noalias() = su[static_cast<std::size_t>(a)] * row[c];
      const auto at = [&](int i, int j) { return Vec3(piece[0](i, j), piece[1](i, j), piece[2](i, j)); };
      double uu = 0.0;
      double uv = 0.0;
      double vv = 0.0;
      for (int j = 0; j <= m; ++j) {
        for (int i = 0; i <= n; ++i) {
          if (i + 2 <= n) uu = std::max(uu, (at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j)).norm());
          if (j + 2 <= m) vv = std::max(vv, (at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j)).norm());
          if (i + 1 <= n && j + 1 <= m)
            uv = std::max(uv, (at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j)).norm());
        }
      }
      bounds[static_cast<std::size_t>(a + pieces * b)] = {
          scale * n * (n - 1.0) * uu, scale * static_cast<double>(n) * m * uv, scale * m * (m - 1.0) * vv};
    }
  }
  return bounds;
}

SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch, int pieces) {
  SecondDerivativeBounds M{0.0, 0.0, 0.0};
  for (const SecondDerivativeBounds& piece : piece_second_derivative_bounds(patch, pieces)) {
    M = {std::max(M.uu, piece.uu), std::max(M.uv, piece.uv), std::max(M.vv, piece.vv)};
  }
  return M;
}

double flatness_bound(const SecondDerivativeBounds& M, double du, double dv) {
  if (!(du > 0.0 && du <= 1.0 && dv > 0.0 && dv <= 1.0)) {
    throw InvalidInput(detail::message("flatness_bound: steps (", du, ", ", dv, ") are not in (0, 1]"));
  }
  return (M.uu * du * du + 2.0 * M.uv * du * dv + M.vv * dv * dv) / 8.0;
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
  return r2 / 2.0;
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

GridSize grid_for_tolerance(const SecondDerivativeBounds& M, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("grid_for_tolerance: tolerance ", tolerance, " is not positive and finite"));
  }
  constexpr std::int64_t limit = std::int64_t{1} << 20;
  const double e = 8.0 * tolerance;
  // For each N_u with M_uu du^2 < 8 eps, the smallest N_v solves
  // M_vv dv^2 + 2 M_uv du dv - (8 eps - M_uu du^2) <= 0 for dv = 1/N_v.
  const auto segments_v_for = [&](std::int64_t nu) -> std::int64_t {
    const double du = 1.0 / static_cast<double>(nu);
    const double room = e - M.uu * du * du;
    if (room <= 0.0) return -1;
    const double b = M.uv * du;
    double dv;
    if (M.vv > 0.0) {
      dv = (-b + std::sqrt(b * b + M.vv * room)) / M.vv;
    } else if (b > 0.0) {
      dv = room / (2.0 * b);
    } else {
      return 1;
    }
    double nv = std::max(1.0, std::ceil(1.0 / dv));
    if (nv > static_cast<double>(limit)) return -1;
    auto count = static_cast<std::int64_t>(nv);
    while (count > 1 && flatness_bound(M, du, 1.0 / static_cast<double>(count - 1)) <= tolerance) --count;
    while (flatness_bound(M, du, 1.0 / static_cast<double>(count)) > tolerance) ++count;
    return count;
  };
  const double smallest_u = M.uu > 0.0 ? std::sqrt(M.uu / e) : 1.0;
  // Compared as a double first: beyond 2^63 the conversion would be undefined behaviour.
  if (!(std::floor(smallest_u) <= static_cast<double>(limit))) {
    throw InvalidInput(
        detail::message("grid_for_tolerance: tolerance ", tolerance, " needs more than 2^20 segments in u"));
  }
  const std::int64_t first = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(smallest_u)));
  // N_v cannot drop below what M_vv alone needs; once it is there, larger N_u only costs.
  const auto floor_v = static_cast<std::int64_t>(
      std::clamp(std::ceil(std::sqrt(M.vv / e) - 1e-9), 1.0, static_cast<double>(limit) + 1.0));
  GridSize best{-1, -1};
  // The product N_u N_v is searched over N_u from its minimum up to where it cannot improve.
  for (std::int64_t nu = first; nu <= limit; ++nu) {
    const std::int64_t nv = segments_v_for(nu);
    if (nv < 0) continue;
    const bool better = best.segments_u < 0 || nu * nv < best.segments_u * best.segments_v ||
                        (nu * nv == best.segments_u * best.segments_v &&
                         std::abs(nu - nv) < std::abs(best.segments_u - best.segments_v));
    if (better) best = {nu, nv};
    if (nv <= floor_v || nu >= best.segments_u * best.segments_v) break;
  }
  if (best.segments_u < 0) {
    throw InvalidInput(detail::message("grid_for_tolerance: tolerance ", tolerance, " needs more than 2^20 segments"));
  }
  return best;
}

}  // namespace patchwork
