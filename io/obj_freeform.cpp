#include "io/obj_freeform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <istream>
#include <iterator>
#include <optional>
#include <sstream>
#include <utility>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "io/obj_freeform_checks.h"
#include "io/obj_syntax.h"

namespace patchwork {
namespace {

using detail::basis_name;
using detail::direction_name;
using detail::FreeformPart;
using detail::FreeformProblem;
using detail::FreeformRecordView;
using detail::message;
using detail::quoted;
using detail::record_problem;
using detail::TextLines;
using detail::TextToken;
using detail::view_of;

// ---------------------------------------------------------------------------------------------
// The reader

// Statements refused by name, with the reason.
struct Refusal {
  std::string_view keyword;
  std::string_view reason;
};

constexpr Refusal refused_statements[] = {
    {"trim", "trimming curves are not supported (the surface would be shown untrimmed)"},
    {"hole", "trimming holes are not supported (the surface would be shown without them)"},
    {"scrv", "special curves on a surface are not supported"},
    {"sp", "special points on a surface are not supported"},
    {"con", "connectivity between surfaces is not supported"},
    {"bmat", "basis matrices are not supported (only bezier and bspline bases)"},
    {"step", "step sizes (of basis-matrix and cardinal bases) are not supported"},
    {"curv2", "curves in a surface's parameter space (for trimming) are not supported"},
    {"mg", "merging groups are not supported"},
    {"call", "reading another file is not supported"},
    {"csh", "running commands is not supported"},
    {"f", "polygons are not read here: read_obj (io/obj.h) reads faces"},
    {"l", "polygon lines are not read here: read_obj (io/obj.h) reads polygon files"},
    {"p", "polygon points are not read here: read_obj (io/obj.h) reads polygon files"},
};

// Display and rendering attributes: nothing of the geometry (ctech and stech are a renderer's
// tessellation hints; patchwork's tessellator has its own tolerance).
constexpr std::string_view display_statements[] = {"ctech",  "stech",      "s",        "usemtl",   "mtllib",
                                                   "lod",    "bevel",      "c_interp", "d_interp", "maplib",
                                                   "usemap", "shadow_obj", "trace_obj"};

// Where a token stood: its column and the physical line (a continuation line of the statement).
struct Where {
  std::int64_t column = 0;
  std::int64_t physical_line = 0;
};

// A curv or surf block being read, with where each part stood for error messages.
struct OpenRecord {
  FreeformSurface record;  // a curve uses the u fields
  bool surface = false;
  Where keyword;
  std::int64_t degree_line = 0;
  std::array<Where, 2> degree_where;
  std::array<Where, 4> range_where;
  std::vector<Where> point_where;
  std::array<std::int64_t, 2> parameter_line{};  // 0 until its parm is read
  std::array<Where, 2> parm_where;               // the u or v of the parm statement
  std::array<std::vector<Where>, 2> parameter_where;
};

class FreeformReader {
 public:
  FreeformReader(std::string_view text, const std::string& name) : reader_(text, name, '#', /*continuation=*/true) {}

  FreeformDocument read() {
    for (auto tokens = reader_.next_line(); !tokens.empty(); tokens = reader_.next_line()) statement(tokens);
    if (open_) {
      reader_.fail_at_end(
          message("missing 'end' of the ", open_->surface ? "surf" : "curv", " block of line ", open_->record.line));
    }
    if (document_.surfaces.empty() && document_.curves.empty()) {
      reader_.fail_at_end("no free-form curve or surface ('curv' or 'surf') in the file");
    }
    return std::move(document_);
  }

 private:
  Where where(const TextToken& token) const { return {token.column, reader_.token_line(token)}; }

  [[noreturn]] void fail_at(std::int64_t line, const Where& at, const std::string& text) const {
    if (at.physical_line != line && at.physical_line != 0) {
      throw ParseError(reader_.name(), line, at.column,
                       message(text, " (in continuation line ", at.physical_line, ")"));
    }
    throw ParseError(reader_.name(), line, at.column, text);
  }

