#pragma once
// The undirected edges of a polygon soup with every use by a face: the common first step of
// topology analysis, orientation and repair. Works on any face list (non-manifold included).

#include <cstdint>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// One face's use of an edge: the face, and whether it walks the edge from its first vertex.
struct EdgeUse {
  std::uint32_t face;
  bool forward;
};

/// Edges numbered in order of first use; vertices[e] = {a, b} as first walked.
struct EdgeTable {
  std::vector<std::array<std::uint32_t, 2>> vertices;
  std::vector<std::vector<EdgeUse>> uses;
  /// corner_edge[c] = the edge from corner c of the flat index list to the next corner of its face.
  std::vector<std::uint32_t> corner_edge;
};

/// The edge table of a face list, in O(corners) expected time.
EdgeTable build_edge_table(const FaceVertexMesh& mesh);

}  // namespace patchwork
