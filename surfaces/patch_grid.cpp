#include "surfaces/patch_grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/assert.h"
#include "core/errors.h"
#include "core/streaming_store.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

void tabulate(int degree, std::span<const double> ts, std::vector<double>& values, std::vector<double>& derivatives) {
  const std::size_t width = static_cast<std::size_t>(degree) + 1;
  values.resize(ts.size() * width);
  derivatives.resize(ts.size() * width);
  for (std::size_t k = 0; k < ts.size(); ++k) {
    bernstein_all(degree, ts[k], std::span<double>(values.data() + k * width, width));
    bernstein_all_derivatives(degree, ts[k], 1, std::span<double>(derivatives.data() + k * width, width));
  }
}

std::vector<double> uniform_parameters(std::size_t segments) {
  if (segments < 1) throw InvalidInput("PatchGridWeights::uniform: at least one segment per direction");
  std::vector<double> ts(segments + 1);
  for (std::size_t k = 0; k <= segments; ++k) ts[k] = static_cast<double>(k) / static_cast<double>(segments);
  return ts;
}

// The net contracted in one direction with weights w and their derivatives dw: in v (a row of
// fixed v: Q_i = sum_j w_j P_ij, i = 0..n) or in u (a column: Q_j = sum_i w_i P_ij, j = 0..m);
// dQ likewise with dw.
void contract(const BezierPatch3& patch, std::span<const double> w, std::span<const double> dw, bool in_v, Vec3* Q,
              Vec3* dQ) {
  const int kept = in_v ? patch.degree_u() : patch.degree_v();
  const int summed = in_v ? patch.degree_v() : patch.degree_u();
  for (int k = 0; k <= kept; ++k) {
    Vec3 q = Vec3::Zero();
    Vec3 dq = Vec3::Zero();
    for (int l = 0; l <= summed; ++l) {
      const Vec3& P = in_v ? patch.control_point(k, l) : patch.control_point(l, k);
      q += w[l] * P;
      dq += dw[l] * P;
    }
    Q[k] = q;
    dQ[k] = dq;
  }
}

// The net contracted in v at row b: Q_i = sum_j B_j^m(v_b) P_ij and dQ_i with B_j^m'.
void contract_in_v(const BezierPatch3& patch, const PatchGridWeights& weights, std::size_t b, Vec3* Q, Vec3* dQ) {
  contract(patch, weights.v_values(b), weights.v_derivatives(b), true, Q, dQ);
}

using detail::interleave;

// Scratch for one grid row in structure-of-arrays form.
struct RowScratch {
  double* px;
  double* py;
  double* pz;
  double* nx;
  double* ny;
  double* nz;
  double* regular;  // 1 where F_u x F_v is not degenerate
};

// One grid row of a patch of u-degree N: points and unit normals from the net contracted in v
// (Q, and dQ for F_v) and the u tables by index first (bu[i * count + a]), computed in
// structure-of-arrays scratch, then written as Vec3s to `points` and `normals`. Returns whether
// some point of the row is degenerate (its normal is to be redone). N is known at compile time
// so the sums over i stay in registers, and the arrays are restrict so the compiler vectorises
// across the row. The sums are those of the generic loop in evaluate_grid, in the same order,
// and without fused multiply-adds, so every instruction set gives the same bits.
template <int N>
[[gnu::always_inline]] inline bool grid_row_body(std::size_t count, const double* __restrict bu,
                                                 const double* __restrict dbu, const Vec3* __restrict Q,
                                                 const Vec3* __restrict dQ, double threshold, double sign,
                                                 double* __restrict px, double* __restrict py, double* __restrict pz,
                                                 double* __restrict nx, double* __restrict ny, double* __restrict nz,
                                                 double* __restrict regular, double* __restrict points,
                                                 double* __restrict normals) {
  double degenerate = 0.0;
  for (std::size_t a = 0; a < count; ++a) {
    double x = 0.0, y = 0.0, z = 0.0, ux = 0.0, uy = 0.0, uz = 0.0, vx = 0.0, vy = 0.0, vz = 0.0;
    for (int i = 0; i <= N; ++i) {
      const double w = bu[static_cast<std::size_t>(i) * count + a];
      const double dw = dbu[static_cast<std::size_t>(i) * count + a];
      x += w * Q[i].x();
      y += w * Q[i].y();
      z += w * Q[i].z();
      ux += dw * Q[i].x();
      uy += dw * Q[i].y();
      uz += dw * Q[i].z();
      vx += w * dQ[i].x();
      vy += w * dQ[i].y();
      vz += w * dQ[i].z();
    }
    px[a] = x;
    py[a] = y;
    pz[a] = z;
    const double cx = uy * vz - uz * vy;
    const double cy = uz * vx - ux * vz;
    const double cz = ux * vy - uy * vx;
    const double norm = std::sqrt(cx * cx + cy * cy + cz * cz);
    // No branch around the division (std::max is one), so the loop vectorises; the tiny
    // summand only keeps it finite at norm 0, and degenerate points are redone by the caller.
    const double inverse = sign / (norm + 1e-300);
    nx[a] = cx * inverse;
    ny[a] = cy * inverse;
    nz[a] = cz * inverse;
    regular[a] = norm > threshold ? 1.0 : 0.0;
    degenerate = norm > threshold ? degenerate : 1.0;
  }
  interleave(count, px, py, pz, points);
  interleave(count, nx, ny, nz, normals);
  return degenerate != 0.0;
}

