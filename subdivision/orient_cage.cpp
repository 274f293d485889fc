#include "subdivision/orient_cage.h"

#include "meshes/edge_table.h"
#include "meshes/orientation.h"

namespace patchwork {

CageOrientation orient_cage(const SubdivisionCage& cage) {
  const FaceVertexMesh& mesh = cage.mesh;
  const detail::EdgeTable table(mesh);
  const detail::OrientationWalk walk = detail::walk_orientation(mesh, table);
  const std::vector<std::uint32_t>& component = walk.components.of_face;

  // walk.flip orients each component like its first face; the other orientation flips the
  // complement. Keep the one that flips fewer faces.
  std::vector<std::size_t> faces(walk.components.count, 0), walk_flips(walk.components.count, 0);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    ++faces[component[f]];
    walk_flips[component[f]] += walk.flip[f];
  }
  CageOrientation result;
  std::vector<bool> flip(mesh.face_count(), false);
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t c = component[f];
    if (!walk.component_orientable[c]) continue;
    flip[f] = walk.flip[f] != (2 * walk_flips[c] > faces[c]);
    if (flip[f]) result.flipped.push_back(FaceId{f});
  }
  for (const bool orientable : walk.component_orientable) result.non_orientable_components += !orientable;
  const auto& corners = mesh.face_indices();
  for (std::uint32_t c = 0; c < corners.size(); ++c) {
    const std::uint32_t t = table.twin(c);
    // Each edge once (from its lower corner); the same first vertex is the same direction.
    if (t < detail::EdgeTable::crowded && c < t && corners[c] == corners[t] &&
        !walk.component_orientable[component[table.face_of(c)]]) {
      ++result.seam_edges;
    }
  }

  result.cage = cage;
  if (result.flipped.empty()) return result;
  std::vector<std::uint32_t> indices = corners;
  detail::flip_corners(mesh.face_sizes(), flip, indices);
  result.cage.mesh = FaceVertexMesh(mesh.positions(), mesh.face_sizes(), std::move(indices));
  if (result.cage.face_varying) detail::flip_corners(mesh.face_sizes(), flip, result.cage.face_varying->indices);
  return result;
}

}  // namespace patchwork
