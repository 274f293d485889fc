#include "surfaces/prepared_surface.h"

#include <array>
#include <chrono>
#include <cmath>
#include <mutex>

#include "core/errors.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace detail {

// What a PreparedSurface holds: the cell bounds and the control diagonal from the start, the
// rest made once on first use.
struct PreparedParts {
  std::vector<std::vector<SecondDerivativeBounds>> cells;
  double control_diagonal = 0.0;
  std::once_flag tight_once;
  double tight_diagonal = 0.0;
  // Pieces by (k = 1, 2, 4) x (control, tight diagonal).
  std::array<std::once_flag, 6> pieces_once;
  std::array<std::unique_ptr<SurfacePieces>, 6> pieces;
  // The solids of the k = 1 pieces, per diagonal: filled in once, only read by the camera mode
  // with BackFaceCulling::automatic, which asks for them first.
  std::array<std::once_flag, 2> solids_once;
};

}  // namespace detail

PreparedSurface::PreparedSurface(const PatchSet& set) : set_(&set), parts_(std::make_unique<detail::PreparedParts>()) {
  parts_->cells = detail::cell_bounds(set);
  parts_->control_diagonal = set.size();
}

PreparedSurface::~PreparedSurface() = default;
PreparedSurface::PreparedSurface(PreparedSurface&&) noexcept = default;
PreparedSurface& PreparedSurface::operator=(PreparedSurface&&) noexcept = default;

const std::vector<std::vector<SecondDerivativeBounds>>& PreparedSurface::cell_bounds() const noexcept {
  return parts_->cells;
}

double PreparedSurface::tight_diagonal() const {
  std::call_once(parts_->tight_once,
                 [this] { parts_->tight_diagonal = detail::tight_or_control_diagonal(*set_, true); });
  return parts_->tight_diagonal;
}

double PreparedSurface::control_diagonal() const noexcept { return parts_->control_diagonal; }

const SurfacePieces& PreparedSurface::pieces(int k, bool tight_diagonal, bool with_solids) const {
  if (k != 1 && k != 2 && k != 4)
    throw InvalidInput(detail::message("PreparedSurface::pieces: k = ", k, " is not 1, 2 or 4"));
  if (k > 1 && !set_->t_junctions().empty()) {
    throw InvalidInput(detail::message("PreparedSurface::pieces: the set has ", set_->t_junctions().size(),
                                       " T-junctions, which split pieces do not join"));
  }
  const std::size_t slot = static_cast<std::size_t>(k == 1 ? 0 : k == 2 ? 1 : 2) * 2 + (tight_diagonal ? 1 : 0);
  const double diagonal = tight_diagonal ? this->tight_diagonal() : control_diagonal();
  std::call_once(parts_->pieces_once[slot], [&] {
    parts_->pieces[slot] = std::make_unique<SurfacePieces>(detail::pieces_of(*set_, parts_->cells, k, diagonal, false));
  });
  SurfacePieces& made = *parts_->pieces[slot];
  if (k == 1 && with_solids) {
    std::call_once(parts_->solids_once[tight_diagonal ? 1 : 0], [&] { made.solids = detail::solids_of(*set_); });
  }
  return made;
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
  const SurfacePieces& whole = prepared.pieces(1, relative, with_solids);
  // Splitting: only with a valid tolerance and no other mode (plan_patches reports the rest).
  const int modes =
      options.tolerance.has_value() + relative + options.segments.has_value() + options.camera.has_value();
  const double eps = options.tolerance ? *options.tolerance
                     : relative        ? *options.relative_tolerance * whole.diagonal
                                       : 0.0;
  const auto& cells = prepared.cell_bounds();
  int best_k = 1;
  SplitEstimate best;
  // Split pieces do not join T-junctions: such sets are tessellated whole.
  if (options.split_patches && modes == 1 && std::isfinite(eps) && eps > 0.0 && prepared.set().t_junctions().empty()) {
    try {
      best = detail::estimated_split(cells, 1, eps, options.threads);
      for (int k : {2, 4}) {
        SplitEstimate candidate = detail::estimated_split(cells, k, eps, options.threads);
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
  const SurfacePieces& chosen = best_k == 1 ? whole : prepared.pieces(best_k, relative);
  detail::Tessellator(chosen, options, planned).run(result, keep_scratch);
  result.tessellation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result.measure_seconds;
}

}  // namespace patchwork
