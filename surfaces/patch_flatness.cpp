#include "surfaces/patch_flatness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "surfaces/grid_bounds.h"

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

// max |d^(a+b) F / du^a dv^b| over the patch: n!/(n-a)! m!/(m-b)! times the largest forward
// difference Delta_u^a Delta_v^b of the net (zero where a degree is too low).
template <class At>
double derivative_net_bound(const At& at, int n, int m, int a, int b) {
  if (a > n || b > m) return 0.0;
  // The signed binomial coefficients of the difference operators (orders up to 4 here).
  const auto coefficients = [](int order) {
    std::array<double, 5> c{};
    double binomial = 1.0;
    for (int k = 0; k <= order; ++k) {
      c[static_cast<std::size_t>(k)] = (order - k) % 2 == 0 ? binomial : -binomial;
      binomial = binomial * (order - k) / (k + 1);
    }
    return c;
  };
  PATCHWORK_ASSERT(a <= 4 && b <= 4, "differences up to order 4");
  const std::array<double, 5> cu = coefficients(a);
  const std::array<double, 5> cv = coefficients(b);
  double scale = 1.0;
  for (int q = 0; q < a; ++q) scale *= n - q;
  for (int q = 0; q < b; ++q) scale *= m - q;
  double largest = 0.0;
  for (int j = 0; j + b <= m; ++j) {
    for (int i = 0; i + a <= n; ++i) {
      Vec3 difference = Vec3::Zero();
      for (int q = 0; q <= b; ++q) {
        for (int p = 0; p <= a; ++p) {
          difference += (cu[static_cast<std::size_t>(p)] * cv[static_cast<std::size_t>(q)]) * at(i + p, j + q);
        }
      }
      largest = std::max(largest, difference.squaredNorm());
    }
  }
  return scale * std::sqrt(largest);
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
  // Third and fourth differences: each mixed partial lies in the hull of its scaled net.
  for (int k = 0; k < 4; ++k) d.third[k] = derivative_net_bound(at, n, m, 3 - k, k);
  for (int k = 0; k < 5; ++k) d.fourth[k] = derivative_net_bound(at, n, m, 4 - k, k);
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

// The boxes cover a grid cell's lower triangle (0,0), (1,0), (1,1) (normalised: du = dv = 1),
// finer towards s = 1/2 and t = 1/2, where the second moments peak and the third vanish: there
// the bound has to be tight, elsewhere the quadratic part has room. 16 intervals a side, the
// boxes with t <= s.
constexpr std::array<double, 17> moment_cuts = {0.0,     0.125,    0.25, 0.3125,   0.375,   0.4375,
                                                0.46875, 0.484375, 0.5,  0.515625, 0.53125, 0.5625,
                                                0.625,   0.6875,   0.75, 0.875,    1.0};
constexpr std::size_t moment_boxes = 16 * 17 / 2;

// At x = (s, t), 0 <= t <= s <= 1, over each box: the range of the second moments
// (s(1-s), 2t(1-s), t(1-t)) and the largest magnitudes of the third (s(1-s)(1-2s),
// t(1-s)(1-2s), t(1-s)(1-2t), t(1-t)(1-2t)), box by box (structure of arrays: the bound's loop
// over the boxes vectorises).
struct MomentTable {
  std::array<std::array<double, moment_boxes>, 3> low;
  std::array<std::array<double, moment_boxes>, 3> high;
  std::array<std::array<double, moment_boxes>, 4> third;
};

// max |f| over [x0, x1] for f with critical points `critical`.
template <class F>
double largest_magnitude(const F& f, double x0, double x1, std::initializer_list<double> critical) {
  double largest = std::max(std::abs(f(x0)), std::abs(f(x1)));
  for (double c : critical) {
    if (c > x0 && c < x1) largest = std::max(largest, std::abs(f(c)));
  }
  return largest;
}

const MomentTable& lower_triangle_moments() {
  static const MomentTable table = [] {
    const auto variance = [](double x) { return x * (1.0 - x); };
    const auto cubic = [](double x) { return x * (1.0 - x) * (1.0 - 2.0 * x); };  // critical at 1/2 +- sqrt(3)/6
    const auto left = [](double x) { return (1.0 - x) * (1.0 - 2.0 * x); };       // critical at 3/4
    const auto right = [](double x) { return x * (1.0 - 2.0 * x); };              // critical at 1/4
    const double offset = std::sqrt(3.0) / 6.0;
    // Boxes nearest the diagonal's midpoint first: there the bound is largest, so a test against
    // a tolerance that fails tends to fail within the first few.
    std::vector<std::pair<std::size_t, std::size_t>> order;
    for (std::size_t a = 0; a + 1 < moment_cuts.size(); ++a) {
      for (std::size_t b = 0; b <= a; ++b) order.emplace_back(a, b);
    }
    const auto distance = [](const std::pair<std::size_t, std::size_t>& box) {
      const double s = 0.5 * (moment_cuts[box.first] + moment_cuts[box.first + 1]) - 0.5;
      const double t = 0.5 * (moment_cuts[box.second] + moment_cuts[box.second + 1]) - 0.5;
      return s * s + t * t;
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](const auto& x, const auto& y) { return distance(x) < distance(y); });
    MomentTable t{};
    std::size_t r = 0;
    for (const auto& [a, b] : order) {
      const double s0 = moment_cuts[a], s1 = moment_cuts[a + 1];
      const double t0 = moment_cuts[b], t1 = moment_cuts[b + 1];
      const double s_high = s0 <= 0.5 && 0.5 <= s1 ? 0.25 : std::max(variance(s0), variance(s1));
      const double t_high = t0 <= 0.5 && 0.5 <= t1 ? 0.25 : std::max(variance(t0), variance(t1));
      t.low[0][r] = std::min(variance(s0), variance(s1));
      t.low[1][r] = 2.0 * t0 * (1.0 - s1);
      t.low[2][r] = std::min(variance(t0), variance(t1));
      t.high[0][r] = s_high;
      // t(1-s) <= s(1-s) and <= t(1-t) where t <= s.
      t.high[1][r] = std::min(2.0 * t1 * (1.0 - s0), 2.0 * std::min(s_high, t_high));
      t.high[2][r] = t_high;
      t.third[0][r] = largest_magnitude(cubic, s0, s1, {0.5 - offset, 0.5 + offset});
      t.third[1][r] = t1 * largest_magnitude(left, s0, s1, {0.75});
      t.third[2][r] = (1.0 - s0) * largest_magnitude(right, t0, t1, {0.25});
      t.third[3][r] = largest_magnitude(cubic, t0, t1, {0.5 - offset, 0.5 + offset});
      ++r;
    }
    PATCHWORK_ASSERT(r == moment_boxes, "one entry per box");
    return t;
  }();
  return table;
}

