#pragma once
// `patchwork convert IN OUT`: between the mesh formats (OBJ, OFF, PLY) and glTF (.glb, .gltf),
// chosen by extension. A mesh becomes glTF with its polygons fanned into triangles (from each
// face's first corner: exact for convex faces) and angle-weighted vertex normals split at creases
// over 30 degrees (meshes/normals.h); glTF becomes a mesh through its welded positions.

#include <string>

namespace patchwork::tools {

/// Converts `input` to `output`. \throws IoError or ParseError for unreadable or malformed input
/// or a failed write (nothing written), InvalidInput for an unknown extension.
void run_convert(const std::string& input, const std::string& output);

}  // namespace patchwork::tools
