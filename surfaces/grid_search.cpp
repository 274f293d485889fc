// The grid search (surfaces/patch_flatness.h): the grid of fewest cells whose bound meets a
// tolerance, by the quick bounds first and then the cell bound, and what a GridSearchMemo keeps
// of it from call to call.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/errors.h"
#include "surfaces/grid_bounds.h"
#include "surfaces/patch_flatness.h"

namespace patchwork {

namespace {

// The memo's entry of the nu x nv grid, or nullptr.
GridSearchMemo::CellBound* known_cell_bound(GridSearchMemo& memo, std::int64_t nu, std::int64_t nv) {
  auto& known = memo.cell_bounds;
  const auto entry = std::find_if(known.begin(), known.end(), [&](const auto& e) { return e.nu == nu && e.nv == nv; });
  return entry == known.end() ? nullptr : &*entry;
}

// Whether the cell bound of the nu x nv grid is at most `tolerance`, from the memo's value where
// that decides it. A grid asked about first is tested as without a memo (stopping once a box
// exceeds the tolerance); asked again where that value does not decide, its whole bound is kept.
// grid_cell_bound(d, du, dv, stop) returns the bound itself when it is at most stop, and
// otherwise a value above stop that the bound is at least: either way the comparison with the
// tolerance is that of the bound itself, so the memo's answers are the direct ones.
bool cell_bound_meets(const DirectionalBounds& d, std::int64_t nu, std::int64_t nv, double tolerance,
                      GridSearchMemo* memo) {
  const double du = 1.0 / static_cast<double>(nu);
  const double dv = 1.0 / static_cast<double>(nv);
  if (!memo) return detail::grid_cell_bound(d, du, dv, tolerance) <= tolerance;
  auto& known = memo->cell_bounds;
  GridSearchMemo::CellBound* entry = known_cell_bound(*memo, nu, nv);
  if (!entry) {
    const double value = detail::grid_cell_bound(d, du, dv, tolerance);
    if (known.size() < GridSearchMemo::most_cell_bounds) known.push_back({nu, nv, value, value <= tolerance});
    return value <= tolerance;
  }
  if (entry->exact) return entry->value <= tolerance;
  if (entry->value > tolerance) return false;
  // Asked again, at a tolerance the value known does not decide (a camera's tolerances creep):
  // the whole bound, once, so that no later tolerance needs it again.
  entry->value = detail::grid_cell_bound(d, du, dv);
  entry->exact = true;
  return entry->value <= tolerance;
}

GridSize search_grid(const SecondDerivativeBounds& M, double tolerance, std::int64_t min_segments, GridSearchMemo* memo) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    throw InvalidInput(detail::message("grid_for_tolerance: tolerance ", tolerance, " is not positive and finite"));
  }
  constexpr std::int64_t limit = std::int64_t{1} << 20;
  if (min_segments < 1 || min_segments > limit) {
    throw InvalidInput(detail::message("grid_for_tolerance: at least ", min_segments, " segments is not in [1, 2^20]"));
  }
  // The bound falls as either rate grows (both the norm and the directional bound do), so the
  // smallest rates are found by bisection and the fewest cells by one walk along N_u.
  const auto meets = [&](std::int64_t nu, std::int64_t nv) {
    return detail::quick_grid_bound(M, 1.0 / static_cast<double>(nu), 1.0 / static_cast<double>(nv)) <= tolerance;
  };
  if (!meets(limit, limit)) {
    throw InvalidInput(
        detail::message("grid_for_tolerance: tolerance ", tolerance, " needs more than 2^20 segments per side"));
  }
  // The smallest x in [min_segments, high] with ok(x), given ok(high): doubling from there, then
  // bisection (the answers are small next to 2^20, and each test is a bound).
  const auto smallest = [min_segments](std::int64_t high, const auto& ok) {
    std::int64_t low = min_segments;
    for (std::int64_t step = min_segments; step < high; step *= 2) {
      if (ok(step)) {
        high = step;
        break;
      }
      low = step + 1;
    }
    while (low < high) {
      const std::int64_t mid = low + (high - low) / 2;
      if (ok(mid)) {
        high = mid;
      } else {
        low = mid + 1;
      }
    }
    return high;
  };
  const std::int64_t first = smallest(limit, [&](std::int64_t nu) { return meets(nu, limit); });
  // N_v cannot drop below what it needs at the finest N_u; once it is there, larger N_u only costs.
  const std::int64_t floor_v = smallest(limit, [&](std::int64_t nv) { return meets(limit, nv); });
  GridSize best{-1, -1};
  std::int64_t nv = limit;  // meets(nu, nv) holds for every nu >= first
  for (std::int64_t nu = first; nu <= limit; ++nu) {
    if (nv > min_segments && meets(nu, nv - 1)) {
      nv = smallest(nv - 1, [&](std::int64_t v) { return meets(nu, v); });
    }
    const bool better = best.segments_u < 0 || nu * nv < best.segments_u * best.segments_v ||
                        (nu * nv == best.segments_u * best.segments_v &&
                         std::abs(nu - nv) < std::abs(best.segments_u - best.segments_v));
    if (better) best = {nu, nv};
    if (nv <= floor_v || nu >= best.segments_u * best.segments_v) break;
  }
  // The search used the quick bounds; the cell bound is tighter but costs some 30 times as much,
  // so it only looks for grids with fewer cells than that answer: for each N_u, the most
  // segments N_v with fewer cells, and if that meets it, the fewest that do (bisection). Most
  // candidates fail on the cell bound's value at the cells' centres alone (a few multiplies).
  // Up to 64 x 64 cells a piece: beyond, the candidates would be many and the cubic terms, which
  // the cell bound tightens most, small (h^3 against h^2).
  if (!M.directions) return best;
  constexpr std::int64_t refined_cells = std::int64_t{64} * 64;
  if (best.segments_u * best.segments_v > refined_cells) return best;
  const auto meets_cell_bound = [&](std::int64_t nu, std::int64_t nv) {
    const double du = 1.0 / static_cast<double>(nu);
    const double dv = 1.0 / static_cast<double>(nv);
    if (detail::grid_cell_centre_value(*M.directions, du, dv) > tolerance) return false;  // a lower bound of the cell bound
    if (detail::quick_grid_bound(M, du, dv) <= tolerance) return true;
    return cell_bound_meets(*M.directions, nu, nv, tolerance, memo);
  };
  for (std::int64_t nu = min_segments; nu * min_segments < best.segments_u * best.segments_v; ++nu) {
    const std::int64_t most = (best.segments_u * best.segments_v - 1) / nu;
    if (most < min_segments || !meets_cell_bound(nu, most)) continue;
    best = {nu, smallest(most, [&](std::int64_t nv) { return meets_cell_bound(nu, nv); })};
  }
  return best;
}

}  // namespace