// The bound on a grid cell's lower triangle (0,0), (du,0), (du,dv). At x = (s du, t dv), to
// fourth order (sum_k lambda_k d_k = 0 removes the first):
//   L(x) - F(x) = (1/2) sum_i w_i H_i(x) + (1/6) sum_j c_j mu_j T_j(x) + sum_k lambda_k R_k,
// w = (s(1-s) du^2, 2t(1-s) du dv, t(1-t) dv^2) >= 0 (so the largest Gram entries bound
// |sum w_i H_i|^2), mu the third moments of MomentTable times du^(3-j) dv^j, c = (1, 3, 3, 1),
// T the third derivatives, and |R_k| <= (1/24) sum_a C(4,a) |d^4 F / du^(4-a) dv^a| |d_ku|^(4-a)
// |d_kv|^a, whose weighted sum is at most the normalised m_1 (4-a >= 2) or m_3 (a >= 2) times
// du^(4-a) dv^a (|d_ku| <= du, |d_kv| <= dv). The directional bound's remainder puts |d_k|^3
// where the cubic moments are: they vanish at the diagonal's midpoint, where the quadratic term
// peaks, so taking the maximum of the whole sum box by box recovers most of it.
// Cloned for AVX2 (chosen at load time where the CPU has it): twice the doubles per
// instruction in the boxes' loop, the same bits (no FMA: each product and sum rounds as in the
// default clone, and nothing is contracted, -ffp-contract=off in surfaces/CMakeLists.txt, so the
// rates do not depend on the machine). x86-64 Linux only (ifunc).
#if defined(__x86_64__) && defined(__linux__)
#define PATCHWORK_AVX2_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define PATCHWORK_AVX2_CLONES
#endif
PATCHWORK_AVX2_CLONES double lower_triangle_bound(
    const DirectionalBounds& d, double du, double dv, double stop_above = std::numeric_limits<double>::infinity()) {
  const MomentTable& table = lower_triangle_moments();
  const std::array<double, 3> scale = {du * du, du * dv, dv * dv};
  // The coefficients of w_i w_j, and for each whether its largest value over a box is at the
  // boxes' high ends (g >= 0) or low ends.
  std::array<double, 6> g{};
  std::array<const double*, 6> a{};
  std::array<const double*, 6> b{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i; j < 3; ++j, ++k) {
      g[k] = (i == j ? 1.0 : 2.0) * d.gram_max[i][j] * scale[i] * scale[j];
      a[k] = g[k] >= 0.0 ? table.high[i].data() : table.low[i].data();
      b[k] = g[k] >= 0.0 ? table.high[j].data() : table.low[j].data();
    }
  }
  const std::array<double, 4> third = {d.third[0] * du * du * du / 6.0, d.third[1] * du * du * dv / 2.0,
                                       d.third[2] * du * dv * dv / 2.0, d.third[3] * dv * dv * dv / 6.0};
  const auto [fourth_u, fourth_v] = detail::fourth_order_coefficients(d.fourth, du, dv);
  // Chunks of boxes, nearest the midpoint first (MomentTable); stop once one exceeds stop_above.
  constexpr std::size_t chunk = 8;
  static_assert(moment_boxes % chunk == 0);
  double largest = 0.0;
  for (std::size_t first = 0; first < moment_boxes && largest <= stop_above; first += chunk) {
    std::array<double, chunk> q{};
    for (std::size_t m = 0; m < 6; ++m) {
      for (std::size_t r = 0; r < chunk; ++r) q[r] += g[m] * a[m][first + r] * b[m][first + r];
    }
    for (std::size_t r = 0; r < chunk; ++r) {
      const std::size_t box = first + r;
      q[r] = 0.5 * std::sqrt(std::max(q[r], 0.0)) + third[0] * table.third[0][box] + third[1] * table.third[1][box] +
             third[2] * table.third[2][box] + third[3] * table.third[3][box] + fourth_u * table.high[0][box] +
             fourth_v * table.high[2][box];
    }
    largest = std::max(largest, *std::max_element(q.begin(), q.end()));
  }
  return largest;
}

}  // namespace

