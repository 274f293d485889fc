#pragma once
// Large patch sets tessellated a batch of whole shells at a time, into one mesh.
//
// A tessellation's working memory (per-piece bounds and pieces, boundary samples, welding and
// vertex-order tables) is several times its mesh; for a scene of many separate objects it need
// not be held for all of them at once. Shells (shells(set): patches joined by shared edges and
// T-junctions) share no mesh vertex, so each batch of whole shells is tessellated on its own
// (PatchSet::subset, the set's own adjacency) and its mesh appended to the result:
//   - peak memory: the result's arrays plus one batch's working memory;
//   - every guarantee per batch, so for the whole: the error bound, the welding (no weld crosses
//     a shell), exact pole normals, thread-count independence (the batches depend on the set and
//     batch_patches alone);
//   - what differs from tessellate(set, options): each batch chooses its own split of patches
//     into pieces (surfaces/prepared_surface.h), and the vertex order is per batch.
// A relative tolerance is made absolute once, from the whole set's tight box. A camera (its
// near limit and the solids of back-face culling speak of the whole set) and atlas UVs (a cell
// per patch of the set) keep the whole set in one batch.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"

namespace patchwork {

/// tessellate_in_batches' batch size: at least this many patches a batch. A batch's working
/// memory is then a few tens of megabytes, and each batch still has work for every core.
inline constexpr std::size_t default_batch_patches = 1024;

/// The batches of `set`: its shells in their order (shells()), gathered until a batch has at
/// least batch_patches patches (the last may have fewer), each batch's patches increasing.
/// \throws InvalidInput if batch_patches is 0.
std::vector<std::vector<std::uint32_t>> tessellation_batches(const PatchSet& set, std::size_t batch_patches);

/// tessellate(set, options), one batch (tessellation_batches) at a time (see the file comment):
/// batch b is tessellated as tessellate(set.subset(batch b), options) with a relative tolerance
/// replaced by the absolute one it names for the whole set and max_triangles less the triangle
/// estimates of the batches before (the budget is checked on the tessellator's estimate, as in
/// the single run, summed over the batches; each batch's is of its own split). The mesh is the batches' meshes in order (indices and position_ids
/// shifted past the batches before), triangle_patches are the set's patches; tolerance,
/// error_bound, weld_gap and measured_error are the largest of the batches', the culled counts,
/// welded_vertices and the seconds their sums. A single batch is exactly tessellate(set, options).
/// \throws InvalidInput as tessellate(set, options) does: bad options with its messages, before
///         any batch; an error of a batch (the budget, a piece too fine) naming the batch, its
///         first patch and the estimates before it (piece numbers count within the batch); or
///         if batch_patches is 0.
Tessellation tessellate_in_batches(const PatchSet& set, const TessellationOptions& options,
                                   std::size_t batch_patches = default_batch_patches);

}  // namespace patchwork
