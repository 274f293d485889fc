// format_gltf, encode_gltf_levels and write_gltf (io/gltf.h): the writer; io/gltf_reader.cpp reads.
//
// A file is written in two passes over the meshes. The first (plan_gltf) makes every check,
// finds the centre the positions are stored from, the stored floats' box and their rounding, and
// lays out the buffer: with those, the JSON is complete before a byte of the buffer exists. The
// second (write_planned) writes the JSON, then the buffer straight from the mesh arrays,
// converting gltf_chunk_elements elements at a time (float conversion, Z-up map, index
// narrowing), so nothing holds a copy of the buffer: the file's bytes go to a string
// (format_gltf) or to the file being written (write_gltf). The bytes are those tinygltf 2.7.0
// gave when it serialised a model holding the whole buffer (keys in sorted order, as its
// nlohmann::json object keeps them; the same number types), which tests/io/gltf_test.cpp pins.

#include "io/gltf.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "io/atomic_file.h"
#include "meshes/topology.h"

namespace patchwork {
namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

using nlohmann::json;

// The largest buffer written: the 4 GiB a GLB chunk can hold, less 1 MiB for the GLB header and
// the JSON.
constexpr std::uint64_t max_buffer_bytes = 0xffffffffull - (1ull << 20);

// glTF's enumerations (glTF 2.0, 5.1.2 accessor.componentType, 5.11.4 bufferView.target,
// 5.24.4 primitive.mode).
constexpr int component_unsigned_short = 5123;
constexpr int component_unsigned_int = 5125;
constexpr int component_float = 5126;
constexpr int target_array_buffer = 34962;
constexpr int target_element_array_buffer = 34963;
constexpr int mode_triangles = 4;

// The GLB container (glTF 2.0, 4.4): magic "glTF", version 2, chunk types "JSON" and "BIN\0".
constexpr std::uint32_t glb_magic = 0x46546C67u;
constexpr std::uint32_t glb_version = 2;
constexpr std::uint32_t chunk_json = 0x4E4F534Au;
constexpr std::uint32_t chunk_bin = 0x004E4942u;

// A .gltf's buffer: a data: URI whose base64 text follows this prefix.
constexpr std::string_view data_uri_prefix = "data:application/octet-stream;base64,";

// Where the bytes of a file go, in order.
using ByteSink = std::function<void(std::string_view)>;

std::uint64_t padded_to_4(std::uint64_t bytes) { return (bytes + 3) / 4 * 4; }

// ---------------------------------------------------------------------------------------------
// Values as stored

// Z-up to Y-up: (x, y, z) -> (x, z, -y), a rotation about +x (see io/gltf.h).
Vec3 to_gltf_axes(const Vec3& v, bool z_up) { return z_up ? Vec3(v.x(), v.z(), -v.y()) : v; }

// The float nearest x. \throws InvalidInput naming the value if it does not fit in a float
// (checked before the cast: converting a double beyond the float range is undefined behaviour).
float to_float(double x, const char* what, std::size_t vertex) {
  if (!(std::abs(x) <= std::numeric_limits<float>::max())) {
    throw InvalidInput(
        detail::message("format_gltf: ", what, " of vertex ", vertex, " (", x, ") does not fit in a float"));
  }
  return static_cast<float>(x);
}

// A unit direction (validate() allows 1e-6 slack) normalised in double and rounded to float:
// one rounding, so the float vector's length is 1 to within about 1e-7.
void append_unit(std::vector<float>& out, const Vec3& direction) {
  const Vec3 unit = direction / direction.norm();
  for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(unit[c]));
}

// Whether an edge of the welded triangles is used by exactly one of them (meshes/topology.h).
bool has_boundary_edge(const RenderMesh& mesh) { return analyze(welded_faces(mesh)).boundary_edges > 0; }