  void statement(std::span<const TextToken> tokens) {
    const std::string_view keyword = tokens[0].text;
    for (const Refusal& refusal : refused_statements) {
      if (keyword == refusal.keyword) {
        reader_.fail(tokens[0], message("unsupported statement ", quoted(keyword), ": ", refusal.reason));
      }
    }
    if (open_ && keyword != "parm" && keyword != "end") {
      reader_.fail(tokens[0], message("expected 'parm' or 'end' in the ", open_->surface ? "surf" : "curv",
                                      " block of line ", open_->record.line, ", found ", quoted(keyword)));
    }
    if (keyword == "v") {
      vertex(tokens);
    } else if (keyword == "vt" || keyword == "vp") {
      numbers(tokens, 1, 3);
      if (keyword == "vt") ++texture_count_;
    } else if (keyword == "vn") {
      numbers(tokens, 3, 3);
      ++normal_count_;
    } else if (keyword == "g" || keyword == "o") {
      group_.clear();
      for (std::size_t k = 1; k < tokens.size(); ++k) group_.append(k > 1 ? " " : "").append(tokens[k].text);
    } else if (keyword == "cstype") {
      cstype(tokens);
    } else if (keyword == "deg") {
      deg(tokens);
    } else if (keyword == "curv" || keyword == "surf") {
      open(tokens, keyword == "surf");
    } else if (keyword == "parm") {
      parm(tokens);
    } else if (keyword == "end") {
      end(tokens);
    } else if (std::find(std::begin(display_statements), std::end(display_statements), keyword) ==
               std::end(display_statements)) {
      reader_.fail(tokens[0], message("unknown OBJ statement ", quoted(keyword)));
    }
  }

  double finite_number(const TextToken& token, const char* what) const {
    double value = 0.0;
    if (!detail::parse_double(token.text, value) || !std::isfinite(value)) {
      reader_.fail(token, message("expected a finite ", what, ", found ", quoted(token.text)));
    }
    return value;
  }

  // A statement of `min` to `max` finite numbers after its keyword.
  void expect_count(std::span<const TextToken> tokens, std::size_t min, std::size_t max) const {
    const std::size_t count = tokens.size() - 1;
    if (count < min || count > max) {
      reader_.fail(count > max ? tokens[max + 1].column : tokens.back().end_column(),
                   message("expected ", min, min == max ? "" : message(" to ", max), " numbers after ",
                           quoted(tokens[0].text), ", found ", count));
    }
  }

  void numbers(std::span<const TextToken> tokens, std::size_t min, std::size_t max) const {
    expect_count(tokens, min, max);
    for (std::size_t k = 1; k < tokens.size(); ++k) finite_number(tokens[k], "number");
  }

  void vertex(std::span<const TextToken> tokens) {
    expect_count(tokens, 3, 4);
    const Vec3 point(finite_number(tokens[1], "coordinate"), finite_number(tokens[2], "coordinate"),
                     finite_number(tokens[3], "coordinate"));
    const double w = tokens.size() == 5 ? finite_number(tokens[4], "weight") : 1.0;
    if (!(w > 0.0)) reader_.fail(tokens[4], message("expected a weight > 0, found ", quoted(tokens[4].text)));
    vertices_.push_back(point);
    vertex_weights_.push_back(w);
  }

  void cstype(std::span<const TextToken> tokens) {
    const bool rational = tokens.size() == 3 && tokens[1].text == "rat";
    if (tokens.size() != 2 && !rational) {
      reader_.fail(tokens.size() > 1 ? tokens[1].column : tokens[0].end_column(),
                   "expected 'cstype [rat] bezier' or 'cstype [rat] bspline'");
    }
    const TextToken& type = tokens.back();
    if (type.text == "bezier" || type.text == "bspline") {
      basis_ = type.text == "bezier" ? FreeformBasis::bezier : FreeformBasis::bspline;
      rational_ = rational;
      has_cstype_ = true;
    } else if (type.text == "cardinal" || type.text == "taylor" || type.text == "bmatrix") {
      reader_.fail(type,
                   message("unsupported statement 'cstype ", type.text,
                           "': only bezier and bspline bases are supported (the tessellator evaluates no other)"));
    } else {
      reader_.fail(type, message("unknown cstype ", quoted(type.text), " (expected bezier or bspline)"));
    }
  }