namespace detail {

std::array<double, 2> fourth_order_coefficients(const std::array<double, 5>& f, double du, double dv) {
  // Term a: C(4, a) f_a du^(4-a) dv^a |d_ku/du|^(4-a) |d_kv/dv|^a; the normalised offsets are at
  // most 1, so the product is at most (d_ku/du)^2 where 4-a >= 2 and (d_kv/dv)^2 where a >= 2,
  // whose weighted sums are the normalised m_1 and m_3.
  return {(f[0] * du * du + 4.0 * f[1] * du * dv + 6.0 * f[2] * dv * dv) * du * du / 24.0,
          (4.0 * f[3] * du * dv + f[4] * dv * dv) * dv * dv / 24.0};
}

}  // namespace detail

namespace {

// The bounds of the patch with u and v swapped.
DirectionalBounds transposed(const DirectionalBounds& d) {
  DirectionalBounds t = d;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      t.gram_max[i][j] = d.gram_max[2 - i][2 - j];
      t.gram_min[i][j] = d.gram_min[2 - i][2 - j];
    }
  }
  std::reverse(t.third.begin(), t.third.end());
  std::reverse(t.fourth.begin(), t.fourth.end());
  return t;
}

}  // namespace

namespace detail {

// The cell bound's value at the centres of the cell's diagonal on both halves, where the second
// moments are (du^2/4, du dv/2, dv^2/4) and the third vanish: no larger than the cell bound (the
// box holding that point bounds it from above), so a grid whose centre value exceeds a tolerance
// cannot meet it.
double grid_cell_centre_value(const DirectionalBounds& d, double du, double dv) {
  const std::array<double, 3> w = {du * du / 4.0, du * dv / 2.0, dv * dv / 4.0};
  double q = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) q += d.gram_max[i][j] * w[i] * w[j];
  }
  return 0.5 * std::sqrt(std::max(q, 0.0));
}

