#pragma once
// Section 8 of docs/performance.md: NURBS surfaces. The exact sphere and torus of
// surfaces/nurbs_shapes.h, tessellated by patchwork (their Bezier extraction as one PatchSet of
// rational patches) and by Open CASCADE's BRepMesh_IncrementalMesh on one face of the same
// surface as a Geom_BSplineSurface (report/occt_peer.h), both measured by one meter.
//
// The meter: the distance of a point to the exact surface is known in closed form,
//   sphere (centre c, radius R)        d(x) = | |x - c| - R |
//   torus (about z, radii R > r)       d(x) = | sqrt((rho - R)^2 + z^2) - r |,  rho = sqrt(x^2 + y^2)
// (x relative to the centre), and mesh -> surface is the largest d over every triangle, sampled
// on a barycentric lattice, the worst triangles again on a fine one (a sup found from below).
// The other side follows from it: for a closed mesh inside the surface's tube that wraps the
// surface once, the closest-point projection onto the surface maps the mesh onto the surface,
// so every surface point x is the foot of a mesh point y and dist(x, mesh) <= |x - y| = d(y):
// surface -> mesh <= mesh -> surface, and the two-sided Hausdorff distance is the one measured.
// (Open CASCADE's meshes of both are checked closed in tests/report/occt_peer_test.cpp,
// patchwork's in tests/surfaces/rational_tessellation_test.cpp.)
//
// The ideal uniform count at sagitta e: equilateral triangles whose corners lie on a sphere of
// radius 1 / kappa have circumradius rho with e = rho^2 kappa / 2 to leading order, so area
// (3 sqrt 3 / 4) rho^2 = (3 sqrt 3 / 2) e / kappa ~ 2.6 e / kappa each. One size everywhere, made
// for the largest normal curvature kappa_max, needs
//   N_ideal(e) = area * kappa_max / (2.598 e):
//   sphere  area 4 pi R^2,      kappa_max = 1 / R                  -> 4 pi R / (2.598 e)
//   torus   area 4 pi^2 R r,    kappa_max = max(1 / r, 1 / (R - r)) (the tube's circles, or the
//           inner equator's), with R = 2, r = 1/2: 4 pi^2 * 2 / (2.598 e)
// A mesh that stretches its triangles along the flatter direction (the torus's parallels) can
// go below it.

#include <string>
#include <vector>

#include "report/report_section.h"
#include "report/teapot_runs.h"
#include "surfaces/nurbs_surface.h"

namespace patchwork::performance {

/// An exact shape: its NURBS surface and what the meter and the ideal count need.
struct ExactShape {
  std::string name;
  NurbsSurface surface;
  /// The distance d(x) of the file comment.
  double (*distance)(const Vec3& x);
  double area;
  double max_curvature;
};

/// The unit sphere and the torus with radii 2 and 1/2, both about the origin.
std::vector<ExactShape> exact_shapes();

/// The ideal uniform triangle count at sagitta e (file comment).
double ideal_uniform_triangles(const ExactShape& shape, double e);

/// The largest distance of the mesh to the shape's surface: each triangle sampled on the
/// barycentric lattice of order `lattice`, the `refine` worst of them again at order 64.
/// \throws InvalidInput if an index is out of range or lattice < 1.
double mesh_to_surface_distance(const ExactShape& shape, const std::vector<Vec3>& positions,
                                const std::vector<std::uint32_t>& indices, int lattice, int refine);

/// The section and the patchwork rows whose measured distance exceeds their own a-priori bound.
struct NurbsSection {
  ReportSection section;
  std::vector<std::string> violations;
};

/// Runs and writes section 8 (data files `nurbs_<shape>_<method>.dat` into data_dir); quick: a few
/// rows, fewer repeats. Without Open CASCADE, patchwork's rows alone and a line saying why.
NurbsSection nurbs_section(const std::filesystem::path& data_dir, bool quick);

}  // namespace patchwork::performance
