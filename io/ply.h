#pragma once
// Stanford PLY (Greg Turk's polygon file format), text or binary in either byte order:
//
//   ply
//   format binary_little_endian 1.0      or ascii 1.0, binary_big_endian 1.0
//   comment any text                     comment and obj_info lines are ignored
//   element vertex 4
//   property float x                     x, y, z of any scalar type (float, double, int, ...);
//   property float y                     other properties (nx, red, ...) and lists are read past
//   property float z
//   property uchar red
//   element face 2
//   property list uchar int vertex_indices   (or vertex_index): count type and index type integer
//   element edge 0                       other elements are read past, whatever their size
//   property int vertex1
//   end_header
//   <data: the elements in header order; ascii: one element per line, numbers separated by spaces>
//
// Scalar types: char uchar short ushort int uint float double, also spelled int8 uint8 int16
// uint16 int32 uint32 float32 float64. Reading is strict: the header declares one 'vertex'
// element with x, y, z and at most one 'face' element, each element has exactly the values its
// properties declare, integers fit their type, coordinates are finite, a face has at least 3
// corners in [0, V), and nothing follows the last element; anything else is a ParseError with
// the file, the line and column (header and ascii data) or, in binary data, line 0 and column =
// 1-based byte position with the 0-based byte offset in the message. A count is checked against
// the bytes left before anything is reserved or read for it (a header claiming 10^12 faces fails
// at once). An element without properties takes no data.
// Writing: double x y z, faces as 'list uchar int vertex_indices' (uint for a count above 255
// or an index above 2^31 - 1), in the chosen format; whole or not at all.

#include <filesystem>
#include <string>
#include <string_view>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// The encoding of the data after a PLY header.
enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

/// Parses the bytes of a PLY file; `name` is used in error messages. \throws ParseError.
FaceVertexMesh parse_ply(std::string_view bytes, const std::string& name);

/// Reads a PLY file. \throws IoError if it cannot be read, ParseError if it is malformed.
FaceVertexMesh read_ply(const std::filesystem::path& path);

/// The bytes of the PLY file of the mesh in `format`.
std::string format_ply(const FaceVertexMesh& mesh, PlyFormat format);

/// Writes a PLY file atomically. \throws IoError.
void write_ply(const std::filesystem::path& path, const FaceVertexMesh& mesh, PlyFormat format);

}  // namespace patchwork
