#pragma once
// Uniform subdivision of a cage through OpenSubdiv (Far::TopologyRefiner and PrimvarRefiner).
//
// Level k of Catmull-Clark or bilinear subdivision has one quad per face corner at level 1 and
// four per quad after that; Loop has four triangles per triangle per level. The result is a
// cage again (positions, vertex data, face-varying values and the tags as they are at level k:
// semi-sharp creases lose one unit of sharpness per level), so it can be refined further or
// turned into a limit surface.

#include <cstdint>

#include "meshes/topology.h"
#include "subdivision/cage.h"

namespace patchwork {

/// The largest number of faces a refinement may produce (about 6 GiB of output).
inline constexpr std::int64_t max_refined_faces = 100'000'000;

/// The most levels of uniform refinement (OpenSubdiv's limit).
inline constexpr int max_refinement_levels = 10;

struct UniformRefinement {
  /// The level-k mesh with its data and tags (hole faces included and listed in cage.holes).
  SubdivisionCage cage;
  /// The topology of the surface, the level-k faces that are not holes: refined_topology() of the
  /// cage's (analyze() of the result where the cage has holes or isolated vertices or is not
  /// orientable).
  TopologyReport topology;
  int level;
};

/// The number of faces uniform refinement to `levels` produces (closed form, no refinement).
std::int64_t refined_face_count(const FaceVertexMesh& mesh, SubdivisionScheme scheme, int levels);

/// The topology of `cage` (an orientable manifold without isolated vertices, with `report` =
/// analyze(cage); a non-orientable one's proving cycle would have to be found among the refined faces)
/// after `levels` levels of `scheme`, without refining: subdivision keeps every component's chi,
/// genus, boundary loops and orientability, and the counts follow the closed forms per
/// component (quad schemes: V' = V + E + F, E' = 2E + C, F' = C for C face corners, then C = 4F;
/// Loop: V' = V + E, E' = 2E + 3F, F' = 4F; boundary edges double).
/// \throws InvalidInput if the report is not of an orientable manifold without isolated vertices.
TopologyReport refined_topology(const FaceVertexMesh& cage, const TopologyReport& report, SubdivisionScheme scheme,
                                int levels);

/// Refines `cage` uniformly `levels` times (0 returns it as it is).
/// \throws what validate_cage() throws; InvalidInput unless 0 <= levels <= 10 and the result
///         has at most max_refined_faces faces.
UniformRefinement refine_uniform(const SubdivisionCage& cage, int levels);

/// The faces of the cage that are not holes, over the same vertices.
FaceVertexMesh surface_faces(const SubdivisionCage& cage);

}  // namespace patchwork
