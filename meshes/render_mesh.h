#pragma once
// A triangle mesh ready to draw: per-vertex attributes in separate arrays (the layout of glTF
// buffers) and a flat list of triangles.
//
//   positions      p0 p1 p2 ...          one per vertex
//   normals        n0 n1 n2 ...          unit, one per vertex (or none)
//   uvs            t0 t1 t2 ...          one per vertex (or none)
//   tangents       (x, y, z, w) ...      unit xyz along increasing u, w = +1 or -1 the
//                                        handedness of (normal x tangent) against dF/dv (or none)
//   indices        [a b c  a b c ...]    3 per triangle, counter-clockwise seen from the side the
//                                        normals point to
//   position_ids   one per vertex        the welded position a vertex stands for
//
// A renderer needs a separate vertex wherever an attribute jumps (a crease in the normals, a
// seam in the UVs); topology needs one vertex per point. position_ids keeps both: vertices split
// only for their attributes share a position id, and welded_faces() gives the mesh over those
// ids that meshes/topology.h analyses.

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork {

struct RenderMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<Vec4> tangents;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> position_ids;

  /// Number of vertices.
  std::size_t vertex_count() const noexcept { return positions.size(); }
  /// Number of triangles.
  std::size_t triangle_count() const noexcept { return indices.size() / 3; }
};

/// Checks sizes (attributes empty or one per vertex, indices a multiple of 3), index ranges,
/// finite values, unit normals and tangents (to 1e-6), w = +-1, and that vertices sharing a
/// position id share the position. \throws InvalidInput naming the first element that fails.
void validate(const RenderMesh& mesh);

/// The triangles over the welded positions (one vertex per position id, at the position of the
/// first vertex with that id): the mesh whose topology the render mesh has.
/// \throws InvalidInput if validate() fails.
FaceVertexMesh welded_faces(const RenderMesh& mesh);

}  // namespace patchwork
