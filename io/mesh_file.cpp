#include "io/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <functional>
#include <utility>

#include "core/errors.h"
#include "io/obj.h"
#include "io/off.h"

namespace patchwork {
namespace {

enum class MeshFormat { obj, off, ply };

// The format named by the extension of `path`. \throws IoError for any other extension.
MeshFormat mesh_format_of(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".ply") return MeshFormat::ply;
  throw IoError(path.string(),
                detail::message("unknown mesh file extension ", detail::quoted(path.extension().string()),
                                " (expected .obj, .off or .ply)"));
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// from_chars takes no leading '+'; a single one is allowed in front of a digit or a point.
std::string_view without_plus(std::string_view token) {
  if (token.size() >= 2 && token[0] == '+' && token[1] != '+' && token[1] != '-') token.remove_prefix(1);
  return token;
}

}  // namespace

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

FaceVertexMesh read_mesh(const std::filesystem::path& path) {
  switch (mesh_format_of(path)) {
    case MeshFormat::obj:
      return read_obj(path);
    case MeshFormat::off:
      return read_off(path);
    case MeshFormat::ply:
      return read_ply(path);
  }
  throw IoError(path.string(), "read_mesh: unknown format");  // not reached: the switch is complete
}

void write_mesh(const std::filesystem::path& path, const FaceVertexMesh& mesh, PlyFormat ply_format) {
  switch (mesh_format_of(path)) {
    case MeshFormat::obj:
      write_obj(path, mesh);
      return;
    case MeshFormat::off:
      write_off(path, mesh);
      return;
    case MeshFormat::ply:
      write_ply(path, mesh, ply_format);
      return;
  }
}

namespace detail {

TextLines::TextLines(std::string_view text, std::string name, char comment, bool continuation)
    : text_(text), name_(std::move(name)), comment_(comment), continuation_(continuation) {}

std::span<const TextToken> TextLines::next_line() {
  tokens_.clear();
  token_lines_.clear();
  std::int64_t first_line = 0;
  while (position_ < text_.size()) {
    const std::size_t end = std::min(text_.find('\n', position_), text_.size());
    std::string_view line = text_.substr(position_, end - position_);
    position_ = std::min(end + 1, text_.size());
    ++physical_line_;
    if (first_line == 0) first_line = physical_line_;
    if (comment_ != '\0') line = line.substr(0, std::min(line.find(comment_), line.size()));
    std::size_t last = line.size();
    while (last > 0 && is_space(line[last - 1])) --last;
    const bool continued = continuation_ && last > 0 && line[last - 1] == '\\';
    if (continued) line = line.substr(0, last - 1);
    std::size_t k = 0;
    while (k < line.size()) {
      while (k < line.size() && is_space(line[k])) ++k;
      const std::size_t start = k;
      while (k < line.size() && !is_space(line[k])) ++k;
      if (k > start) {
        tokens_.push_back({line.substr(start, k - start), static_cast<std::int64_t>(start) + 1});
        token_lines_.push_back(physical_line_);
      }
    }
    if (continued && position_ < text_.size()) continue;
    if (!tokens_.empty()) {
      last_token_line_ = token_lines_.back();
      last_token_end_ = tokens_.back().end_column();
      line_ = first_line;
      return tokens_;
    }
    first_line = 0;
  }
  tokens_.clear();
  token_lines_.clear();
  line_ = physical_line_;
  return tokens_;
}

void TextLines::fail(std::int64_t column, const std::string& message) const {
  throw ParseError(name_, line_, column, message);
}

std::int64_t TextLines::token_line(const TextToken& token) const {
  // A copy of a token (not in this line) has no continuation line to name.
  const std::less<const TextToken*> before;
  const bool in_line =
      !tokens_.empty() && !before(&token, tokens_.data()) && before(&token, tokens_.data() + tokens_.size());
  return in_line ? token_lines_[static_cast<std::size_t>(&token - tokens_.data())] : line_;
}

void TextLines::fail(const TextToken& token, const std::string& message) const {
  const std::int64_t physical = token_line(token);
  if (physical != line_) {
    throw ParseError(name_, line_, token.column, detail::message(message, " (in continuation line ", physical, ")"));
  }
  throw ParseError(name_, line_, token.column, message);
}

void TextLines::fail_at_end(const std::string& message) const {
  throw ParseError(name_, last_token_line_, last_token_end_, message);
}

std::string quoted(std::string_view token) {
  constexpr std::size_t max_shown = 32;
  static constexpr char hex[] = "0123456789abcdef";
  std::string result = "'";
  for (std::size_t k = 0; k < std::min(token.size(), max_shown); ++k) {
    const auto c = static_cast<unsigned char>(token[k]);
    if (c >= 0x20 && c < 0x7f) {
      result += static_cast<char>(c);
    } else {
      result.append("\\x").append(1, hex[c >> 4]).append(1, hex[c & 0xf]);
    }
  }
  if (token.size() > max_shown) result += "...";
  return result + "'";
}

bool parse_double(std::string_view token, double& value) {
  token = without_plus(token);
  const char* last = token.data() + token.size();
  const auto [end, error] = std::from_chars(token.data(), last, value);
  return error == std::errc() && end == last;
}

bool parse_integer(std::string_view token, std::int64_t& value) {
  token = without_plus(token);
  const char* last = token.data() + token.size();
  const auto [end, error] = std::from_chars(token.data(), last, value);
  return error == std::errc() && end == last;
}

void append_double(std::string& text, double x) {
  char buffer[32];  // the longest shortest form, "-2.2250738585072014e-308", has 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), x);
  text.append(buffer, result.ptr);
}

std::size_t reservable(std::uint64_t count, std::size_t remaining_bytes, std::size_t min_bytes) {
  const std::uint64_t fit = remaining_bytes / std::max<std::size_t>(min_bytes, 1);
  return static_cast<std::size_t>(std::min(count, fit));
}

Positions positions_from_flat(const std::vector<double>& xyz) {
  const auto rows = static_cast<Eigen::Index>(xyz.size() / 3);
  Positions positions(rows, 3);
  if (rows > 0) positions = Eigen::Map<const Positions>(xyz.data(), rows, 3);
  return positions;
}

}  // namespace detail
}  // namespace patchwork
