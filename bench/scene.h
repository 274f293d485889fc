#pragma once
// Scenes for the scale benchmarks: many rotated copies of one patch set.
//
// Copy k (k = 0..copies-1) is the set rotated about a unit axis by an angle, both drawn from a
// fixed generator seeded with k, then moved to cell (k mod s, k div s) of an s x s grid in the
// xy-plane (s = ceil(sqrt(copies))) whose spacing is 1.5 times the diagonal of the set's
// control-point box. Copies never touch, so a scene of c copies has c times the patches, edges
// and loops of one, and no joins between copies: the cost of tessellating it should be c times
// the cost of one.

#include <cstddef>
#include <vector>

#include "surfaces/bezier_patch.h"

namespace patchwork::bench {

/// `copies` rotated copies of `patches` on a grid (see the file comment); copy k's patches are
/// patches.size() * k .. patches.size() * (k + 1) - 1.
std::vector<BezierPatch3> rotated_copies(const std::vector<BezierPatch3>& patches, std::size_t copies);

}  // namespace patchwork::bench
