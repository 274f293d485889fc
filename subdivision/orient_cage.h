#pragma once
// Orienting a subdivision cage before it is refined. Meshes from the wild often have faces
// wound the wrong way; validate_cage() refuses a cage whose orientable components are not
// consistently oriented, because OpenSubdiv would refine every edge walked the same way by its
// two faces as a non-manifold, infinitely sharp seam. orient_cage() flips faces (reverses their
// corners after the first, meshes/orientation.h, with their face-varying indices) so that every
// orientable component is consistent, and says which faces it flipped: nothing is re-oriented
// behind the caller's back.
//
// Of the two consistent orientations of a component it keeps the one most of its faces already
// have (on a tie, that of its first face), so the fewest faces flip and a cage with a few stray
// faces comes back as its author meant it. Non-orientable components (Moebius band, Klein
// bottle) keep their winding: it decides where their seam lies, and no winding has none.

#include <cstddef>
#include <vector>

#include "meshes/ids.h"
#include "subdivision/cage.h"

namespace patchwork {

/// What orient_cage() did.
struct CageOrientation {
  /// The cage with the faces of `flipped` flipped (same vertices, faces, tags and data).
  SubdivisionCage cage;
  /// The faces that were flipped, ascending.
  std::vector<FaceId> flipped;
  /// Edge-connected components that are not orientable (kept as wound).
  std::size_t non_orientable_components = 0;
  /// Edges of those components whose two faces walk them the same way: the seams OpenSubdiv
  /// refines as non-manifold edges.
  std::size_t seam_edges = 0;
};

/// Orients every orientable component of `cage` consistently, flipping the fewest faces (see the
/// file comment). Idempotent: on a consistently oriented cage it flips nothing. Any face list is
/// accepted (edges of three or more faces join nothing here; validate_cage() refuses them).
CageOrientation orient_cage(const SubdivisionCage& cage);

}  // namespace patchwork
