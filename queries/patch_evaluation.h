#pragma once
// Evaluation of one patch of a set, of its kind (polynomial or rational), without copying it:
// what the queries' Newton steps and reported normals need.

#include <cstdint>

#include "core/types.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_set.h"

namespace patchwork::detail {

/// F and its partial derivatives with a + b <= order at (u, v) of patch p.
PartialDerivatives<3> patch_derivatives(const PatchSet& set, std::uint32_t p, double u, double v, int order);

/// F(u, v) of patch p.
Vec3 patch_point(const PatchSet& set, std::uint32_t p, double u, double v);

/// The unit normal of patch p at (u, v), the limit normal at collapsed edges (surface_normal.h).
Vec3 patch_unit_normal(const PatchSet& set, std::uint32_t p, double u, double v);

/// The local minimum of |F(u, v) - q| over [0,1]^2 that projected Newton reaches from (u, v) (the
/// Hessian of the squared distance where positive definite, gradient steps where not; every step
/// halved until the distance does not grow). Returns (u, v) and the distance.
struct PatchFoot {
  double u;
  double v;
  double distance;
};
PatchFoot newton_foot(const PatchSet& set, std::uint32_t p, double u, double v, const Vec3& q);

}  // namespace patchwork::detail