template <int N>
bool grid_row_portable(std::size_t count, const double* bu, const double* dbu, const Vec3* Q, const Vec3* dQ,
                       double threshold, double sign, RowScratch row, double* points, double* normals) {
  return grid_row_body<N>(count, bu, dbu, Q, dQ, threshold, sign, row.px, row.py, row.pz, row.nx, row.ny, row.nz,
                          row.regular, points, normals);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// The same code for AVX2 (4 doubles a vector instead of SSE2's 2; no FMA: same results), chosen
// at run time where the processor has it: about twice the points per second.
#define PATCHWORK_GRID_AVX2 1
template <int N>
[[gnu::target("avx2")]] bool grid_row_avx2(std::size_t count, const double* bu, const double* dbu, const Vec3* Q,
                                           const Vec3* dQ, double threshold, double sign, RowScratch row,
                                           double* points, double* normals) {
  return grid_row_body<N>(count, bu, dbu, Q, dQ, threshold, sign, row.px, row.py, row.pz, row.nx, row.ny, row.nz,
                          row.regular, points, normals);
}

#endif

}  // namespace

namespace detail {
bool has_avx2() {
#ifdef PATCHWORK_GRID_AVX2
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return avx2;
#else
  return false;
#endif
}
}  // namespace detail

namespace {
using detail::has_avx2;

// grid_row_body, dispatched: bu and dbu are the row direction's Bernstein values and derivatives
// by index first, Q and dQ the net contracted in the other direction with its values and
// derivatives; `sign` multiplies the normal (-1 when the row runs along v, whose cross product is
// F_v x F_u).
template <int N>
bool grid_row(std::size_t count, const double* bu, const double* dbu, const Vec3* Q, const Vec3* dQ, double threshold,
              double sign, RowScratch row, double* points, double* normals, bool allow_avx2) {
#ifdef PATCHWORK_GRID_AVX2
  if (allow_avx2 && has_avx2()) return grid_row_avx2<N>(count, bu, dbu, Q, dQ, threshold, sign, row, points, normals);
#endif
  static_cast<void>(allow_avx2);
  return grid_row_portable<N>(count, bu, dbu, Q, dQ, threshold, sign, row, points, normals);
}

// A table of Bernstein rows (table(k)[i] for parameter k, index i) by index first:
// out[i * count + k], as grid_row reads it.
template <int N, class Rows>
std::vector<double> by_index(std::size_t count, const Rows& table) {
  std::vector<double> out((N + 1) * count);
  for (std::size_t k = 0; k < count; ++k) {
    for (int i = 0; i <= N; ++i) out[static_cast<std::size_t>(i) * count + k] = table(k)[static_cast<std::size_t>(i)];
  }
  return out;
}

// Structure-of-arrays scratch for rows of `count` points, and with `interleaved`, a row of
// points and one of normals as Vec3s (where rows are streamed out, evaluate_grid_rows).
struct RowBuffer {
  RowBuffer(std::size_t count, bool interleaved) : storage((interleaved ? 13 : 7) * count) {
    double* d = storage.data();
    row = {d, d + count, d + 2 * count, d + 3 * count, d + 4 * count, d + 5 * count, d + 6 * count};
    if (interleaved) {
      points = d + 7 * count;
      normals = d + 10 * count;
    }
  }
  std::vector<double> storage;
  RowScratch row{};
  double* points = nullptr;
  double* normals = nullptr;
};

// Points and unit normals (no tangents) of a patch of u-degree N, a row (fixed v) at a time.
template <int N>
void evaluate_grid_rows(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out,
                        double threshold, bool allow_avx2) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
  const std::size_t count_u = weights.us().size();
  const std::size_t count_v = weights.vs().size();
  const std::vector<double> bu = by_index<N>(count_u, [&](std::size_t a) { return weights.u_values(a); });
  const std::vector<double> dbu = by_index<N>(count_u, [&](std::size_t a) { return weights.u_derivatives(a); });
  // Streaming: each row goes to scratch first, then out with streaming stores.
  const bool stream = out.streaming;
  const RowBuffer buffer(count_u, stream);
  for (std::size_t b = 0; b < count_v; ++b) {
    std::array<Vec3, N + 1> Q;
    std::array<Vec3, N + 1> dQ;
    contract_in_v(patch, weights, b, Q.data(), dQ.data());
    double* points = stream ? buffer.points : out.points[count_u * b].data();
    double* normals = stream ? buffer.normals : out.normals[count_u * b].data();
    const bool degenerate = grid_row<N>(count_u, bu.data(), dbu.data(), Q.data(), dQ.data(), threshold, 1.0, buffer.row,
                                        points, normals, allow_avx2);
    if (degenerate) {
      for (std::size_t a = 0; a < count_u; ++a) {
        if (buffer.row.regular[a] != 0.0) continue;
        const Vec3 normal = unit_normal(patch, weights.us()[a], weights.vs()[b]);
        std::copy(normal.data(), normal.data() + 3, normals + 3 * a);
      }
    }
    if (stream) {
      stream_copy(out.points.data() + count_u * b, points, count_u * sizeof(Vec3));
      stream_copy(out.normals.data() + count_u * b, normals, count_u * sizeof(Vec3));
    }
  }
  if (stream) stream_fence();
}

