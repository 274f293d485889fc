#include "io/obj.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "io/obj_syntax.h"

namespace patchwork {
namespace {

using detail::message;
using detail::TextLines;
using detail::TextToken;

// Statements of the OBJ specification that carry nothing a FaceVertexMesh holds: vertex data
// other than positions, grouping, and display and rendering attributes (ctech and stech are the
// free-form ones). Free-form geometry itself is refused (read_obj_freeform reads it).
constexpr std::string_view ignored_statements[] = {
    "vt",    "vn",       "vp",       "g",   "o",      "s",      "mg",         "usemtl",    "mtllib", "l",     "p",
    "bevel", "c_interp", "d_interp", "lod", "maplib", "usemap", "shadow_obj", "trace_obj", "ctech",  "stech", "call"};

bool is_ignored(std::string_view keyword) {
  return std::find(std::begin(ignored_statements), std::end(ignored_statements), keyword) !=
         std::end(ignored_statements);
}

// The vertex a corner token refers to, as a 0-based index that may be >= the vertices defined so
// far (forward references are checked at the end). `vertices` is the number defined so far.
std::int64_t corner_vertex(const TextLines& reader, const TextToken& corner, std::int64_t vertices) {
  const detail::ObjReference reference = detail::parse_obj_reference(reader, corner, "a face corner");
  return detail::resolve_obj_index(reader, corner, reference.vertex, vertices, "vertex", "vertices");
}

}  // namespace

FaceVertexMesh parse_obj(std::string_view text, const std::string& name) {
  TextLines reader(text, name, '#', /*continuation=*/true);
  std::vector<double> xyz;
  std::vector<std::uint32_t> face_sizes;
  std::vector<std::uint32_t> face_indices;
  // The largest index used by a face and where it stands: forward references are allowed, so
  // indices are checked against the vertex count at the end of the file.
  std::int64_t max_index = -1;
  std::int64_t max_index_line = 0;
  std::int64_t max_index_column = 0;
  for (auto tokens = reader.next_line(); !tokens.empty(); tokens = reader.next_line()) {
    const std::string_view keyword = tokens[0].text;
    if (keyword == "v") {
      if (tokens.size() < 4 || tokens.size() > 8) {
        reader.fail(tokens.size() > 8 ? tokens[8].column : tokens.back().end_column(),
                    message("expected a vertex 'v x y z' with at most 4 more numbers (w or a colour), found ",
                            tokens.size() - 1, tokens.size() == 2 ? " number" : " numbers"));
      }
      if (xyz.size() / 3 >= detail::max_mesh_vertices) {
        reader.fail(tokens[0].column, message("more than ", detail::max_mesh_vertices, " vertices"));
      }
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        double value = 0.0;
        if (!detail::parse_double(tokens[k].text, value) || (k <= 3 && !std::isfinite(value))) {
          reader.fail(tokens[k],
                      message(k <= 3 ? "expected a finite coordinate, found " : "expected a number, found ",
                              detail::quoted(tokens[k].text)));
        }
        if (k <= 3) xyz.push_back(value);
      }
    } else if (keyword == "f") {
      const std::size_t corners = tokens.size() - 1;
      if (corners < 3) {
        reader.fail(corners == 0 ? tokens[0].end_column() : tokens[1].column,
                    message("a face has at least 3 corners, found ", corners));
      }
      if (corners > 0xffffffffu)
        reader.fail(tokens[1], message("a face has ", corners, " corners (32-bit sizes)"));
      const auto vertices = static_cast<std::int64_t>(xyz.size() / 3);
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::int64_t index = corner_vertex(reader, tokens[k], vertices);
        if (index > max_index) {
          max_index = index;
          max_index_line = reader.line();
          max_index_column = tokens[k].column;
        }
        // Indices beyond 32 bits are out of range for any vertex count and reported at the end.
        face_indices.push_back(static_cast<std::uint32_t>(std::min<std::int64_t>(index, 0xffffffff)));
      }
      face_sizes.push_back(static_cast<std::uint32_t>(corners));
    } else if (detail::is_obj_freeform_statement(keyword)) {
      reader.fail(tokens[0], message("free-form statement ", detail::quoted(keyword),
                                     " in a polygon OBJ file: free-form curves and surfaces are read by "
                                     "read_obj_freeform (io/obj_freeform.h), not as a mesh"));
    } else if (!is_ignored(keyword)) {
      reader.fail(tokens[0].column, message("unknown OBJ statement ", detail::quoted(keyword)));
    }
  }
  const auto vertices = static_cast<std::int64_t>(xyz.size() / 3);
  if (vertices == 0) reader.fail_at_end("no vertex ('v x y z') in the file");
  if (max_index >= vertices) {
    throw ParseError(name, max_index_line, max_index_column,
                     message("face uses vertex ", max_index + 1, " but the file defines ", vertices, " vertices"));
  }
  return FaceVertexMesh(detail::positions_from_flat(xyz), std::move(face_sizes), std::move(face_indices));
}

FaceVertexMesh read_obj(const std::filesystem::path& path) { return parse_obj(read_file(path), path.string()); }

std::string format_obj(const FaceVertexMesh& mesh) {
  if (mesh.vertex_count() == 0) throw InvalidInput("format_obj: the mesh has no vertex (an OBJ file needs one)");
  std::string text;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = mesh.position(v);
    text += "v ";
    detail::append_double(text, p.x());
    text += ' ';
    detail::append_double(text, p.y());
    text += ' ';
    detail::append_double(text, p.z());
    text += '\n';
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    text += 'f';
    for (std::uint32_t index : mesh.face(f)) {
      text += ' ';
      text += std::to_string(std::uint64_t{index} + 1);
    }
    text += '\n';
  }
  return text;
}

void write_obj(const std::filesystem::path& path, const FaceVertexMesh& mesh) {
  write_file_atomically(path, format_obj(mesh));
}

}  // namespace patchwork
