#pragma once
// The binary PatchBvh's walk for a ray, on its double boxes: the pieces a ray may reach when the
// 4-wide float tree (queries/wide_bvh.h) declines the ray, which happens where the ray starts so
// far out that floats cannot place it within the float boxes' pad.
//
// The slab test is conservative whatever the ray's distance and direction: each slab parameter
// (b - o) / d carries two roundings (gamma_2 relative, plus the least normal double where it
// underflows), so the near end is moved down and the far end up by 4u of themselves before they
// are compared (pbrt's argument, Pharr et al., 3rd ed., 3.9.2, on both ends).

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "queries/patch_bvh.h"

namespace patchwork::detail {

/// Appends to `pieces` every piece whose box the ray o + t d (t_min <= t <= t_max) may reach: a
/// superset of those whose boxes the exact ray meets.
void double_box_pieces(const PatchBvh& bvh, const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                       std::vector<std::uint32_t>& pieces);

}  // namespace patchwork::detail
