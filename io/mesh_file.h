#pragma once
// Mesh files chosen by their extension, and the rules the mesh formats share.
//
//   .obj  io/obj.h   Wavefront OBJ (text)
//   .off  io/off.h   Geomview OFF (text)
//   .ply  io/ply.h   Stanford PLY (text or binary, either byte order)
//
// The extension is compared without regard to case (.OBJ is .obj). Every reader reads the whole
// file first and parses it strictly: a file that is missing or a directory is an IoError, any
// content the format does not allow is a ParseError naming the file, the line and the column
// (binary PLY data: line 0 and column = 1-based byte position, the 0-based offset in the message).
// Readers trust no count in a file: nothing is reserved for more elements than the bytes left
// could hold. Every writer uses the shortest decimal (or the exact binary) form of each double,
// so writing and reading back gives the same mesh bit for bit; files are written whole or not at
// all (io/atomic_file.h).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/ply.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// The extension of `path` in lower case, with its dot (".glb"; empty if it has none).
std::string lower_extension(const std::filesystem::path& path);

/// Reads a .obj, .off or .ply file by its extension.
/// \throws IoError for another extension or an unreadable file, ParseError if it is malformed.
FaceVertexMesh read_mesh(const std::filesystem::path& path);

/// Writes a .obj, .off or .ply file by its extension (PLY in `ply_format`), atomically.
/// \throws IoError for another extension or a failed write (nothing written), InvalidInput as the
///         format's writer (format_obj refuses a mesh without vertices).
void write_mesh(const std::filesystem::path& path, const FaceVertexMesh& mesh,
                PlyFormat ply_format = PlyFormat::binary_little_endian);

namespace detail {

// ---------------------------------------------------------------------------------------------
// Shared by the readers and writers in io/obj.cpp, io/off.cpp and io/ply.cpp.

/// A whitespace-separated token of a text line and its 1-based byte column.
struct TextToken {
  std::string_view text;
  std::int64_t column;
  /// The column just after the token.
  std::int64_t end_column() const noexcept { return column + static_cast<std::int64_t>(text.size()); }
};

/// Splits a text into lines of tokens, remembering lines and columns for error messages.
/// Spaces, tabs, '\r', '\v' and '\f' separate tokens (Windows line endings read); blank lines
/// are skipped; `comment` (if not '\0') starts a comment that runs to the end of its line.
/// With `continuation` (OBJ), a line whose last character before any comment and trailing space
/// is '\' goes on in the next line: the '\' is dropped and the tokens of both form one line,
/// which line() numbers by the line it starts in; each token keeps the column in its own line.
class TextLines {
 public:
  TextLines(std::string_view text, std::string name, char comment, bool continuation = false);

  /// The tokens of the next line that has any; empty at the end of the text (then line() and
  /// fail_at_end() refer to just after the last token). Valid until the next call.
  std::span<const TextToken> next_line();
  /// The 1-based number of the line last returned (where it starts, with continuation lines).
  std::int64_t line() const noexcept { return line_; }
  /// The physical line a token of the line last returned stands in (line() for a copy).
  std::int64_t token_line(const TextToken& token) const;
  /// The byte offset where the next line starts.
  std::size_t offset() const noexcept { return position_; }
  /// The bytes not read yet.
  std::size_t remaining() const noexcept { return text_.size() - position_; }
  const std::string& name() const noexcept { return name_; }

  /// Fails at `column` of the line last returned. \throws ParseError.
  [[noreturn]] void fail(std::int64_t column, const std::string& message) const;
  /// Fails at a token of the line last returned: its column, and for a token in a continuation
  /// line, that line's number in the message (the error's line is where the statement starts).
  /// \throws ParseError.
  [[noreturn]] void fail(const TextToken& token, const std::string& message) const;
  /// Fails just after the last token of the text (1:1 for a blank text). \throws ParseError.
  [[noreturn]] void fail_at_end(const std::string& message) const;

 private:
  std::string_view text_;
  std::string name_;
  char comment_;
  bool continuation_;
  std::size_t position_ = 0;
  std::int64_t line_ = 0;
  std::int64_t physical_line_ = 0;
  std::int64_t last_token_line_ = 1;
  std::int64_t last_token_end_ = 1;
  std::vector<TextToken> tokens_;
  std::vector<std::int64_t> token_lines_;  // the physical line of each token
};

/// A token as it may appear in a message: quoted, at most 32 bytes, bytes other than printable
/// ASCII as \xNN (a NUL byte from a binary file would otherwise cut what() short).
std::string quoted(std::string_view token);

/// Parses the whole token as a decimal double (an optional leading '+' allowed; nan and inf
/// spellings parse, range errors do not). Returns false if it is not one.
bool parse_double(std::string_view token, double& value);

/// Parses the whole token as a decimal 64-bit integer (an optional leading '+' allowed).
bool parse_integer(std::string_view token, std::int64_t& value);

/// Appends the shortest decimal form of x that reads back to the same double.
void append_double(std::string& text, double x);

/// How many of `count` elements to reserve room for when each takes at least `min_bytes` of
/// the `remaining_bytes` of a file: never more than the file could hold.
std::size_t reservable(std::uint64_t count, std::size_t remaining_bytes, std::size_t min_bytes);

/// The N x 3 position matrix of flat coordinates x0 y0 z0 x1 y1 z1 ... (size a multiple of 3).
Positions positions_from_flat(const std::vector<double>& xyz);

/// The largest vertex count a file may declare: ids are 32-bit with all ones invalid.
inline constexpr std::uint64_t max_mesh_vertices = 0xfffffffeu;

}  // namespace detail
}  // namespace patchwork
