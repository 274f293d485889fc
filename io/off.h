#pragma once
// Geomview OFF, the 3-dimensional text form:
//
//   OFF                 header (optional); COFF, NOFF, CNOFF, STOFF, STCNOFF ... also read
//   # a comment         '#' starts a comment anywhere, to the end of the line
//   4 4 6               counts: vertices V, faces F, edges E (E optional and ignored)
//   0 0 0               V vertex lines 'x y z', optionally followed by more numbers
//   1 0 0               (colour, normal, texture coordinates of the C/N/ST variants)
//   0 1 0
//   0 0 1
//   3 0 2 1             F face lines 'k i0 ... ik-1', 0-based indices, optionally followed by
//   3 0 1 3             a colour of at most 4 numbers
//   3 0 3 2
//   3 1 2 3
//
// The counts may also stand on the header line ('OFF 4 4 6'). Reading is strict and line by line:
// a face has k >= 3 corners and exactly k indices in [0, V) before its colour, coordinates are
// finite, nothing but comments follows the last face, and anything else (binary OFF, the 4D and
// n-dimensional variants, wrong counts, an empty file) is a ParseError with the file, the line
// and the column. Nothing is reserved for counts beyond what the rest of the file can hold.
// Writing: 'OFF', 'V F 0', shortest round-trip decimals, one face per line; whole or not at all.

#include <filesystem>
#include <string>
#include <string_view>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// Parses OFF text; `name` is used in error messages. \throws ParseError.
FaceVertexMesh parse_off(std::string_view text, const std::string& name);

/// Reads an OFF file. \throws IoError if it cannot be read, ParseError if it is malformed.
FaceVertexMesh read_off(const std::filesystem::path& path);

/// The OFF text of the mesh.
std::string format_off(const FaceVertexMesh& mesh);

/// Writes an OFF file atomically. \throws IoError.
void write_off(const std::filesystem::path& path, const FaceVertexMesh& mesh);

}  // namespace patchwork
