#pragma once
// Orientation of polygon meshes (seed Def 47-49).
//
// A mesh is orientable when its faces can be flipped (corner order reversed) so that every edge
// shared by two faces is walked in opposite directions (Def 47). The search is a breadth-first
// walk over faces through edges with exactly two faces; an edge with more faces joins nothing
// here (the mesh is not a manifold there, see analyze()). When the walk meets a face that would
// have to be both flipped and not flipped, the component is non-orientable, and the cycle of
// faces through the walk's tree and that edge proves it (a Moebius band's strip, for example).
// orient() is idempotent: on an oriented mesh it flips nothing.

#include <cstdint>
#include <span>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// What orient() did.
struct Orientation {
  /// The mesh with faces flipped (same vertices, same face order).
  FaceVertexMesh mesh;
  /// The faces that were flipped, ascending.
  std::vector<FaceId> flipped;
  /// Per edge-connected component (numbered by their smallest face), whether it is orientable.
  std::vector<bool> component_orientable;
  /// For each non-orientable component, a cycle of faces, each sharing an edge with the next
  /// and the last with the first, along which orientation cannot be consistent.
  std::vector<std::vector<FaceId>> non_orientable_cycles;
};

/// A consistent orientation of every orientable component (the first face of each component, in
/// face order, keeps its orientation). Non-orientable components are oriented as far as the walk
/// goes and reported.
Orientation orient(const FaceVertexMesh& mesh);

/// Like orient(), then every closed orientable component whose signed volume is negative is
/// flipped whole, so that its normals point out (Def 49, the outer normal field).
Orientation orient_outward(const FaceVertexMesh& mesh);

/// The signed volume enclosed by the faces (each polygon fanned into triangles from its first
/// corner): sum det(p0, p_k, p_k+1) / 6. Positive for a closed surface with outward normals.
double signed_volume(const FaceVertexMesh& mesh);

/// Edge-connected components: component[f] for every face, numbered 0.. by smallest face.
std::vector<std::uint32_t> face_components(const FaceVertexMesh& mesh);

namespace detail {

class EdgeTable;

/// Reverses, for every face f with flip[f], its run of `per_corner` (one entry per face corner in
/// face order: vertex indices, face-varying indices) after the first corner, as orient() flips.
void flip_corners(std::span<const std::uint32_t> face_sizes, const std::vector<bool>& flip,
                  std::vector<std::uint32_t>& per_corner);

/// Edge-connected components from an edge table (analyze() and orient() share one table).
struct FaceComponents {
  /// of_face[f]: the component of face f, numbered 0.. by smallest face.
  std::vector<std::uint32_t> of_face;
  std::size_t count = 0;
};
FaceComponents face_components(const FaceVertexMesh& mesh, const EdgeTable& table);

/// What orient() finds, without the flipped mesh, and the edge-connected components with it.
struct OrientationWalk {
  FaceComponents components;
  /// flip[f]: whether face f is flipped.
  std::vector<bool> flip;
  std::vector<bool> component_orientable;
  std::vector<std::vector<FaceId>> non_orientable_cycles;
};
OrientationWalk walk_orientation(const FaceVertexMesh& mesh, const EdgeTable& table);

}  // namespace detail

}  // namespace patchwork
