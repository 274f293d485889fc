#pragma once
// Patches moved by a translation, for the tests of what far from the origin does to float
// storage (the teapot at (1e5, -2e5, 3e4): io/gltf.h, tools/tessellate_command.h).

#include <utility>
#include <vector>

#include "core/types.h"
#include "surfaces/bezier_patch.h"

namespace patchwork::testing {

/// Every control point of every patch plus `shift` (rounded once, in double).
inline std::vector<BezierPatch3> moved(const std::vector<BezierPatch3>& patches, const Vec3& shift) {
  std::vector<BezierPatch3> out;
  for (const BezierPatch3& patch : patches) {
    std::vector<Vec3> points = patch.control_points();
    for (Vec3& p : points) p += shift;
    out.emplace_back(patch.degree_u(), patch.degree_v(), std::move(points));
  }
  return out;
}

}  // namespace patchwork::testing
