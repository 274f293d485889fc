#include "io/bpt.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"

namespace patchwork {
namespace {

// Tokens in messages are quoted as in the mesh formats.
using detail::quoted;

// Reads a text line by line and splits lines into whitespace-separated tokens, remembering
// where each token stands for error messages (line and column 1-based, columns in bytes).
class LineReader {
 public:
  LineReader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  struct Token {
    std::string_view text;
    std::int64_t column;
    /// The column just after the token.
    std::int64_t end_column() const noexcept { return column + static_cast<std::int64_t>(text.size()); }
  };

  /// The tokens of the next non-blank line, or an empty list at the end of the text (then
  /// line() and end_column() point just after the last token of the text).
  std::vector<Token> next_line() {
    while (position_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', position_), text_.size());
      const std::string_view line = text_.substr(position_, end - position_);
      position_ = end + 1;
      ++line_;
      std::vector<Token> tokens;
      std::size_t k = 0;
      while (k < line.size()) {
        while (k < line.size() && is_space(line[k])) ++k;
        const std::size_t start = k;
        while (k < line.size() && !is_space(line[k])) ++k;
        if (k > start) tokens.push_back({line.substr(start, k - start), static_cast<std::int64_t>(start) + 1});
      }
      if (!tokens.empty()) {
        last_token_line_ = line_;
        last_token_end_ = tokens.back().end_column();
        return tokens;
      }
    }
    return {};
  }

  /// Fails at `column` of the current line.
  [[noreturn]] void fail(std::int64_t column, const std::string& message) const {
    throw ParseError(name_, line_, column, message);
  }
  /// Fails at the end of the data: just after the last token (1:1 for a blank text).
  [[noreturn]] void fail_at_end(const std::string& message) const {
    throw ParseError(name_, last_token_line_, last_token_end_, message);
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  std::string_view text_;
  std::string name_;
  std::size_t position_ = 0;
  std::int64_t line_ = 0;
  std::int64_t last_token_line_ = 1;
  std::int64_t last_token_end_ = 1;
};

// The tokens of a line that must hold exactly `count` values, `what()` (called only for the
// message: a file has a line per control point) saying what they are. A missing value is
// reported just after the last token of the line, a surplus one at its own column.
template <class What>
std::vector<LineReader::Token> expect_line(LineReader& reader, std::size_t count, const What& what) {
  std::vector<LineReader::Token> tokens = reader.next_line();
  if (tokens.empty()) reader.fail_at_end("unexpected end of file: expected " + std::string(what()));
  if (tokens.size() != count) {
    reader.fail(tokens.size() > count ? tokens[count].column : tokens.back().end_column(),
                detail::message("expected ", what(), " (", count, count == 1 ? " number" : " numbers", "), found ",
                                tokens.size()));
  }
  return tokens;
}

std::int64_t parse_integer(const LineReader& reader, const LineReader::Token& token, const std::string& what) {
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(token.text.data(), token.text.data() + token.text.size(), value);
  if (error != std::errc() || end != token.text.data() + token.text.size()) {
    reader.fail(token.column, detail::message("expected ", what, " (an integer), found ", quoted(token.text)));
  }
  return value;
}

double parse_number(const LineReader& reader, const LineReader::Token& token) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.text.data(), token.text.data() + token.text.size(), value);
  if (error != std::errc() || end != token.text.data() + token.text.size() || !std::isfinite(value)) {
    reader.fail(token.column, detail::message("expected a finite coordinate, found ", quoted(token.text)));
  }
  return value;
}

}  // namespace

std::vector<BezierPatch3> parse_bpt(std::string_view text, const std::string& name) {
  LineReader reader(text, name);
  const auto header = expect_line(reader, 1, [] { return "the number of patches"; });
  const std::int64_t count = parse_integer(reader, header[0], "the number of patches");
  if (count < 1) reader.fail(header[0].column, detail::message("the number of patches must be at least 1, found ", count));
  std::vector<BezierPatch3> patches;  // not reserved: `count` is not trusted before its data is read
  for (std::int64_t p = 0; p < count; ++p) {
    const auto degrees = expect_line(reader, 2, [&] { return detail::message("the degrees 'n m' of patch ", p); });
    const std::int64_t n = parse_integer(reader, degrees[0], "degree n");
    const std::int64_t m = parse_integer(reader, degrees[1], "degree m");
    for (const auto& [degree, token] : {std::pair{n, degrees[0]}, std::pair{m, degrees[1]}}) {
      if (degree < 0 || degree > max_bpt_degree) {
        reader.fail(token.column, detail::message("degree ", degree, " of patch ", p, " is not in [0, ", max_bpt_degree, "]"));
      }
    }
    const std::int64_t points = (n + 1) * (m + 1);
    std::vector<Vec3> control_points;
    control_points.reserve(static_cast<std::size_t>(points));  // at most 65^2, bounded by the degree limit
    for (std::int64_t k = 0; k < points; ++k) {
      const auto xyz = expect_line(reader, 3, [&] { return detail::message("point ", k, " of patch ", p, " as 'x y z'"); });
      control_points.emplace_back(parse_number(reader, xyz[0]), parse_number(reader, xyz[1]), parse_number(reader, xyz[2]));
    }
    patches.emplace_back(static_cast<int>(n), static_cast<int>(m), std::move(control_points));
  }
  const auto rest = reader.next_line();
  if (!rest.empty()) {
    reader.fail(rest.front().column,
                detail::message("unexpected data after the last of ", count, " patches: ", quoted(rest.front().text)));
  }
  return patches;
}

std::vector<BezierPatch3> read_bpt(const std::filesystem::path& path) { return parse_bpt(read_file(path), path.string()); }

std::string format_bpt(std::span<const BezierPatch3> patches) {
  // Write only what parse_bpt reads back: at least one patch, degrees within the limit.
  if (patches.empty()) throw InvalidInput("format_bpt: no patches (a BPT file holds at least one)");
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].degree_u() > max_bpt_degree || patches[p].degree_v() > max_bpt_degree) {
      throw InvalidInput(detail::message("format_bpt: patch ", p, " has degrees (", patches[p].degree_u(), ", ",
                                         patches[p].degree_v(), "), above the BPT limit ", max_bpt_degree));
    }
  }
  std::string text = std::to_string(patches.size()) + "\n";
  char buffer[64];
  for (const BezierPatch3& patch : patches) {
    text += std::to_string(patch.degree_u()) + " " + std::to_string(patch.degree_v()) + "\n";
    for (const Vec3& p : patch.control_points()) {
      for (int c = 0; c < 3; ++c) {
        const auto result = std::to_chars(buffer, buffer + sizeof(buffer), p[c]);  // shortest round-trip form
        text.append(buffer, result.ptr);
        text += c < 2 ? ' ' : '\n';
      }
    }
  }
  return text;
}

void write_bpt(const std::filesystem::path& path, std::span<const BezierPatch3> patches) {
  write_file_atomically(path, format_bpt(patches));
}

}  // namespace patchwork
