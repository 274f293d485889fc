#pragma once
// Patch sets the query tests share: a NURBS surface's Bezier patches joined as its knots say, and
// the teapot.

#include <string>

#include "io/bpt.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/patch_set.h"

namespace patchwork::testing {

/// The patch set of a NURBS surface (its Bezier extraction with the knots' joins).
inline PatchSet nurbs_patch_set(const NurbsSurface& surface) {
  const NurbsBezierPatches pieces = bezier_patches(surface);
  return PatchSet(pieces.patches, pieces.joins);
}

/// data/teapot.bpt, read once.
inline const PatchSet& teapot_set() {
  static const PatchSet set(read_bpt(std::string(PATCHWORK_DATA_DIR) + "/teapot.bpt"));
  return set;
}

}  // namespace patchwork::testing
