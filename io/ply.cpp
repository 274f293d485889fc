#include "io/ply.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"

namespace patchwork {
namespace {

using detail::message;
using detail::TextLines;
using detail::TextToken;

// ---------------------------------------------------------------------------------------------
// Scalar types

enum class ScalarType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct ScalarInfo {
  ScalarType type;
  std::string_view name;        // the classic name
  std::string_view sized_name;  // the name with its size
  std::size_t size;             // bytes in binary data
  bool integer;
  std::int64_t min;  // integer types: the range
  std::int64_t max;
};

constexpr ScalarInfo scalar_infos[] = {
    {ScalarType::int8, "char", "int8", 1, true, -128, 127},
    {ScalarType::uint8, "uchar", "uint8", 1, true, 0, 255},
    {ScalarType::int16, "short", "int16", 2, true, -32768, 32767},
    {ScalarType::uint16, "ushort", "uint16", 2, true, 0, 65535},
    {ScalarType::int32, "int", "int32", 4, true, -2147483648LL, 2147483647LL},
    {ScalarType::uint32, "uint", "uint32", 4, true, 0, 4294967295LL},
    {ScalarType::float32, "float", "float32", 4, false, 0, 0},
    {ScalarType::float64, "double", "float64", 8, false, 0, 0},
};

const ScalarInfo& info(ScalarType type) { return scalar_infos[static_cast<std::size_t>(type)]; }

std::optional<ScalarType> scalar_type(std::string_view name) {
  for (const ScalarInfo& s : scalar_infos) {
    if (s.name == name || s.sized_name == name) return s.type;
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Header

// What the reader does with a property.
enum class Role : std::uint8_t { skip, x, y, z, face_indices };

struct Property {
  std::string name;
  bool list = false;
  ScalarType count_type = ScalarType::uint8;  // lists only
  ScalarType type = ScalarType::float32;      // the value type, or the item type of a list
  std::int64_t line = 0;
  Role role = Role::skip;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::int64_t line = 0;
  std::vector<Property> properties;

  // The fewest bytes (binary) or tokens (ascii) one record takes: a face has at least 3 indices.
  std::size_t min_record_bytes() const {
    std::size_t bytes = 0;
    for (const Property& p : properties) {
      bytes += p.list ? info(p.count_type).size + (p.role == Role::face_indices ? 3 * info(p.type).size : 0)
                      : info(p.type).size;
    }
    return bytes;
  }
  std::size_t min_record_tokens() const {
    std::size_t tokens = 0;
    for (const Property& p : properties) tokens += p.role == Role::face_indices ? 4 : 1;
    return tokens;
  }
};

struct Header {
  PlyFormat format = PlyFormat::ascii;
  std::vector<Element> elements;
  std::uint64_t vertex_count = 0;
};

std::string_view format_name(PlyFormat format) {
  switch (format) {
    case PlyFormat::ascii:
      return "ascii";
    case PlyFormat::binary_little_endian:
      return "binary_little_endian";
    case PlyFormat::binary_big_endian:
      return "binary_big_endian";
  }
  return "ascii";
}

ScalarType parse_type(const TextLines& reader, const TextToken& token) {
  const auto type = scalar_type(token.text);
  if (!type) {
    reader.fail(token.column,
                message("unknown PLY type ", detail::quoted(token.text),
                        " (expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64)"));
  }
  return *type;
}

// Reads the header up to and including 'end_header' and checks what the mesh needs from it.
Header parse_header(TextLines& reader) {
  auto tokens = reader.next_line();
  if (tokens.empty()) reader.fail_at_end("empty file: expected the PLY magic line 'ply'");
  if (tokens[0].text != "ply" || reader.line() != 1 || tokens.size() != 1) {
    reader.fail(tokens[0].column,
                message("expected the PLY magic line 'ply' as the first line, found ", detail::quoted(tokens[0].text)));
  }
  Header header;
  bool has_format = false;
  while (true) {
    tokens = reader.next_line();
    if (tokens.empty()) reader.fail_at_end("unexpected end of file in the PLY header: expected 'end_header'");
    const std::string_view keyword = tokens[0].text;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (tokens.size() != 1) reader.fail(tokens[1].column, "unexpected text after 'end_header'");
      break;
    }
    if (keyword == "format") {
      if (has_format) reader.fail(tokens[0].column, "a second 'format' line");
      if (tokens.size() != 3) {
        reader.fail(tokens.size() > 3 ? tokens[3].column : tokens.back().end_column(),
                    "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      bool known = false;
      for (PlyFormat format : {PlyFormat::ascii, PlyFormat::binary_little_endian, PlyFormat::binary_big_endian}) {
        if (tokens[1].text == format_name(format)) {
          header.format = format;
          known = true;
        }
      }
      if (!known) {
        reader.fail(tokens[1].column, message("unknown PLY format ", detail::quoted(tokens[1].text),
                                              " (expected ascii, binary_little_endian or binary_big_endian)"));
      }
      if (tokens[2].text != "1.0")
        reader.fail(tokens[2].column,
                    message("unsupported PLY version ", detail::quoted(tokens[2].text), " (expected 1.0)"));
      has_format = true;
    } else if (keyword == "element") {
      if (tokens.size() != 3) {
        reader.fail(tokens.size() > 3 ? tokens[3].column : tokens.back().end_column(), "expected 'element NAME COUNT'");
      }
      std::int64_t count = 0;
      if (!detail::parse_integer(tokens[2].text, count) || count < 0) {
        reader.fail(tokens[2].column, message("expected the count of element ", detail::quoted(tokens[1].text),
                                              " (an integer >= 0), found ", detail::quoted(tokens[2].text)));
      }
      for (const Element& e : header.elements) {
        if (e.name == tokens[1].text)
          reader.fail(tokens[1].column, message("element ", detail::quoted(e.name), " declared twice"));
      }
      header.elements.push_back({std::string(tokens[1].text), static_cast<std::uint64_t>(count), reader.line(), {}});
    } else if (keyword == "property") {
      if (header.elements.empty()) reader.fail(tokens[0].column, "'property' before any 'element'");
      Element& element = header.elements.back();
      Property property;
      property.line = reader.line();
      if (tokens.size() >= 2 && tokens[1].text == "list") {
        if (tokens.size() != 5) {
          reader.fail(tokens.size() > 5 ? tokens[5].column : tokens.back().end_column(),
                      "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        }
        property.list = true;
        property.count_type = parse_type(reader, tokens[2]);
        if (!info(property.count_type).integer) {
          reader.fail(tokens[2].column, message("the count type of a list must be an integer type, found ",
                                                detail::quoted(tokens[2].text)));
        }
        property.type = parse_type(reader, tokens[3]);
        property.name = std::string(tokens[4].text);
      } else {
        if (tokens.size() != 3) {
          reader.fail(tokens.size() > 3 ? tokens[3].column : tokens.back().end_column(),
                      "expected 'property TYPE NAME'");
        }
        property.type = parse_type(reader, tokens[1]);
        property.name = std::string(tokens[2].text);
      }
      for (const Property& p : element.properties) {
        if (p.name == property.name) {
          reader.fail(tokens.back().column, message("property ", detail::quoted(p.name), " of element ",
                                                    detail::quoted(element.name), " declared twice"));
        }
      }
      element.properties.push_back(std::move(property));
    } else {
      reader.fail(tokens[0].column, message("unknown PLY header line ", detail::quoted(keyword),
                                            " (expected format, element, property, comment, obj_info or end_header)"));
    }
  }
  if (!has_format) reader.fail(1, "the PLY header has no 'format' line");

  // The roles: x, y, z of the vertex element, the index list of the face element.
  Element* vertex = nullptr;
  for (Element& element : header.elements) {
    if (element.name == "vertex") {
      vertex = &element;
      if (element.count > detail::max_mesh_vertices) {
        throw ParseError(
            reader.name(), element.line, 1,
            message("element vertex has ", element.count, " vertices, above the limit ", detail::max_mesh_vertices));
      }
      header.vertex_count = element.count;
      for (std::string_view axis : {"x", "y", "z"}) {
        const auto p = std::find_if(element.properties.begin(), element.properties.end(),
                                    [axis](const Property& q) { return q.name == axis; });
        if (p == element.properties.end()) {
          throw ParseError(reader.name(), element.line, 1,
                           message("element vertex has no property ", detail::quoted(axis)));
        }
        if (p->list)
          throw ParseError(reader.name(), p->line, 1, message("vertex property ", detail::quoted(axis), " is a list"));
        p->role = axis == "x" ? Role::x : axis == "y" ? Role::y : Role::z;
      }
    } else if (element.name == "face") {
      Property* indices = nullptr;
      for (Property& p : element.properties) {
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (indices)
          throw ParseError(reader.name(), p.line, 1, "element face has both 'vertex_indices' and 'vertex_index'");
        if (!p.list || !info(p.type).integer) {
          throw ParseError(reader.name(), p.line, 1,
                           message("face property ", detail::quoted(p.name), " must be a list of an integer type"));
        }
        indices = &p;
      }
      if (!indices)
        throw ParseError(reader.name(), element.line, 1, "element face has no list property 'vertex_indices'");
      indices->role = Role::face_indices;
    }
  }
  if (!vertex) reader.fail(1, "the PLY header declares no 'element vertex'");
  return header;
}

// ---------------------------------------------------------------------------------------------
// Data: the same walk over ascii text and binary bytes, one source type each.

// What is being read, for messages: "property 'x' of vertex 3".
struct Where {
  const Element* element;
  std::uint64_t record;
  const Property* property;
};

std::string describe(const Where& where) {
  return message("property ", detail::quoted(where.property->name), " of ", where.element->name, " ", where.record);
}

class AsciiSource {
 public:
  explicit AsciiSource(TextLines& reader) : reader_(reader) {}

  std::size_t remaining() const { return reader_.remaining(); }
  std::size_t reservable(const Element& element) const {
    return detail::reservable(element.count, remaining(), 2 * element.min_record_tokens());  // "0 " per value
  }
  void check_fits(const Element&) const {}  // a record is a line: the text runs out first

  void begin_record(const Element& element, std::uint64_t record) {
    tokens_ = reader_.next_line();
    next_ = 0;
    if (tokens_.empty()) {
      reader_.fail_at_end(
          message("unexpected end of file: expected ", element.name, " ", record, " of ", element.count));
    }
  }
  void end_record(const Element& element, std::uint64_t record) const {
    if (next_ < tokens_.size()) {
      reader_.fail(tokens_[next_].column,
                   message(element.name, " ", record,
                           " has more values than its properties declare: ", detail::quoted(tokens_[next_].text)));
    }
  }
  // One value of `type`, range-checked for integer types, rounded to float for float.
  double value(ScalarType type, const Where& where) {
    if (next_ == tokens_.size()) {
      reader_.fail(tokens_.back().end_column(),
                   message("end of line: expected ", describe(where), " (", info(type).name, ")"));
    }
    last_ = tokens_[next_++];
    const ScalarInfo& s = info(type);
    if (s.integer) {
      std::int64_t integer = 0;
      if (!detail::parse_integer(last_.text, integer) || integer < s.min || integer > s.max) {
        fail_last(message("expected ", describe(where), " as ", s.name, " (an integer in [", s.min, ", ", s.max,
                          "]), found ", detail::quoted(last_.text)));
      }
      return static_cast<double>(integer);
    }
    double real = 0.0;
    if (!detail::parse_double(last_.text, real)) {
      fail_last(message("expected ", describe(where), " as ", s.name, ", found ", detail::quoted(last_.text)));
    }
    // IEEE conversion: rounds, or gives an infinity that the finiteness checks report.
    return type == ScalarType::float32 ? static_cast<double>(static_cast<float>(real)) : real;
  }
  // The items of a list with `count` items must be on the line.
  void check_list(std::uint64_t count, ScalarType, const Where& where) const {
    if (count > tokens_.size() - next_) {
      reader_.fail(tokens_.back().end_column(), message(describe(where), " has ", count, " items but ",
                                                        tokens_.size() - next_, " values follow on the line"));
    }
  }
  [[noreturn]] void fail_last(const std::string& text) const { reader_.fail(last_.column, text); }
  void finish() {
    const auto rest = reader_.next_line();
    if (!rest.empty())
      reader_.fail(rest[0].column, message("unexpected data after the last element: ", detail::quoted(rest[0].text)));
  }

 private:
  TextLines& reader_;
  std::span<const TextToken> tokens_;
  std::size_t next_ = 0;
  TextToken last_{{}, 1};
};

class BinarySource {
 public:
  BinarySource(std::string_view bytes, std::size_t offset, bool big_endian, std::string name)
      : bytes_(bytes), offset_(offset), big_endian_(big_endian), name_(std::move(name)) {}

  std::size_t remaining() const { return bytes_.size() - offset_; }
  std::size_t reservable(const Element& element) const {
    return detail::reservable(element.count, remaining(), element.min_record_bytes());
  }
  // Fails at once if the records cannot fit in the bytes left, before any is read.
  void check_fits(const Element& element) const {
    const std::size_t min_bytes = element.min_record_bytes();
    if (min_bytes > 0 && element.count > remaining() / min_bytes) {
      fail_at(offset_, message("binary data ends early: element ", detail::quoted(element.name), " declares ",
                               element.count, " records of at least ", min_bytes, " bytes from byte offset ", offset_,
                               " but only ", remaining(), " bytes remain"));
    }
  }

  void begin_record(const Element&, std::uint64_t) const {}
  void end_record(const Element&, std::uint64_t) const {}

  double value(ScalarType type, const Where& where) {
    const std::size_t size = info(type).size;
    if (remaining() < size) {
      fail_at(offset_, message("binary data ends at byte offset ", bytes_.size(), " inside ", describe(where), " (",
                               info(type).name, " at byte offset ", offset_, ")"));
    }
    last_ = offset_;
    // Assemble the bytes most significant first, then give them the type's meaning.
    std::uint64_t raw = 0;
    for (std::size_t k = 0; k < size; ++k) {
      const auto byte = static_cast<unsigned char>(bytes_[offset_ + (big_endian_ ? k : size - 1 - k)]);
      raw = (raw << 8) | byte;
    }
    offset_ += size;
    switch (type) {
      case ScalarType::int8:
        return static_cast<std::int8_t>(static_cast<std::uint8_t>(raw));
      case ScalarType::uint8:
        return static_cast<std::uint8_t>(raw);
      case ScalarType::int16:
        return static_cast<std::int16_t>(static_cast<std::uint16_t>(raw));
      case ScalarType::uint16:
        return static_cast<std::uint16_t>(raw);
      case ScalarType::int32:
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(raw));
      case ScalarType::uint32:
        return static_cast<std::uint32_t>(raw);
      case ScalarType::float32:
        return std::bit_cast<float>(static_cast<std::uint32_t>(raw));
      case ScalarType::float64:
        return std::bit_cast<double>(raw);
    }
    return 0.0;
  }
  void check_list(std::uint64_t count, ScalarType item, const Where& where) const {
    if (count > remaining() / info(item).size) {
      fail_at(offset_,
              message("binary data ends early: ", describe(where), " has ", count, " items of ", info(item).size,
                      " bytes from byte offset ", offset_, " but only ", remaining(), " bytes remain"));
    }
  }
  [[noreturn]] void fail_last(const std::string& text) const {
    fail_at(last_, message(text, " (at byte offset ", last_, ")"));
  }
  void finish() const {
    if (remaining() > 0) {
      fail_at(offset_,
              message(remaining(), " bytes of unexpected data after the last element, from byte offset ", offset_));
    }
  }

 private:
  // Line 0 (binary data has no lines), column = 1-based byte position.
  [[noreturn]] void fail_at(std::size_t offset, const std::string& text) const {
    throw ParseError(name_, 0, static_cast<std::int64_t>(offset) + 1, text);
  }
  std::string_view bytes_;
  std::size_t offset_;
  bool big_endian_;
  std::string name_;
  std::size_t last_ = 0;
};

template <class Source>
FaceVertexMesh read_data(Source& source, const Header& header) {
  std::vector<double> xyz;
  std::vector<std::uint32_t> face_sizes;
  std::vector<std::uint32_t> face_indices;
  const double vertex_count = static_cast<double>(header.vertex_count);
  for (const Element& element : header.elements) {
    if (element.properties.empty()) continue;  // takes no data, whatever its count
    source.check_fits(element);
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    if (is_vertex) xyz.reserve(3 * source.reservable(element));
    if (is_face) {
      face_sizes.reserve(source.reservable(element));
      face_indices.reserve(3 * source.reservable(element));
    }
    for (std::uint64_t record = 0; record < element.count; ++record) {
      source.begin_record(element, record);
      double point[3] = {0.0, 0.0, 0.0};
      for (const Property& property : element.properties) {
        const Where where{&element, record, &property};
        if (!property.list) {
          const double value = source.value(property.type, where);
          if (property.role == Role::skip) continue;
          if (!std::isfinite(value)) source.fail_last(message(describe(where), " is not finite"));
          point[property.role == Role::x ? 0 : property.role == Role::y ? 1 : 2] = value;
          continue;
        }
        const double count = source.value(property.count_type, where);
        if (count < 0) source.fail_last(message(describe(where), " has a negative item count ", count));
        if (property.role == Role::face_indices && count < 3) {
          source.fail_last(message("face ", record, " has ", count, " corners (at least 3)"));
        }
        source.check_list(static_cast<std::uint64_t>(count), property.type, where);
        for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(count); ++k) {
          const double item = source.value(property.type, where);
          if (property.role != Role::face_indices) continue;
          if (item < 0) source.fail_last(message("face ", record, " has the negative vertex index ", item));
          if (item >= vertex_count) {
            source.fail_last(
                message("face ", record, " uses vertex ", item, " but there are ", header.vertex_count, " vertices"));
          }
          face_indices.push_back(static_cast<std::uint32_t>(item));
        }
        if (property.role == Role::face_indices) face_sizes.push_back(static_cast<std::uint32_t>(count));
      }
      source.end_record(element, record);
      if (is_vertex) xyz.insert(xyz.end(), point, point + 3);
    }
  }
  source.finish();
  return FaceVertexMesh(detail::positions_from_flat(xyz), std::move(face_sizes), std::move(face_indices));
}

// ---------------------------------------------------------------------------------------------
// Writing

// Appends the `size` low bytes of `raw` in the byte order of `format`.
void append_bytes(std::string& bytes, std::uint64_t raw, std::size_t size, PlyFormat format) {
  for (std::size_t k = 0; k < size; ++k) {
    const std::size_t shift = 8 * (format == PlyFormat::binary_big_endian ? size - 1 - k : k);
    bytes += static_cast<char>(static_cast<unsigned char>((raw >> shift) & 0xff));
  }
}

}  // namespace

FaceVertexMesh parse_ply(std::string_view bytes, const std::string& name) {
  TextLines reader(bytes, name, '\0');
  const Header header = parse_header(reader);
  if (header.format == PlyFormat::ascii) {
    AsciiSource source(reader);
    return read_data(source, header);
  }
  BinarySource source(bytes, reader.offset(), header.format == PlyFormat::binary_big_endian, name);
  return read_data(source, header);
}

FaceVertexMesh read_ply(const std::filesystem::path& path) { return parse_ply(read_file(path), path.string()); }

std::string format_ply(const FaceVertexMesh& mesh, PlyFormat format) {
  std::uint32_t largest_face = 0;
  for (std::uint32_t size : mesh.face_sizes()) largest_face = std::max(largest_face, size);
  const bool uchar_count = largest_face <= 255;
  const bool int_index = mesh.vertex_count() <= std::size_t{2147483648u};  // indices up to 2^31 - 1
  std::string bytes = "ply\nformat ";
  bytes.append(format_name(format)).append(" 1.0\n");
  bytes += "element vertex " + std::to_string(mesh.vertex_count()) + "\n";
  bytes += "property double x\nproperty double y\nproperty double z\n";
  bytes += "element face " + std::to_string(mesh.face_count()) + "\n";
  bytes.append("property list ").append(uchar_count ? "uchar" : "uint").append(int_index ? " int" : " uint");
  bytes += " vertex_indices\nend_header\n";
  if (format == PlyFormat::ascii) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const Vec3 p = mesh.position(v);
      detail::append_double(bytes, p.x());
      bytes += ' ';
      detail::append_double(bytes, p.y());
      bytes += ' ';
      detail::append_double(bytes, p.z());
      bytes += '\n';
    }
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
      const auto face = mesh.face(f);
      bytes += std::to_string(face.size());
      for (std::uint32_t index : face) bytes.append(" ").append(std::to_string(index));
      bytes += '\n';
    }
    return bytes;
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = mesh.position(v);
    for (int c = 0; c < 3; ++c) append_bytes(bytes, std::bit_cast<std::uint64_t>(p[c]), 8, format);
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    append_bytes(bytes, face.size(), uchar_count ? 1 : 4, format);
    for (std::uint32_t index : face) append_bytes(bytes, index, 4, format);
  }
  return bytes;
}

void write_ply(const std::filesystem::path& path, const FaceVertexMesh& mesh, PlyFormat format) {
  write_file_atomically(path, format_ply(mesh, format));
}

}  // namespace patchwork
