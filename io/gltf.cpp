// format_gltf, encode_gltf_levels and write_gltf (io/gltf.h): the writer; io/gltf_reader.cpp reads.

#include "io/gltf.h"

// Debian ships tinygltf as a shared library built with its defaults (stb_image, stb_image_write,
// nlohmann/json, the file system callbacks): include the header plainly, without
// TINYGLTF_IMPLEMENTATION or any TINYGLTF_NO_* macro, so our view of its classes is the library's.
#include <tiny_gltf.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "meshes/topology.h"

namespace patchwork {
namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

// The largest buffer written: the 4 GiB a GLB chunk (and tinygltf's base64 encoder) can hold,
// less 1 MiB for the GLB header and the JSON.
constexpr std::uint64_t max_buffer_bytes = 0xffffffffull - (1ull << 20);

// ---------------------------------------------------------------------------------------------
// Writing

// Z-up to Y-up: (x, y, z) -> (x, z, -y), a rotation about +x (see io/gltf.h).
Vec3 to_gltf_axes(const Vec3& v, bool z_up) { return z_up ? Vec3(v.x(), v.z(), -v.y()) : v; }

// The float nearest x. \throws InvalidInput naming the value if it does not fit in a float
// (checked before the cast: converting a double beyond the float range is undefined behaviour).
float to_float(double x, const char* what, std::size_t vertex) {
  if (!(std::abs(x) <= std::numeric_limits<float>::max())) {
    throw InvalidInput(detail::message("format_gltf: ", what, " of vertex ", vertex, " (", x, ") does not fit in a float"));
  }
  return static_cast<float>(x);
}

// A unit direction (validate() allows 1e-6 slack) normalised in double and rounded to float:
// one rounding, so the float vector's length is 1 to within about 1e-7.
void append_unit(std::vector<float>& out, const Vec3& direction) {
  const Vec3 unit = direction / direction.norm();
  for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(unit[c]));
}

// The glTF document under construction: one buffer, and a bufferView per accessor.
class GltfBuilder {
 public:
  GltfBuilder() { model_.buffers.emplace_back(); }

  /// Appends `values` as a new bufferView (at a multiple of 4 bytes, zero-padded after) with an
  /// accessor over it; returns the accessor's index.
  template <class T>
  int add(const std::vector<T>& values, int components, int component_type, int target) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    data.insert(data.end(), bytes, bytes + view.byteLength);
    data.resize((data.size() + 3) / 4 * 4, 0);
    model_.bufferViews.push_back(view);

    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size() - 1);
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.count = values.size() / static_cast<std::size_t>(components);
    accessor.type = components == 1 ? TINYGLTF_TYPE_SCALAR : components;  // TINYGLTF_TYPE_VECn is n
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  tinygltf::Accessor& accessor(int index) { return model_.accessors[static_cast<std::size_t>(index)]; }
  tinygltf::Model& model() { return model_; }

 private:
  tinygltf::Model model_;
};

// Whether an edge of the welded triangles is used by exactly one of them (meshes/topology.h).
bool has_boundary_edge(const RenderMesh& mesh) { return analyze(welded_faces(mesh)).boundary_edges > 0; }

// The bytes the buffer will take, each bufferView padded to 4.
std::uint64_t buffer_bytes(const RenderMesh& mesh, std::size_t index_bytes) {
  const auto padded = [](std::uint64_t bytes) { return (bytes + 3) / 4 * 4; };
  const std::uint64_t n = mesh.vertex_count();
  std::uint64_t total = 12 * n + padded(static_cast<std::uint64_t>(mesh.indices.size()) * index_bytes);
  if (!mesh.normals.empty()) total += 12 * n;
  if (!mesh.uvs.empty()) total += 8 * n;
  if (!mesh.tangents.empty()) total += 16 * n;
  return total;
}

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

