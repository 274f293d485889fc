#pragma once
// What a camera sees of a patch: "model only what a scene needs".
//
// Tolerance from the view: a deviation e at depth z covers e f_px / z pixels, f_px = (height / 2)
// / tan(fov / 2) the focal length in pixels; so a patch whose nearest control point is at depth
// z_min (the surface lies in the net's convex hull, so none of it is nearer) gets
// eps = pixel_tolerance * z_min / f_px, which the tessellator rounds down to the ladder 2^(k/16)
// (tolerance_on_ladder) so that its grid searches repeat from frame to frame.
//
// Culling, both conservative:
//   - frustum: every control point outside one of the planes (left, right, bottom, top, near);
//   - back-facing: g(u, v) = (F(u,v) - eye) . (F_u x F_v) >= 0 everywhere, decided on its
//     Bernstein coefficients (degrees (3n-1, 3m-1), computed exactly in the product basis): all
//     clearly positive means the eye is behind every tangent plane of the patch (the tangent-plane
//     test of Loop, Niessner & Eisenacher, "Effective back-patch culling for hardware
//     tessellation", 2011). The normals are F_u x F_v, the front side is where they point.
//
// Camera space: d = (target - eye) / |target - eye| the view direction, r = d x up the right
// direction, t = r x d the true up; a point p has depth (p - eye) . d.

#include <vector>

#include "core/types.h"
#include "surfaces/bezier_patch.h"

namespace patchwork {

/// A pinhole camera.
struct Camera {
  Vec3 eye;
  Vec3 target;
  /// The world's up direction (the teapot is Z-up); must not be parallel to the view direction.
  Vec3 up = Vec3::UnitZ();
  /// Vertical field of view, degrees, in (0, 180).
  double fov_degrees = 45.0;
  int width = 1920;
  int height = 1080;
};

/// Checks the camera. \throws InvalidInput naming the bad field (eye = target, up parallel to the
/// view, fov outside (0, 180), width or height < 1, a coordinate not finite).
void validate(const Camera& camera);

/// Focal length in pixels: (height / 2) / tan(fov / 2).
double focal_length_pixels(const Camera& camera);

/// The smallest depth of the patch's control points (negative if some lie behind the eye).
double nearest_depth(const BezierPatch3& patch, const Camera& camera);

/// All control points are outside one plane of the view frustum (or behind the eye).
bool outside_frustum(const BezierPatch3& patch, const Camera& camera);

/// The Bernstein coefficients of (F - eye) . (F_u x F_v), degrees (3n-1, 3m-1), first index
/// fastest; empty if n or m is 0 (F_u x F_v is then zero).
std::vector<double> facing_coefficients(const BezierPatch3& patch, const Vec3& eye);

/// Every point of the patch faces away from the eye (all facing coefficients > 1e-12 of their
/// largest magnitude; a degree-0 patch has no area and counts as back-facing).
bool back_facing(const BezierPatch3& patch, const Vec3& eye);

}  // namespace patchwork
