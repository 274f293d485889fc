#pragma once
// The index-based half-edge mesh (seed Def 55), structure of arrays with implicit twins.
//
//   edge e has half-edges 2e and 2e+1, twin(h) = h ^ 1
//
//            destination(h) = origin(twin(h))
//                 ^   |
//       face(h)   h   | twin(h)   face(twin(h))   (invalid: the outer face, at the boundary)
//                 |   v
//               origin(h)
//
// Per half-edge: origin, next, prev and face (the outer face is the invalid FaceId). Faces walk
// their half-edges counter-clockwise; boundary half-edges (no face) are linked into loops that
// walk each hole the other way round. A vertex's halfedge() leaves it, and on the boundary it is
// the outgoing boundary half-edge, so one rotation (twin(prev(h))) visits the whole fan.
//
// Building validates: a HalfedgeMesh is always an oriented 2-manifold with boundary. Anything
// else (an edge with three faces, a vertex whose faces form several fans, a face repeating a
// vertex, inconsistent orientation) is a TopologyError naming the faces and vertices, thrown
// before anything is built; such data stays in a FaceVertexMesh, which analyze() explains.

#include <cstdint>
#include <vector>

#include "meshes/face_vertex_mesh.h"
#include "meshes/ids.h"

namespace patchwork {

class HalfedgeMesh {
 public:
  /// Builds from a face list in O(corners + vertices) time.
  /// \throws TopologyError if the faces do not form an oriented 2-manifold with boundary.
  explicit HalfedgeMesh(const FaceVertexMesh& mesh);

  std::size_t vertex_count() const noexcept { return vertex_halfedge_.size(); }
  std::size_t halfedge_count() const noexcept { return origin_.size(); }
  std::size_t edge_count() const noexcept { return origin_.size() / 2; }
  std::size_t face_count() const noexcept { return face_halfedge_.size(); }

  VertexId origin(HalfedgeId h) const noexcept { return VertexId(origin_[h.index()]); }
  VertexId destination(HalfedgeId h) const noexcept { return VertexId(origin_[twin(h).index()]); }
  static HalfedgeId twin(HalfedgeId h) noexcept { return HalfedgeId(h.value ^ 1u); }
  HalfedgeId next(HalfedgeId h) const noexcept { return HalfedgeId(next_[h.index()]); }
  HalfedgeId prev(HalfedgeId h) const noexcept { return HalfedgeId(prev_[h.index()]); }
  /// The face of h; invalid for a boundary half-edge (the outer face, -1 in Def 55).
  FaceId face(HalfedgeId h) const noexcept { return FaceId(face_[h.index()]); }
  static EdgeId edge(HalfedgeId h) noexcept { return EdgeId(h.value >> 1); }
  /// Half-edge 0 or 1 of an edge.
  static HalfedgeId halfedge(EdgeId e, int side) noexcept { return HalfedgeId(2 * e.value + static_cast<std::uint32_t>(side)); }
  /// An outgoing half-edge (the boundary one on the boundary); invalid for an isolated vertex.
  HalfedgeId halfedge(VertexId v) const noexcept { return HalfedgeId(vertex_halfedge_[v.index()]); }
  /// A half-edge of face f.
  HalfedgeId halfedge(FaceId f) const noexcept { return HalfedgeId(face_halfedge_[f.index()]); }

  bool is_boundary(HalfedgeId h) const noexcept { return !face(h).valid(); }
  bool is_boundary(EdgeId e) const noexcept { return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1)); }
  bool is_boundary(VertexId v) const noexcept { return halfedge(v).valid() && is_boundary(halfedge(v)); }
  bool is_isolated(VertexId v) const noexcept { return !halfedge(v).valid(); }

  const Positions& positions() const noexcept { return positions_; }
  Vec3 position(VertexId v) const { return positions_.row(static_cast<Eigen::Index>(v.index())).transpose(); }

  /// Number of corners of face f.
  std::size_t face_size(FaceId f) const;
  /// The vertices of face f in order.
  std::vector<VertexId> face_vertices(FaceId f) const;
  /// Vertices around v (the destinations of its outgoing half-edges), in rotation order.
  std::vector<VertexId> vertex_neighbours(VertexId v) const;

  /// Checks every invariant: twin(twin(h)) = h, next(prev(h)) = h, origin(twin(h)) =
  /// destination(h), every face and boundary cycle closes, faces are set consistently, every
  /// vertex's fan is complete. \throws std::logic_error naming the broken invariant.
  void validate() const;

 private:
  // The ids' values (the invalid id is 0xffffffff), as plain integers so that construction can
  // take over the edge table's arrays.
  Positions positions_;
  std::vector<std::uint32_t> origin_;
  std::vector<std::uint32_t> next_;
  std::vector<std::uint32_t> prev_;
  std::vector<std::uint32_t> face_;
  std::vector<std::uint32_t> vertex_halfedge_;
  std::vector<std::uint32_t> face_halfedge_;
};

/// The face list of a half-edge mesh (faces in id order, each from halfedge(f)).
FaceVertexMesh to_face_vertex_mesh(const HalfedgeMesh& mesh);

}  // namespace patchwork
