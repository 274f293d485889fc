#include "surfaces/tessellation_pattern.h"

#include <algorithm>
#include <functional>
#include <numeric>

#include "core/assert.h"
#include "core/errors.h"

namespace patchwork {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// Point indices of a pattern: corners 0..3, then the edges' inner points, then the interior
// grid (i, j), 1 <= i < inner_u, 1 <= j < inner_v, row by row.
class PatternIndex {
 public:
  // inner_v: the interior's rows need no count to be numbered (row j starts (inner_u - 1) j in).
  PatternIndex(const PatternRates& rates, int inner_u, int /*inner_v*/) : inner_u_(inner_u) {
    std::uint32_t offset = 4;
    for (int k = 0; k < 4; ++k) {
      edge_offset_[k] = offset;
      offset += static_cast<std::uint32_t>(rates.edges[k] - 1);
    }
    interior_offset_ = offset;
  }
  std::uint32_t corner(int c) const { return static_cast<std::uint32_t>(c); }
  std::uint32_t edge(int k, int step) const { return edge_offset_[k] + static_cast<std::uint32_t>(step - 1); }
  std::uint32_t interior(int i, int j) const {
    return interior_offset_ + static_cast<std::uint32_t>((i - 1) + (inner_u_ - 1) * (j - 1));
  }
  std::uint32_t interior_offset() const { return interior_offset_; }

 private:
  int inner_u_;
  std::array<std::uint32_t, 4> edge_offset_{};
  std::uint32_t interior_offset_ = 0;
};

double ratio(int k, int n) { return static_cast<double>(k) / static_cast<double>(n); }

void add_boundary_points(const PatternRates& rates, std::vector<PatternPoint>& points) {
  const std::array<Vec2, 4> corners = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int c = 0; c < 4; ++c)
    points.push_back({corners[c], PatternPoint::Kind::corner, static_cast<std::uint8_t>(c), 0});
  for (int k = 0; k < 4; ++k) {
    const int e = rates.edges[k];
    for (int step = 1; step < e; ++step) {
      const double t = edge_step_parameter(rates, k, step);
      // boundary_curve directions: v0 and v1 along increasing u, u1 and u0 along increasing v.
      const Vec2 uv = k == 0 ? Vec2(t, 0) : k == 1 ? Vec2(1, t) : k == 2 ? Vec2(t, 1) : Vec2(0, t);
      points.push_back({uv, PatternPoint::Kind::edge, static_cast<std::uint8_t>(k), step});
    }
  }
}

void add_interior_points(int inner_u, int inner_v, std::vector<PatternPoint>& points) {
  for (int j = 1; j < inner_v; ++j) {
    for (int i = 1; i < inner_u; ++i) {
      points.push_back({Vec2(ratio(i, inner_u), ratio(j, inner_v)), PatternPoint::Kind::interior, 0, 0});
    }
  }
}

// The cells [i0, i1) x [j0, j1) of a grid whose point (i, j) has index at(i, j).
template <class At>
void add_grid_cells(int i0, int i1, int j0, int j1, const At& at, std::vector<Triangle>& triangles) {
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

// Joins the outer points (at positions `along` in [0, 1] counter-clockwise along the side) to the
// inner points (positions (offset + t) / inner_rate, t = 0 .. inner.size() - 1) by advancing, at
// each step, along the sequence whose next point comes first. Both run counter-clockwise, the
// inner row inside.
void stitch_side(const std::vector<std::uint32_t>& outer, const std::vector<double>& along,
                 const std::vector<std::uint32_t>& inner, int inner_rate, int offset, std::vector<Triangle>& triangles) {
  const std::size_t a = outer.size() - 1;
  const std::size_t b = inner.size() - 1;
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a || j < b) {
    const double next_outer = i < a ? along[i + 1] : 2.0;  // past the end: the inner row goes on
    const double next_inner = ratio(offset + static_cast<int>(j + 1), inner_rate);
    if (j == b || (i < a && next_outer <= next_inner)) {
      triangles.push_back({outer[i], outer[i + 1], inner[j]});
      ++i;
    } else {
      triangles.push_back({outer[i], inner[j + 1], inner[j]});
      ++j;
    }
  }
}

}  // namespace

