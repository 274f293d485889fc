// Patches at scattered parameters (surfaces/patch_grid.h), not on a grid: evaluate_samples
// (points, normals, tangents; a tessellated piece's boundary), evaluate_point (single points of a
// bound's refinement) and evaluate_points (positions only, many at a time; the meter).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/assert.h"
#include "core/errors.h"
#include "surfaces/patch_grid.h"
#include "surfaces/surface_normal.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// evaluate_points' kernel also for AVX2 (patch_grid.cpp's grid kernels say why: no FMA, the same
// results), chosen at run time by detail::has_avx2.
#define PATCHWORK_GRID_AVX2 1
#endif

namespace patchwork {
namespace detail {

void check_samples_output(std::span<const Vec2> uvs, const GridSamplesView& out) {
  if (out.points.size() < uvs.size() || out.normals.size() < uvs.size() ||
      (!out.tangents.empty() && out.tangents.size() < uvs.size())) {
    throw InvalidInput(message("evaluate_samples: room for ", std::min(out.points.size(), out.normals.size()),
                               " samples, ", uvs.size(), " points"));
  }
  for (const Vec2& uv : uvs) {
    if (!uv.allFinite())
      throw InvalidInput(message("evaluate_samples: parameter (", uv.x(), ", ", uv.y(), ") is not finite"));
  }
}

namespace {
// values[0..d-1] of degree d - 1 raised to degree d in place (de Casteljau's recurrence
// B_i^d = (1 - t) B_i^(d-1) + t B_(i-1)^(d-1)).
void raise_bernstein_degree(int d, double t, double* values) {
  double carry = 0.0;
  for (int i = 0; i < d; ++i) {
    const double b = values[i];
    values[i] = carry + (1.0 - t) * b;
    carry = t * b;
  }
  values[d] = carry;
}
}  // namespace

void bernstein_values_and_derivatives(int n, double t, double* values, double* derivatives) {
  PATCHWORK_ASSERT(n >= 0, "a degree is not negative");
  // B_i^n' = n (B_{i-1}^{n-1} - B_i^{n-1}): the values of degree n-1 first, then both.
  values[0] = 1.0;
  for (int d = 1; d < n; ++d) raise_bernstein_degree(d, t, values);
  if (n == 0) {
    derivatives[0] = 0.0;
    return;
  }
  // values[0..n-1] now hold degree n - 1.
  for (int i = 0; i <= n; ++i) {
    const double left = i > 0 ? values[i - 1] : 0.0;
    const double right = i < n ? values[i] : 0.0;
    derivatives[i] = n * (left - right);
  }
  raise_bernstein_degree(n, t, values);
}

}  // namespace detail

namespace {

// The Bernstein sums of F, F_u and F_v for degrees (N, M), both at most 3, unrolled at compile
// time in plain doubles (Eigen's small-vector expressions were not inlined here), in two steps:
// the net's lines summed across at one parameter t (line_sums: rows i at t = v, or columns j at
// t = u), then the lines along the other parameter s (sums_along). fixed_sums takes the rows;
// samples along a side share their first step (evaluate_samples_fixed).
template <int Lines>
struct LineSums {
  std::array<std::array<double, 3>, Lines> q;   // each line summed with B_k(t)
  std::array<std::array<double, 3>, Lines> dq;  // and with B_k'(t)
};

// Rows (Rows = true: line i = P_i0 .. P_iM, t = v) or columns (line j = P_0j .. P_Nj, t = u).
template <int N, int M, bool Rows, int Lines = Rows ? N + 1 : M + 1, int Across = Rows ? M : N>
LineSums<Lines> line_sums(const std::vector<Vec3>& P, double t) {
  std::array<double, Across + 1> b;
  std::array<double, Across + 1> db;
  detail::bernstein_values_and_derivatives(Across, t, b.data(), db.data());
  LineSums<Lines> lines;
  for (int l = 0; l < Lines; ++l) {
    double q[3] = {0.0, 0.0, 0.0};
    double dq[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k <= Across; ++k) {
      const int i = Rows ? l : k;
      const int j = Rows ? k : l;
      const double* c = P[static_cast<std::size_t>(i + (N + 1) * j)].data();
      for (int x = 0; x < 3; ++x) {
        q[x] += b[static_cast<std::size_t>(k)] * c[x];
        dq[x] += db[static_cast<std::size_t>(k)] * c[x];
      }
    }
    for (std::size_t x = 0; x < 3; ++x) {
      lines.q[static_cast<std::size_t>(l)][x] = q[x];
      lines.dq[static_cast<std::size_t>(l)][x] = dq[x];
    }
  }
  return lines;
}

// F = sum_l B_l(s) q_l, its derivative along the lines' parameter s and across (from dq).
template <int Lines>
void sums_along(const LineSums<Lines>& lines, double s, Vec3& f, Vec3& along, Vec3& across) {
  std::array<double, Lines> b;
  std::array<double, Lines> db;
  detail::bernstein_values_and_derivatives(Lines - 1, s, b.data(), db.data());
  double point[3] = {0.0, 0.0, 0.0};
  double ds[3] = {0.0, 0.0, 0.0};
  double dt[3] = {0.0, 0.0, 0.0};
  for (std::size_t l = 0; l < static_cast<std::size_t>(Lines); ++l) {
    for (std::size_t x = 0; x < 3; ++x) {
      point[x] += b[l] * lines.q[l][x];
      ds[x] += db[l] * lines.q[l][x];
      dt[x] += b[l] * lines.dq[l][x];
    }
  }
  f = Vec3(point[0], point[1], point[2]);
  along = Vec3(ds[0], ds[1], ds[2]);
  across = Vec3(dt[0], dt[1], dt[2]);
}

template <int N, int M>
void fixed_sums(const std::vector<Vec3>& P, double u, double v, Vec3& f, Vec3& fu, Vec3& fv) {
  sums_along<N + 1>(line_sums<N, M, true>(P, v), u, f, fu, fv);
}

// evaluate_samples for degrees (N, M), both at most 3. A tessellated piece's boundary points
// come side by side: a run of samples with one v (a side along u) shares its row sums, a run
// with one u its column sums, so a side's point costs about half a lone point.
template <int N, int M>
void evaluate_samples_fixed(const BezierPatch3& patch, std::span<const Vec2> uvs, GridSamplesView out, double threshold,
                            double derivative_threshold) {
  const std::vector<Vec3>& P = patch.control_points();
  const auto run_end = [&](std::size_t k, int axis) {
    std::size_t end = k + 1;
    while (end < uvs.size() && uvs[end][axis] == uvs[k][axis]) ++end;
    return end;
  };
  std::size_t k = 0;
  while (k < uvs.size()) {
    Vec3 point, du, dv;
    const std::size_t same_v = run_end(k, 1);
    const std::size_t same_u = same_v == k + 1 ? run_end(k, 0) : k + 1;
    if (same_u > k + 1) {
      const LineSums<M + 1> columns = line_sums<N, M, false>(P, uvs[k].x());
      for (; k < same_u; ++k) {
        sums_along<M + 1>(columns, uvs[k].y(), point, dv, du);
        detail::store_sample(patch, uvs[k].x(), uvs[k].y(), point, du, dv, threshold, derivative_threshold, k, out);
      }
      continue;
    }
    const LineSums<N + 1> rows = line_sums<N, M, true>(P, uvs[k].y());
    for (; k < same_v; ++k) {
      sums_along<N + 1>(rows, uvs[k].x(), point, du, dv);
      detail::store_sample(patch, uvs[k].x(), uvs[k].y(), point, du, dv, threshold, derivative_threshold, k, out);
    }
  }
}

// evaluate_point for degrees (N, M), both at most 3.
template <int N, int M>
Vec3 evaluate_point_fixed(const BezierPatch3& patch, double u, double v) {
  Vec3 point, du, dv;
  fixed_sums<N, M>(patch.control_points(), u, v, point, du, dv);
  return point;
}

template <int N>
Vec3 evaluate_point_fixed_u(int m, const BezierPatch3& patch, double u, double v) {
  switch (m) {
    case 1:
      return evaluate_point_fixed<N, 1>(patch, u, v);
    case 2:
      return evaluate_point_fixed<N, 2>(patch, u, v);
    default:
      return evaluate_point_fixed<N, 3>(patch, u, v);
  }
}

template <int N>
bool evaluate_samples_fixed_u(int m, const BezierPatch3& patch, std::span<const Vec2> uvs, GridSamplesView out,
                              double threshold, double derivative_threshold) {
  switch (m) {
    case 1:
      evaluate_samples_fixed<N, 1>(patch, uvs, out, threshold, derivative_threshold);
      return true;
    case 2:
      evaluate_samples_fixed<N, 2>(patch, uvs, out, threshold, derivative_threshold);
      return true;
    case 3:
      evaluate_samples_fixed<N, 3>(patch, uvs, out, threshold, derivative_threshold);
      return true;
    default:
      return false;
  }
}

}  // namespace

Vec3 evaluate_point(const BezierPatch3& patch, double u, double v) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  if (m >= 1 && m <= 3) {
    if (n == 1) return evaluate_point_fixed_u<1>(m, patch, u, v);
    if (n == 2) return evaluate_point_fixed_u<2>(m, patch, u, v);
    if (n == 3) return evaluate_point_fixed_u<3>(m, patch, u, v);
  }
  return patch.evaluate(u, v);
}