// Where a mesh's positions are stored from: the centre of their box (in glTF's axes), so that the
// float offsets are at most half the box's extent and their rounding is relative to it, not to
// the distance from the origin (see io/gltf.h).
// \throws InvalidInput naming the first position that does not fit in a float (viewers add the
// translation in float).
Vec3 position_origin(const RenderMesh& mesh, bool z_up) {
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = to_gltf_axes(mesh.positions[v], z_up);
    for (int c = 0; c < 3; ++c) to_float(p[c], "position", v);
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return 0.5 * low + 0.5 * high;  // no overflow: the positions fit in a float
}

// A bound on |fl(f + t) - p| (and on |f + t - p| exactly), for the float offset f = float(d) of
// d = fl(p - t), one coordinate: the float rounding |f - d|, plus u (|f| + |t| + |d|) twice for
// the subtraction before it and the reader's addition after it (u = 2^-53, round to nearest), the
// sum enlarged by 4u for its own roundings.
double offset_rounding(double f, double d, double t) {
  constexpr double u = 0x1p-53;
  return (std::abs(f - d) + 2 * u * (std::abs(f) + std::abs(t) + std::abs(d))) * (1 + 4 * u);
}

// The stored floats' box and the largest rounding distance of a level's positions.
struct PositionBounds {
  std::vector<double> low = std::vector<double>(3, std::numeric_limits<double>::infinity());
  std::vector<double> high = std::vector<double>(3, -std::numeric_limits<double>::infinity());
  double rounding = 0.0;
};

// The first pass over a level's positions, relative to `origin`: the min/max of the stored floats
// (as the validator compares them; in vertex order, so that a -0 and a +0 keep the side the
// writer has always given them), and the largest rounding distance (offset_rounding over the
// coordinates, its norm enlarged by 8u for the norm's roundings).
// \throws InvalidInput naming the first offset that does not fit in a float.
PositionBounds position_bounds(const RenderMesh& mesh, bool z_up, const Vec3& origin) {
  PositionBounds bounds;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = to_gltf_axes(mesh.positions[v], z_up);
    Vec3 error;
    for (std::size_t c = 0; c < 3; ++c) {
      const int i = static_cast<int>(c);
      const double d = p[i] - origin[i];
      const float f = to_float(d, "position", v);
      bounds.low[c] = std::min(bounds.low[c], static_cast<double>(f));
      bounds.high[c] = std::max(bounds.high[c], static_cast<double>(f));
      error[i] = offset_rounding(f, d, origin[i]);
    }
    bounds.rounding = std::max(bounds.rounding, error.stableNorm() * (1 + 0x1p-50));  // no underflow of tiny errors
  }
  return bounds;
}

// ---------------------------------------------------------------------------------------------
// The plan: checks, layout and JSON before the buffer

// One level's part of the buffer.
struct LevelLayout {
  bool short_indices = false;  // UNSIGNED_SHORT indices, else UNSIGNED_INT
  double position_rounding = 0.0;
};

// What a file holds, everything but its buffer's bytes.
struct GltfPlan {
  GltfFormat format = GltfFormat::glb;
  bool z_up = true;
  Vec3 origin = Vec3::Zero();
  std::vector<LevelLayout> levels;
  std::uint64_t buffer_bytes = 0;
  // glb: the compact JSON; gltf: the indented JSON, the buffer's base64 text to go at uri_at.
  std::string json;
  std::size_t uri_at = 0;
  std::uint64_t file_bytes = 0;
};

// The glTF document under construction: one buffer, and a bufferView per accessor, each at a
// multiple of 4 bytes. Fields are those tinygltf serialised, with its number types (int, size_t,
// double: 1 and 1.0 print differently) and the optional ones left out where it left them out.
class JsonBuilder {
 public:
  /// Adds a bufferView of `count` elements of `components` values of `value_bytes` each, and an
  /// accessor over it; returns the accessor's index.
  int add(std::size_t count, int components, std::size_t value_bytes, int component_type, int target) {
    json view = {
        {"buffer", 0}, {"byteLength", count * static_cast<std::size_t>(components) * value_bytes}, {"target", target}};
    if (bytes_ > 0) view["byteOffset"] = static_cast<std::size_t>(bytes_);
    bytes_ = padded_to_4(bytes_ + count * static_cast<std::size_t>(components) * value_bytes);
    views_.push_back(std::move(view));
    static constexpr std::array<const char*, 5> types = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    accessors_.push_back({{"bufferView", static_cast<int>(views_.size() - 1)},
                          {"componentType", component_type},
                          {"count", count},
                          {"type", types[static_cast<std::size_t>(components)]}});
    return static_cast<int>(accessors_.size() - 1);
  }
  json& accessor(int index) { return accessors_[static_cast<std::size_t>(index)]; }
  std::uint64_t bytes() const { return bytes_; }
  json& document() { return document_; }

