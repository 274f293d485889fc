#pragma once
// Repair of polygon soups into manifold, consistently oriented meshes, reporting every change.
// A mesh from the wild is explained, never dropped silently:
//
//   1. Consecutive repeated corners of a face are merged (a a b c -> a b c). A face left with
//      fewer than 3 corners is removed, and listed; this is the only way a face is ever removed.
//      A face that still repeats a vertex (a pinched face a b a c) gets a copy of that vertex.
//   2. Non-manifold edges (more than two faces) and vertices (faces in several fans) are split:
//      corners at a vertex are joined only across edges with exactly two faces; each group of
//      joined corners (a fan) gets its own copy of the vertex. An edge whose faces still share
//      both copies is cut by giving the faces beyond the first two their own copies.
//   3. Faces are flipped to a consistent orientation where the surface is orientable (orient()).
//      Non-orientable components stay so and are reported with a proving cycle.

#include <cstdint>
#include <string>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

struct RepairReport {
  /// The repaired mesh; new vertices are appended after the input's.
  FaceVertexMesh mesh;
  /// source_vertex[v]: the input vertex that vertex v of the repaired mesh copies.
  std::vector<std::uint32_t> source_vertex;
  /// face_source[f]: the input face that face f of the repaired mesh comes from.
  std::vector<std::uint32_t> face_source;
  /// Input faces removed because fewer than 3 distinct corners remained.
  std::vector<std::uint32_t> removed_faces;
  /// Input faces whose repeated consecutive corners were merged.
  std::vector<std::uint32_t> merged_corner_faces;
  /// Input vertices that were duplicated (split), each listed once.
  std::vector<std::uint32_t> split_vertices;
  /// Input faces flipped for a consistent orientation.
  std::vector<std::uint32_t> flipped_faces;
  /// Whether every component of the result is orientable.
  bool orientable;
  /// A proving cycle of (output) faces per non-orientable component.
  std::vector<std::vector<FaceId>> non_orientable_cycles;
  /// Whether anything changed.
  bool changed() const noexcept {
    return !removed_faces.empty() || !merged_corner_faces.empty() || !split_vertices.empty() || !flipped_faces.empty();
  }
};

/// Repairs `mesh` as described above. The result is a manifold; if `orientable`, it builds a
/// HalfedgeMesh.
RepairReport repair(const FaceVertexMesh& mesh);

/// One line per change, for logs and the CLI.
std::string describe(const RepairReport& report);

}  // namespace patchwork
