#include "surfaces/prepared_surface.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>

#include "core/errors.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace detail {

// What a PreparedSurface holds: the cell bounds and the control diagonal from the start, the
// rest made once on first use under `lock` (not std::call_once: libstdc++'s can hang on the call
// after one whose callable threw, GCC bug 66146, and making split pieces can throw bad_alloc).
struct PreparedParts {
  std::uint64_t identity = 0;
  std::vector<std::vector<SecondDerivativeBounds>> cells;
  double control_diagonal = 0.0;
  std::mutex lock;
  std::optional<double> tight_diagonal;
  // Pieces for k = 1, 2, 4.
  std::array<std::unique_ptr<const SurfacePieces>, 3> pieces;
  std::unique_ptr<const std::vector<std::int32_t>> solids;
};

}  // namespace detail

PreparedSurface::PreparedSurface(const PatchSet& set) : set_(&set), parts_(std::make_unique<detail::PreparedParts>()) {
  static std::atomic<std::uint64_t> made{0};
  parts_->identity = ++made;
  parts_->cells = detail::cell_bounds(set);
  parts_->control_diagonal = set.size();
}

std::uint64_t PreparedSurface::identity() const noexcept { return parts_->identity; }

PreparedSurface::~PreparedSurface() = default;
PreparedSurface::PreparedSurface(PreparedSurface&&) noexcept = default;
PreparedSurface& PreparedSurface::operator=(PreparedSurface&&) noexcept = default;

const std::vector<std::vector<SecondDerivativeBounds>>& PreparedSurface::cell_bounds() const noexcept {
  return parts_->cells;
}

double PreparedSurface::tight_diagonal() const {
  const std::lock_guard<std::mutex> guard(parts_->lock);
  if (!parts_->tight_diagonal) parts_->tight_diagonal = detail::tight_or_control_diagonal(*set_, true);
  return *parts_->tight_diagonal;
}

double PreparedSurface::control_diagonal() const noexcept { return parts_->control_diagonal; }

const SurfacePieces& PreparedSurface::pieces(int k) const {
  if (k != 1 && k != 2 && k != 4)
    throw InvalidInput(detail::message("PreparedSurface::pieces: k = ", k, " is not 1, 2 or 4"));
  if (k > 1 && !set_->t_junctions().empty()) {
    throw InvalidInput(detail::message("PreparedSurface::pieces: the set has ", set_->t_junctions().size(),
                                       " T-junctions, which split pieces do not join"));
  }
  const std::size_t slot = k == 1 ? 0 : k == 2 ? 1 : 2;
  const std::lock_guard<std::mutex> guard(parts_->lock);
  std::unique_ptr<const SurfacePieces>& made = parts_->pieces[slot];
  if (!made)
    made = std::make_unique<const SurfacePieces>(detail::pieces_of(*set_, parts_->cells, k, control_diagonal(), false));
  return *made;
}

const std::vector<std::int32_t>& PreparedSurface::solids() const {
  const std::lock_guard<std::mutex> guard(parts_->lock);
  if (!parts_->solids) parts_->solids = std::make_unique<const std::vector<std::int32_t>>(detail::solids_of(*set_));
  return *parts_->solids;
}

Tessellation tessellate(const PreparedSurface& prepared, const TessellationOptions& options) {
  return detail::fresh_tessellation(
      [&](Tessellation& result) { detail::tessellate_prepared(prepared, options, result, false); });
}

void tessellate(const PreparedSurface& prepared, const TessellationOptions& options, Tessellation& result) {
  detail::tessellate_prepared(prepared, options, result, true);
}

void detail::tessellate_prepared(const PreparedSurface& prepared, const TessellationOptions& options,
                                 Tessellation& result, bool keep_scratch) {
  using detail::SplitEstimate;
  const auto start = std::chrono::steady_clock::now();
  const bool relative = options.relative_tolerance.has_value();
  // The solids cost a volume integral per patch: only automatic back-face culling needs them.
  const bool with_solids = options.camera && options.back_face_culling == BackFaceCulling::automatic;
  const std::vector<std::int32_t>* solids = with_solids ? &prepared.solids() : nullptr;
  const SurfacePieces& whole = prepared.pieces(1);
  const double diagonal = relative ? prepared.tight_diagonal() : prepared.control_diagonal();
  // Splitting: only with a valid tolerance and no other mode (plan_patches reports the rest).
  const int modes =
      options.tolerance.has_value() + relative + options.segments.has_value() + options.camera.has_value();
  const double eps = options.tolerance ? *options.tolerance : relative ? *options.relative_tolerance * diagonal : 0.0;
  const auto& cells = prepared.cell_bounds();
  int best_k = 1;
  SplitEstimate best;
  // The per-frame call (a result passed in) keeps what its grid searches learn, per split k and
  // piece, for the next run on this surface: the bounds do not change, only the tolerances.
  std::array<std::vector<GridSearchMemo>, 3>* memos = nullptr;
  if (keep_scratch) {
    detail::TessellatorScratch& scratch = result.scratch.get();
    if (scratch.memo_owner != prepared.identity()) {
      for (auto& memo : scratch.grid_memos) memo.clear();
      scratch.memo_owner = prepared.identity();
    }
    memos = &scratch.grid_memos;
  }
  const auto memos_of = [&](int k) -> std::vector<GridSearchMemo>* {
    if (!memos) return nullptr;
    std::vector<GridSearchMemo>& memo = (*memos)[k == 1 ? 0 : k == 2 ? 1 : 2];
    memo.resize(cells.size() * static_cast<std::size_t>(k * k));
    return &memo;
  };
  // Split pieces do not join T-junctions: such sets are tessellated whole.
  if (options.split_patches && modes == 1 && std::isfinite(eps) && eps > 0.0 && prepared.set().t_junctions().empty()) {
    try {
      best = detail::estimated_split(cells, 1, eps, options.threads, memos_of(1));
      for (int k : {2, 4}) {
        SplitEstimate candidate = detail::estimated_split(cells, k, eps, options.threads, memos_of(k));
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
  const SurfacePieces& chosen = best_k == 1 ? whole : prepared.pieces(best_k);
  // The chosen pieces are in the estimate's order (patch by patch, k x k each).
  PATCHWORK_ASSERT(chosen.count == cells.size() * static_cast<std::size_t>(best_k * best_k), "pieces of the split");
  detail::Tessellator(chosen, options, planned, diagonal, solids, memos_of(best_k)).run(result, keep_scratch);
  result.tessellation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result.measure_seconds;
}

}  // namespace patchwork
