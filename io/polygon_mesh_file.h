#pragma once
// Polygon meshes in any mesh format patchwork reads and writes: OBJ, OFF and PLY as they are
// (io/mesh_file.h), glTF through a render mesh (io/gltf.h). What the CLI's convert and subdivide
// commands and the Python module share.

#include <filesystem>

#include "meshes/face_vertex_mesh.h"
#include "meshes/render_mesh.h"

namespace patchwork {

/// Whether `path` ends in .glb or .gltf (any case).
bool is_gltf(const std::filesystem::path& path);

/// The polygon mesh of a .obj, .off or .ply file, or the welded triangles of a .glb or .gltf file
/// (welded_faces of its render mesh). \throws IoError, ParseError naming the file.
FaceVertexMesh read_polygon_mesh(const std::filesystem::path& path);

/// A polygon mesh as a render mesh: the polygons triangulated by triangulate_faces
/// (meshes/polygon.h: ear clipping, keeping each face's winding) and angle-weighted vertex
/// normals split at creases over 30 degrees (meshes/normals.h).
/// \throws InvalidInput naming the face for a face that is not simple.
RenderMesh render_mesh_of(const FaceVertexMesh& mesh);

/// Writes a polygon mesh by extension: OBJ, OFF, PLY as they are; glTF as render_mesh_of(mesh).
/// Atomic. \throws IoError for another extension or a failed write, InvalidInput as the writers.
void write_polygon_mesh(const std::filesystem::path& path, const FaceVertexMesh& mesh);

}  // namespace patchwork