// The bound on both triangles of a grid cell: the upper one (0,0), (du,dv), (0,dv) is the lower
// one of the patch with u and v swapped. Stops (with a value above it) once one half exceeds
// stop_above: a test against a tolerance that fails mostly fails on the first half.
double grid_cell_bound(const DirectionalBounds& d, double du, double dv, double stop_above) {
  const double lower = lower_triangle_bound(d, du, dv, stop_above);
  if (lower > stop_above) return lower;
  return std::max(lower, lower_triangle_bound(transposed(d), dv, du, stop_above));
}

// The norm bound and the directional bound of a grid: quick, for searching.
double quick_grid_bound(const SecondDerivativeBounds& M, double du, double dv) {
  const double norms = (M.uu * du * du + 2.0 * M.uv * du * dv + M.vv * dv * dv) / 8.0;
  // Grid triangles have their vertices ordered alike in u and v: m_2 >= 0.
  return M.directions ? std::min(norms, directional_bound(*M.directions, du, dv, 1)) : norms;
}

}  // namespace detail

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
    for (int k = 0; k < 5; ++k) d.fourth[k] = std::max(d.fourth[k], b.directions->fourth[k]);
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
    for (double& f : d.fourth) f *= s2 * s2;
    scaled.directions = d;
  }
  return scaled;
}

namespace {

// The control points of a degree-n Bezier segment over [t0, t1] are linear in the whole curve's:
// Q_i = sum_k S(i, k) P_k, Q_i the blossom at (t0 x (n - i), t1 x i). Each column of S is that
// blossom of the k-th unit control polygon, by de Casteljau steps at those parameters.
template <class Matrix>
Matrix segment_matrix(int n, double t0, double t1) {
  Matrix S(n + 1, n + 1);
  std::array<double, 66> work{};  // n <= 64 (BPT's degree limit; larger nets take the heap path)
  std::vector<double> heap;
  double* w = work.data();
  if (n + 1 > static_cast<int>(work.size())) {
    heap.resize(static_cast<std::size_t>(n) + 1);
    w = heap.data();
  }
  for (int k = 0; k <= n; ++k) {
    for (int i = 0; i <= n; ++i) {
      std::fill(w, w + n + 1, 0.0);
      w[k] = 1.0;
      for (int step = 0; step < n; ++step) {
        const double t = step < n - i ? t0 : t1;
        for (int j = 0; j + step < n; ++j) w[j] = (1.0 - t) * w[j] + t * w[j + 1];
      }
      S(i, k) = w[0];
    }
  }
  return S;
}

// piece_second_derivative_bounds on nets held in `Matrix` (the heap for any degree, the stack up
// to degree 7 in both directions: a patch set's pieces are mostly bicubic). The products are
// Eigen's coefficient-wise ones either way (the sizes stay below its GEMM threshold), so the
// bounds are the same bit for bit.
template <class Matrix>
std::vector<SecondDerivativeBounds> piece_bounds(const BezierPatch3& patch, int pieces) {
  // The net of piece (a, b) is S_a P S_b^T per coordinate (segment matrices in u and v): the same
  // points as de Casteljau sub-patches, without building a patch per piece.
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  std::array<Matrix, 3> net;
  for (int c = 0; c < 3; ++c) {
    net[c].resize(n + 1, m + 1);
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) net[c](i, j) = patch.control_point(i, j)[c];
    }
  }
  std::vector<Matrix> su;
  std::vector<Matrix> sv;
  su.reserve(static_cast<std::size_t>(pieces));
  sv.reserve(static_cast<std::size_t>(pieces));
  for (int a = 0; a < pieces; ++a) {
    su.push_back(segment_matrix<Matrix>(n, static_cast<double>(a) / pieces, static_cast<double>(a + 1) / pieces));
    sv.push_back(
        segment_matrix<Matrix>(m, static_cast<double>(a) / pieces, static_cast<double>(a + 1) / pieces).transpose());
  }
  std::vector<SecondDerivativeBounds> bounds(static_cast<std::size_t>(pieces) * static_cast<std::size_t>(pieces));
  std::array<Matrix, 3> row;
  std::array<Matrix, 3> piece;
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

}  // namespace

