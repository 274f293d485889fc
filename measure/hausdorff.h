#pragma once
// The distance between a triangle mesh and the exact surface of a set of Bezier patches,
// measured from the geometry alone: the error meter of docs/performance.md, blind to how the
// mesh was made (patchwork's tessellator, three.js, Open CASCADE).
//
//   surface_to_mesh = sup over surface points x of  min over mesh points y    |x - y|
//   mesh_to_surface = sup over mesh points y    of  min over surface points x |x - y|
//   hausdorff       = max(surface_to_mesh, mesh_to_surface)
//
// How each sup is found:
//   surface -> mesh  samples: a uniform (g+1) x (g+1) grid on every patch, and under every
//                    mesh triangle (when its corners' closest surface points lie on one patch)
//                    the centroid of the parameter triangle those points span, so a fine mesh
//                    is sampled inside every triangle. The distance of a surface point to the
//                    mesh is exact (closest point on the triangles, CGAL's AABB tree).
//   mesh -> surface  samples: every vertex and every triangle's centroid. The closest surface
//                    point starts at the closest point of a proxy (each patch's grid,
//                    triangulated, in a second AABB tree) and is refined by Newton steps on
//                    |S(u, v) - y|^2 in (u, v), clamped to the patch.
//   refinement       the `refine` samples with the largest distances on each side are taken
//                    further: the triangles (parameter triangles) they belong to are sampled on
//                    a barycentric lattice of order `lattice`, and the best sample climbs the
//                    distance by a compass search in its own parameters. Each mesh point of the
//                    refined set is then checked against every patch whose box is nearer than
//                    its distance (its closest point may lie across a patch edge), with Newton
//                    from that patch's nearest grid point.
//
// Every distance reported is attained: a surface point at that exact distance from the mesh,
// or a mesh point at that distance from a surface point found by Newton. Sampling finds the sups
// from below; the refinement makes the shortfall small where the distance is smooth (validated
// on closed forms in tests/measure/hausdorff_test.cpp). Degenerate (zero-area) triangles take
// part as mesh samples, not as the target of surface samples (their points lie on the
// neighbouring triangles' edges unless the mesh is torn; the surface side then only overstates).

#include <algorithm>
#include <cstdint>
#include <span>

#include "core/types.h"
#include "surfaces/bezier_patch.h"

namespace patchwork {

struct HausdorffOptions {
  /// Segments per direction of each patch's uniform sample grid (and of the proxy).
  int grid_segments = 64;
  /// Order of the barycentric lattice on refined triangles ((k+1)(k+2)/2 points).
  int lattice = 6;
  /// Samples refined on each side.
  int refine = 64;
  /// Threads; 0 = all cores. The result does not depend on it.
  int threads = 0;
};

/// Where one of the two sups was found.
struct HausdorffWitness {
  /// The distance.
  double distance = 0.0;
  /// The surface point and its patch parameters.
  Vec3 surface_point = Vec3::Zero();
  std::uint32_t patch = 0;
  double u = 0.0;
  double v = 0.0;
  /// The mesh point and its triangle.
  Vec3 mesh_point = Vec3::Zero();
  std::uint32_t triangle = 0;
};

struct HausdorffDistance {
  HausdorffWitness surface_to_mesh;
  HausdorffWitness mesh_to_surface;
  /// Samples measured on each side.
  std::size_t surface_samples = 0;
  std::size_t mesh_samples = 0;

  /// The two-sided distance.
  double hausdorff() const noexcept { return std::max(surface_to_mesh.distance, mesh_to_surface.distance); }
};

/// The two one-sided distances between the patches' surface and the triangle mesh (positions,
/// three indices per triangle); see the file comment for how they are measured.
/// \throws InvalidInput if there are no patches or no non-degenerate triangle, an index is out of
///         range, a position is not finite, or an option is out of range (grid_segments in
///         [1, 4096], lattice in [1, 64], refine >= 0).
HausdorffDistance hausdorff_distance(std::span<const BezierPatch3> patches, std::span<const Vec3> positions,
                                     std::span<const std::uint32_t> indices, const HausdorffOptions& options = {});

/// The closest point of one patch to `point`, by damped Newton steps on |S(u, v) - point|^2 from
/// (u, v), clamped to [0,1]^2; returns the parameters reached (a local minimum).
Vec2 closest_parameters(const BezierPatch3& patch, const Vec3& point, Vec2 start);

}  // namespace patchwork
