#pragma once
// The edge list (seed Def 54): edges as vertex pairs, faces as lists of edge indices, and per
// edge its left and right face, -1 (the invalid FaceId) at the boundary.
//
//   edge e = (from, to): left(e) is the face that walks it from -> to (counter-clockwise faces
//   have the edge on their left), right(e) the face that walks it to -> from.
//
// Edges are numbered in order of first use by the faces. Like the half-edge mesh, an edge list
// needs each edge walked at most once in each direction: more is a TopologyError.

#include <array>
#include <cstdint>
#include <vector>

#include "meshes/face_vertex_mesh.h"
#include "meshes/halfedge_mesh.h"

namespace patchwork {

class EdgeListMesh {
 public:
  /// Builds the edge list of a face list.
  /// \throws TopologyError if an edge is used by more than two faces or twice in one direction.
  explicit EdgeListMesh(const FaceVertexMesh& mesh);

  const Positions& positions() const noexcept { return positions_; }
  std::size_t edge_count() const noexcept { return edges_.size(); }
  std::size_t face_count() const noexcept { return face_edges_.size(); }
  /// The vertices (from, to) of edge e.
  const std::array<VertexId, 2>& edge(EdgeId e) const noexcept { return edges_[e.index()]; }
  /// The face walking e from -> to, or invalid.
  FaceId left(EdgeId e) const noexcept { return left_[e.index()]; }
  /// The face walking e to -> from, or invalid.
  FaceId right(EdgeId e) const noexcept { return right_[e.index()]; }
  /// The edges of face f in walking order.
  const std::vector<EdgeId>& face_edges(FaceId f) const noexcept { return face_edges_[f.index()]; }

  /// Checks that left/right faces and face edge lists agree. \throws std::logic_error.
  void validate() const;

 private:
  Positions positions_;
  std::vector<std::array<VertexId, 2>> edges_;
  std::vector<FaceId> left_;
  std::vector<FaceId> right_;
  std::vector<std::vector<EdgeId>> face_edges_;
};

/// The face list of an edge list: each face's corners recovered from its edges' directions.
FaceVertexMesh to_face_vertex_mesh(const EdgeListMesh& mesh);

/// The edge list of a half-edge mesh (through its face list; same numbering as from that list).
EdgeListMesh to_edge_list(const HalfedgeMesh& mesh);

/// The half-edge mesh of an edge list. \throws TopologyError as HalfedgeMesh does.
HalfedgeMesh to_halfedge_mesh(const EdgeListMesh& mesh);

}  // namespace patchwork
