#pragma once
// What the commands share about output files: the extension that picks the format, and writing
// a polygon mesh to any of them.

#include <string>

#include "meshes/face_vertex_mesh.h"

namespace patchwork::tools {

/// The extension of `path` in lower case, with its dot (".glb").
std::string lower_extension(const std::string& path);

/// Whether `path` ends in .glb or .gltf (any case).
bool is_gltf(const std::string& path);

/// \throws InvalidInput naming `command` unless `path` ends in .obj, .off, .ply, .glb or .gltf.
void check_mesh_output(const std::string& command, const std::string& path);

/// Writes a polygon mesh by extension: OBJ, OFF, PLY as they are; glTF with the polygons
/// triangulated by triangulate_faces (meshes/polygon.h: ear clipping, keeping each face's winding)
/// and angle-weighted vertex normals split at creases over 30 degrees (meshes/normals.h). Atomic.
/// \throws InvalidInput naming the face for a glTF output of a face that is not simple.
void write_polygon_mesh(const std::string& path, const FaceVertexMesh& mesh);

}  // namespace patchwork::tools