// The attribute accessors of the primitive (the indices are added by the caller), the positions
// relative to `origin`; returns the largest rounding distance of a position (offset_rounding
// over the coordinates, its norm enlarged by 8u for the norm's roundings).
double add_attributes(GltfBuilder& builder, tinygltf::Primitive& primitive, const RenderMesh& mesh, bool z_up,
                      const Vec3& origin) {
  const std::size_t n = mesh.vertex_count();
  std::vector<float> values;
  values.reserve(4 * n);
  double rounding = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 p = to_gltf_axes(mesh.positions[v], z_up);
    Vec3 error;
    for (int c = 0; c < 3; ++c) {
      const double d = p[c] - origin[c];
      const float f = to_float(d, "position", v);
      values.push_back(f);
      error[c] = offset_rounding(f, d, origin[c]);
    }
    rounding = std::max(rounding, error.stableNorm() * (1 + 0x1p-50));  // no underflow of tiny errors
  }
  const int position = builder.add(values, 3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  // min/max of the stored floats, as the validator compares them.
  std::vector<double> low(3, std::numeric_limits<double>::infinity());
  std::vector<double> high(3, -std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < values.size(); ++k) {
    low[k % 3] = std::min(low[k % 3], static_cast<double>(values[k]));
    high[k % 3] = std::max(high[k % 3], static_cast<double>(values[k]));
  }
  builder.accessor(position).minValues = low;
  builder.accessor(position).maxValues = high;
  primitive.attributes["POSITION"] = position;

  if (!mesh.normals.empty()) {
    values.clear();
    for (const Vec3& normal : mesh.normals) append_unit(values, to_gltf_axes(normal, z_up));
    primitive.attributes["NORMAL"] =
        builder.add(values, 3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  if (!mesh.uvs.empty()) {
    values.clear();
    for (std::size_t v = 0; v < n; ++v) {
      for (int c = 0; c < 2; ++c) values.push_back(to_float(mesh.uvs[v][c], "uv", v));
    }
    primitive.attributes["TEXCOORD_0"] =
        builder.add(values, 2, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  if (!mesh.tangents.empty()) {
    values.clear();
    for (const Vec4& tangent : mesh.tangents) {
      append_unit(values, to_gltf_axes(tangent.head<3>(), z_up));
      values.push_back(static_cast<float>(tangent.w()));  // exactly +1 or -1 (validate())
    }
    primitive.attributes["TANGENT"] =
        builder.add(values, 4, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  return rounding;
}

// The default material: light grey, not metallic, half rough.
tinygltf::Material default_material(bool double_sided) {
  tinygltf::Material material;
  material.name = "default";
  material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.5;
  material.doubleSided = double_sided;
  return material;
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
  if (levels.empty()) throw InvalidInput("format_gltf: no mesh to write");
  if (levels.size() > 1 && coverage.size() != levels.size()) {
    throw InvalidInput(detail::message("format_gltf: ", levels.size(), " levels of detail need as many screen coverages, got ",
                                       coverage.size()));
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
    throw InvalidInput(detail::message("format_gltf: the buffer would take ", bytes, " bytes, more than a glTF buffer can hold"));
  }

  GltfEncoding encoding;
  GltfBuilder builder;
  tinygltf::Model& model = builder.model();
  model.asset.version = "2.0";
  model.asset.generator = "patchwork";
  // Not value_or: the topology pass runs only when the caller did not say.
  model.materials.push_back(
      default_material(options.double_sided ? *options.double_sided : has_boundary_edge(levels.front())));
  // Every level is stored from level 0's centre, so that a viewer that places the levels of an
  // MSFT_lod chain by the first node's transform (or by each node's own) puts them in one place.
  // Each level's positions must fit in a float (position_origin checks).
  const Vec3 origin = position_origin(levels.front(), options.z_up);
  for (const RenderMesh& mesh : levels.subspan(1)) position_origin(mesh, options.z_up);
  // One mesh and one node per level; the scene holds the first node, which names the others.
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const RenderMesh& mesh = levels[level];
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = 0;
    encoding.position_rounding.push_back(add_attributes(builder, primitive, mesh, options.z_up, origin));
    // At most 65535 vertices: indices up to 65534, so the restart value 65535 never appears (the
    // same holds for 32 bits: validate() allows at most 2^32 - 2 vertices).
    if (mesh.vertex_count() <= 0xffff) {
      const std::vector<std::uint16_t> indices(mesh.indices.begin(), mesh.indices.end());
      primitive.indices = builder.add(indices, 1, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                      TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    } else {
      primitive.indices = builder.add(mesh.indices, 1, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                      TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    const std::string name = level == 0 ? options.name : detail::message(options.name, "_lod", level);
    tinygltf::Mesh gltf_mesh;
    gltf_mesh.name = name;
    gltf_mesh.primitives.push_back(std::move(primitive));
    model.meshes.push_back(std::move(gltf_mesh));
    tinygltf::Node node;
    node.name = name;
    node.mesh = static_cast<int>(level);
    // JSON numbers are doubles: tinygltf writes the shortest form that reads back to the same one.
    if (origin != Vec3::Zero()) node.translation = {origin.x(), origin.y(), origin.z()};
    model.nodes.push_back(std::move(node));
  }
  if (levels.size() > 1) {
    tinygltf::Value::Array ids;
    tinygltf::Value::Array coverages;
    for (std::size_t level = 1; level < levels.size(); ++level) ids.emplace_back(static_cast<int>(level));
    for (const double c : coverage) coverages.emplace_back(c);
    tinygltf::Value::Object lod;
    lod["ids"] = tinygltf::Value(std::move(ids));
    model.nodes[0].extensions["MSFT_lod"] = tinygltf::Value(std::move(lod));
    tinygltf::Value::Object extras;
    extras["MSFT_screencoverage"] = tinygltf::Value(std::move(coverages));
    model.nodes[0].extras = tinygltf::Value(std::move(extras));
    model.extensionsUsed.push_back("MSFT_lod");
  }
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(std::move(scene));
  model.defaultScene = 0;

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  const bool binary = format == GltfFormat::glb;
  // Writing to a stream fails only for images, and there are none.
  [[maybe_unused]] const bool written = writer.WriteGltfSceneToStream(&model, out, !binary, binary);
  PATCHWORK_ASSERT(written && out, "tinygltf failed to serialise a model without images");
  encoding.bytes = std::move(out).str();
  if (encoding.bytes.size() > 0xffffffffu) {
    throw InvalidInput(
        detail::message("format_gltf: the file would take ", encoding.bytes.size(), " bytes, more than 4 GiB"));
  }
  return encoding;
}

double write_gltf(const std::filesystem::path& path, const RenderMesh& mesh, const GltfOptions& options) {
  return write_gltf_levels(path, std::span<const RenderMesh>(&mesh, 1), {}, options).front();
}

std::vector<double> write_gltf_levels(const std::filesystem::path& path, std::span<const RenderMesh> levels,
                                      std::span<const double> coverage, const GltfOptions& options) {
  const GltfFormat format = gltf_format_of(path);
  GltfEncoding encoding = encode_gltf_levels(levels, coverage, format, options);
  write_file_atomically(path, encoding.bytes);
  return std::move(encoding.position_rounding);
}

}  // namespace patchwork
