#pragma once
// Exact shapes as NURBS surfaces (The NURBS Book, ch. 7-8): surfaces of revolution and of
// extrusion of any NURBS curve, and from them the sphere, torus, cylinder and cone.
//
// Revolution (A8.1): profile point P_j (weight w_j) at distance r_j from the axis, its foot O_j
// on the axis, X_j = (P_j - O_j) / r_j, Y_j = A x X_j (A the unit axis): the surface's row j is
// the circle arc about O_j of radius r_j in the plane (X_j, Y_j) through `angle`, so
//   P_ij = O_j + r_j (x_i X_j + y_i Y_j),   w_ij = w_i^arc w_j,
// with (x_i, y_i), w_i^arc the unit arc's control points and weights (quadratic pieces of at most
// 90 degrees, circle_arc, joined by join_rational_pieces). u runs around the axis
// (counter-clockwise seen from +A), v along the profile; a profile point on the axis (r_j = 0,
// or within 1e-14 of the profile's reach from the axis point, as a circle's cos(pi/2) is) gives
// a collapsed row, a pole. A revolution through 2 pi closes: the first and last columns agree
// to rounding (sin 2 pi), and the patch set joins them.
// Extrusion: P_i0 = P_i, P_i1 = P_i + d, weights w_i in both rows, degree 1 along v.
//
// Normals (S_u x S_v): the sphere, torus, cylinder and cone below point outward.

#include "curves/bspline_curve.h"
#include "surfaces/nurbs_surface.h"

namespace patchwork {

/// The circle arc about `center` of `radius` in the plane of the orthonormal axes x_axis,
/// y_axis, from angle `start` to `end` (radians), as one NURBS curve on [0, 1].
/// \throws InvalidInput as circle_arc does.
NurbsCurve<3> nurbs_circle_arc(const Vec3& center, const Vec3& x_axis, const Vec3& y_axis, double radius, double start,
                               double end);

/// The surface swept by `profile` turning through `angle` (radians, 0 < angle <= 2 pi) about
/// the axis through `axis_point` along `axis` (see the file comment).
/// \throws InvalidInput if the axis is zero or not finite, or the angle is out of range.
NurbsSurface revolve(const NurbsCurve<3>& profile, const Vec3& axis_point, const Vec3& axis, double angle);

/// The surface swept by `profile` moved along `direction` (u along the profile, v along the
/// direction). \throws InvalidInput if the direction is zero or not finite.
NurbsSurface extrude(const NurbsCurve<3>& profile, const Vec3& direction);

/// The sphere: a half circle from the south pole (-z) to the north pole revolved about z.
NurbsSurface nurbs_sphere(const Vec3& center, double radius);
/// The torus about z: the circle of radius `minor` at distance `major` from the axis, revolved.
/// \throws InvalidInput unless 0 < minor < major.
NurbsSurface nurbs_torus(const Vec3& center, double major, double minor);
/// The open cylinder about z from center.z to center.z + height.
NurbsSurface nurbs_cylinder(const Vec3& center, double radius, double height);
/// The open cone about z: the base circle of `radius` at center.z, the apex `height` above.
NurbsSurface nurbs_cone(const Vec3& center, double radius, double height);

}  // namespace patchwork
