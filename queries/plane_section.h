#pragma once
// Plane sections of a patch set: the curve where the plane {x : n.(x - p) = 0} cuts the surface,
// as polylines whose vertices lie on the exact surface and on the plane (to rounding) and whose
// segments lie within a tolerance of the exact curve.
//
// The section of one patch is the zero set of the signed distance f(u, v) = n.(F(u, v) - p)
// (n the unit normal). For a polynomial patch f is a scalar Bernstein patch with coefficients
//   c_ij = n.(P_ij - p);
// for a rational patch F = H / w, the numerator g = n.H_xyz - (n.p) w, coefficients
//   c_ij = w_ij n.(P_ij - p),
// has the zero set and the sign of f (w > 0). The search subdivides (u, v) cells:
//   - a cell whose coefficients are all of one strict sign holds no zero (convex hull property);
//     one whose coefficients are >= 0 (or <= 0) with zeros touches the plane only on its
//     boundary: at a corner or along a whole side whose coefficients all vanish;
//   - a cell is a leaf when f_v (or f_u) has coefficients of one strict sign on it, so the curve
//     is a graph v = g(u) (or u = g(v)) there, and it has exactly two boundary crossings: then it
//     holds one arc between them;
//   - otherwise it is split in four (near the middle, where f is not near zero at the new corners).
// Boundary crossings are roots (bernstein_roots) of f along whole iso-lines of the patch, computed
// once per line, so neighbouring cells agree; along a shared edge of the set they are computed once
// on one patch's edge and mapped to the other's, so the pieces of both patches meet at the same
// point. Inside a leaf the arc is sampled at K + 1 uniform values of the graph's parameter, each
// vertex the root of f on the iso-line (bisection to the last bit).
//
// The bound (docs/queries.md, "Plane sections"). In a leaf's own parameters (s, t) in [0, 1]^2, with
// the curve t = g(s), A = sup |f_s| / inf |f_t| >= |g'|, B = sup |f_ss| + 2 sup |f_st| A +
// sup |f_tt| A^2 over inf |f_t| >= |g''| (all from the leaf's differenced nets), M_ss, M_st, M_tt
// bounds on the surface's second derivatives (surfaces/patch_flatness.h, surfaces/rational_bounds.h)
// and M_t >= sup |F_t|, a segment over a step h in s lies within
//   (h^2 / 8) (M_ss + 2 M_st A + M_tt A^2 + M_t B)
// of the arc between its ends, point by point (the chord of F along the parameter segment, plus
// F_t times the gap between g and its linear interpolant). K is the least number of steps that
// makes this <= tolerance; a leaf that would need more than 64 is split instead.
//
// Degenerate cases:
//   - a patch whose coefficients all vanish (to rounding) lies in the plane: it is reported whole
//     (patches_in_plane), and the sides of its neighbours along it are not reported again;
//   - a cell side whose coefficients all vanish lies in the plane: a polyline along it (the iso-line
//     sampled, its bound (h^2 / 8) M_ss), or, when the side collapses to a point, that point;
//   - a point where the plane touches the surface without crossing it (a vanishing corner of cells
//     of one sign, a pole, or a small cell where f keeps changing sign without any crossing on the
//     cell's boundary) is a tangent point, not a polyline: it lies within the bound of the plane
//     and any section near it within the bound of it;
//   - a cell whose box is within the tolerance with two crossings that it cannot resolve as one
//     arc (a pole among them) joins them by a segment, its bound the diagonal of the box of the
//     cell's control points (the curve and the segment both lie in it); a cell with other than two
//     crossings is split further, down to 10^-3 of the tolerance or until f's coefficients are 64
//     times their rounding level, and then joins its crossings as a star from the first (the curve
//     crossing itself at a saddle), within the same bound. A piece whose box exceeds the tolerance,
//     a cell with a single crossing, and the cells left when a patch's search reaches 2^14 cells
//     (a tangency along a curve inside a patch) are counted as uncertified.
// Nodes within the set's tolerance are one when their patches are one or share an edge; patches
// that only touch (the teapot's handle against its body) keep theirs apart.
// T-junctions of the set are not followed: a polyline ends there (open).

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "surfaces/patch_set.h"

namespace patchwork {

/// A point of the section: on the patch `patch` at parameters uv.
struct SectionVertex {
  Vec3 point;
  std::uint32_t patch;
  Vec2 uv;
};

/// A chain of section vertices. Closed: the last vertex joins the first (not repeated).
struct SectionPolyline {
  std::vector<SectionVertex> vertices;
  bool closed;
};

/// The plane section of a patch set.
struct PlaneSection {
  /// The section curves, chained across shared edges.
  std::vector<SectionPolyline> polylines;
  /// Isolated points where the plane touches the surface (the section near each lies within
  /// error_bound of it).
  std::vector<SectionVertex> tangent_points;
  /// Patches that lie in the plane (every coefficient of f zero to rounding), ascending.
  std::vector<std::uint32_t> patches_in_plane;
  /// Largest bound over the segments (and tangent points): every segment lies within it of the
  /// exact section curve. <= the tolerance unless uncertified_pieces > 0.
  double error_bound = 0.0;
  /// Pieces the subdivision could not certify (see the file comment); 0 for a full answer.
  std::size_t uncertified_pieces = 0;
  /// Cells examined (the cost of the search).
  std::size_t cells = 0;
};

/// The section of `set` by the plane through `point` with normal `normal` (any length), every
/// segment within `tolerance` of the exact curve (see the file comment).
/// \throws InvalidInput naming the argument if point or normal is not finite, normal is zero or
///         tolerance is not finite and > 0.
PlaneSection plane_section(const PatchSet& set, const Vec3& point, const Vec3& normal, double tolerance);

}  // namespace patchwork