  /// The whole document: compact for glb; indented by 2 for gltf, the buffer's URI then the bare
  /// data: prefix (the caller puts the base64 text after it).
  std::string dump(GltfFormat format) {
    document_["accessors"] = std::move(accessors_);
    document_["bufferViews"] = std::move(views_);
    json buffer = {{"byteLength", static_cast<std::size_t>(bytes_)}};
    if (format == GltfFormat::gltf) buffer["uri"] = data_uri_prefix;
    document_["buffers"] = json::array({std::move(buffer)});
    return document_.dump(format == GltfFormat::gltf ? 2 : -1);
  }

 private:
  json document_ = json::object();
  json accessors_ = json::array();
  json views_ = json::array();
  std::uint64_t bytes_ = 0;
};

// The bytes the buffer will take, each bufferView padded to 4.
std::uint64_t buffer_bytes(const RenderMesh& mesh, std::size_t index_bytes) {
  const std::uint64_t n = mesh.vertex_count();
  std::uint64_t total = 12 * n + padded_to_4(static_cast<std::uint64_t>(mesh.indices.size()) * index_bytes);
  if (!mesh.normals.empty()) total += 12 * n;
  if (!mesh.uvs.empty()) total += 8 * n;
  if (!mesh.tangents.empty()) total += 16 * n;
  return total;
}

// The default material: light grey, not metallic, half rough.
json default_material(bool double_sided) {
  json material = {{"name", "default"},
                   {"pbrMetallicRoughness",
                    {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}}};
  if (double_sided) material["doubleSided"] = true;
  return material;
}

