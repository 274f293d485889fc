#include "io/off.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"

namespace patchwork {
namespace {

using detail::message;
using detail::TextLines;
using detail::TextToken;

// The most numbers a face line may carry after its indices: a colour map index, RGB or RGBA.
constexpr std::size_t max_face_colour = 4;

// What a header keyword [ST][C][N][4][n]OFF says, or nothing if the token is not one.
enum class OffHeader { three_dimensional, four_dimensional, n_dimensional };

std::optional<OffHeader> off_header(std::string_view token) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return std::nullopt;
  std::string_view prefix = token.substr(0, token.size() - 3);
  const auto take = [&prefix](std::string_view part) {
    if (prefix.substr(0, part.size()) != part) return false;
    prefix.remove_prefix(part.size());
    return true;
  };
  take("ST");
  take("C");
  take("N");
  const bool four = take("4");
  const bool n = take("n");
  if (!prefix.empty()) return std::nullopt;
  if (n) return OffHeader::n_dimensional;
  return four ? OffHeader::four_dimensional : OffHeader::three_dimensional;
}

std::int64_t integer_token(const TextLines& reader, const TextToken& token, const std::string& what) {
  std::int64_t value = 0;
  if (!detail::parse_integer(token.text, value)) {
    reader.fail(token.column, message("expected ", what, " (an integer), found ", detail::quoted(token.text)));
  }
  return value;
}

// Parses the counts 'V F [E]' from `tokens`; returns V and F.
std::pair<std::int64_t, std::int64_t> parse_counts(const TextLines& reader, std::span<const TextToken> tokens) {
  if (tokens.size() < 2 || tokens.size() > 3) {
    reader.fail(tokens.size() > 3 ? tokens[3].column : tokens.back().end_column(),
                message("expected the counts 'V F E' (vertices, faces, optional edges), found ", tokens.size(),
                        tokens.size() == 1 ? " number" : " numbers"));
  }
  const char* names[] = {"the vertex count V", "the face count F", "the edge count E"};
  std::int64_t counts[3] = {0, 0, 0};
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    counts[k] = integer_token(reader, tokens[k], names[k]);
    if (counts[k] < 0) reader.fail(tokens[k].column, message(names[k], " is negative: ", counts[k]));
  }
  if (static_cast<std::uint64_t>(counts[0]) > detail::max_mesh_vertices) {
    reader.fail(tokens[0].column,
                message("the vertex count ", counts[0], " exceeds the limit ", detail::max_mesh_vertices));
  }
  return {counts[0], counts[1]};
}

}  // namespace

