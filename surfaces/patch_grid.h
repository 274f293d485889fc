#pragma once
// Evaluation of a patch on a whole (u, v) grid with precomputed Bernstein weights: the fast
// path of the tessellator. The weights of B_i^n(u), B_i^n'(u) (and likewise in v) are
// tabulated once per grid and degree and reused for every patch of those degrees. Per grid row
// v_k the net is first contracted in v (Q_i = sum_j B_j^m(v_k) P_ij and Q'_i with B_j^m'),
// then every point costs three sums over i:
//   F = sum_i B_i^n(u) Q_i,   F_u = sum_i B_i^n'(u) Q_i,   F_v = sum_i B_i^n(u) Q'_i.

#include <cstddef>
#include <span>
#include <vector>

#include "curves/bernstein.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/rational_bezier_patch.h"
#include "surfaces/surface_normal.h"

namespace patchwork {

/// Bernstein values and first derivatives of degrees (n, m) at grid parameters us x vs.
class PatchGridWeights {
 public:
  /// \throws InvalidInput if a degree is negative, a list is empty, or a parameter not finite.
  PatchGridWeights(int n, int m, std::span<const double> us, std::span<const double> vs);
  /// Re-tabulates for degrees (n, m) at us x vs, keeping the storage (a caller evaluating many
  /// small grids, such as the tessellator's patch sides, allocates once).
  /// \throws InvalidInput as the constructor.
  void assign(int n, int m, std::span<const double> us, std::span<const double> vs);
  /// A uniform grid of (segments_u + 1) x (segments_v + 1) parameters on [0,1]^2.
  static PatchGridWeights uniform(int n, int m, std::size_t segments_u, std::size_t segments_v);

  int degree_u() const noexcept { return n_; }
  int degree_v() const noexcept { return m_; }
  std::span<const double> us() const noexcept { return us_; }
  std::span<const double> vs() const noexcept { return vs_; }
  /// B_i^n(us[k]) for i = 0..n.
  std::span<const double> u_values(std::size_t k) const noexcept { return row(u_values_, n_, k); }
  /// d/du B_i^n(us[k]) for i = 0..n.
  std::span<const double> u_derivatives(std::size_t k) const noexcept { return row(u_derivatives_, n_, k); }
  /// B_j^m(vs[k]) for j = 0..m.
  std::span<const double> v_values(std::size_t k) const noexcept { return row(v_values_, m_, k); }
  /// d/dv B_j^m(vs[k]) for j = 0..m.
  std::span<const double> v_derivatives(std::size_t k) const noexcept { return row(v_derivatives_, m_, k); }