GridSize grid_for_tolerance(const SecondDerivativeBounds& M, double tolerance, std::int64_t min_segments) {
  return search_grid(M, tolerance, min_segments, nullptr);
}

double flatness_bound(const SecondDerivativeBounds& M, std::int64_t nu, std::int64_t nv, double good_enough,
                      GridSearchMemo& memo) {
  const double du = 1.0 / static_cast<double>(nu), dv = 1.0 / static_cast<double>(nv);
  const double quick = detail::quick_grid_bound(M, du, dv);
  if (quick <= good_enough || !M.directions) return quick;
  auto& known = memo.cell_bounds;
  GridSearchMemo::CellBound* entry = known_cell_bound(memo, nu, nv);
  if (!entry) {
    if (known.size() >= GridSearchMemo::most_cell_bounds) return std::min(quick, detail::grid_cell_bound(*M.directions, du, dv));
    entry = &known.emplace_back(GridSearchMemo::CellBound{nu, nv, 0.0, false});
  }
  if (!entry->exact) {
    // The whole bound: grid_cell_bound without a stop, as flatness_bound takes it.
    entry->value = detail::grid_cell_bound(*M.directions, du, dv);
    entry->exact = true;
  }
  return std::min(quick, entry->value);
}

GridSize grid_for_tolerance(const SecondDerivativeBounds& M, double tolerance, std::int64_t min_segments,
                            GridSearchMemo& memo) {
  for (const GridSearchMemo::Answer& answer : memo.answers) {
    if (answer.tolerance == tolerance && answer.min_segments == min_segments) return answer.grid;
  }
  // Throws before anything is remembered: a failing request is not an answer.
  const GridSize grid = search_grid(M, tolerance, min_segments, &memo);
  memo.answers.insert(memo.answers.begin(), {tolerance, min_segments, grid});
  if (memo.answers.size() > 2) memo.answers.pop_back();
  return grid;
}

}  // namespace patchwork
