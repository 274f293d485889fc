#include "surfaces/patch_grid.h"

#include <algorithm>

#include "core/errors.h"
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

}  // namespace

PatchGridWeights::PatchGridWeights(int n, int m, std::span<const double> us, std::span<const double> vs)
    : n_(n), m_(m), us_(us.begin(), us.end()), vs_(vs.begin(), vs.end()) {
  if (n < 0 || m < 0) throw InvalidInput(detail::message("PatchGridWeights: degrees (", n, ", ", m, ") are negative"));
  if (us_.empty() || vs_.empty()) throw InvalidInput("PatchGridWeights: empty parameter list");
  tabulate(n, us_, u_values_, u_derivatives_);
  tabulate(m, vs_, v_values_, v_derivatives_);
}

PatchGridWeights PatchGridWeights::uniform(int n, int m, std::size_t segments_u, std::size_t segments_v) {
  return PatchGridWeights(n, m, uniform_parameters(segments_u), uniform_parameters(segments_v));
}

PatchGridSamples evaluate_grid(const BezierPatch3& patch, const PatchGridWeights& weights, bool with_tangents) {
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  if (weights.degree_u() != n || weights.degree_v() != m) {
    throw InvalidInput(detail::message("evaluate_grid: weights of degrees (", weights.degree_u(), ", ", weights.degree_v(),
                                       ") for a patch of degrees (", n, ", ", m, ")"));
  }
  PatchGridSamples samples{weights.us().size(), weights.vs().size(), {}, {}, {}};
  samples.points.resize(samples.count_u * samples.count_v);
  samples.normals.resize(samples.points.size());
  if (with_tangents) samples.tangents.resize(samples.points.size());
  std::vector<Vec3> Q(static_cast<std::size_t>(n) + 1);
  std::vector<Vec3> dQ(static_cast<std::size_t>(n) + 1);
  // Degeneracy is judged as in unit_normal: relative to the net's size.
  Eigen::AlignedBox3d box(patch.control_points().front());
  for (const Vec3& p : patch.control_points()) box.extend(p);
  const double scale = box.diagonal().norm();
  const double threshold = 1e-12 * std::max(n * m, 1) * scale * scale;
  const double derivative_threshold = 1e-12 * std::max({n, m, 1}) * scale;
  for (std::size_t b = 0; b < samples.count_v; ++b) {
    const std::span<const double> bv = weights.v_values(b);
    const std::span<const double> dbv = weights.v_derivatives(b);
    for (int i = 0; i <= n; ++i) {
      Vec3 q = Vec3::Zero();
      Vec3 dq = Vec3::Zero();
      for (int j = 0; j <= m; ++j) {
        q += bv[j] * patch.control_point(i, j);
        dq += dbv[j] * patch.control_point(i, j);
      }
      Q[i] = q;
      dQ[i] = dq;
    }
    for (std::size_t a = 0; a < samples.count_u; ++a) {
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
      const std::size_t index = a + samples.count_u * b;
      samples.points[index] = point;
      const Vec3 normal = du.cross(dv);
      const bool regular = normal.norm() > threshold;
      const Vec3 unit = regular ? normal.normalized() : unit_normal(patch, weights.us()[a], weights.vs()[b]);
      samples.normals[index] = unit;
      if (!with_tangents) continue;
      const Vec3 tangent = du - du.dot(unit) * unit;
      if (regular && tangent.norm() > derivative_threshold) {
        // Regular point: F_u lies in the tangent plane and (n x F_u) . F_v = n . (F_u x F_v) > 0.
        const Vec3 t = tangent.normalized();
        samples.tangents[index] = Vec4(t.x(), t.y(), t.z(), 1.0);
      } else {
        samples.tangents[index] = unit_tangent(patch, weights.us()[a], weights.vs()[b], unit);
      }
    }
  }
  return samples;
}

}  // namespace patchwork
