#pragma once
// Limit surfaces to render-ready meshes, with the patch tessellator (surfaces/tessellator.h):
// each base face is one piece over [0,1]^2, neighbouring faces share their edge's points, and
// everything the tessellator promises holds (welded, crack-free, exact unit normals, tangents,
// UVs, a-priori bound and measured error, reordered for the vertex cache).
//
// Catmull-Clark and bilinear faces are quads: the bounds come from the Bezier nets of their
// patches (LimitSurface::face_bounds), so tolerance and segments modes both work. A Loop
// triangle (corners (0,0), (1,0), (0,1)) becomes a quad with its fourth corner on the third:
// (s, t) -> (s (1 - t), t), its edge t = 1 collapsed like the teapot's poles; Loop's box-spline
// and Gregory patches have no derivative bound here, so Loop is tessellated in segments mode
// only, and its error_bound is infinity (the measured error is still reported).

#include "subdivision/limit_surface.h"
#include "surfaces/tessellator.h"

namespace patchwork {

/// The base faces of `surface` (holes left out) as tessellator pieces. pieces.count pieces;
/// piece_faces[k] is the base face of piece k.
struct LimitPieces {
  SurfacePieces pieces;
  std::vector<std::uint32_t> piece_faces;
};
/// The pieces of a limit surface (it must outlive them).
LimitPieces limit_pieces(const LimitSurface& surface);

/// Tessellates a limit surface (options as for patch sets; the camera mode is not available).
/// Tessellation::triangle_patches holds each triangle's base face.
/// \throws InvalidInput as tessellate() does; for Loop unless segments are given.
Tessellation tessellate_limit(const LimitSurface& surface, const TessellationOptions& options);

}  // namespace patchwork
