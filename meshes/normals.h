#pragma once
// Face and vertex normals (seed 4.4.1) and normals split at creases.
//
//   face normal      Newell's normal of the face, normalised (zero for a degenerate face)
//   vertex normals   the normalised sum of the unit normals of the faces around the vertex,
//                    weighted by 1 (the seed's average), by the corner angle, or by face area
//   split normals    a vertex is duplicated where the angle between neighbouring faces' normals
//                    exceeds a threshold, so a crease keeps two normals and smooth parts one

#include <cstdint>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// The unit normal of face f (zero vector if its area is zero).
Vec3 face_normal(const FaceVertexMesh& mesh, std::size_t f);
/// face_normal of every face.
std::vector<Vec3> face_normals(const FaceVertexMesh& mesh);

/// How face normals are weighted at a vertex.
enum class NormalWeighting { uniform, angle, area };

/// One unit normal per vertex (zero for an isolated vertex or where the weighted sum cancels).
std::vector<Vec3> vertex_normals(const FaceVertexMesh& mesh, NormalWeighting weighting = NormalWeighting::angle);

/// A mesh whose vertices are duplicated along creases, with one normal per (new) vertex.
struct SplitNormals {
  FaceVertexMesh mesh;
  std::vector<Vec3> normals;
  /// source_vertex[v] = the input vertex that new vertex v copies.
  std::vector<std::uint32_t> source_vertex;
};

/// Splits vertices where adjacent faces' normals differ by more than `crease_angle` (radians):
/// faces around a vertex are grouped by walking across edges whose dihedral angle stays below
/// the threshold; each group gets its own copy of the vertex and an angle-weighted normal.
/// Vertices with one group are not duplicated. \throws InvalidInput if the angle is negative.
SplitNormals split_normals(const FaceVertexMesh& mesh, double crease_angle);

}  // namespace patchwork