double edge_step_parameter(const PatternRates& rates, int edge, int step) {
  const EdgeSegments* pieces = rates.segments[static_cast<std::size_t>(edge)];
  if (pieces == nullptr) return ratio(step, rates.edges[static_cast<std::size_t>(edge)]);
  for (std::size_t s = 0; s < pieces->rates.size(); ++s) {
    const int rate = pieces->rates[s];
    if (step <= rate || s + 1 == pieces->rates.size()) {
      // The piece's own ends exactly, so that a junction is where its parts meet.
      if (step == rate) return pieces->at[s + 1];
      return pieces->at[s] + (pieces->at[s + 1] - pieces->at[s]) * ratio(step, rate);
    }
    step -= rate;
  }
  return 1.0;
}

InnerGrid inner_grid(const PatternRates& rates) {
  const bool evenly = std::all_of(rates.segments.begin(), rates.segments.end(), [](const EdgeSegments* p) { return p == nullptr; });
  const bool grid = evenly && rates.edges[0] == rates.inner_u && rates.edges[2] == rates.inner_u &&
                    rates.edges[1] == rates.inner_v && rates.edges[3] == rates.inner_v;
  if (grid) return {rates.inner_u, rates.inner_v, true};
  return {std::max(rates.inner_u, 2), std::max(rates.inner_v, 2), false};
}

std::uint32_t first_edge_point(const PatternRates& rates, int edge) {
  return PatternIndex(rates, std::max(rates.inner_u, 2), std::max(rates.inner_v, 2)).edge(edge, 1);
}

TessellationPattern make_pattern_boundary(const PatternRates& rates) {
  TessellationPattern pattern;
  make_pattern_boundary(rates, pattern);
  return pattern;
}

