#include "tools/output_files.h"

#include "core/errors.h"

namespace patchwork::tools {

void check_mesh_output(const std::string& command, const std::string& path) {
  const std::string extension = lower_extension(path);
  if (!is_gltf(path) && extension != ".obj" && extension != ".off" && extension != ".ply") {
    throw InvalidInput(detail::message(command, ": output ", path, " must end in .obj, .off, .ply, .glb or .gltf"));
  }
}

}  // namespace patchwork::tools