// Every check, the layout and the JSON of the file of `levels` (the bytes but the buffer's).
// \throws InvalidInput as format_gltf_levels.
GltfPlan plan_gltf(std::span<const RenderMesh> levels, std::span<const double> coverage, GltfFormat format,
                   const GltfOptions& options) {
  if (levels.empty()) throw InvalidInput("format_gltf: no mesh to write");
  if (levels.size() > 1 && coverage.size() != levels.size()) {
    throw InvalidInput(detail::message("format_gltf: ", levels.size(),
                                       " levels of detail need as many screen coverages, got ", coverage.size()));
  }
  for (std::size_t k = 0; k < coverage.size(); ++k) {
    const double previous = k == 0 ? 1.0 : coverage[k - 1];
    if (!(coverage[k] >= 0.0 && coverage[k] <= previous)) {
      throw InvalidInput(detail::message("format_gltf: screen coverage ", k, " (", coverage[k],
                                         ") is not in [0, 1] and at most the one before"));
    }
  }
  std::uint64_t bytes = 0;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const RenderMesh& mesh = levels[level];
    validate(mesh);
    if (mesh.triangle_count() == 0) {
      throw InvalidInput(detail::message("format_gltf: the mesh of level ", level,
                                         " has no triangle (glTF accessors hold at least one element)"));
    }
    if (!mesh.tangents.empty() && mesh.normals.empty()) {
      throw InvalidInput("format_gltf: the mesh has tangents but no normals (glTF ignores tangents without normals)");
    }
    bytes += buffer_bytes(mesh, mesh.vertex_count() <= 0xffff ? 2 : 4);
  }
  if (bytes > max_buffer_bytes) {
    throw InvalidInput(
        detail::message("format_gltf: the buffer would take ", bytes, " bytes, more than a glTF buffer can hold"));
  }

  GltfPlan plan;
  plan.format = format;
  plan.z_up = options.z_up;
  JsonBuilder builder;
  json& document = builder.document();
  document["asset"] = {{"generator", "patchwork"}, {"version", "2.0"}};
  // Not value_or: the topology pass runs only when the caller did not say.
  document["materials"] =
      json::array({default_material(options.double_sided ? *options.double_sided : has_boundary_edge(levels.front()))});
  // Every level is stored from level 0's centre, so that a viewer that places the levels of an
  // MSFT_lod chain by the first node's transform (or by each node's own) puts them in one place.
  // Each level's positions must fit in a float (position_origin checks).
  plan.origin = position_origin(levels.front(), options.z_up);
  for (const RenderMesh& mesh : levels.subspan(1)) position_origin(mesh, options.z_up);
  // One mesh and one node per level; the scene holds the first node, which names the others.
  json meshes = json::array();
  json nodes = json::array();
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const RenderMesh& mesh = levels[level];
    const std::size_t n = mesh.vertex_count();
    LevelLayout layout;
    json attributes = json::object();
    const PositionBounds bounds = position_bounds(mesh, options.z_up, plan.origin);
    layout.position_rounding = bounds.rounding;
    const int position = builder.add(n, 3, sizeof(float), component_float, target_array_buffer);
    builder.accessor(position)["min"] = bounds.low;
    builder.accessor(position)["max"] = bounds.high;
    attributes["POSITION"] = position;
    if (!mesh.normals.empty())
      attributes["NORMAL"] = builder.add(n, 3, sizeof(float), component_float, target_array_buffer);
    if (!mesh.uvs.empty()) {
      for (std::size_t v = 0; v < n; ++v) {
        for (int c = 0; c < 2; ++c) to_float(mesh.uvs[v][c], "uv", v);
      }
      attributes["TEXCOORD_0"] = builder.add(n, 2, sizeof(float), component_float, target_array_buffer);
    }
    if (!mesh.tangents.empty())
      attributes["TANGENT"] = builder.add(n, 4, sizeof(float), component_float, target_array_buffer);
    // At most 65535 vertices: indices up to 65534, so the restart value 65535 never appears (the
    // same holds for 32 bits: validate() allows at most 2^32 - 2 vertices).
    layout.short_indices = n <= 0xffff;
    const int indices = layout.short_indices ? builder.add(mesh.indices.size(), 1, sizeof(std::uint16_t),
                                                           component_unsigned_short, target_element_array_buffer)
                                             : builder.add(mesh.indices.size(), 1, sizeof(std::uint32_t),
                                                           component_unsigned_int, target_element_array_buffer);
    const std::string name = level == 0 ? options.name : detail::message(options.name, "_lod", level);
    const json primitive = {
        {"attributes", std::move(attributes)}, {"indices", indices}, {"material", 0}, {"mode", mode_triangles}};
    meshes.push_back({{"name", name}, {"primitives", json::array({primitive})}});
    json node = {{"mesh", static_cast<int>(level)}, {"name", name}};
    // JSON numbers are doubles: the shortest form that reads back to the same one.
    if (plan.origin != Vec3::Zero()) node["translation"] = {plan.origin.x(), plan.origin.y(), plan.origin.z()};
    nodes.push_back(std::move(node));
    plan.levels.push_back(layout);
  }
  if (levels.size() > 1) {
    json ids = json::array();
    for (std::size_t level = 1; level < levels.size(); ++level) ids.push_back(static_cast<int>(level));
    nodes[0]["extensions"] = {{"MSFT_lod", {{"ids", std::move(ids)}}}};
    nodes[0]["extras"] = {{"MSFT_screencoverage", std::vector<double>(coverage.begin(), coverage.end())}};
    document["extensionsUsed"] = json::array({"MSFT_lod"});
  }
  document["meshes"] = std::move(meshes);
  document["nodes"] = std::move(nodes);
  document["scene"] = 0;
  document["scenes"] = json::array({{{"nodes", json::array({0})}}});

  plan.buffer_bytes = builder.bytes();
  PATCHWORK_ASSERT(plan.buffer_bytes == bytes, "the bufferViews take the bytes buffer_bytes counts");
  plan.json = builder.dump(format);
  if (format == GltfFormat::glb) {
    // Header, JSON chunk (padded with spaces), BIN chunk (the buffer is a multiple of 4 long).
    plan.file_bytes = 12 + 8 + padded_to_4(plan.json.size()) + 8 + plan.buffer_bytes;
  } else {
    // The one data: URI: a '"' in a string is written \", so the text below with its bare
    // quotes is the buffer's "uri" member and nothing else.
    const std::string uri = detail::message("\"uri\": \"", data_uri_prefix, "\"");
    const std::size_t at = plan.json.find(uri);
    PATCHWORK_ASSERT(at != std::string::npos && plan.json.find(uri, at + 1) == std::string::npos,
                     "the JSON holds the buffer's URI once");
    plan.uri_at = at + uri.size() - 1;  // before the closing quote
    // The base64 text (4 characters per 3 bytes, the last group padded) and a newline.
    plan.file_bytes = plan.json.size() + 4 * ((plan.buffer_bytes + 2) / 3) + 1;
  }
  if (plan.file_bytes > 0xffffffffu) {
    throw InvalidInput(
        detail::message("format_gltf: the file would take ", plan.file_bytes, " bytes, more than 4 GiB"));
  }
  return plan;
}

