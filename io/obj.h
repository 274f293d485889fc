#pragma once
// Wavefront OBJ, the polygon part: vertices and faces; free-form geometry refused, the rest read past.
//
//   # a comment (also after a statement)
//   v 0 0 0            x y z, optionally w or a colour after them (3 to 7 numbers; xyz used)
//   v 1 0 0
//   v 0 1 0
//   vt 0 0             texture coordinates, normals, groups, materials ... are ignored
//   f 1 2 3            corners as v, v/vt, v//vn or v/vt/vn; 1-based, or negative: relative,
//   f -3 -2/1 -1//4    -1 is the last vertex defined before the face
//
// Reading: a face has at least 3 corners (repeated vertices are kept for topology analysis to
// report); absolute indices may refer to vertices defined later in the file; coordinates are
// finite; a line ending in '\' goes on in the next one (errors name the line it starts in); a
// statement OBJ does not define, an empty file or one without any vertex is a ParseError with the
// file, the line and the column. The statements read past are vt, vn, vp, g, o, s, mg, usemtl,
// mtllib, l, p and those of rendering (lod, ctech, stech, shadow_obj, trace_obj, maplib, usemap,
// bevel, c_interp, d_interp, call). Free-form geometry (cstype, deg, bmat, step, curv, curv2,
// surf, parm, trim, hole, scrv, sp, end, con) is a ParseError pointing to read_obj_freeform
// (io/obj_freeform.h): reading past it would give a mesh without those surfaces.
// Writing: 'v x y z' lines in the shortest decimal form that reads back to the same double,
// then 'f' lines with 1-based indices; whole or not at all.

#include <filesystem>
#include <string>
#include <string_view>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// Parses OBJ text; `name` is used in error messages. \throws ParseError.
FaceVertexMesh parse_obj(std::string_view text, const std::string& name);

/// Reads an OBJ file. \throws IoError if it cannot be read, ParseError if it is malformed.
FaceVertexMesh read_obj(const std::filesystem::path& path);

/// The OBJ text of the mesh. \throws InvalidInput if it has no vertex (the reader refuses that).
std::string format_obj(const FaceVertexMesh& mesh);

/// Writes an OBJ file atomically. \throws InvalidInput as format_obj (nothing written), IoError.
void write_obj(const std::filesystem::path& path, const FaceVertexMesh& mesh);

}  // namespace patchwork
