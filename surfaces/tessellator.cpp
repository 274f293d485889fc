#include "surfaces/tessellator.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/parallel.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace detail {

TessellatorScratchHandle::TessellatorScratchHandle() noexcept = default;
TessellatorScratchHandle::~TessellatorScratchHandle() = default;
TessellatorScratchHandle::TessellatorScratchHandle(const TessellatorScratchHandle&) noexcept {}
TessellatorScratchHandle& TessellatorScratchHandle::operator=(const TessellatorScratchHandle&) noexcept {
  return *this;
}
TessellatorScratchHandle::TessellatorScratchHandle(TessellatorScratchHandle&&) noexcept = default;
TessellatorScratchHandle& TessellatorScratchHandle::operator=(TessellatorScratchHandle&&) noexcept = default;
TessellatorScratch& TessellatorScratchHandle::get() {
  if (!scratch_) scratch_ = std::make_unique<TessellatorScratch>();
  return *scratch_;
}
void TessellatorScratchHandle::release() noexcept { scratch_.reset(); }

// The stages in order (the header lists their files).
// Tessellates into `result`, reusing its arrays' storage.
void Tessellator::run(Tessellation& result) {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  const clock::time_point start = clock::now();
  plan_patches();
  build_edge_classes();
  // Raising only adds triangles: a plan over the budget is refused before its stitched
  // patterns are built and bounded (at a tolerance that needs billions of triangles, that
  // alone would take minutes and gigabytes).
  check_triangle_budget();
  if (!options_.segments) raise_rates_to_bounds();
  check_triangle_budget();
  number_welded_points();
  // The per-patch arrays of the last run into `result` keep their storage (a caller tessellating
  // again and again then allocates next to nothing).
  outputs_ = &result.scratch.get().outputs;
  outputs_->resize(count_);
  parallel_for(count_, options_.threads, [&](std::size_t p) {
    (*outputs_)[p].clear();
    if (!plans_[p].culled) tessellate_patch(static_cast<std::uint32_t>(p));
  });
  assemble(result);
  result.measure_seconds = 0.0;
  if (options_.measure) {
    const clock::time_point measuring = clock::now();
    result.measured_error = measure(result.mesh);
    result.measure_seconds = seconds_since(measuring);
  }
  if (options_.optimize) optimize_vertex_cache(result);
  // The vertex-fetch order also drops unused vertices (PatchOutput::unused_interior).
  if (options_.optimize || unused_interior_) optimize_vertex_fetch(result.mesh);
  if (unused_interior_) {
    const auto& ids = result.mesh.position_ids;
    result.welded_vertices = ids.empty() ? 0 : 1 + *std::max_element(ids.begin(), ids.end());
  }
  result.tessellation_seconds = seconds_since(start) - result.measure_seconds;
}

}  // namespace detail

using detail::cell_bounds;
using detail::estimated_split;
using detail::pieces_of;
using detail::SplitEstimate;
using detail::Tessellator;
using detail::tight_or_control_diagonal;

Tessellation tessellate(const SurfacePieces& pieces, const TessellationOptions& options) {
  Tessellation result;
  Tessellator(pieces, options).run(result);
  result.scratch.release();
  return result;
}

Tessellation tessellate(const PatchSet& set, const TessellationOptions& options) {
  Tessellation result;
  tessellate(set, options, result);
  result.scratch.release();
  return result;
}

void tessellate(const PatchSet& set, const TessellationOptions& options, Tessellation& result) {
  const bool relative = options.relative_tolerance.has_value();
  const std::vector<std::vector<SecondDerivativeBounds>> cells = cell_bounds(set);
  // The solids cost a volume integral per patch: only automatic back-face culling needs them.
  const bool with_solids = options.camera && options.back_face_culling == BackFaceCulling::automatic;
  const SurfacePieces whole = pieces_of(set, cells, 1, tight_or_control_diagonal(set, relative), with_solids);
  // Splitting: only with a valid tolerance and no other mode (plan_patches reports the rest).
  const int modes =
      options.tolerance.has_value() + relative + options.segments.has_value() + options.camera.has_value();
  const double eps = options.tolerance ? *options.tolerance
                     : relative        ? *options.relative_tolerance * whole.diagonal
                                       : 0.0;
  int best_k = 1;
  SplitEstimate best;
  // Split pieces do not join T-junctions: such sets are tessellated whole.
  if (options.split_patches && modes == 1 && std::isfinite(eps) && eps > 0.0 && set.t_junctions().empty()) {
    try {
      best = estimated_split(cells, 1, eps);
      for (int k : {2, 4}) {
        SplitEstimate candidate = estimated_split(cells, k, eps);
        if (candidate.cells < best.cells) best = std::move(candidate), best_k = k;
      }
    } catch (const InvalidInput&) {
      // A tolerance too fine for any grid: the whole patches give the error message.
      best_k = 1;
      best.grids.clear();
    }
  }
  // The grids found for the choice are the plan's (the same bounds at the same tolerance).
  const std::vector<GridSize>* planned = best.grids.empty() ? nullptr : &best.grids;
  if (best_k == 1) return Tessellator(whole, options, planned).run(result);
  const SurfacePieces split = pieces_of(set, cells, best_k, whole.diagonal);
  Tessellator(split, options, planned).run(result);
}

}  // namespace patchwork