// The same for a single column (one u, many v: the side of a pattern), as one row along v of
// v-degree M: the net contracted in u (R_j = sum_i B_i^n(u) P_ij, dR_j with B_i^n'), so each
// point costs a row kernel's sums instead of a contraction of the whole net.
template <int M>
void evaluate_grid_column(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out,
                          double threshold, bool allow_avx2) {
  const std::size_t count_v = weights.vs().size();
  const std::vector<double> bv = by_index<M>(count_v, [&](std::size_t b) { return weights.v_values(b); });
  const std::vector<double> dbv = by_index<M>(count_v, [&](std::size_t b) { return weights.v_derivatives(b); });
  std::array<Vec3, M + 1> R;
  std::array<Vec3, M + 1> dR;
  contract(patch, weights.u_values(0), weights.u_derivatives(0), false, R.data(), dR.data());
  const RowBuffer buffer(count_v, false);
  // Along v the kernel's cross product is F_v x F_u: sign -1 gives F_u x F_v.
  const bool degenerate = grid_row<M>(count_v, bv.data(), dbv.data(), R.data(), dR.data(), threshold, -1.0, buffer.row,
                                      out.points[0].data(), out.normals[0].data(), allow_avx2);
  if (!degenerate) return;
  for (std::size_t b = 0; b < count_v; ++b) {
    if (buffer.row.regular[b] == 0.0) out.normals[b] = unit_normal(patch, weights.us()[0], weights.vs()[b]);
  }
}

}  // namespace

PatchGridWeights::PatchGridWeights(int n, int m, std::span<const double> us, std::span<const double> vs)
    : n_(n), m_(m) {
  assign(n, m, us, vs);
}

void PatchGridWeights::assign(int n, int m, std::span<const double> us, std::span<const double> vs) {
  // Every check before the first change; the lists copied through a scratch when they are this
  // object's own (w.assign(k, l, w.us(), w.vs()) is a natural call).
  if (n < 0 || m < 0) throw InvalidInput(detail::message("PatchGridWeights: degrees (", n, ", ", m, ") are negative"));
  if (us.empty() || vs.empty()) throw InvalidInput("PatchGridWeights: empty parameter list");
  for (const std::span<const double> list : {us, vs}) {
    for (const double t : list) {
      if (!std::isfinite(t)) throw InvalidInput(detail::message("PatchGridWeights: parameter ", t, " is not finite"));
    }
  }
  const auto copy = [](std::span<const double> from, std::vector<double>& to) {
    const bool inside = !to.empty() && from.data() >= to.data() && from.data() < to.data() + to.size();
    if (!inside) {
      to.assign(from.begin(), from.end());  // keeps the storage
      return;
    }
    const std::vector<double> scratch(from.begin(), from.end());
    to = scratch;
  };
  copy(us, us_);
  copy(vs, vs_);
  n_ = n;
  m_ = m;
  tabulate(n, us_, u_values_, u_derivatives_);
  tabulate(m, vs_, v_values_, v_derivatives_);
}

