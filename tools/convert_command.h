#pragma once
// `patchwork convert IN OUT`: between the mesh formats (OBJ, OFF, PLY) and glTF (.glb, .gltf),
// chosen by extension. A mesh becomes glTF with its polygons triangulated (ear clipping in
// each face's plane, meshes/polygon.h; self-intersecting faces refused) and angle-weighted vertex normals split at creases
// over 30 degrees (meshes/normals.h); glTF becomes a mesh through its welded positions.
// Files of patches (BPT, free-form OBJ) convert into each other: BPT to free-form OBJ as one
// Bezier record per patch; free-form OBJ to BPT as the Bezier pieces of its surfaces over their
// ranges, refused when a piece is rational (BPT has no weights).

#include <string>

namespace patchwork::tools {

/// Converts `input` to `output`. \throws IoError or ParseError for unreadable or malformed input
/// or a failed write (nothing written), InvalidInput for an unknown extension.
void run_convert(const std::string& input, const std::string& output);

}  // namespace patchwork::tools