// ---------------------------------------------------------------------------------------------
// Writing the planned file

// Where the buffer's bytes go: to the sink as they are (glb), or as base64 text (gltf's data:
// URI, RFC 4648 with '=' padding and no line breaks, tinygltf's base64_encode): each 3 bytes as 4
// characters, a group split between two writes carried to the next.
class BufferStream {
 public:
  BufferStream(const ByteSink& sink, bool base64) : sink_(sink), base64_(base64) {}

  void write(const void* data, std::size_t size) {
    written_ += size;
    const auto* bytes = static_cast<const unsigned char*>(data);
    if (!base64_) {
      sink_(std::string_view(reinterpret_cast<const char*>(bytes), size));
      return;
    }
    text_.clear();
    while (carried_ > 0 && carried_ < 3 && size > 0) {
      carry_[carried_++] = *bytes++;
      --size;
    }
    if (carried_ == 3) {
      encode(carry_.data(), 3);
      carried_ = 0;
    }
    const std::size_t whole = size / 3 * 3;
    for (std::size_t k = 0; k < whole; k += 3) encode(bytes + k, 3);
    for (std::size_t k = whole; k < size; ++k) carry_[carried_++] = bytes[k];
    sink_(text_);
  }

  /// Zero bytes up to the next multiple of 4 (after a bufferView).
  void pad() {
    static constexpr std::array<unsigned char, 3> zeros = {0, 0, 0};
    write(zeros.data(), static_cast<std::size_t>(padded_to_4(written_) - written_));
  }

  /// Ends the base64 text: the last 1 or 2 bytes as 2 or 3 characters and '=' up to 4.
  void finish() {
    if (!base64_ || carried_ == 0) return;
    text_.clear();
    encode(carry_.data(), carried_);
    carried_ = 0;
    sink_(text_);
  }

  std::uint64_t written() const { return written_; }

 private:
  // Appends the characters of `count` (1 to 3) bytes, padded with '=' to 4.
  void encode(const unsigned char* b, std::size_t count) {
    static constexpr std::string_view alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned b0 = b[0];
    const unsigned b1 = count > 1 ? b[1] : 0u;
    const unsigned b2 = count > 2 ? b[2] : 0u;
    const std::array<unsigned, 4> sextets = {b0 >> 2u, ((b0 & 0x03u) << 4u) | (b1 >> 4u),
                                             ((b1 & 0x0fu) << 2u) | (b2 >> 6u), b2 & 0x3fu};
    for (std::size_t k = 0; k < 4; ++k) text_.push_back(k <= count ? alphabet[sextets[k]] : '=');
  }

