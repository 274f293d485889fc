#pragma once
// A triangle mesh as a peer tessellator returns it, in the coordinates of the input patches.

#include <cstdint>
#include <vector>

#include "core/types.h"

namespace patchwork::performance {

struct PeerMesh {
  std::vector<Vec3> positions;
  /// Three vertex indices per triangle.
  std::vector<std::uint32_t> indices;

  /// Number of triangles.
  std::size_t triangle_count() const noexcept { return indices.size() / 3; }
};

}  // namespace patchwork::performance