  void deg(std::span<const TextToken> tokens) {
    if (tokens.size() != 2 && tokens.size() != 3) {
      reader_.fail(tokens.size() > 3 ? tokens[3].column : tokens[0].end_column(), "expected 'deg du' or 'deg du dv'");
    }
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      std::int64_t value = 0;
      if (!detail::parse_integer(tokens[k].text, value) || value < 1 || value > max_obj_freeform_degree) {
        reader_.fail(tokens[k], message("expected a degree in [1, ", max_obj_freeform_degree, "], found ",
                                        quoted(tokens[k].text)));
      }
      degrees_[k - 1] = static_cast<int>(value);
      degree_where_[k - 1] = where(tokens[k]);
    }
    degree_count_ = static_cast<int>(tokens.size()) - 1;
    degree_line_ = reader_.line();
  }

  void open(std::span<const TextToken> tokens, bool surface) {
    const char* keyword = surface ? "surf" : "curv";
    if (!has_cstype_) reader_.fail(tokens[0], message("'", keyword, "' without a 'cstype' before it"));
    if (degree_count_ == 0) reader_.fail(tokens[0], message("'", keyword, "' without a 'deg' before it"));
    if (surface && degree_count_ != 2) {
      reader_.fail(tokens[0], message("'surf' needs 'deg du dv'; the deg of line ", degree_line_, " gives one degree"));
    }
    const std::size_t range_size = surface ? 4 : 2;
    if (tokens.size() < range_size + 1) {
      reader_.fail(tokens.back().end_column(), message(surface ? "expected 'surf u0 u1 v0 v1' and control points"
                                                               : "expected 'curv t0 t1' and control points"));
    }
    OpenRecord block;
    block.surface = surface;
    block.keyword = where(tokens[0]);
    block.degree_line = degree_line_;
    block.degree_where = degree_where_;
    FreeformSurface& record = block.record;
    record.name = group_;
    record.basis = basis_;
    record.rational = rational_;
    record.degree_u = degrees_[0];
    record.degree_v = surface ? degrees_[1] : 0;
    record.line = reader_.line();
    std::array<double, 4> range{};
    for (std::size_t k = 0; k < range_size; ++k) {
      range[k] = finite_number(tokens[k + 1], "parameter");
      block.range_where[k] = where(tokens[k + 1]);
    }
    record.u0 = range[0];
    record.u1 = range[1];
    record.v0 = range[2];
    record.v1 = range[3];
    for (std::size_t k = range_size + 1; k < tokens.size(); ++k) {
      const std::int64_t index = control_vertex(tokens[k], surface);
      record.points.push_back(vertices_[static_cast<std::size_t>(index)]);
      record.weights.push_back(vertex_weights_[static_cast<std::size_t>(index)]);
      block.point_where.push_back(where(tokens[k]));
    }
    open_ = std::move(block);
  }

  // The vertex a control point names (0-based); in a surf, a vt or vn index must name one read so far.
  std::int64_t control_vertex(const TextToken& token, bool surface) const {
    const detail::ObjReference reference = detail::parse_obj_reference(reader_, token, "a control point");
    if (!surface && (reference.texture != 0 || reference.normal != 0)) {
      reader_.fail(token, message("curv control points are vertex indices, found ", quoted(token.text)));
    }
    const auto defined = [&](std::int64_t raw, std::int64_t count, const char* element, const char* elements) {
      const std::int64_t index = detail::resolve_obj_index(reader_, token, raw, count, element, elements);
      if (index >= count) {
        reader_.fail(token, message(quoted(token.text), " uses ", element, " ", index + 1, " but only ", count, " ",
                                    elements, " are defined before it"));
      }
      return index;
    };
    if (reference.texture != 0) defined(reference.texture, texture_count_, "texture coordinate", "texture coordinates");
    if (reference.normal != 0) defined(reference.normal, normal_count_, "normal", "normals");
    return defined(reference.vertex, static_cast<std::int64_t>(vertices_.size()), "vertex", "vertices");
  }