  const ByteSink& sink_;
  bool base64_;
  std::array<unsigned char, 3> carry_{};
  std::size_t carried_ = 0;
  std::string text_;
  std::uint64_t written_ = 0;
};

// Writes `count` elements into `out` as one bufferView, `chunk` at a time: convert(e, staging)
// appends element e's values to the staging array, which holds one chunk.
template <class T, class Convert>
void write_view(BufferStream& out, std::size_t count, std::size_t chunk, std::vector<T>& staging, Convert convert) {
  for (std::size_t begin = 0; begin < count; begin += chunk) {
    const std::size_t end = std::min(count, begin + chunk);
    staging.clear();
    for (std::size_t e = begin; e < end; ++e) convert(e, staging);
    out.write(staging.data(), staging.size() * sizeof(T));
  }
  out.pad();
}

// The buffer of `levels` as planned, in the order of the bufferViews.
void write_buffer(const GltfPlan& plan, std::span<const RenderMesh> levels, std::size_t chunk, BufferStream& out) {
  const bool z_up = plan.z_up;
  const Vec3& origin = plan.origin;
  std::vector<float> floats;
  floats.reserve(4 * chunk);
  std::vector<std::uint16_t> shorts;
  std::vector<std::uint32_t> ints;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const RenderMesh& mesh = levels[level];
    const std::size_t n = mesh.vertex_count();
    // The same arithmetic as position_bounds, which checked that every value fits.
    write_view(out, n, chunk, floats, [&](std::size_t v, std::vector<float>& values) {
      const Vec3 p = to_gltf_axes(mesh.positions[v], z_up);
      for (int c = 0; c < 3; ++c) values.push_back(static_cast<float>(p[c] - origin[c]));
    });
    if (!mesh.normals.empty()) {
      write_view(out, n, chunk, floats, [&](std::size_t v, std::vector<float>& values) {
        append_unit(values, to_gltf_axes(mesh.normals[v], z_up));
      });
    }
    if (!mesh.uvs.empty()) {
      write_view(out, n, chunk, floats, [&](std::size_t v, std::vector<float>& values) {
        for (int c = 0; c < 2; ++c) values.push_back(static_cast<float>(mesh.uvs[v][c]));
      });
    }
    if (!mesh.tangents.empty()) {
      write_view(out, n, chunk, floats, [&](std::size_t v, std::vector<float>& values) {
        const Vec4& tangent = mesh.tangents[v];
        append_unit(values, to_gltf_axes(tangent.head<3>(), z_up));
        values.push_back(static_cast<float>(tangent.w()));  // exactly +1 or -1 (validate())
      });
    }
    if (plan.levels[level].short_indices) {
      write_view(out, mesh.indices.size(), chunk, shorts, [&](std::size_t k, std::vector<std::uint16_t>& values) {
        values.push_back(static_cast<std::uint16_t>(mesh.indices[k]));
      });
    } else {
      write_view(out, mesh.indices.size(), chunk, ints,
                 [&](std::size_t k, std::vector<std::uint32_t>& values) { values.push_back(mesh.indices[k]); });
    }
  }
  PATCHWORK_ASSERT(out.written() == plan.buffer_bytes, "the buffer written is the one planned");
}

// A little-endian 32-bit word.
std::string_view word(const std::uint32_t& value) { return {reinterpret_cast<const char*>(&value), sizeof value}; }

