#pragma once
// Open CASCADE's BRepMesh_IncrementalMesh as a peer tessellator for the report.
//
// Each Bezier patch becomes one face: a Geom_BezierSurface whose pole (i+1, j+1) is P_ij, so
// OCCT's (U, V) in [0,1]^2 is patchwork's (u, v) (surfaces/bezier_patch.h), trimmed by its
// natural bounds (BRepBuilderAPI_MakeFace). The faces are put in one compound, not sewn: OCCT
// meshes every face's boundary on its own, so neighbouring faces do not share vertices. Each
// face's nodes are appended as they are (no welding); triangles are wound so that their normal
// agrees with F_u x F_v of the patch (flipped for a reversed face).
//
// A NurbsSurface becomes a Geom_BSplineSurface with the same degrees, poles, weights and knots:
// pole (i+1, j+1) = P_ij (OCCT's poles are indexed (U, V), 1-based; patchwork's are listed u
// fastest), and the knot vectors as OCCT wants them, distinct values with their multiplicities
// (a clamped cubic's 0 0 0 0 0.5 1 1 1 1 is values 0 0.5 1, multiplicities 4 1 4). The cross-check
// (occt_evaluate) and the NURBS section of the report (one face on that surface) share it.
// No Open CASCADE header is included here: only report/occt_peer.cpp sees them.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "report/peer_mesh.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/nurbs_surface.h"

namespace patchwork::performance {

struct OcctRun {
  /// The mesh of the last repeat.
  PeerMesh mesh;
  /// Median and minimum wall time of one BRepMesh_IncrementalMesh call, in seconds.
  double seconds_median;
  double seconds_min;
  int repeats;
};

/// Open CASCADE's version string ("7.6.3").
std::string occt_version();

/// Meshes every patch as one face with BRepMesh_IncrementalMesh (absolute linear deflection in
/// model units, angular deflection in radians, not in parallel), `repeats` times; each repeat
/// meshes fresh faces built before its timer starts, and only the meshing call is timed.
/// Returns the last mesh, in the patches' own coordinates.
/// \throws InvalidInput unless both deflections are positive and finite, repeats >= 1 and every
///         degree is within [1, 25] (Geom_BezierSurface's limits).
/// \throws NumericalError if OCCT fails or leaves a face without a triangulation.
OcctRun occt_tessellate(std::span<const BezierPatch3> patches, double linear_deflection, double angular_deflection,
                        int repeats);

/// `tessellate(1)`, and if that took under a second `tessellate(repeats)` (the first call then a
/// warm-up): a fine deflection takes tens of seconds a run, and one timed run there is enough.
OcctRun timed_enough(const std::function<OcctRun(int repeats)>& tessellate, int repeats);

/// Meshes one face on the Geom_BSplineSurface of `surface` (trimmed by its domain,
/// BRepBuilderAPI_MakeFace) as occt_tessellate meshes a patch's face.
/// \throws InvalidInput as occt_tessellate (degrees within [1, 25], Geom_BSplineSurface's limits).
/// \throws NumericalError if OCCT fails or leaves the face without a triangulation.
OcctRun occt_tessellate(const NurbsSurface& surface, double linear_deflection, double angular_deflection, int repeats);

/// A surface point and its first partial derivatives.
struct SurfaceJet {
  Vec3 point;
  Vec3 du;
  Vec3 dv;
};

/// Open CASCADE's evaluation of `surface` at each (u, v): the point by Geom_BSplineSurface::D0,
/// the derivatives by D1 (the surface built as in the file comment).
/// \throws InvalidInput if a degree is outside [1, 25] or a parameter is not finite or outside the
///         domain (OCCT would extrapolate there).
/// \throws NumericalError if OCCT refuses the surface: among valid NurbsSurfaces, an unclamped
///         knot vector whose end knot also stands p + 1 times (knots beyond the valid range,
///         then a value p + 1 times at its end: OCCT takes it for an interior knot of too high a
///         multiplicity), and knots closer than OCCT's Epsilon. The cross-check tests clamped knots.
std::vector<SurfaceJet> occt_evaluate(const NurbsSurface& surface, std::span<const Vec2> parameters);

namespace detail {

/// One OCCT mesh with each vertex's parameters: the vertices of patch k are
/// [first_vertex[k], first_vertex[k+1]), and uv[i] is vertex i's (u, v) on that patch.
struct OcctParametricMesh {
  PeerMesh mesh;
  std::vector<Vec2> uv;
  std::vector<std::size_t> first_vertex;
};

/// Meshes once as occt_tessellate does (untimed), keeping OCCT's (U, V) of every node.
/// \throws as occt_tessellate.
OcctParametricMesh occt_parametric_mesh(std::span<const BezierPatch3> patches, double linear_deflection,
                                        double angular_deflection);

}  // namespace detail
}  // namespace patchwork::performance
