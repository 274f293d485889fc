#include "io/polygon_mesh_file.h"

#include <numbers>

#include "io/gltf.h"
#include "io/mesh_file.h"
#include "meshes/normals.h"
#include "meshes/polygon.h"

namespace patchwork {

bool is_gltf(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  return extension == ".glb" || extension == ".gltf";
}

FaceVertexMesh read_polygon_mesh(const std::filesystem::path& path) {
  return is_gltf(path) ? welded_faces(read_gltf(path)) : read_mesh(path);
}

RenderMesh render_mesh_of(const FaceVertexMesh& mesh) {
  const SplitNormals split = split_normals(mesh, 30.0 * std::numbers::pi / 180.0);
  RenderMesh render;
  for (std::size_t v = 0; v < split.mesh.vertex_count(); ++v) {
    render.positions.push_back(split.mesh.position(v));
    // A vertex of no face, or only of zero-area faces, has no normal; glTF wants a unit one.
    const Vec3& n = split.normals[v];
    render.normals.push_back(n.norm() > 0.0 ? n.normalized() : Vec3::UnitZ());
    render.position_ids.push_back(split.source_vertex[v]);
  }
  render.indices = triangulate_faces(split.mesh);
  return render;
}

void write_polygon_mesh(const std::filesystem::path& path, const FaceVertexMesh& mesh) {
  if (is_gltf(path)) {
    write_gltf(path, render_mesh_of(mesh));
  } else {
    write_mesh(path, mesh);
  }
}

}  // namespace patchwork