void evaluate_samples(const BezierPatch3& patch, std::span<const Vec2> uvs, GridSamplesView out) {
  detail::check_samples_output(uvs, out);
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const detail::DegeneracyThresholds limits = detail::degeneracy_thresholds(patch);
  const double threshold = limits.normal;
  const double derivative_threshold = limits.derivative;
  // The usual degrees (the teapot's are 3) unrolled.
  if ((n == 1 && evaluate_samples_fixed_u<1>(m, patch, uvs, out, threshold, derivative_threshold)) ||
      (n == 2 && evaluate_samples_fixed_u<2>(m, patch, uvs, out, threshold, derivative_threshold)) ||
      (n == 3 && evaluate_samples_fixed_u<3>(m, patch, uvs, out, threshold, derivative_threshold))) {
    return;
  }
  for (std::size_t k = 0; k < uvs.size(); ++k) {
    const double u = uvs[k].x();
    const double v = uvs[k].y();
    Vec3 point, du, dv;
    detail::bernstein_sums(patch.control_points(), n, m, u, v, point, du, dv);
    detail::store_sample(patch, u, v, point, du, dv, threshold, derivative_threshold, k, out);
  }
}

// --- F alone at scattered points (evaluate_points) ---------------------------------------------

namespace {

// B_0^N(t) .. B_N^N(t) by bernstein_all's recursion (Satz 20), the same operations in the same
// order, so the values are bernstein_all's bit for bit.
template <int N>
[[gnu::always_inline]] inline void bernstein_values(double t, double* out) {
  const double r = 1.0 - t;
  out[0] = 1.0;
#pragma GCC unroll 4
  for (int k = 1; k <= N; ++k) {
    double previous = 0.0;  // B_{i-1}^{k-1}
#pragma GCC unroll 4
    for (int i = 0; i < k; ++i) {
      const double current = out[i];
      out[i] = r * current + t * previous;
      previous = current;
    }
    out[k] = t * previous;
  }
}

// A net of degrees (N, M) in D coordinates (3: points; 4: homogeneous, w last), coordinate by
// coordinate, so that each coefficient is one scalar across the points of a vectorised loop.
template <int N, int M, int D>
struct CoordinateNet {
  double c[D][N + 1][M + 1];
};

// A point from its coordinates h (for D = 4 homogeneous: divided by w).
template <int D>
[[gnu::always_inline]] inline void store_point(const double (&h)[D], double* x, double* y, double* z) {
  if constexpr (D == 4) {
    *x = h[0] / h[3];
    *y = h[1] / h[3];
    *z = h[2] / h[3];
  } else {
    *x = h[0];
    *y = h[1];
    *z = h[2];
  }
}

// F at `count` points (us[a], vs[a]) into coordinate arrays: Q_i = sum_j B_j^M(v) P_ij, then
// F = sum_i B_i^N(u) Q_i (with D = 4, divided by w), the sums of evaluate_grid in its order.
// Everything is unrolled (at most 4 x 4 x 4 terms) and nothing in the loop branches, so the
// compiler vectorises it across points.
template <int N, int M, int D>
[[gnu::always_inline]] inline void points_body(std::size_t count, const double* __restrict us,
                                               const double* __restrict vs, const CoordinateNet<N, M, D>& net,
                                               double* __restrict x, double* __restrict y, double* __restrict z) {
  for (std::size_t a = 0; a < count; ++a) {
    double bu[N + 1];
    double bv[M + 1];
    bernstein_values<N>(us[a], bu);
    bernstein_values<M>(vs[a], bv);
    double h[D] = {};
#pragma GCC unroll 4
    for (int i = 0; i <= N; ++i) {
      double q[D] = {};
#pragma GCC unroll 4
      for (int j = 0; j <= M; ++j) {
#pragma GCC unroll 4
        for (int c = 0; c < D; ++c) q[c] += bv[j] * net.c[c][i][j];
      }
#pragma GCC unroll 4
      for (int c = 0; c < D; ++c) h[c] += bu[i] * q[c];
    }
    store_point<D>(h, x + a, y + a, z + a);
  }
}

// The same on a row, every point at v: the net contracted in v once (the same sums, so the
// same bits), then per point only the sum over i.
template <int N, int M, int D>
[[gnu::always_inline]] inline void row_body(std::size_t count, const double* __restrict us, double v,
                                            const CoordinateNet<N, M, D>& net, double* __restrict x,
                                            double* __restrict y, double* __restrict z) {
  double bv[M + 1];
  bernstein_values<M>(v, bv);
  double q[D][N + 1];
  for (int i = 0; i <= N; ++i) {
    double sum[D] = {};
    for (int j = 0; j <= M; ++j) {
      for (int c = 0; c < D; ++c) sum[c] += bv[j] * net.c[c][i][j];
    }
    for (int c = 0; c < D; ++c) q[c][i] = sum[c];
  }
  for (std::size_t a = 0; a < count; ++a) {
    double bu[N + 1];
    bernstein_values<N>(us[a], bu);
    double h[D] = {};
#pragma GCC unroll 4
    for (int i = 0; i <= N; ++i) {
#pragma GCC unroll 4
      for (int c = 0; c < D; ++c) h[c] += bu[i] * q[c][i];
    }
    store_point<D>(h, x + a, y + a, z + a);
  }
}

// Each body as a function of its own, portable and for AVX2 (with both loops in one function,
// GCC 12 left the scattered one scalar).
template <int N, int M, int D>
void points_portable(std::size_t count, const double* us, const double* vs, const CoordinateNet<N, M, D>& net,
                     double* x, double* y, double* z) {
  points_body<N, M, D>(count, us, vs, net, x, y, z);
}

template <int N, int M, int D>
void row_portable(std::size_t count, const double* us, double v, const CoordinateNet<N, M, D>& net, double* x,
                  double* y, double* z) {
  row_body<N, M, D>(count, us, v, net, x, y, z);
}

#ifdef PATCHWORK_GRID_AVX2
template <int N, int M, int D>
[[gnu::target("avx2")]] void points_avx2(std::size_t count, const double* us, const double* vs,
                                         const CoordinateNet<N, M, D>& net, double* x, double* y, double* z) {
  points_body<N, M, D>(count, us, vs, net, x, y, z);
}

template <int N, int M, int D>
[[gnu::target("avx2")]] void row_avx2(std::size_t count, const double* us, double v, const CoordinateNet<N, M, D>& net,
                                      double* x, double* y, double* z) {
  row_body<N, M, D>(count, us, v, net, x, y, z);
}
#endif

// The points of a net of degrees (N, M) with D coordinates, a chunk at a time through
// structure-of-arrays scratch.
template <int N, int M, int D, int Dim>
void evaluate_points_fixed(const BezierPatch<Dim>& patch, std::span<const double> us, std::span<const double> vs,
                           std::span<Vec3> points, bool allow_avx2) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
  CoordinateNet<N, M, D> net;
  for (int i = 0; i <= N; ++i) {
    for (int j = 0; j <= M; ++j) {
      for (int c = 0; c < D; ++c) net.c[c][i][j] = patch.control_point(i, j)[c];
    }
  }
  constexpr std::size_t chunk = 128;
  std::array<double, chunk> x;
  std::array<double, chunk> y;
  std::array<double, chunk> z;
  for (std::size_t first = 0; first < us.size(); first += chunk) {
    const std::size_t count = std::min(chunk, us.size() - first);
    const double* u = us.data() + first;
    const double* v = vs.data() + first;
    // A chunk on one row of v (the meter's inner cells come a row at a time) takes the row body.
    const bool one_row = std::all_of(
        v, v + count, [&](double t) { return std::bit_cast<std::uint64_t>(t) == std::bit_cast<std::uint64_t>(v[0]); });
    bool done = false;
#ifdef PATCHWORK_GRID_AVX2
    if (allow_avx2 && detail::has_avx2()) {
      if (one_row) {
        row_avx2<N, M, D>(count, u, v[0], net, x.data(), y.data(), z.data());
      } else {
        points_avx2<N, M, D>(count, u, v, net, x.data(), y.data(), z.data());
      }
      done = true;
    }
#else
    static_cast<void>(allow_avx2);
#endif
    if (done) {
    } else if (one_row) {
      row_portable<N, M, D>(count, u, v[0], net, x.data(), y.data(), z.data());
    } else {
      points_portable<N, M, D>(count, u, v, net, x.data(), y.data(), z.data());
    }
    detail::interleave(count, x.data(), y.data(), z.data(), points[first].data());
  }
}

