// evaluate_grid for rational patches (surfaces/patch_grid.h).

#include <algorithm>
#include <vector>

#include "surfaces/patch_grid.h"

namespace patchwork {

void evaluate_grid(const RationalBezierPatch& patch, const PatchGridWeights& weights, GridSamplesView out) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  detail::check_grid_output(n, m, weights, out);
  const std::size_t count_u = weights.us().size();
  const std::size_t count_v = weights.vs().size();
  const BezierPatch4& H = patch.homogeneous();
  const detail::DegeneracyThresholds limits = detail::degeneracy_thresholds(patch);
  const double threshold = limits.normal;
  const double derivative_threshold = limits.derivative;
  std::vector<Vec4> Q(static_cast<std::size_t>(n) + 1);
  std::vector<Vec4> dQ(static_cast<std::size_t>(n) + 1);
  for (std::size_t b = 0; b < count_v; ++b) {
    // Q_i = sum_j B_j^m(v) H_ij and dQ_i with the derivatives B_j^m'(v).
    const std::span<const double> bv = weights.v_values(b);
    const std::span<const double> dbv = weights.v_derivatives(b);
    for (int i = 0; i <= n; ++i) {
      Q[i].setZero();
      dQ[i].setZero();
      for (int j = 0; j <= m; ++j) {
        Q[i] += bv[j] * H.control_point(i, j);
        dQ[i] += dbv[j] * H.control_point(i, j);
      }
    }
    for (std::size_t a = 0; a < count_u; ++a) {
      const std::span<const double> bu = weights.u_values(a);
      const std::span<const double> dbu = weights.u_derivatives(a);
      Vec4 h = Vec4::Zero();
      Vec4 hu = Vec4::Zero();
      Vec4 hv = Vec4::Zero();
      for (int i = 0; i <= n; ++i) {
        h += bu[i] * Q[i];
        hu += dbu[i] * Q[i];
        hv += bu[i] * dQ[i];
      }
      Vec3 point, du, dv;
      detail::project_homogeneous(h, hu, hv, point, du, dv);
      detail::store_sample(patch, weights.us()[a], weights.vs()[b], point, du, dv, threshold, derivative_threshold,
                           a + count_u * b, out);
    }
  }
}

void evaluate_samples(const RationalBezierPatch& patch, std::span<const Vec2> uvs, GridSamplesView out) {
  detail::check_samples_output(uvs, out);
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const BezierPatch4& H = patch.homogeneous();
  const detail::DegeneracyThresholds limits = detail::degeneracy_thresholds(patch);
  const double threshold = limits.normal;
  const double derivative_threshold = limits.derivative;
  for (std::size_t k = 0; k < uvs.size(); ++k) {
    const double u = uvs[k].x();
    const double v = uvs[k].y();
    Vec4 h, hu, hv;
    detail::bernstein_sums(H.control_points(), n, m, u, v, h, hu, hv);
    Vec3 point, du, dv;
    detail::project_homogeneous(h, hu, hv, point, du, dv);
    detail::store_sample(patch, u, v, point, du, dv, threshold, derivative_threshold, k, out);
  }
}

}  // namespace patchwork
