#include "surfaces/tessellation_pattern.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "core/errors.h"

namespace patchwork {
namespace {

double signed_area(const TessellationPattern& pattern, const std::array<std::uint32_t, 3>& t) {
  const Vec2 a = pattern.points[t[0]].uv, b = pattern.points[t[1]].uv, c = pattern.points[t[2]].uv;
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

// A valid triangulation of the unit square without T-junctions: every triangle counter-clockwise
// with positive area, areas summing to 1, every directed edge used once, and an edge without its
// twin only on the boundary of the square.
void expect_triangulation_of_square(const TessellationPattern& pattern) {
  double total = 0.0;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : pattern.triangles) {
    const double area = signed_area(pattern, t);
    RC_ASSERT(area > 0.0);
    total += area;
    for (int k = 0; k < 3; ++k) RC_ASSERT(++directed[std::pair(t[k], t[(k + 1) % 3])] == 1);
  }
  RC_ASSERT(std::abs(total - 1.0) < 1e-12);
  for (const auto& [edge, count] : directed) {
    if (directed.count({edge.second, edge.first}) != 0) continue;
    const Vec2 a = pattern.points[edge.first].uv, b = pattern.points[edge.second].uv;
    const bool on_side = (a.x() == 0 && b.x() == 0) || (a.x() == 1 && b.x() == 1) || (a.y() == 0 && b.y() == 0) ||
                         (a.y() == 1 && b.y() == 1);
    RC_ASSERT(on_side);
  }
  // Every point is used, and the boundary of the square has exactly its own points on it.
  std::vector<bool> used(pattern.points.size(), false);
  for (const auto& t : pattern.triangles) {
    for (std::uint32_t p : t) used[p] = true;
  }
  RC_ASSERT(std::all_of(used.begin(), used.end(), [](bool b) { return b; }));
}

RC_GTEST_PROP(TessellationPattern, IsATriangulationOfTheSquareWithoutTJunctions, ()) {
  const PatternRates rates{
      *rc::gen::inRange(1, 13),
      *rc::gen::inRange(1, 13),
      {*rc::gen::inRange(1, 17), *rc::gen::inRange(1, 17), *rc::gen::inRange(1, 17), *rc::gen::inRange(1, 17)}};
  const TessellationPattern pattern = make_pattern(rates);
  expect_triangulation_of_square(pattern);
  const InnerGrid inner = inner_grid(rates);
  std::size_t boundary = 4;
  for (int e : rates.edges) boundary += static_cast<std::size_t>(e - 1);
  RC_ASSERT(pattern.points.size() == boundary + static_cast<std::size_t>((inner.u - 1) * (inner.v - 1)));
  // Each edge keeps exactly its own rate: its points, in boundary_curve direction, at step / rate.
  for (std::size_t k = 4; k < boundary; ++k) {
    const PatternPoint& p = pattern.points[k];
    RC_ASSERT(p.kind == PatternPoint::Kind::edge);
    const double t = static_cast<double>(p.step) / rates.edges[p.index];
    const Vec2 expected = p.index == 0   ? Vec2(t, 0)
                          : p.index == 1 ? Vec2(1, t)
                          : p.index == 2 ? Vec2(t, 1)
                                         : Vec2(0, t);
    RC_ASSERT(p.uv == expected);
  }
  if (pattern.grid) RC_ASSERT(pattern.triangles.size() == 2u * rates.inner_u * rates.inner_v);
}

// The boundary part is make_pattern's boundary points and exactly those of its triangles with a
// boundary corner; the rest are the inner cells that for_each_inner_triangle lists.
RC_GTEST_PROP(TessellationPattern, BoundaryPartAndInnerCellsMakeTheWholePattern, ()) {
  const PatternRates rates{
      *rc::gen::inRange(1, 10),
      *rc::gen::inRange(1, 10),
      {*rc::gen::inRange(1, 12), *rc::gen::inRange(1, 12), *rc::gen::inRange(1, 12), *rc::gen::inRange(1, 12)}};
  const TessellationPattern whole = make_pattern(rates);
  TessellationPattern boundary = make_pattern({2, 2, {1, 2, 3, 4}});  // storage to be reused
  make_pattern_boundary(rates, boundary);
  RC_ASSERT(boundary.grid == whole.grid);
  const auto first_interior = static_cast<std::uint32_t>(boundary.points.size());
  RC_ASSERT(first_interior <= whole.points.size());
  for (std::uint32_t k = 0; k < first_interior; ++k) {
    RC_ASSERT(whole.points[k].kind != PatternPoint::Kind::interior);
    RC_ASSERT(boundary.points[k].uv == whole.points[k].uv);
    RC_ASSERT(boundary.points[k].step == whole.points[k].step);
  }
  using Triangle = std::array<std::uint32_t, 3>;
  std::multiset<Triangle> expected_boundary;
  std::multiset<Triangle> expected_inner;
  for (const Triangle& t : whole.triangles) {
    const bool touches = t[0] < first_interior || t[1] < first_interior || t[2] < first_interior;
    (touches ? expected_boundary : expected_inner).insert(t);
  }
  RC_ASSERT(std::multiset<Triangle>(boundary.triangles.begin(), boundary.triangles.end()) == expected_boundary);
  std::multiset<Triangle> inner;
  for_each_inner_triangle(inner_grid(rates), first_interior, [&](const Triangle& t) { inner.insert(t); });
  RC_ASSERT(inner == expected_inner);
}

TEST(TessellationPattern, EqualRatesGiveThePlainGrid) {
  const TessellationPattern pattern = make_pattern({3, 2, {3, 2, 3, 2}});
  EXPECT_TRUE(pattern.grid);
  EXPECT_EQ(pattern.points.size(), 12u);
  EXPECT_EQ(pattern.triangles.size(), 12u);
  EXPECT_EQ(first_edge_point({3, 2, {3, 2, 3, 2}}, 0), 4u);
  EXPECT_EQ(first_edge_point({3, 2, {3, 2, 3, 2}}, 2), 7u);
}

// Only a side whose edge rate differs from the inner rate along it is stitched; the others keep
// their ring of grid cells. Here only u1 (rate 5 against 2 inner rows): the cells of the two
// columns left of it are the grid's, and the strip has one triangle per segment on either side.
TEST(TessellationPattern, OnlyMismatchedSidesAreStitched) {
  const PatternRates rates{3, 2, {3, 5, 3, 2}};
  const TessellationPattern pattern = make_pattern(rates);
  EXPECT_FALSE(pattern.grid);
  EXPECT_EQ(pattern.triangles.size(), 2u * 2 * 2 + 5 + 2);
  int cells = 0;
  int strip = 0;
  for (const auto& t : pattern.triangles) {
    const double right =
        std::max({pattern.points[t[0]].uv.x(), pattern.points[t[1]].uv.x(), pattern.points[t[2]].uv.x()});
    if (right <= 2.0 / 3.0) {
      ++cells;
      EXPECT_DOUBLE_EQ(signed_area(pattern, t), 1.0 / 12.0);  // half a 1/3 x 1/2 cell
    } else {
      ++strip;
    }
  }
  EXPECT_EQ(cells, 8);
  EXPECT_EQ(strip, 7);
}

TEST(TessellationPattern, RatesBelowOneAreRejected) {
  EXPECT_THROW(make_pattern({0, 2, {1, 1, 1, 1}}), InvalidInput);
  EXPECT_THROW(make_pattern({2, 2, {1, 0, 1, 1}}), InvalidInput);
}

}  // namespace
}  // namespace patchwork
