#pragma once
// What the commands share about output files: the extension that picks the format (reading and
// writing polygon meshes in any format is io/polygon_mesh_file.h).

#include <string>

#include "io/mesh_file.h"          // lower_extension, which the commands use with these
#include "io/polygon_mesh_file.h"  // is_gltf, write_polygon_mesh

namespace patchwork::tools {

/// \throws InvalidInput naming `command` unless `path` ends in .obj, .off, .ply, .glb or .gltf.
void check_mesh_output(const std::string& command, const std::string& path);

}  // namespace patchwork::tools