FaceVertexMesh parse_off(std::string_view text, const std::string& name) {
  TextLines reader(text, name, '#');
  auto tokens = reader.next_line();
  if (tokens.empty()) reader.fail_at_end("unexpected end of file: expected the header 'OFF' or the counts 'V F E'");
  if (const auto header = off_header(tokens[0].text)) {
    if (*header != OffHeader::three_dimensional) {
      reader.fail(tokens[0].column, message("unsupported OFF variant ", detail::quoted(tokens[0].text),
                                            " (only 3-dimensional OFF is read, with optional ST, C, N prefixes)"));
    }
    if (tokens.size() > 1 && tokens[1].text == "BINARY") reader.fail(tokens[1].column, "binary OFF is not supported");
    tokens = tokens.subspan(1);
    if (tokens.empty()) {
      tokens = reader.next_line();
      if (tokens.empty()) reader.fail_at_end("unexpected end of file: expected the counts 'V F E'");
    }
  } else {
    std::int64_t ignored = 0;
    if (!detail::parse_integer(tokens[0].text, ignored)) {
      reader.fail(tokens[0].column,
                  message("expected the header 'OFF' or the counts 'V F E', found ", detail::quoted(tokens[0].text)));
    }
  }
  const auto [vertex_count, face_count] = parse_counts(reader, tokens);

  std::vector<double> xyz;
  xyz.reserve(3 * detail::reservable(static_cast<std::uint64_t>(vertex_count), reader.remaining(), 6));  // "0 0 0\n"
  for (std::int64_t v = 0; v < vertex_count; ++v) {
    tokens = reader.next_line();
    if (tokens.empty())
      reader.fail_at_end(message("unexpected end of file: expected vertex ", v, " of ", vertex_count, " as 'x y z'"));
    if (tokens.size() < 3) {
      reader.fail(tokens.back().end_column(), message("expected vertex ", v, " as 'x y z', found ", tokens.size(),
                                                      tokens.size() == 1 ? " number" : " numbers"));
    }
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      double value = 0.0;
      if (!detail::parse_double(tokens[k].text, value) || (k < 3 && !std::isfinite(value))) {
        reader.fail(tokens[k].column,
                    message(k < 3 ? "expected a finite coordinate of vertex " : "expected a number after vertex ", v,
                            ", found ", detail::quoted(tokens[k].text)));
      }
      if (k < 3) xyz.push_back(value);
    }
  }

  std::vector<std::uint32_t> face_sizes;
  std::vector<std::uint32_t> face_indices;
  const std::size_t faces_to_reserve =
      detail::reservable(static_cast<std::uint64_t>(face_count), reader.remaining(), 8);
  face_sizes.reserve(faces_to_reserve);  // "3 0 0 0\n"
  face_indices.reserve(3 * faces_to_reserve);
  for (std::int64_t f = 0; f < face_count; ++f) {
    tokens = reader.next_line();
    if (tokens.empty()) {
      reader.fail_at_end(
          message("unexpected end of file: expected face ", f, " of ", face_count, " as 'k i0 ... ik-1'"));
    }
    const std::int64_t corners = integer_token(reader, tokens[0], message("the corner count k of face ", f));
    if (corners < 3) reader.fail(tokens[0].column, message("face ", f, " has ", corners, " corners (at least 3)"));
    const auto given = static_cast<std::int64_t>(tokens.size()) - 1;
    if (given < corners) {
      reader.fail(tokens.back().end_column(), message("face ", f, " has ", corners, " corners but ", given,
                                                      given == 1 ? " index" : " indices", " follow"));
    }
    for (std::int64_t k = 1; k <= corners; ++k) {
      const TextToken& token = tokens[static_cast<std::size_t>(k)];
      const std::int64_t index = integer_token(reader, token, message("a vertex index of face ", f));
      if (index < 0) reader.fail(token.column, message("face ", f, " has the negative vertex index ", index));
      if (index >= vertex_count) {
        reader.fail(token.column,
                    message("face ", f, " uses vertex ", index, " but there are ", vertex_count, " vertices"));
      }
      face_indices.push_back(static_cast<std::uint32_t>(index));
    }
    const auto colour = static_cast<std::size_t>(given - corners);
    if (colour > max_face_colour) {
      reader.fail(tokens[static_cast<std::size_t>(corners) + 1 + max_face_colour].column,
                  message("face ", f, " has ", colour, " numbers after its ", corners,
                          " indices (a colour has at most ", max_face_colour, "): is the corner count wrong?"));
    }
    for (std::size_t k = static_cast<std::size_t>(corners) + 1; k < tokens.size(); ++k) {
      double value = 0.0;
      if (!detail::parse_double(tokens[k].text, value)) {
        reader.fail(tokens[k].column,
                    message("expected a colour value of face ", f, ", found ", detail::quoted(tokens[k].text)));
      }
    }
    face_sizes.push_back(static_cast<std::uint32_t>(corners));  // corners < tokens per line: fits
  }
  tokens = reader.next_line();
  if (!tokens.empty()) {
    reader.fail(tokens[0].column,
                message("unexpected data after the last of ", face_count, " faces: ", detail::quoted(tokens[0].text)));
  }
  return FaceVertexMesh(detail::positions_from_flat(xyz), std::move(face_sizes), std::move(face_indices));
}

FaceVertexMesh read_off(const std::filesystem::path& path) { return parse_off(read_file(path), path.string()); }

std::string format_off(const FaceVertexMesh& mesh) {
  std::string text = "OFF\n";
  text += std::to_string(mesh.vertex_count()) + " " + std::to_string(mesh.face_count()) + " 0\n";
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = mesh.position(v);
    detail::append_double(text, p.x());
    text += ' ';
    detail::append_double(text, p.y());
    text += ' ';
    detail::append_double(text, p.z());
    text += '\n';
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    text += std::to_string(face.size());
    for (std::uint32_t index : face) {
      text += ' ';
      text += std::to_string(index);
    }
    text += '\n';
  }
  return text;
}

void write_off(const std::filesystem::path& path, const FaceVertexMesh& mesh) {
  write_file_atomically(path, format_off(mesh));
}

}  // namespace patchwork