  void parm(std::span<const TextToken> tokens) {
    if (!open_) reader_.fail(tokens[0], "'parm' outside a curv or surf block");
    if (tokens.size() < 2 || (tokens[1].text != "u" && tokens[1].text != "v")) {
      reader_.fail(tokens.size() > 1 ? tokens[1].column : tokens[0].end_column(), "expected 'parm u' or 'parm v'");
    }
    const std::size_t direction = tokens[1].text == "u" ? 0 : 1;
    if (direction == 1 && !open_->surface) reader_.fail(tokens[1], "'parm v' in a curv block (a curve has only u)");
    if (open_->parameter_line[direction] != 0) {
      reader_.fail(tokens[1], message("a second 'parm ", tokens[1].text, "' in the block (the first is on line ",
                                      open_->parameter_line[direction], ")"));
    }
    std::vector<double>& values = direction == 0 ? open_->record.parameters_u : open_->record.parameters_v;
    for (std::size_t k = 2; k < tokens.size(); ++k) {
      values.push_back(finite_number(tokens[k], "parameter"));
      open_->parameter_where[direction].push_back(where(tokens[k]));
    }
    open_->parameter_line[direction] = reader_.line();
    open_->parm_where[direction] = where(tokens[1]);
  }

  void end(std::span<const TextToken> tokens) {
    if (!open_) reader_.fail(tokens[0], "'end' outside a curv or surf block");
    if (tokens.size() > 1) reader_.fail(tokens[1], "expected 'end' alone");
    for (std::size_t direction = 0; direction < (open_->surface ? 2u : 1u); ++direction) {
      if (open_->parameter_line[direction] == 0) {
        reader_.fail(tokens[0], message("the ", open_->surface ? "surf" : "curv", " block of line ", open_->record.line,
                                        " has no 'parm ", direction_name(static_cast<int>(direction)), "'"));
      }
    }
    FreeformSurface& surface = open_->record;
    if (open_->surface) {
      check(view_of(surface));
      document_.surfaces.push_back(std::move(surface));
    } else {
      FreeformCurve curve{surface.name,
                          surface.basis,
                          surface.rational,
                          surface.degree_u,
                          std::move(surface.parameters_u),
                          surface.u0,
                          surface.u1,
                          std::move(surface.points),
                          std::move(surface.weights),
                          surface.line};
      check(view_of(curve));
      document_.curves.push_back(std::move(curve));
    }
    open_.reset();
  }

  // The shared checks on the whole record, failing where the part at fault stands.
  void check(const FreeformRecordView& record) const {
    const std::optional<FreeformProblem> problem = record_problem(record);
    if (!problem) return;
    const OpenRecord& block = *open_;
    const auto direction = static_cast<std::size_t>(problem->direction);
    switch (problem->part) {
      case FreeformPart::degree:
        fail_at(block.degree_line, block.degree_where[direction], problem->message);
      case FreeformPart::parameter:
        fail_at(block.parameter_line[direction], block.parameter_where[direction][problem->index], problem->message);
      case FreeformPart::parameter_count:
        fail_at(block.parameter_line[direction], block.parm_where[direction], problem->message);
      case FreeformPart::range:
        fail_at(block.record.line, block.range_where[2 * direction + problem->index], problem->message);
      case FreeformPart::point_count:
        fail_at(block.record.line, block.keyword, problem->message);
      case FreeformPart::point:
      case FreeformPart::weight:
        fail_at(block.record.line, block.point_where[problem->index], problem->message);
    }
    fail_at(block.record.line, block.keyword, problem->message);  // not reached: the switch is complete
  }

