#include "tools/output_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <numbers>

#include "core/errors.h"
#include "io/gltf.h"
#include "io/mesh_file.h"
#include "meshes/normals.h"
#include "meshes/polygon.h"
#include "meshes/render_mesh.h"

namespace patchwork::tools {

namespace {

// Each face ear-clipped into triangles (meshes/polygon.h), normals split at 30 degree creases.
RenderMesh render_mesh(const FaceVertexMesh& mesh) {
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

}  // namespace

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool is_gltf(const std::string& path) {
  const std::string extension = lower_extension(path);
  return extension == ".glb" || extension == ".gltf";
}

void check_mesh_output(const std::string& command, const std::string& path) {
  const std::string extension = lower_extension(path);
  if (!is_gltf(path) && extension != ".obj" && extension != ".off" && extension != ".ply") {
    throw InvalidInput(detail::message(command, ": output ", path, " must end in .obj, .off, .ply, .glb or .gltf"));
  }
}

void write_polygon_mesh(const std::string& path, const FaceVertexMesh& mesh) {
  if (is_gltf(path)) {
    write_gltf(path, render_mesh(mesh));
  } else {
    write_mesh(path, mesh);
  }
}

}  // namespace patchwork::tools
