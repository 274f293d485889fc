#include "queries/patch_evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfaces/rational_bezier_patch.h"
#include "surfaces/surface_normal.h"

namespace patchwork::detail {

PartialDerivatives<3> patch_derivatives(const PatchSet& set, std::uint32_t p, double u, double v, int order) {
  if (const RationalBezierPatch* rational = set.rational(p)) return partial_derivatives(*rational, u, v, order);
  return partial_derivatives(set.control_nets()[p], u, v, order);
}

Vec3 patch_point(const PatchSet& set, std::uint32_t p, double u, double v) {
  if (const RationalBezierPatch* rational = set.rational(p)) return rational->evaluate(u, v);
  return set.control_nets()[p].evaluate(u, v);
}

Vec3 patch_unit_normal(const PatchSet& set, std::uint32_t p, double u, double v) {
  if (const RationalBezierPatch* rational = set.rational(p)) return unit_normal(*rational, u, v);
  return unit_normal(set.control_nets()[p], u, v);
}

PatchFoot newton_foot(const PatchSet& set, std::uint32_t p, double u, double v, const Vec3& q) {
  constexpr double roundoff = std::numeric_limits<double>::epsilon();
  PatchFoot best{u, v, (patch_point(set, p, u, v) - q).norm()};
  for (int iteration = 0; iteration < 40; ++iteration) {
    const PartialDerivatives<3> d = patch_derivatives(set, p, best.u, best.v, 2);
    const Vec3 r = d.at(0, 0) - q;
    const Vec2 gradient(d.at(1, 0).dot(r), d.at(0, 1).dot(r));
    Eigen::Matrix2d hessian;
    hessian(0, 0) = d.at(1, 0).squaredNorm() + d.at(2, 0).dot(r);
    hessian(1, 1) = d.at(0, 1).squaredNorm() + d.at(0, 2).dot(r);
    hessian(0, 1) = hessian(1, 0) = d.at(1, 0).dot(d.at(0, 1)) + d.at(1, 1).dot(r);
    // On an edge of the domain with the gradient pointing out, that coordinate stays fixed.
    const bool fix_u = (best.u <= 0.0 && gradient[0] > 0.0) || (best.u >= 1.0 && gradient[0] < 0.0);
    const bool fix_v = (best.v <= 0.0 && gradient[1] > 0.0) || (best.v >= 1.0 && gradient[1] < 0.0);
    Vec2 step = Vec2::Zero();
    if (fix_u && fix_v) break;
    if (fix_u || fix_v) {
      const int c = fix_u ? 1 : 0;
      const double h = hessian(c, c);
      step[c] = h > 0.0 ? -gradient[c] / h : -gradient[c] / std::max(1e-300, d.at(c == 0 ? 1 : 0, c == 0 ? 0 : 1).squaredNorm());
    } else {
      const Eigen::LLT<Eigen::Matrix2d> llt(hessian);
      if (llt.info() == Eigen::Success && hessian.determinant() > 0.0) {
        step = -llt.solve(gradient);
      } else {
        // Not convex (or a collapsed edge): a Gauss-Newton step, regularised.
        Eigen::Matrix2d gauss;
        gauss << d.at(1, 0).squaredNorm(), d.at(1, 0).dot(d.at(0, 1)), d.at(1, 0).dot(d.at(0, 1)), d.at(0, 1).squaredNorm();
        gauss.diagonal().array() += 1e-12 * std::max(1e-300, gauss.trace());
        step = -gauss.ldlt().solve(gradient);
      }
    }
    if (!step.allFinite()) break;
    step = step.cwiseMax(-0.5).cwiseMin(0.5);
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      const double nu = std::clamp(best.u + step[0], 0.0, 1.0);
      const double nv = std::clamp(best.v + step[1], 0.0, 1.0);
      const Vec3 point = patch_point(set, p, nu, nv);
      const double distance = (point - q).norm();
      // Equal up to rounding counts as no worse: at a minimum the distance is flat, and the
      // converged, orthogonal foot is the one to keep.
      if (distance <= best.distance + 8 * roundoff * (best.distance + q.cwiseAbs().maxCoeff() + point.cwiseAbs().maxCoeff())) {
        const bool moved = std::abs(nu - best.u) + std::abs(nv - best.v) > 4 * roundoff;
        best = {nu, nv, distance};
        improved = moved;
        break;
      }
      step *= 0.5;
    }
    if (!improved) break;
  }
  return best;
}

}  // namespace patchwork::detail
