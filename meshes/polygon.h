#pragma once
// Single polygons (seed Def 41-45): a polygon is a closed sequence of points p_0 .. p_{k-1}.
//
//   simple       no two edges meet except neighbours at their shared corner (Def 43)
//   planar       all corners within `tolerance` of one plane (Def 42)
//   Newell's normal  N = sum_i (p_i - p_{i+1}) x (p_i + p_{i+1}) / 4 = sum_i p_i x p_{i+1} / 2:
//                for a planar polygon its length is the area and its direction follows the
//                corners counter-clockwise (right-hand rule); robust for non-planar and
//                non-convex polygons
//   orientation with respect to a normal n (Def 44-45): counter-clockwise when N . n > 0

#include <span>

#include "core/types.h"

namespace patchwork {

/// Newell's normal (length = area for a planar polygon). \throws InvalidInput for < 3 points.
Vec3 newell_normal(std::span<const Vec3> polygon);

/// Area of a planar polygon: |newell_normal|.
double polygon_area(std::span<const Vec3> polygon);

/// Whether every corner lies within `tolerance` of the plane through the centroid with Newell's
/// normal. A polygon of zero area is planar only if all its points coincide within tolerance.
bool is_planar(std::span<const Vec3> polygon, double tolerance);

/// Whether the polygon, projected onto the plane of its Newell normal, has no self-intersections
/// and no repeated corners (edges meet only at shared corners of neighbours). O(k^2).
bool is_simple(std::span<const Vec3> polygon);

/// +1 if the corners run counter-clockwise seen from the tip of `normal` (Def 45), -1 if
/// clockwise, 0 if degenerate (zero area, or the polygon's plane contains `normal`).
int orientation(std::span<const Vec3> polygon, const Vec3& normal);

}  // namespace patchwork
