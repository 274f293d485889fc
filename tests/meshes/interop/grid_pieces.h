#pragma once
// The random pieces of a triangulated grid that both cross-checks draw: pieces touch at corners
// (non-manifold vertices), yet a vertex never gets more triangles than its closed grid fan, so
// OpenMesh's and CGAL's add_face can always link the fans.

#include <rapidcheck.h>

#include <cstdint>
#include <vector>

#include "tests/meshes/interop/interop_test_meshes.h"

namespace patchwork::test {

/// Some triangles of the fan-triangulated n x m grid (n, m in [1, 5]), each rotated, all drawn
/// by RapidCheck (so a counterexample shrinks). Call inside a property.
inline FaceVertexMesh drawn_grid_pieces() {
  const auto n = *rc::gen::inRange<std::uint32_t>(1, 6);
  const auto m = *rc::gen::inRange<std::uint32_t>(1, 6);
  const auto keep = *rc::gen::container<std::vector<bool>>(2 * n * m, rc::gen::arbitrary<bool>());
  const auto rotation =
      *rc::gen::container<std::vector<std::uint32_t>>(2 * n * m, rc::gen::inRange<std::uint32_t>(0, 3));
  return grid_triangles(n, m, keep, rotation);
}

}  // namespace patchwork::test
