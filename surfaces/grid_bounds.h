#pragma once
// The grid bounds that the flatness bounds (patch_flatness.cpp) make and the grid search
// (grid_search.cpp) asks for, shared by the two files only (surfaces/patch_flatness.h gives
// their formulas). Internal: not installed.

#include <limits>

#include "surfaces/patch_flatness.h"

namespace patchwork::detail {

/// The cell bound's value at the centres of the diagonals of both halves of a grid cell of steps
/// (du, dv): a lower bound of grid_cell_bound, a few multiplies.
double grid_cell_centre_value(const DirectionalBounds& d, double du, double dv);

/// The bound on both triangles of every grid cell of steps (du, dv); once a half exceeds
/// `stop_above`, a value above it that the bound is at least.
double grid_cell_bound(const DirectionalBounds& d, double du, double dv,
                       double stop_above = std::numeric_limits<double>::infinity());

/// The smaller of the norm bound and the directional bound of a grid of steps (du, dv).
double quick_grid_bound(const SecondDerivativeBounds& M, double du, double dv);

}  // namespace patchwork::detail
