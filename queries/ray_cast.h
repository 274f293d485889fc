#pragma once
// Every hit of a ray o + t d (t_min <= t <= t_max) with the surface of a patch set, in order of t.
//
// The ray is the intersection of two planes through it, with unit normals a and b orthogonal to
// d and to each other; a surface point is on the ray when both signed distances vanish:
//
//   g_1(u, v) = a . (F(u, v) - o) = 0,   g_2(u, v) = b . (F(u, v) - o) = 0.
//
// On a piece (queries/net_piece.h) each g_k times the weight w is a scalar Bernstein polynomial
// with coefficients w_ij a . (P_ij - o), so a piece whose coefficients of g_1 or of g_2 all have
// one sign (beyond rounding) holds no hit (convex hull): that is the only way a piece is dropped,
// so no hit is missed. The PatchBvh's boxes skip pieces the ray does not reach first.
//
// A piece where the 2 x 2 Jacobian of (w g_1, w g_2) is regular for every value its differenced
// nets allow (the interval determinant excludes 0) holds at most one hit (the map is injective on
// the convex piece, by the mean value theorem); Newton from its centre finds it, and a last
// Newton step on the patch itself places it. Other pieces are halved; once a piece is within
// 1e-7 of the size (its control box's diagonal, or 2^-30 in both parameters), a piece whose
// centre, moved onto the ray by Newton, is within 1e-9 of the size of it is a tangent (grazing)
// hit, flagged. Hits within 1e-9 of the size of each other (the same point
// found from two patches at a shared edge or corner, or from two pieces) are reported once.
// The size is the scene's diagonal, or more where the ray starts so far out that its own
// rounding is coarser (docs/queries.md gives the lengths).
//
// The normal is the patch's unit normal (surface_normal.h), the limit normal at collapsed edges.

#include <cstdint>
#include <limits>
#include <vector>

#include "core/types.h"
#include "queries/patch_bvh.h"
#include "surfaces/patch_set.h"

namespace patchwork {

/// One point where a ray meets the surface.
struct RayHit {
  /// Ray parameter: the point is origin + t direction.
  double t = 0.0;
  std::uint32_t patch = 0;
  double u = 0.0;
  double v = 0.0;
  /// F(u, v).
  Vec3 point = Vec3::Zero();
  /// The unit normal of the patch at (u, v) (F_u x F_v normalised, or its limit).
  Vec3 normal = Vec3::Zero();
  /// The ray touches the surface here without crossing it (or crosses it at a cosine below
  /// 1e-6 between the ray and the normal): a tangent hit.
  bool grazing = false;
};

/// What limits a ray.
struct RayOptions {
  double t_min = 0.0;
  double t_max = std::numeric_limits<double>::infinity();
};

/// Every hit in order of t, and how many pieces were examined.
struct RayHits {
  std::vector<RayHit> hits;
  std::int64_t pieces = 0;
};

/// Every hit of the ray with the surface of the hierarchy's patch set, in order of t.
/// \throws InvalidInput if origin is not finite, direction is not finite or zero, or
///         !(t_min <= t_max) (t_max may be infinite).
RayHits ray_cast(const PatchBvh& bvh, const Vec3& origin, const Vec3& direction, const RayOptions& options = {});

/// The same on a patch set (builds its PatchBvh; keep one for many rays).
RayHits ray_cast(const PatchSet& set, const Vec3& origin, const Vec3& direction, const RayOptions& options = {});

}  // namespace patchwork
