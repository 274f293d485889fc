#pragma once
// A patch set prepared for tessellating again and again: the form a renderer calls every frame.
//
// Preparing does once what every tessellation of a set needs whatever its tolerance or camera:
//   - per patch, the second-derivative bounds of its 4 x 4 sub-nets (patch_flatness.h), which
//     every rate rests on;
//   - the pieces: the whole patches with their shared and collapsed edges, T-junctions and weld
//     gaps, and the patches split 2 x 2 and 4 x 4 (SurfacePieces), with their joins;
//   - the diagonal of the surface's tight box (relative tolerances are fractions of it) and of
//     its control points' box;
//   - the solids that back-face culling relies on (a volume integral per patch).
// The split pieces, the tight box and the solids are made on first use (a set tessellated only
// at coarse tolerances never splits; only BackFaceCulling::automatic needs the solids).
//
// What a tessellation then costs is what its options change: the split choice and the grid of
// every piece at the tolerance (with a camera: each patch's tolerance and whether it is culled),
// the rates of the shared edges and the stitched patterns, the evaluation into the output, the
// vertex order. Nothing is kept from one tessellation for the next but what the Tessellation
// passed in again holds (tessellate(prepared, options, result)): its storage, and its grid memos
// (surfaces/patch_flatness.h), which name this surface by identity() and give the same grids as
// a search without them.
//
// A PreparedSurface refers to its PatchSet, which must outlive it. Tessellating does not change
// what it has made; what it makes on first use is made once, under a lock (an exception while
// making it leaves nothing made, and the next call tries again): several threads may tessellate
// one PreparedSurface at once, each into its own Tessellation. A moved-from PreparedSurface may
// only be destroyed or assigned to.

#include <memory>
#include <vector>

#include "surfaces/patch_flatness.h"
#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"

namespace patchwork {

namespace detail {
struct PreparedParts;
}  // namespace detail

class PreparedSurface {
 public:
  /// Prepares `set` (see the file comment). \pre `set` outlives this object.
  /// \throws InvalidInput if every control point of the set is the same point.
  explicit PreparedSurface(const PatchSet& set);
  /// A temporary set would not outlive its preparation.
  explicit PreparedSurface(PatchSet&&) = delete;
  explicit PreparedSurface(const PatchSet&&) = delete;
  ~PreparedSurface();
  PreparedSurface(PreparedSurface&&) noexcept;
  PreparedSurface& operator=(PreparedSurface&&) noexcept;
  PreparedSurface(const PreparedSurface&) = delete;
  PreparedSurface& operator=(const PreparedSurface&) = delete;

  /// The patch set prepared.
  const PatchSet& set() const noexcept { return *set_; }
  /// Per patch, the second-derivative bounds of its 4 x 4 sub-nets (piece i + 4 j is
  /// [i/4, (i+1)/4] x [j/4, (j+1)/4]).
  const std::vector<std::vector<SecondDerivativeBounds>>& cell_bounds() const noexcept;
  /// The diagonal of the surface's tight bounding box (made on first use).
  double tight_diagonal() const;
  /// The diagonal of the control points' box (PatchSet::size()).
  double control_diagonal() const noexcept;
  /// The pieces of the patches split k x k (k = 1: the patches; 2 and 4 made on first use); their
  /// `diagonal` is the control points' (a tessellation with a relative tolerance uses the tight
  /// one) and they carry no solids (solids() holds them).
  /// \throws InvalidInput unless k is 1, 2 or 4, or for k > 1 when the set has T-junctions.
  const SurfacePieces& pieces(int k) const;
  /// Per patch, the solid it bounds, or -1 (SurfacePieces::solids; made on first use: a volume
  /// integral per patch, which only BackFaceCulling::automatic needs).
  const std::vector<std::int32_t>& solids() const;
  /// A number no other PreparedSurface of the process has had (from 1): what a Tessellation's
  /// scratch names as the surface its memos are of.
  std::uint64_t identity() const noexcept;

 private:
  const PatchSet* set_;
  std::unique_ptr<detail::PreparedParts> parts_;
};

/// Tessellates a prepared surface (tessellator.h describes the result; the same result as
/// tessellate(prepared.set(), options), bit for bit).
/// \throws InvalidInput as tessellate(PatchSet, options).
Tessellation tessellate(const PreparedSurface& prepared, const TessellationOptions& options);

/// tessellate(prepared, options) into `result`, reusing its arrays' storage and its last plan
/// (see the file comment): the per-frame call.
/// \throws as tessellate(prepared, options), before `result` is changed.
void tessellate(const PreparedSurface& prepared, const TessellationOptions& options, Tessellation& result);

}  // namespace patchwork