 private:
  static std::span<const double> row(const std::vector<double>& table, int degree, std::size_t k) noexcept {
    const std::size_t width = static_cast<std::size_t>(degree) + 1;
    return {table.data() + k * width, width};
  }
  int n_;
  int m_;
  std::vector<double> us_;
  std::vector<double> vs_;
  std::vector<double> u_values_;
  std::vector<double> u_derivatives_;
  std::vector<double> v_values_;
  std::vector<double> v_derivatives_;
};

/// Points and unit normals on a grid, stored row by row: sample (a, b) at a + us.size() * b.
struct PatchGridSamples {
  std::size_t count_u;
  std::size_t count_v;
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  /// Unit tangents along u with handedness w (surface_normal.h unit_tangent); empty unless asked.
  std::vector<Vec4> tangents;
};

/// Where evaluate_grid writes, in storage the caller owns (a tessellator's output arrays): one
/// slot per grid point, row by row as in PatchGridSamples.
struct GridSamplesView {
  std::span<Vec3> points;
  std::span<Vec3> normals;
  /// Empty: no tangents.
  std::span<Vec4> tangents;
  /// Write points and normals with streaming stores (core/streaming_store.h): for outputs far
  /// larger than the caches that are not read back soon (a large tessellation); the values are
  /// the same. Only the row kernel (degrees 1-3, no tangents, more than one column) streams.
  bool streaming = false;
};

/// evaluate_grid(patch, weights, with_tangents) into `out` (tangents if out.tangents is not empty).
/// \throws InvalidInput if the weights' degrees differ from the patch's, or a span of `out` is
///         shorter than the grid (tangents: empty or at least as long).
void evaluate_grid(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out);

/// evaluate_grid for a rational patch: F = H / w and its unit normals (the limit normal where
/// F_u x F_v vanishes, as at a NURBS sphere's poles) and tangents, from the homogeneous net H
/// contracted as above (F_u = (H_u - F w_u) / w, likewise F_v). Not vectorised.
/// \throws InvalidInput as evaluate_grid(BezierPatch3, ...) does.
void evaluate_grid(const RationalBezierPatch& patch, const PatchGridWeights& weights, GridSamplesView out);

/// evaluate_grid's samples at a list of parameter pairs that is no grid (a piece's boundary
/// points): sample k of `out` is at uvs[k] (tangents if out.tangents is not empty). For a few
/// points this costs far less than a grid's tables.
/// \throws InvalidInput if a parameter is not finite or a span of `out` is shorter than `uvs`
///         (tangents: empty or at least as long).
void evaluate_samples(const BezierPatch3& patch, std::span<const Vec2> uvs, GridSamplesView out);

/// F(u, v) for many single points (a bound's samples): degrees 1-3 by the Bernstein sums
/// sum_ij B_i^n(u) B_j^m(v) P_ij (nonnegative weights summing to 1 on [0,1]^2), where
/// BezierPatch::evaluate's de Casteljau costs some five times as much; other degrees by
/// BezierPatch::evaluate. \pre u, v finite.
Vec3 evaluate_point(const BezierPatch3& patch, double u, double v);

/// evaluate_samples for a rational patch (F = H / w, as its evaluate_grid).
void evaluate_samples(const RationalBezierPatch& patch, std::span<const Vec2> uvs, GridSamplesView out);

namespace detail {
/// Checks the parameters and the room in `out` for evaluate_samples. \throws InvalidInput.
void check_samples_output(std::span<const Vec2> uvs, const GridSamplesView& out);

/// B_i^n(t) and d/dt B_i^n(t) for i = 0..n into values[0..n], derivatives[0..n].
void bernstein_values_and_derivatives(int n, double t, double* values, double* derivatives);


/// F, F_u and F_v at (u, v) of the net `points` (P_ij at i + (n+1) j; Vec3 or homogeneous Vec4)
/// by the Bernstein sums: the point evaluators' loop for any degrees.
template <class Point>
void bernstein_sums(const std::vector<Point>& points, int n, int m, double u, double v, Point& f, Point& fu,
                    Point& fv) {
  thread_local std::vector<double> bu, dbu, bv, dbv;
  bu.resize(static_cast<std::size_t>(n) + 1), dbu.resize(bu.size());
  bv.resize(static_cast<std::size_t>(m) + 1), dbv.resize(bv.size());
  bernstein_values_and_derivatives(n, u, bu.data(), dbu.data());
  bernstein_values_and_derivatives(m, v, bv.data(), dbv.data());
  f.setZero(), fu.setZero(), fv.setZero();
  for (std::size_t i = 0; i < bu.size(); ++i) {
    Point q = Point::Zero();
    Point dq = Point::Zero();
    for (std::size_t j = 0; j < bv.size(); ++j) {
      q += bv[j] * points[i + bu.size() * j];
      dq += dbv[j] * points[i + bu.size() * j];
    }
    f += bu[i] * q;
    fu += dbu[i] * q;
    fv += bu[i] * dq;
  }
}

/// F = h / w and its partials from the homogeneous point h = (w F, w) and its partials (the
/// quotient rule: F_u = (h_u - F w_u) / w).
inline void project_homogeneous(const Vec4& h, const Vec4& hu, const Vec4& hv, Vec3& point, Vec3& du, Vec3& dv) {
  const double w = h[3];
  point = h.head<3>() / w;
  du = (hu.head<3>() - point * hu[3]) / w;
  dv = (hv.head<3>() - point * hv[3]) / w;
}

/// Vec3s from three coordinate arrays (vectorised: the Vec3s are packed doubles): xyz[3a + c]
/// from x[a], y[a], z[a] for a < count.
[[gnu::always_inline]] inline void interleave(std::size_t count, const double* __restrict x, const double* __restrict y,
                                              const double* __restrict z, double* __restrict xyz) {
  for (std::size_t a = 0; a < count; ++a) {
    xyz[3 * a] = x[a];
    xyz[3 * a + 1] = y[a];
    xyz[3 * a + 2] = z[a];
  }
}

/// Whether the processor runs AVX2 (x86-64; false elsewhere): the grid and point kernels take
/// their AVX2 copies then (no FMA: the same results).
bool has_avx2();

/// Checks the weights' degrees against (n, m) and the room in `out`. \throws InvalidInput.
void check_grid_output(int n, int m, const PatchGridWeights& weights, const GridSamplesView& out);

/// Stores sample `index` of `out` from F, F_u and F_v at (u, v) of `patch`: the unit normal
/// from F_u x F_v where its length exceeds `threshold`, else the limit normal; the tangent (when
/// out has tangents) from F_u where it keeps `derivative_threshold` off the normal, else
/// unit_tangent's limit.
template <class Patch>
void store_sample(const Patch& patch, double u, double v, const Vec3& point, const Vec3& du, const Vec3& dv,
                  double threshold, double derivative_threshold, std::size_t index, GridSamplesView& out) {
  out.points[index] = point;
  const Vec3 normal = du.cross(dv);
  const double length = normal.norm();
  const bool regular = length > threshold;
  const Vec3 unit = regular ? Vec3(normal / length) : degenerate_unit_normal(patch, u, v);
  out.normals[index] = unit;
  if (out.tangents.empty()) return;
  const Vec3 tangent = du - du.dot(unit) * unit;
  if (regular && tangent.norm() > derivative_threshold) {
    // Regular point: F_u lies in the tangent plane and (n x F_u) . F_v = n . (F_u x F_v) > 0.
    const Vec3 t = tangent.normalized();
    out.tangents[index] = Vec4(t.x(), t.y(), t.z(), 1.0);
  } else {
    out.tangents[index] = unit_tangent(patch, u, v, unit);
  }
}

/// evaluate_grid(patch, weights, out) without the instruction-set dispatch (AVX2 where the
/// processor has it): the reference the dispatched kernel must match bit for bit (tests).
void evaluate_grid_portable(const BezierPatch3& patch, const PatchGridWeights& weights, GridSamplesView out);
}  // namespace detail

/// F alone at scattered points: points[k] = F(us[k], vs[k]) for every k (no derivatives, no
/// normals; what the tessellator's meter samples). Per point the Bernstein values of u and v
/// come from bernstein_all's recursion, the net is contracted in v (Q_i = sum_j B_j^m(v) P_ij)
/// and F = sum_i B_i^n(u) Q_i: the sums of evaluate_grid in its order, so a point equals
/// evaluate_grid's point at the same parameters bit for bit. Degrees 1-3 run a kernel that
/// vectorises across points (AVX2 where the processor has it, without FMA: the same bits).
/// Parameters are not checked (those outside [0,1] extrapolate).
/// \throws InvalidInput if us and vs differ in length or points is shorter.
void evaluate_points(const BezierPatch3& patch, std::span<const double> us, std::span<const double> vs,
                     std::span<Vec3> points);

/// evaluate_points for a rational patch: F = H / w from the homogeneous net H, contracted as
/// above (evaluate_grid(RationalBezierPatch, ...)'s point bit for bit).
/// \throws InvalidInput as evaluate_points(BezierPatch3, ...) does.
void evaluate_points(const RationalBezierPatch& patch, std::span<const double> us, std::span<const double> vs,
                     std::span<Vec3> points);

namespace detail {
/// evaluate_points without the instruction-set dispatch, of a polynomial net (Dim = 3) or of a
/// rational patch's homogeneous net (Dim = 4: F = H / w): the reference the dispatched kernel
/// must match bit for bit (tests). Instantiated for 3 and 4.
template <int Dim>
void evaluate_points_portable(const BezierPatch<Dim>& net, std::span<const double> us, std::span<const double> vs,
                              std::span<Vec3> points);
}  // namespace detail

/// F and the unit normal at every grid point (the limit normal where F_u x F_v vanishes), and the
/// unit tangents if `with_tangents`.
/// \throws InvalidInput if the weights' degrees differ from the patch's.
PatchGridSamples evaluate_grid(const BezierPatch3& patch, const PatchGridWeights& weights, bool with_tangents = false);

}  // namespace patchwork
