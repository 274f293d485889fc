#pragma once
// The (u, v) pattern of a tessellated patch, apart from any surface: where the points go and how
// they are joined into triangles, given an inner rate per direction and a rate per edge (the
// shape of OpenSubdiv's Bfr::Tessellation).
//
//   c3 ------- edge v1 (rate e2) ------- c2        c0 = (0,0)  c1 = (1,0)
//    |   .     .     .     .     .    |            c2 = (1,1)  c3 = (0,1)
//    |   .   inner grid N_u x N_v .   |  edge u1
//  edge u0   .     .     .     .     (rate e1)     edge k runs from corner k to corner k+1
//  (rate e3) .     .     .     .      |            counter-clockwise around the square
//    |   .     .     .     .     .    |
//   c0 ------- edge v0 (rate e0) ------- c1
//
// Points come boundary first: the four corners, then each edge's inner points (steps 1 .. e-1 in
// the direction of boundary_curve: u increasing on v0 and v1, v increasing on u0 and u1; evenly
// spaced, or evenly within each piece of an edge made of pieces, EdgeSegments), then the
// interior. So two patches sharing an edge with one rate see the same boundary points, and a
// tessellator can give them one set of vertex ids.
//
// When every edge rate equals the inner rate along it, the pattern is the N_u x N_v grid, each
// cell split along its (i, j)-(i+1, j+1) diagonal. Otherwise the inner grid keeps at least two
// segments per direction; a side whose edge rate equals the inner rate along it keeps its ring
// of grid cells, and every other side loses its ring and is stitched to the grid's outermost
// points along it by merging the two point sequences in order: every edge keeps its own rate,
// and no point lies inside another triangle's edge (no T-junctions).
// Triangles are counter-clockwise in (u, v).

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace patchwork {

/// The points of an edge made of pieces (a T-junction's long edge): piece s spans [at[s],
/// at[s+1]] of the edge's boundary_curve parameter (at.front() = 0, at.back() = 1) in rates[s]
/// even steps, so the edge's points are those of the pieces, end to end.
struct EdgeSegments {
  std::vector<double> at;
  std::vector<int> rates;
  friend bool operator==(const EdgeSegments&, const EdgeSegments&) = default;
};

/// The rates of a pattern: segments of the inner grid and of each edge (v0, u1, v1, u0).
struct PatternRates {
  int inner_u;
  int inner_v;
  std::array<int, 4> edges;
  /// Per edge, null for evenly spaced points, else its pieces (not owned; edges[k] is then the
  /// sum of their rates). A pattern with pieces is never the plain grid.
  std::array<const EdgeSegments*, 4> segments{};
};

/// The boundary_curve parameter of step `step` (0 .. rates.edges[edge]) of an edge: step / rate,
/// or along its pieces.
double edge_step_parameter(const PatternRates& rates, int edge, int step);

/// Where a pattern point lies.
struct PatternPoint {
  enum class Kind : std::uint8_t { corner, edge, interior };
  Vec2 uv;
  Kind kind;
  /// Corner 0..3 or edge 0..3 (PatchEdge order); unused for interior points.
  std::uint8_t index;
  /// Step 1 .. rate-1 along the edge, in boundary_curve direction (edge points only).
  std::int32_t step;
};

struct TessellationPattern {
  /// Corners, then edge points edge by edge, then interior points.
  std::vector<PatternPoint> points;
  /// Point indices, counter-clockwise in (u, v).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// The pattern is the plain inner grid (every edge rate equals the inner rate along it).
  bool grid;
};

/// The inner grid a pattern uses: the rates themselves for a plain grid, else at least 2 each.
struct InnerGrid {
  int u;
  int v;
  bool grid;
};

/// The inner grid of the pattern for `rates`.
InnerGrid inner_grid(const PatternRates& rates);

/// The pattern for `rates`: make_pattern_boundary's points and triangles, then the interior
/// points and the inner cells. \throws InvalidInput if a rate is < 1 or the pattern would have
/// more than 2^31 points.
TessellationPattern make_pattern(const PatternRates& rates);

/// Calls f(triangle) for the triangles of the inner cells [1, N_u - 1) x [1, N_v - 1) of an inner
/// grid N, in make_pattern's order and numbering, given the index of its first interior point.
template <class F>
void for_each_inner_triangle(const InnerGrid& inner, std::uint32_t first_interior, const F& f) {
  const auto row = static_cast<std::uint32_t>(inner.u - 1);
  for (int j = 1; j + 1 < inner.v; ++j) {
    for (int i = 1; i + 1 < inner.u; ++i) {
      const std::uint32_t a =
          first_interior + static_cast<std::uint32_t>(i - 1) + row * static_cast<std::uint32_t>(j - 1);
      f(std::array<std::uint32_t, 3>{a, a + 1, a + row + 1});
      f(std::array<std::uint32_t, 3>{a, a + row + 1, a + row});
    }
  }
}

/// The part of make_pattern(rates) that touches the boundary: the corner and edge points and
/// every triangle with a corner among them, indexed as in the whole pattern. What is left out is
/// regular: the interior points (i / N_u, j / N_v), 1 <= i < N_u, 1 <= j < N_v, row by row (N the
/// inner grid), and the cells [1, N_u - 1) x [1, N_v - 1) between them, each split along its
/// (i, j)-(i+1, j+1) diagonal; a tessellator writes those straight into its output.
/// \throws InvalidInput as make_pattern does.
TessellationPattern make_pattern_boundary(const PatternRates& rates);

/// make_pattern_boundary(rates) into `pattern`, reusing its arrays' storage.
void make_pattern_boundary(const PatternRates& rates, TessellationPattern& pattern);

/// Index of the first point of edge `edge` in a pattern with these rates (its step 1).
std::uint32_t first_edge_point(const PatternRates& rates, int edge);

}  // namespace patchwork