std::vector<SecondDerivativeBounds> piece_second_derivative_bounds(const BezierPatch3& patch, int pieces) {
  if (pieces < 1 || pieces > 64) {
    throw InvalidInput(detail::message("second_derivative_bounds: ", pieces, " pieces is not in [1, 64]"));
  }
  if (pieces == 1) return {second_derivative_bounds(patch)};
  if (patch.degree_u() <= 7 && patch.degree_v() <= 7) {
    return piece_bounds<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 8, 8>>(patch, pieces);
  }
  return piece_bounds<Eigen::MatrixXd>(patch, pieces);
}

SecondDerivativeBounds merged_bounds(const std::vector<SecondDerivativeBounds>& bounds) {
  PATCHWORK_ASSERT(!bounds.empty(), "bounds of at least one domain");
  SecondDerivativeBounds M = bounds.front();
  for (const SecondDerivativeBounds& piece : bounds) M = merged_bounds(M, piece);
  return M;
}

SecondDerivativeBounds second_derivative_bounds(const BezierPatch3& patch, int pieces) {
  return merged_bounds(piece_second_derivative_bounds(patch, pieces));
}

double flatness_bound(const SecondDerivativeBounds& M, double du, double dv, double good_enough) {
  if (!(du > 0.0 && du <= 1.0 && dv > 0.0 && dv <= 1.0)) {
    throw InvalidInput(detail::message("flatness_bound: steps (", du, ", ", dv, ") are not in (0, 1]"));
  }
  const double quick = detail::quick_grid_bound(M, du, dv);
  if (quick <= good_enough || !M.directions) return quick;
  return std::min(quick, detail::grid_cell_bound(*M.directions, du, dv));
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

namespace {

// refined_triangle_flatness_bound on part p of the triangle, with the surface f and the
// triangle's interpolant l at the part's corners: on the part, |F - L| <= |F - L_p| + |L_p - L|,
// and the second, linear, is largest at a corner. L stays the whole triangle's (offsets from the
// parts' own interpolants would add up level by level instead of tending to the true maximum).
double refined_bound(const SecondDerivativeBounds& M, const std::function<Vec3(const Vec2&)>& surface,
                     const std::array<Vec2, 3>& p, const std::array<Vec3, 3>& f, const std::array<Vec3, 3>& l,
                     double aspect, double target, int depth) {
  const double offset = std::max({(f[0] - l[0]).norm(), (f[1] - l[1]).norm(), (f[2] - l[2]).norm()});
  const double bound = offset + triangle_flatness_bound(M, p[0], p[1], p[2], aspect);
  if (bound <= target || depth <= 0) return bound;
  std::array<Vec2, 3> mid;
  std::array<Vec3, 3> f_mid;
  std::array<Vec3, 3> l_mid;
  for (int k = 0; k < 3; ++k) {
    const int next = (k + 1) % 3;
    mid[k] = 0.5 * (p[k] + p[next]);
    f_mid[k] = surface(mid[k]);
    l_mid[k] = 0.5 * (l[k] + l[next]);
  }
  double worst = refined_bound(M, surface, mid, f_mid, l_mid, aspect, target, depth - 1);
  for (int k = 0; k < 3 && worst <= target; ++k) {
    const int previous = (k + 2) % 3;
    worst = std::max(worst, refined_bound(M, surface, {p[k], mid[k], mid[previous]}, {f[k], f_mid[k], f_mid[previous]},
                                          {l[k], l_mid[k], l_mid[previous]}, aspect, target, depth - 1));
  }
  // Parts not visited once one misses the target leave only the unsplit bound standing.
  return worst <= target ? std::min(bound, worst) : bound;
}

}  // namespace

double refined_triangle_flatness_bound(const SecondDerivativeBounds& M, const std::function<Vec3(const Vec2&)>& surface,
                                       const Vec2& p0, const Vec2& p1, const Vec2& p2, double aspect, double target,
                                       int depth) {
  const std::array<Vec3, 3> corners = {surface(p0), surface(p1), surface(p2)};
  return refined_bound(M, surface, {p0, p1, p2}, corners, corners, aspect, target, depth);
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

}  // namespace patchwork
