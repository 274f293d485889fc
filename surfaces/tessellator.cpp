#include "surfaces/tessellator.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/parallel.h"
#include "surfaces/prepared_surface.h"
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
void Tessellator::run(Tessellation& result, bool keep_scratch) {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };
  const clock::time_point start = clock::now();
  plan_patches();
  build_edge_classes();
  // Raising only adds triangles: a plan over the budget is refused before its stitched
  // patterns are built and bounded (at a tolerance that needs billions of triangles, that
  // alone would take minutes and gigabytes).
  check_triangle_budget();
  if (!options_.segments) raise_rates_to_bounds();
  result.scratch.get().estimated_triangles = check_triangle_budget();
  number_welded_points();
  // The per-patch arrays of the last run into `result` keep their storage (a caller tessellating
  // again and again then allocates next to nothing).
  outputs_ = &result.scratch.get().outputs;
  outputs_->resize(count_);
  parallel_for(count_, options_.threads, [&](std::size_t p) { (*outputs_)[p].clear(); });
  assign_patterns(result.scratch.get().patterns);
  // Boundary points are evaluated by their owners, then shared (share_samples).
  sharing_samples_ = static_cast<bool>(pieces_.evaluate_samples);
  sample_owners_ = &result.scratch.get().sample_owners;
  sample_owners_->assign(sharing_samples_ ? boundary_ids_ : 0, ~std::uint64_t{0});
  parallel_for(count_, options_.threads, [&](std::size_t p) {
    if (!plans_[p].culled) tessellate_patch(static_cast<std::uint32_t>(p));
  });
  if (sharing_samples_) {
    parallel_for(count_, options_.threads, [&](std::size_t p) {
      if (!plans_[p].culled) share_samples(static_cast<std::uint32_t>(p));
    });
  }
  assemble(result);
  result.measure_seconds = 0.0;
  if (options_.measure) {
    const clock::time_point measuring = clock::now();
    result.measured_error = measure(result.mesh);
    result.measure_seconds = seconds_since(measuring);
  }
  // The vertex order's arrays stay with a result that is passed in again; else they are made
  // after the rest of the scratch is freed, and freed with the run.
  VertexOrderScratch one_run_order;
  VertexOrderScratch* order = keep_scratch ? &result.scratch.get().order : &one_run_order;
  if (!keep_scratch) {
    result.scratch.release();
    outputs_ = nullptr;
    welded_positions_ = nullptr;
    sample_owners_ = nullptr;
    std::vector<PatchPlan>().swap(plans_);
    std::vector<std::array<EdgeSlot, 4>>().swap(slots_);
    std::vector<CompositeEdge>().swap(composites_);
    std::vector<EdgeClass>().swap(classes_);
    std::vector<std::uint32_t>().swap(corner_ids_);
    std::vector<bool>().swap(corner_owner_);
    std::vector<std::uint32_t>().swap(interior_first_);
  }
  if (options_.optimize) optimize_vertex_cache(result, *order, options_.threads);
  // The vertex-fetch order also drops unused vertices (PatchOutput::unused_interior).
  if (options_.optimize || unused_interior_) optimize_vertex_fetch(result.mesh, *order, options_.threads);
  if (unused_interior_) {
    const auto& ids = result.mesh.position_ids;
    result.welded_vertices = ids.empty() ? 0 : 1 + *std::max_element(ids.begin(), ids.end());
  }
  result.tessellation_seconds = seconds_since(start) - result.measure_seconds;
}

}  // namespace detail

namespace {

// tessellate(set, options, result), preparing the set first (timed with the rest).
void tessellate_set(const PatchSet& set, const TessellationOptions& options, Tessellation& result, bool keep_scratch) {
  const auto start = std::chrono::steady_clock::now();
  const PreparedSurface prepared(set);
  detail::tessellate_prepared(prepared, options, result, keep_scratch);
  result.tessellation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result.measure_seconds;
}

}  // namespace

Tessellation tessellate(const SurfacePieces& pieces, const TessellationOptions& options) {
  return detail::fresh_tessellation(
      [&](Tessellation& result) { detail::Tessellator(pieces, options).run(result, false); });
}

Tessellation tessellate(const PatchSet& set, const TessellationOptions& options) {
  return detail::fresh_tessellation([&](Tessellation& result) { tessellate_set(set, options, result, false); });
}

void tessellate(const PatchSet& set, const TessellationOptions& options, Tessellation& result) {
  tessellate_set(set, options, result, true);
}

}  // namespace patchwork