// The file of plan_gltf's plan into `sink`, the buffer converted `chunk` elements at a time.
void write_planned(const GltfPlan& plan, std::span<const RenderMesh> levels, std::size_t chunk, const ByteSink& sink) {
  PATCHWORK_ASSERT(chunk > 0, "a chunk holds an element");
  if (plan.format == GltfFormat::glb) {
    const std::string_view json_text = plan.json;
    const auto json_length = static_cast<std::uint32_t>(padded_to_4(json_text.size()));
    const auto file_length = static_cast<std::uint32_t>(plan.file_bytes);
    const auto bin_length = static_cast<std::uint32_t>(plan.buffer_bytes);
    for (const std::uint32_t& header : {glb_magic, glb_version, file_length, json_length, chunk_json})
      sink(word(header));
    sink(json_text);
    sink(std::string_view("   ", json_length - json_text.size()));  // the JSON chunk is padded with spaces
    for (const std::uint32_t& header : {bin_length, chunk_bin}) sink(word(header));
    BufferStream buffer(sink, false);
    write_buffer(plan, levels, chunk, buffer);
  } else {
    const std::string_view json_text = plan.json;
    sink(json_text.substr(0, plan.uri_at));
    BufferStream buffer(sink, true);
    write_buffer(plan, levels, chunk, buffer);
    buffer.finish();
    sink(json_text.substr(plan.uri_at));
    sink("\n");
  }
}

// The file's bytes in a string.
std::string planned_bytes(const GltfPlan& plan, std::span<const RenderMesh> levels, std::size_t chunk) {
  std::string bytes;
  bytes.reserve(plan.file_bytes);
  write_planned(plan, levels, chunk, [&](std::string_view piece) { bytes.append(piece); });
  PATCHWORK_ASSERT(bytes.size() == plan.file_bytes, "the file written has the size planned");
  return bytes;
}

std::vector<double> position_rounding(const GltfPlan& plan) {
  std::vector<double> rounding;
  for (const LevelLayout& level : plan.levels) rounding.push_back(level.position_rounding);
  return rounding;
}

// The format named by the extension of `path`. \throws IoError for any other extension.
GltfFormat gltf_format_of(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".glb") return GltfFormat::glb;
  if (extension == ".gltf") return GltfFormat::gltf;
  throw IoError(path.string(), detail::message("write_gltf: unknown extension \"", path.extension().string(),
                                               "\" (expected .glb or .gltf)"));
}

}  // namespace

std::string format_gltf(const RenderMesh& mesh, GltfFormat format, const GltfOptions& options) {
  return encode_gltf_levels(std::span<const RenderMesh>(&mesh, 1), {}, format, options).bytes;
}

std::string format_gltf_levels(std::span<const RenderMesh> levels, std::span<const double> coverage, GltfFormat format,
                               const GltfOptions& options) {
  return encode_gltf_levels(levels, coverage, format, options).bytes;
}

GltfEncoding encode_gltf_levels(std::span<const RenderMesh> levels, std::span<const double> coverage, GltfFormat format,
                                const GltfOptions& options) {
  const GltfPlan plan = plan_gltf(levels, coverage, format, options);
  return {planned_bytes(plan, levels, detail::gltf_chunk_elements), position_rounding(plan)};
}

double write_gltf(const std::filesystem::path& path, const RenderMesh& mesh, const GltfOptions& options) {
  return write_gltf_levels(path, std::span<const RenderMesh>(&mesh, 1), {}, options).front();
}

std::vector<double> write_gltf_levels(const std::filesystem::path& path, std::span<const RenderMesh> levels,
                                      std::span<const double> coverage, const GltfOptions& options) {
  const GltfFormat format = gltf_format_of(path);
  // Every check before the file is created.
  const GltfPlan plan = plan_gltf(levels, coverage, format, options);
  AtomicFile file(path);
  write_planned(plan, levels, detail::gltf_chunk_elements, [&](std::string_view piece) { file.write(piece); });
  file.commit();
  return position_rounding(plan);
}

namespace detail {

std::string format_gltf_levels_in_chunks(std::span<const RenderMesh> levels, std::span<const double> coverage,
                                         GltfFormat format, const GltfOptions& options, std::size_t chunk) {
  if (chunk == 0) throw InvalidInput("format_gltf_levels_in_chunks: a chunk of 0 elements");
  return planned_bytes(plan_gltf(levels, coverage, format, options), levels, chunk);
}

}  // namespace detail
}  // namespace patchwork