PatchGridWeights PatchGridWeights::uniform(int n, int m, std::size_t segments_u, std::size_t segments_v) {
  return PatchGridWeights(n, m, uniform_parameters(segments_u), uniform_parameters(segments_v));
}

namespace {
// evaluate_grid, with the AVX2 row kernel allowed or not.
void evaluate_grid_with(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out,
                        bool allow_avx2);
}  // namespace

PatchGridSamples evaluate_grid(const BezierPatch3& patch, const PatchGridWeights& weights, bool with_tangents) {
  PatchGridSamples samples{weights.us().size(), weights.vs().size(), {}, {}, {}};
  samples.points.resize(samples.count_u * samples.count_v);
  samples.normals.resize(samples.points.size());
  if (with_tangents) samples.tangents.resize(samples.points.size());
  evaluate_grid(patch, weights, {samples.points, samples.normals, samples.tangents});
  return samples;
}

void evaluate_grid(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out) {
  evaluate_grid_with(patch, weights, out, true);
}

namespace detail {
void evaluate_grid_portable(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out) {
  evaluate_grid_with(patch, weights, out, false);
}
}  // namespace detail

namespace detail {

void check_grid_output(int n, int m, const PatchGridWeights& weights, const GridSamplesView& out) {
  if (weights.degree_u() != n || weights.degree_v() != m) {
    throw InvalidInput(message("evaluate_grid: weights of degrees (", weights.degree_u(), ", ", weights.degree_v(),
                               ") for a patch of degrees (", n, ", ", m, ")"));
  }
  const std::size_t count = weights.us().size() * weights.vs().size();
  if (out.points.size() < count || out.normals.size() < count ||
      (!out.tangents.empty() && out.tangents.size() < count)) {
    throw InvalidInput(message("evaluate_grid: room for ", std::min(out.points.size(), out.normals.size()),
                               " samples, the grid has ", count));
  }
}

}  // namespace detail

namespace {

void evaluate_grid_with(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out,
                        bool allow_avx2) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  detail::check_grid_output(n, m, weights, out);
  const std::size_t count_u = weights.us().size();
  const std::size_t count_v = weights.vs().size();
  const bool with_tangents = !out.tangents.empty();
  // Degeneracy is judged as in unit_normal.
  const detail::DegeneracyThresholds limits = detail::degeneracy_thresholds(patch);
  const double threshold = limits.normal;
  const double derivative_threshold = limits.derivative;
  // The usual degrees (the teapot's are 3) without tangents take the vectorised path.
  if (!with_tangents && count_u == 1 && count_v > 1 && m >= 1 && m <= 3) {
    if (m == 1) evaluate_grid_column<1>(patch, weights, out, threshold, allow_avx2);
    if (m == 2) evaluate_grid_column<2>(patch, weights, out, threshold, allow_avx2);
    if (m == 3) evaluate_grid_column<3>(patch, weights, out, threshold, allow_avx2);
    return;
  }
  if (!with_tangents && n >= 1 && n <= 3) {
    if (n == 1) evaluate_grid_rows<1>(patch, weights, out, threshold, allow_avx2);
    if (n == 2) evaluate_grid_rows<2>(patch, weights, out, threshold, allow_avx2);
    if (n == 3) evaluate_grid_rows<3>(patch, weights, out, threshold, allow_avx2);
    return;
  }
  std::vector<Vec3> Q(static_cast<std::size_t>(n) + 1);
  std::vector<Vec3> dQ(static_cast<std::size_t>(n) + 1);
  for (std::size_t b = 0; b < count_v; ++b) {
    contract_in_v(patch, weights, b, Q.data(), dQ.data());
    for (std::size_t a = 0; a < count_u; ++a) {
      const std::span<const double> bu = weights.u_values(a);
      const std::span<const double> dbu = weights.u_derivatives(a);
      Vec3 point = Vec3::Zero();
      Vec3 du = Vec3::Zero();
      Vec3 dv = Vec3::Zero();
      for (int i = 0; i <= n; ++i) {
        point += bu[i] * Q[i];
        du += dbu[i] * Q[i];
        dv += bu[i] * dQ[i];
      }
      detail::store_sample(patch, weights.us()[a], weights.vs()[b], point, du, dv, threshold, derivative_threshold,
                           a + count_u * b, out);
    }
  }
}

}  // namespace

}  // namespace patchwork