// Any degrees, point by point with bernstein_all's tables and the same sums.
template <int Dim>
void evaluate_points_generic(const BezierPatch<Dim>& patch, std::span<const double> us, std::span<const double> vs,
                             std::span<Vec3> points) {
  using Point = typename BezierPatch<Dim>::Point;
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  std::vector<double> bu(static_cast<std::size_t>(n) + 1);
  std::vector<double> bv(static_cast<std::size_t>(m) + 1);
  std::vector<Point> Q(static_cast<std::size_t>(n) + 1);
  for (std::size_t a = 0; a < us.size(); ++a) {
    bernstein_all(n, us[a], bu);
    bernstein_all(m, vs[a], bv);
    Point h = Point::Zero();
    for (int i = 0; i <= n; ++i) {
      Q[i].setZero();
      for (int j = 0; j <= m; ++j) Q[i] += bv[j] * patch.control_point(i, j);
      h += bu[i] * Q[i];
    }
    if constexpr (Dim == 4) {
      points[a] = h.template head<3>() / h[3];
    } else {
      points[a] = h;
    }
  }
}

// evaluate_points of a polynomial (Dim = 3) or homogeneous (Dim = 4) net.
template <int Dim>
void evaluate_points_with(const BezierPatch<Dim>& patch, std::span<const double> us, std::span<const double> vs,
                          std::span<Vec3> points, bool allow_avx2) {
  if (us.size() != vs.size() || points.size() < us.size()) {
    throw InvalidInput(detail::message("evaluate_points: ", us.size(), " u, ", vs.size(), " v and room for ",
                                       points.size(), " points"));
  }
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  if (n < 1 || n > 3 || m < 1 || m > 3) return evaluate_points_generic(patch, us, vs, points);
  // One kernel per degree pair (n, m) in 1..3.
  const auto fixed = [&]<int N, int M>() { evaluate_points_fixed<N, M, Dim, Dim>(patch, us, vs, points, allow_avx2); };
  const auto with_m = [&]<int N>() {
    if (m == 1) fixed.template operator()<N, 1>();
    if (m == 2) fixed.template operator()<N, 2>();
    if (m == 3) fixed.template operator()<N, 3>();
  };
  if (n == 1) with_m.template operator()<1>();
  if (n == 2) with_m.template operator()<2>();
  if (n == 3) with_m.template operator()<3>();
}

}  // namespace

void evaluate_points(const BezierPatch3& patch, std::span<const double> us, std::span<const double> vs,
                     std::span<Vec3> points) {
  evaluate_points_with(patch, us, vs, points, true);
}

void evaluate_points(const RationalBezierPatch& patch, std::span<const double> us, std::span<const double> vs,
                     std::span<Vec3> points) {
  evaluate_points_with(patch.homogeneous(), us, vs, points, true);
}

namespace detail {
template <int Dim>
void evaluate_points_portable(const BezierPatch<Dim>& net, std::span<const double> us, std::span<const double> vs,
                              std::span<Vec3> points) {
  evaluate_points_with(net, us, vs, points, false);
}
template void evaluate_points_portable<3>(const BezierPatch3&, std::span<const double>, std::span<const double>,
                                          std::span<Vec3>);
template void evaluate_points_portable<4>(const BezierPatch4&, std::span<const double>, std::span<const double>,
                                          std::span<Vec3>);
}  // namespace detail

}  // namespace patchwork
