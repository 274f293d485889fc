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
//   projection   a polygon is judged in 2D by dropping the coordinate of N's largest component
//                (axes (k+1, k+2) mod 3 for N's largest |N_k|, so counter-clockwise in 2D is
//                N_k > 0): the 2D coordinates are the 3D ones, exactly, and every orientation
//                test on them is exact (a floating-point filter, then expansion arithmetic,
//                Shewchuk 1997). For a planar polygon this is an affine image of the projection
//                onto its plane, which keeps simplicity and orientation.
//   triangulation  k - 2 triangles by ear clipping (corner numbers 0 .. k-1 of the polygon),
//                each a non-degenerate counter-clockwise triangle with respect to N, together
//                covering the polygon exactly once (a triangle is returned as it is)

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// Newell's normal (length = area for a planar polygon). \throws InvalidInput for < 3 points.
Vec3 newell_normal(std::span<const Vec3> polygon);

/// Area of a planar polygon: |newell_normal|.
double polygon_area(std::span<const Vec3> polygon);

/// Whether every corner lies within `tolerance` of the plane through the centroid with Newell's
/// normal. A polygon of zero area is planar only if all its points coincide within tolerance.
bool is_planar(std::span<const Vec3> polygon, double tolerance);

/// Whether the polygon, projected along the axis of its Newell normal (file comment), has no
/// self-intersections and no repeated corners (edges meet only at shared corners of neighbours),
/// decided by exact orientation tests. O(k^2).
bool is_simple(std::span<const Vec3> polygon);

/// +1 if the corners run counter-clockwise seen from the tip of `normal` (Def 45), -1 if
/// clockwise, 0 if degenerate (zero area, or the polygon's plane contains `normal`).
int orientation(std::span<const Vec3> polygon, const Vec3& normal);

/// The k - 2 triangles of a simple polygon of k >= 4 corners by ear clipping in its projection
/// (file comment), as corner numbers, each counter-clockwise with respect to the Newell normal
/// (their Newell normals sum to the polygon's); a triangle (k = 3) is returned as {0, 1, 2}
/// whatever its shape. A convex polygon gives the fan from corner 0, (0, 1, 2), (0, 2, 3), ...
/// Collinear corners are allowed; a non-planar polygon is triangulated in its projection.
/// O(k^2) for typical polygons, O(k^3) at worst.
/// \throws InvalidInput for < 3 points, or for k >= 4 if the projection has zero area or is not
///         simple (is_simple: self-intersecting, a repeated corner).
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(std::span<const Vec3> polygon);

/// Every face of `mesh` triangulated by triangulate_polygon, face by face in order, as 3 vertex
/// indices per triangle (triangles stay as they are).
/// \throws InvalidInput naming the face and its corners if a face cannot be triangulated.
std::vector<std::uint32_t> triangulate_faces(const FaceVertexMesh& mesh);

}  // namespace patchwork