  TextLines reader_;
  std::vector<Vec3> vertices_;
  std::vector<double> vertex_weights_;
  std::int64_t texture_count_ = 0;
  std::int64_t normal_count_ = 0;
  bool has_cstype_ = false;
  FreeformBasis basis_ = FreeformBasis::bspline;
  bool rational_ = false;
  int degree_count_ = 0;  // 0 until a deg statement
  std::array<int, 2> degrees_{};
  std::array<Where, 2> degree_where_;
  std::int64_t degree_line_ = 0;
  std::string group_;
  std::optional<OpenRecord> open_;
  FreeformDocument document_;
};

// ---------------------------------------------------------------------------------------------
// The writer

// Why a record's name would not read back from 'g name', or "" if it does.
std::string name_problem(const std::string& name) {
  if (name.empty()) return {};
  if (name.front() == ' ' || name.back() == ' ' || name.find("  ") != std::string::npos) {
    return "has leading, trailing or double spaces";
  }
  if (name.find_first_of("\t\r\v\f\n#") != std::string::npos) return "holds a tab, a line break or '#'";
  if (name.back() == '\\') return "ends in '\\' (a line continuation)";
  return {};
}

// Appends the record: its control points, then g (if the name changes), cstype, deg, the curv or
// surf statement with absolute indices, parm and end. `vertices` counts the v lines so far.
void append_record(std::string& text, std::int64_t& vertices, std::string& group, const std::string& name,
                   const FreeformRecordView& record) {
  if (name != group) {
    text.append(name.empty() ? "g" : "g ").append(name).append("\n");
    group = name;
  }
  for (std::size_t k = 0; k < record.points.size(); ++k) {
    text += 'v';
    for (int c = 0; c < 3; ++c) {
      text += ' ';
      detail::append_double(text, record.points[k][c]);
    }
    if (record.rational) {
      text += ' ';
      detail::append_double(text, record.weights[k]);
    }
    text += '\n';
  }
  text.append("cstype ").append(record.rational ? "rat " : "").append(basis_name(record.basis)).append("\ndeg");
  for (int d = 0; d < record.directions; ++d) text.append(" ").append(std::to_string(record.degrees[d]));
  text.append("\n").append(record.keyword);
  for (int k = 0; k < 2 * record.directions; ++k) {
    text += ' ';
    detail::append_double(text, record.range[static_cast<std::size_t>(k)]);
  }
  for (std::size_t k = 0; k < record.points.size(); ++k) text.append(" ").append(std::to_string(++vertices));
  for (int d = 0; d < record.directions; ++d) {
    text.append("\nparm ").append(direction_name(d));
    for (double value : record.parameters[static_cast<std::size_t>(d)]) {
      text += ' ';
      detail::append_double(text, value);
    }
  }
  text.append("\nend\n");
}

// Refuses a record that would not read back. \throws InvalidInput naming the function and the record.
void check_writable(const FreeformRecordView& record, const std::string& name, const char* kind, std::size_t index) {
  const std::string bad_name = name_problem(name);
  const std::optional<FreeformProblem> problem = record_problem(record);
  if (bad_name.empty() && !problem) return;
  throw InvalidInput(message("format_obj_freeform: ", kind, " ", index, " (", quoted(name), ") ",
                             problem ? problem->message : "has a name that " + bad_name));
}

}  // namespace

FreeformDocument parse_obj_freeform(std::string_view text, const std::string& name) {
  return FreeformReader(text, name).read();
}

FreeformDocument parse_obj_freeform(std::istream& in, const std::string& name) {
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(name, "read failed");
  return parse_obj_freeform(text.str(), name);
}

FreeformDocument read_obj_freeform(const std::filesystem::path& path) {
  return parse_obj_freeform(read_file(path), path.string());
}

std::string format_obj_freeform(const FreeformDocument& document) {
  if (document.surfaces.empty() && document.curves.empty()) {
    throw InvalidInput("format_obj_freeform: the document has no curve or surface (the reader refuses such a file)");
  }
  // Every record is checked before anything is written.
  for (std::size_t k = 0; k < document.surfaces.size(); ++k) {
    check_writable(view_of(document.surfaces[k]), document.surfaces[k].name, "surface", k);
  }
  for (std::size_t k = 0; k < document.curves.size(); ++k) {
    check_writable(view_of(document.curves[k]), document.curves[k].name, "curve", k);
  }
  std::string text;
  std::int64_t vertices = 0;
  std::string group;
  for (const FreeformSurface& surface : document.surfaces)
    append_record(text, vertices, group, surface.name, view_of(surface));
  for (const FreeformCurve& curve : document.curves) append_record(text, vertices, group, curve.name, view_of(curve));
  return text;
}

void write_obj_freeform(const std::filesystem::path& path, const FreeformDocument& document) {
  write_file_atomically(path, format_obj_freeform(document));
}

bool is_obj_freeform(std::string_view text) {
  // The readers' own tokenizer: comments, continuation lines and blanks as they see them.
  TextLines lines(text, "", '#', /*continuation=*/true);
  for (auto tokens = lines.next_line(); !tokens.empty(); tokens = lines.next_line()) {
    if (detail::is_obj_freeform_statement(tokens[0].text)) return true;
  }
  return false;
}

}  // namespace patchwork