void make_pattern_boundary(const PatternRates& rates, TessellationPattern& pattern) {
  if (rates.inner_u < 1 || rates.inner_v < 1 ||
      std::any_of(rates.edges.begin(), rates.edges.end(), [](int e) { return e < 1; })) {
    throw InvalidInput(detail::message("make_pattern: rates (", rates.inner_u, ", ", rates.inner_v, "; ",
                                       rates.edges[0], ", ", rates.edges[1], ", ", rates.edges[2], ", ", rates.edges[3],
                                       ") must all be at least 1"));
  }
  for (std::size_t k = 0; k < 4; ++k) {
    const EdgeSegments* pieces = rates.segments[k];
    if (pieces == nullptr) continue;
    const bool valid = !pieces->rates.empty() && pieces->at.size() == pieces->rates.size() + 1 &&
                       pieces->at.front() == 0.0 && pieces->at.back() == 1.0 &&
                       std::adjacent_find(pieces->at.begin(), pieces->at.end(), std::greater_equal<double>()) == pieces->at.end() &&
                       std::all_of(pieces->rates.begin(), pieces->rates.end(), [](int r) { return r >= 1; }) &&
                       std::accumulate(pieces->rates.begin(), pieces->rates.end(), 0) == rates.edges[k];
    if (!valid) {
      throw InvalidInput(detail::message("make_pattern: the pieces of edge ", k, " are not increasing from 0 to 1 with rates >= 1 adding up to ", rates.edges[k]));
    }
  }
  const InnerGrid inner = inner_grid(rates);
  pattern.points.clear();
  pattern.triangles.clear();
  pattern.grid = inner.grid;
  const int nu = inner.u;
  const int nv = inner.v;
  double boundary = 0.0;
  for (int e : rates.edges) boundary += e;
  if (boundary + static_cast<double>(nu + 1) * (nv + 1) > 2147483648.0) {
    throw InvalidInput(detail::message("make_pattern: rates (", nu, ", ", nv, ") give more than 2^31 points"));
  }
  const PatternIndex index(rates, nu, nv);
  pattern.points.reserve(static_cast<std::size_t>(boundary));
  add_boundary_points(rates, pattern.points);

  // Grid point (i, j) of the inner grid; on the boundary it is a corner or an edge point, which
  // is right on a side whose edge rate equals the inner rate along it.
  const auto at = [&](int i, int j) -> std::uint32_t {
    const bool left = i == 0, right = i == nu, bottom = j == 0, top = j == nv;
    if (bottom && left) return index.corner(0);
    if (bottom && right) return index.corner(1);
    if (top && right) return index.corner(2);
    if (top && left) return index.corner(3);
    if (bottom) return index.edge(0, i);
    if (right) return index.edge(1, j);
    if (top) return index.edge(2, i);
    if (left) return index.edge(3, j);
    return index.interior(i, j);
  };
  // A side keeps its ring of grid cells where its edge rate equals the inner rate along it; the
  // other sides are stitched. The grid cells are [i0, i1) x [j0, j1); those touching the
  // boundary are listed here (the rest are the inner cells).
  const auto matches = [&](int side) {
    return rates.segments[static_cast<std::size_t>(side)] == nullptr && rates.edges[side] == (side % 2 == 0 ? nu : nv);
  };
  const int i0 = matches(3) ? 0 : 1;
  const int i1 = matches(1) ? nu : nu - 1;
  const int j0 = matches(0) ? 0 : 1;
  const int j1 = matches(2) ? nv : nv - 1;
  pattern.triangles.reserve(
      4 * static_cast<std::size_t>(nu + nv) +
      2 * static_cast<std::size_t>(rates.edges[0] + rates.edges[1] + rates.edges[2] + rates.edges[3]));
  for (int j = j0; j < j1; ++j) {
    if (j == 0 || j == nv - 1) {
      add_grid_cells(i0, i1, j, j + 1, at, pattern.triangles);
    } else {
      if (i0 == 0) add_grid_cells(0, 1, j, j + 1, at, pattern.triangles);
      if (i1 == nu && nu > 1) add_grid_cells(nu - 1, nu, j, j + 1, at, pattern.triangles);
    }
  }
  if (pattern.grid) return;

  // One stitched strip per other side, joining its edge points to the grid cells' outermost
  // points along it (which reach the corners' neighbours on the sides that keep their ring).
  // Each thread's rows keep their storage from side to side and call to call (a frame makes
  // thousands of patterns).
  thread_local std::vector<std::uint32_t> outer;
  thread_local std::vector<double> along;
  thread_local std::vector<std::uint32_t> inner_row;
  for (int side = 0; side < 4; ++side) {
    if (matches(side)) continue;
    const int e = rates.edges[side];
    outer.assign(1, index.corner(side));
    along.assign(1, 0.0);
    // Counter-clockwise: v0 and u1 run with their boundary_curve, v1 and u0 against it.
    for (int k = 1; k < e; ++k) {
      outer.push_back(index.edge(side, side < 2 ? k : e - k));
      along.push_back(side < 2 ? edge_step_parameter(rates, side, k) : 1.0 - edge_step_parameter(rates, side, e - k));
    }
    outer.push_back(index.corner((side + 1) % 4));
    along.push_back(1.0);
    inner_row.clear();
    int offset = 0;  // the first inner point's step along the side
    switch (side) {
      case 0:
        for (int i = i0; i <= i1; ++i) inner_row.push_back(at(i, 1));
        offset = i0;
        break;
      case 1:
        for (int j = j0; j <= j1; ++j) inner_row.push_back(at(nu - 1, j));
        offset = j0;
        break;
      case 2:
        for (int i = i1; i >= i0; --i) inner_row.push_back(at(i, nv - 1));
        offset = nu - i1;
        break;
      default:
        for (int j = j1; j >= j0; --j) inner_row.push_back(at(1, j));
        offset = nv - j1;
        break;
    }
    stitch_side(outer, along, inner_row, side % 2 == 0 ? nu : nv, offset, pattern.triangles);
  }
}

TessellationPattern make_pattern(const PatternRates& rates) {
  TessellationPattern pattern = make_pattern_boundary(rates);
  const InnerGrid inner = inner_grid(rates);
  const PatternIndex index(rates, inner.u, inner.v);
  PATCHWORK_ASSERT(pattern.points.size() == index.interior_offset(), "boundary points come first");
  pattern.points.reserve(pattern.points.size() + static_cast<std::size_t>(inner.u - 1) * (inner.v - 1));
  add_interior_points(inner.u, inner.v, pattern.points);
  pattern.triangles.reserve(pattern.triangles.size() + 2 * static_cast<std::size_t>(std::max(inner.u - 2, 0)) *
                                                           static_cast<std::size_t>(std::max(inner.v - 2, 0)));
  for_each_inner_triangle(inner, index.interior_offset(), [&](const Triangle& t) { pattern.triangles.push_back(t); });
  return pattern;
}

}  // namespace patchwork
