#include "io/gltf.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/bpt.h"
#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"
#include "tests/support/moved_patches.h"
#include "tests/support/ci_environment.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int array_buffer = 34962;
constexpr int element_array_buffer = 34963;
constexpr int unsigned_short = 5123;
constexpr int unsigned_int = 5125;

// ---------------------------------------------------------------------------------------------
// Meshes

// x rounded to float and back. Through a volatile float: GCC 12.2 at -O2 drops the round trip
// when its SLP vectorizer pairs two of them (Vec3(f32(p.x()), f32(p.z()), ...) came back
// unrounded), and so would Eigen's cast<float>().cast<double>().
double f32(double x) {
  volatile float rounded = static_cast<float>(x);
  return rounded;
}

// Position ids: each vertex gets the first vertex with an equal position.
std::vector<std::uint32_t> first_equal_position(const std::vector<Vec3>& positions) {
  std::vector<std::uint32_t> ids(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    ids[v] = static_cast<std::uint32_t>(v);
    for (std::size_t w = 0; w < v; ++w) {
      if (positions[w] == positions[v]) {
        ids[v] = static_cast<std::uint32_t>(w);
        break;
      }
    }
  }
  return ids;
}

// A cube of side 0.1 centred at (0.3, -0.2, 0.7) (coordinates no float holds exactly), one quad
// of 4 vertices per side: split normals, uvs, tangents along increasing u. Side (n, t, b) has
// corners centre + h n + h (s t + r b), s, r = -1, +1, uv ((s + 1)/2, (r + 1)/2), tangent (t, +1),
// and (t, b, n) is right-handed (t x b = n), so (-,-) (+,-) (+,+) (-,+) is counter-clockwise seen
// from outside. The -y side runs u the other way: uv ((1 - s)/2, ...) and tangent (-t, -1).
RenderMesh cube() {
  const Vec3 centre(0.3, -0.2, 0.7);
  const double h = 0.05;
  struct Side {
    Vec3 n, t;
  };
  const Side sides[] = {{Vec3::UnitX(), Vec3::UnitY()}, {-Vec3::UnitX(), Vec3::UnitZ()},
                        {Vec3::UnitY(), Vec3::UnitZ()}, {-Vec3::UnitY(), Vec3::UnitX()},
                        {Vec3::UnitZ(), Vec3::UnitX()}, {-Vec3::UnitZ(), Vec3::UnitY()}};
  RenderMesh mesh;
  for (const Side& side : sides) {
    const Vec3 b = side.n.cross(side.t);
    const bool flipped = side.n == -Vec3::UnitY();
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    for (const auto& [s, r] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      mesh.positions.push_back(centre + h * side.n + h * (s * side.t + r * b));
      mesh.normals.push_back(side.n);
      mesh.uvs.emplace_back(flipped ? (1 - s) / 2.0 : (s + 1) / 2.0, (r + 1) / 2.0);
      Vec4 tangent;
      tangent << (flipped ? -side.t : side.t), flipped ? -1.0 : 1.0;
      mesh.tangents.push_back(tangent);
    }
    for (const std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + k);
  }
  mesh.position_ids = first_equal_position(mesh.positions);
  return mesh;
}

// The square [0, 1]^2 at z = 0.25, two triangles counter-clockwise seen from +z, positions only.
RenderMesh open_square() {
  RenderMesh mesh;
  mesh.positions = {Vec3(0, 0, 0.25), Vec3(1, 0, 0.25), Vec3(1, 1, 0.25), Vec3(0, 1, 0.25)};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.position_ids = {0, 1, 2, 3};
  return mesh;
}

// A planar grid of columns x rows vertices at (0.01 i, 0.02 j, 0), normal +z, uv (i, j) scaled
// to [0, 1], tangent (+x, +1); two triangles per cell, counter-clockwise seen from +z.
RenderMesh grid(std::uint32_t columns, std::uint32_t rows) {
  RenderMesh mesh;
  for (std::uint32_t j = 0; j < rows; ++j) {
    for (std::uint32_t i = 0; i < columns; ++i) {
      mesh.positions.emplace_back(0.01 * i, 0.02 * j, 0.0);
      mesh.normals.push_back(Vec3::UnitZ());
      mesh.uvs.emplace_back(i / (columns - 1.0), j / (rows - 1.0));
      mesh.tangents.emplace_back(1.0, 0.0, 0.0, 1.0);
    }
  }
  for (std::uint32_t j = 0; j + 1 < rows; ++j) {
    for (std::uint32_t i = 0; i + 1 < columns; ++i) {
      const std::uint32_t a = j * columns + i;
      const std::uint32_t c = a + columns + 1;
      for (const std::uint32_t k : {a, a + 1, c, a, c, c - 1}) mesh.indices.push_back(k);
    }
  }
  mesh.position_ids.resize(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) mesh.position_ids[v] = static_cast<std::uint32_t>(v);
  return mesh;
}

// p in glTF's axes: (x, z, -y) when z_up.
Vec3 gltf_axes(const Vec3& p, bool z_up = true) { return z_up ? Vec3(p.x(), p.z(), -p.y()) : p; }

// The node translation write_gltf stores positions from: the centre of their box in glTF's axes.
Vec3 gltf_origin(const RenderMesh& mesh, bool z_up = true) {
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (const Vec3& p : mesh.positions) {
    low = low.cwiseMin(gltf_axes(p, z_up));
    high = high.cwiseMax(gltf_axes(p, z_up));
  }
  return 0.5 * low + 0.5 * high;
}

// The float stored for position p (glTF's axes), relative to the origin t.
Vec3 stored(const Vec3& p, const Vec3& t, bool z_up = true) {
  const Vec3 g = gltf_axes(p, z_up);
  return Vec3(f32(g.x() - t.x()), f32(g.y() - t.y()), f32(g.z() - t.z()));
}

// What a file written by write_gltf reads back as: every value rounded to float, the positions
// as the stored float offset plus the node's translation, fl(f + t), back in Z-up. (The test
// meshes' normals and tangents are axis vectors, which floats hold exactly.)
RenderMesh rounded(RenderMesh mesh, bool z_up = true) {
  const Vec3 t = gltf_origin(mesh, z_up);
  for (Vec3& p : mesh.positions) {
    const Vec3 g = stored(p, t, z_up) + t;
    p = z_up ? Vec3(g.x(), -g.z(), g.y()) : g;
  }
  for (Vec2& uv : mesh.uvs) uv = Vec2(f32(uv.x()), f32(uv.y()));
  return mesh;
}

// The node write_gltf writes for `mesh`: its mesh, name, and translation unless it is zero.
json expected_node(const RenderMesh& mesh, int index, const std::string& name, bool z_up = true) {
  json node = {{"mesh", index}, {"name", name}};
  const Vec3 t = gltf_origin(mesh, z_up);
  if (t != Vec3::Zero()) node["translation"] = {t.x(), t.y(), t.z()};
  return node;
}

// Where two meshes first differ, or "" if they are equal in every value.
template <class T>
std::string first_difference(const char* what, const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return detail::message(what, ": ", a.size(), " vs ", b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!(a[k] == b[k])) {
      std::ostringstream out;
      out.precision(17);
      out << what << "[" << k << "]: " << a[k] << " vs " << b[k];
      std::string text = out.str();
      std::replace(text.begin(), text.end(), '\n', ' ');
      return text;
    }
  }
  return "";
}

std::string first_difference(const RenderMesh& a, const RenderMesh& b) {
  for (const std::string& difference :
       {first_difference("positions", a.positions, b.positions), first_difference("normals", a.normals, b.normals),
        first_difference("uvs", a.uvs, b.uvs), first_difference("tangents", a.tangents, b.tangents),
        first_difference("indices", a.indices, b.indices),
        first_difference("position_ids", a.position_ids, b.position_ids)}) {
    if (!difference.empty()) return difference;
  }
  return "";
}

// ---------------------------------------------------------------------------------------------
// Reading the files by hand (glTF 2.0 specification, section 4.4 "Binary glTF Layout")

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t x;
  std::memcpy(&x, bytes.data() + offset, sizeof x);
  return x;
}

// The JSON and the BIN chunk of a GLB, with its header, chunk lengths and chunk types checked:
// magic "glTF", version 2, total length = file size, chunks 4-byte aligned and padded.
struct Glb {
  json document;
  std::uint64_t bin_size = 0;
};

Glb parse_glb(const std::string& bytes) {
  Glb glb;
  EXPECT_GE(bytes.size(), 28u);
  if (bytes.size() < 28) return glb;
  EXPECT_EQ(u32_at(bytes, 0), 0x46546C67u) << "magic glTF";
  EXPECT_EQ(u32_at(bytes, 4), 2u) << "version";
  EXPECT_EQ(u32_at(bytes, 8), bytes.size()) << "total length";
  const std::uint32_t json_length = u32_at(bytes, 12);
  EXPECT_EQ(u32_at(bytes, 16), 0x4E4F534Au) << "first chunk JSON";
  EXPECT_EQ(json_length % 4, 0u) << "JSON chunk padded to 4";
  const std::size_t bin_header = 20 + static_cast<std::size_t>(json_length);
  EXPECT_LE(bin_header + 8, bytes.size());
  if (bin_header + 8 > bytes.size()) return glb;
  glb.document = json::parse(bytes.substr(20, json_length));
  const std::uint32_t bin_length = u32_at(bytes, bin_header);
  EXPECT_EQ(bin_header % 4, 0u) << "BIN chunk starts at a multiple of 4";
  EXPECT_EQ(u32_at(bytes, bin_header + 4), 0x004E4942u) << "second chunk BIN";
  EXPECT_EQ(bin_length % 4, 0u) << "BIN chunk padded to 4";
  EXPECT_EQ(bin_header + 8 + bin_length, bytes.size()) << "nothing after the BIN chunk";
  glb.bin_size = bin_length;
  return glb;
}

// The document's layout as io/gltf.h promises it, for `mesh` written with the defaults.
void expect_layout(const json& document, const RenderMesh& mesh, std::uint64_t buffer_size) {
  EXPECT_EQ(document["asset"]["version"], "2.0");
  EXPECT_EQ(document["asset"]["generator"], "patchwork");
  EXPECT_EQ(document["scene"], 0);
  EXPECT_EQ(document["scenes"], json::parse(R"([{"nodes": [0]}])"));
  EXPECT_EQ(document["nodes"], json::array({expected_node(mesh, 0, "patchwork")}));
  ASSERT_EQ(document["meshes"].size(), 1u);
  ASSERT_EQ(document["meshes"][0]["primitives"].size(), 1u);
  const json& primitive = document["meshes"][0]["primitives"][0];
  EXPECT_EQ(primitive["mode"], 4);
  EXPECT_EQ(primitive["material"], 0);
  EXPECT_EQ(primitive["attributes"].contains("NORMAL"), !mesh.normals.empty());
  EXPECT_EQ(primitive["attributes"].contains("TEXCOORD_0"), !mesh.uvs.empty());
  EXPECT_EQ(primitive["attributes"].contains("TANGENT"), !mesh.tangents.empty());

  ASSERT_EQ(document["buffers"].size(), 1u);
  const std::uint64_t length = document["buffers"][0]["byteLength"];
  EXPECT_EQ(length % 4, 0u);
  EXPECT_EQ(length, buffer_size);
  const int indices = primitive["indices"];
  const json& accessors = document["accessors"];
  const json& views = document["bufferViews"];
  EXPECT_EQ(views.size(), accessors.size()) << "one bufferView per accessor";
  std::vector<bool> view_used(views.size(), false);
  for (std::size_t a = 0; a < accessors.size(); ++a) {
    SCOPED_TRACE(detail::message("accessor ", a));
    const json& accessor = accessors[a];
    EXPECT_EQ(accessor.value("byteOffset", 0), 0);
    const std::size_t v = accessor["bufferView"];
    ASSERT_LT(v, views.size());
    EXPECT_FALSE(view_used[v]) << "bufferView " << v << " shared";
    view_used[v] = true;
    const json& view = views[v];
    const std::uint64_t offset = view.value("byteOffset", 0);
    EXPECT_EQ(offset % 4, 0u) << "bufferView " << v << " starts at " << offset;
    EXPECT_FALSE(view.contains("byteStride"));
    EXPECT_LE(offset + static_cast<std::uint64_t>(view["byteLength"]), length);
    EXPECT_EQ(view["target"], static_cast<int>(a) == indices ? element_array_buffer : array_buffer);
  }
  EXPECT_EQ(accessors[indices]["componentType"], mesh.vertex_count() <= 65535 ? unsigned_short : unsigned_int);
  EXPECT_EQ(accessors[indices]["count"], mesh.indices.size());
  EXPECT_EQ(accessors[indices]["type"], "SCALAR");

  // POSITION min/max: those of the stored floats, (x, y, z) stored as (x, z, -y) - t.
  const json& position = accessors[primitive["attributes"]["POSITION"].get<int>()];
  std::vector<double> low(3, std::numeric_limits<double>::infinity());
  std::vector<double> high(3, -std::numeric_limits<double>::infinity());
  const Vec3 t = gltf_origin(mesh);
  for (const Vec3& p : mesh.positions) {
    const Vec3 f = stored(p, t);
    for (int c = 0; c < 3; ++c) {
      low[c] = std::min(low[c], f[c]);
      high[c] = std::max(high[c], f[c]);
    }
  }
  EXPECT_EQ(position["min"].get<std::vector<double>>(), low);
  EXPECT_EQ(position["max"].get<std::vector<double>>(), high);
}

// Reading `path` fails with a ParseError naming it, whose message holds every one of `parts`.
template <class... Parts>
void expect_parse_error(const fs::path& path, const Parts&... parts) {
  try {
    read_gltf(path);
    ADD_FAILURE() << "no ParseError for " << path;
  } catch (const ParseError& e) {
    EXPECT_EQ(e.path(), path.string());
    for (const std::string& part : {std::string(parts)...}) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
}

// A test's own folder under the system's temp folder, removed with everything in it.
class GltfFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    folder_ = fs::temp_directory_path() / ("patchwork_gltf_test_" + test + "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directory(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  fs::path file(const std::string& name) const { return folder_ / name; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  // Writes `mesh` as name.gltf, edits the JSON with `edit`, and saves it as edited.gltf.
  template <class Edit>
  fs::path edited(const RenderMesh& mesh, Edit edit) const {
    write_gltf(file("original.gltf"), mesh);
    json document = json::parse(read_file(file("original.gltf")));
    edit(document);
    write_file_atomically(file("edited.gltf"), document.dump());
    return file("edited.gltf");
  }

  fs::path folder_;
};

std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// ---------------------------------------------------------------------------------------------
// Writing and reading back

TEST_F(GltfFile, CubeReadsBackAsItsFloatRoundedValuesInBothContainers) {
  const RenderMesh mesh = cube();
  validate(mesh);
  const RenderMesh expected = rounded(mesh);
  // The test is not vacuous: float rounding changes the cube's coordinates.
  ASSERT_NE(expected.positions[0], mesh.positions[0]);
  for (const char* name : {"cube.glb", "cube.gltf", "UPPER.GLB", "Mixed.GlTf"}) {
    SCOPED_TRACE(name);
    write_gltf(file(name), mesh);
    const RenderMesh back = read_gltf(file(name));
    EXPECT_EQ(first_difference(back, expected), "");
  }
  EXPECT_EQ(read_file(file("cube.glb")), format_gltf(mesh, GltfFormat::glb));
  EXPECT_EQ(read_file(file("UPPER.GLB")), format_gltf(mesh, GltfFormat::glb));
  EXPECT_EQ(read_file(file("cube.gltf")), format_gltf(mesh, GltfFormat::gltf));
  EXPECT_EQ(read_file(file("cube.gltf")).substr(0, 1), "{");
  // The welded position ids: 8 corners for the 24 vertices.
  std::vector<std::uint32_t> ids = read_gltf(file("cube.glb")).position_ids;
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(std::unique(ids.begin(), ids.end()) - ids.begin(), 8);
  // No temporary file is left behind.
  EXPECT_EQ(entries(), (std::vector<std::string>{"Mixed.GlTf", "UPPER.GLB", "cube.glb", "cube.gltf"}));
}

TEST_F(GltfFile, MovedTeapotAsWrittenStaysWithinTheReportedBound) {
  // The teapot moved to (1e5, -2e5, 3e4), tessellated at an absolute tolerance of 0.002. Floats
  // there are 2^-7 to 2^-6 apart (a rounding of up to 0.0078 per coordinate, four times the
  // tolerance); offsets from the box's centre (at most ~4 from it) round by about 2.4e-7.
  const Vec3 shift(1e5, -2e5, 3e4);
  std::vector<BezierPatch3> patches = testing::moved(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"), shift);
  TessellationOptions options;
  options.tolerance = 0.002;
  const Tessellation result = tessellate(PatchSet(std::move(patches)), options);
  ASSERT_LE(result.error_bound, 0.002);
  const RenderMesh& mesh = result.mesh;
  for (const char* name : {"moved.glb", "moved.gltf"}) {
    SCOPED_TRACE(name);
    const double rounding = write_gltf(file(name), mesh);
    // Far below the tolerance: the file's bound, error_bound + rounding, is the tessellator's.
    EXPECT_LT(rounding, 1e-3 * 0.002);
    EXPECT_GT(rounding, 0.0);
    const RenderMesh back = read_gltf(file(name));
    ASSERT_EQ(back.vertex_count(), mesh.vertex_count());
    double largest = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const double distance = (back.positions[v] - mesh.positions[v]).norm();
      largest = std::max(largest, distance);
      ASSERT_LE(distance, rounding) << "vertex " << v;
    }
    // The bound is not loose by more than a small factor (per-coordinate half-ulps of ~4 in
    // float, sqrt 3 of them at most).
    EXPECT_GT(largest, rounding / 4);
    std::cout << name << ": position rounding bound " << rounding << ", largest " << largest << "\n";
  }
  // The translation is kept at full double precision: the box's centre exactly.
  const json document = parse_glb(read_file(file("moved.glb"))).document;
  const Vec3 t = gltf_origin(mesh);
  EXPECT_EQ(document["nodes"][0]["translation"].get<std::vector<double>>(), (std::vector<double>{t.x(), t.y(), t.z()}));
  EXPECT_NE(t.x(), std::round(t.x())) << "a centre that JSON could hold in few digits would not test this";
}

TEST(Gltf, GlbChunksAndBufferViewsAreAligned) {
  // 3 u16 indices take 6 bytes, so the buffer ends off the 4-byte grid unless padded.
  RenderMesh odd = open_square();
  odd.indices.resize(3);
  for (const RenderMesh& mesh : {cube(), open_square(), odd, grid(3, 3)}) {
    SCOPED_TRACE(mesh.vertex_count());
    const Glb glb = parse_glb(format_gltf(mesh, GltfFormat::glb));
    expect_layout(glb.document, mesh, glb.bin_size);
    EXPECT_FALSE(glb.document["buffers"][0].contains("uri"));
  }
}

TEST(Gltf, GltfEmbedsTheBufferAsADataUri) {
  for (const RenderMesh& mesh : {cube(), open_square()}) {
    SCOPED_TRACE(mesh.vertex_count());
    const json document = json::parse(format_gltf(mesh, GltfFormat::gltf));
    const std::string uri = document["buffers"][0]["uri"];
    const std::string prefix = "data:application/octet-stream;base64,";
    EXPECT_EQ(uri.substr(0, prefix.size()), prefix);
    const std::uint64_t length = document["buffers"][0]["byteLength"];
    EXPECT_EQ((uri.size() - prefix.size()) * 3 / 4 - (uri.back() == '=') - (uri.ends_with("==")), length);
    expect_layout(document, mesh, length);
  }
}

TEST(Gltf, PositionMinMaxAreThoseOfTheStoredFloats) {
  // Cube corners: x in 0.3 -+ 0.05, y in -0.2 -+ 0.05, z in 0.7 -+ 0.05; glTF (x, z, -y), less
  // the box's centre t.
  const json document = parse_glb(format_gltf(cube(), GltfFormat::glb)).document;
  const json& position = document["accessors"][document["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  const Vec3 t = 0.5 * Vec3(0.3 - 0.05, 0.7 - 0.05, 0.2 - 0.05) + 0.5 * Vec3(0.3 + 0.05, 0.7 + 0.05, 0.2 + 0.05);
  EXPECT_EQ(document["nodes"][0]["translation"].get<std::vector<double>>(), (std::vector<double>{t.x(), t.y(), t.z()}));
  const std::vector<double> low = {f32(0.3 - 0.05 - t.x()), f32(0.7 - 0.05 - t.y()), f32(0.2 - 0.05 - t.z())};
  const std::vector<double> high = {f32(0.3 + 0.05 - t.x()), f32(0.7 + 0.05 - t.y()), f32(0.2 + 0.05 - t.z())};
  EXPECT_EQ(position["min"].get<std::vector<double>>(), low);
  EXPECT_EQ(position["max"].get<std::vector<double>>(), high);
  // ... which are not the doubles' min/max.
  EXPECT_NE(position["max"][0].get<double>(), 0.05);
}

TEST(Gltf, IndicesAreUnsignedShortUpTo65535VerticesElseUnsignedInt) {
  struct Case {
    std::uint32_t columns, rows;
    int component_type;
  };
  for (const Case& c : {Case{255, 257, unsigned_short}, Case{256, 256, unsigned_int}}) {
    const RenderMesh mesh = grid(c.columns, c.rows);
    SCOPED_TRACE(mesh.vertex_count());
    ASSERT_EQ(mesh.vertex_count(), c.component_type == unsigned_short ? 65535u : 65536u);
    ASSERT_EQ(*std::max_element(mesh.indices.begin(), mesh.indices.end()), mesh.vertex_count() - 1);
    const std::string bytes = format_gltf(mesh, GltfFormat::glb);
    const Glb glb = parse_glb(bytes);
    const json& document = glb.document;
    const int indices = document["meshes"][0]["primitives"][0]["indices"];
    EXPECT_EQ(document["accessors"][indices]["componentType"], c.component_type);
    expect_layout(document, mesh, glb.bin_size);
    EXPECT_EQ(first_difference(parse_gltf(bytes, "grid.glb"), rounded(mesh)), "");
  }
}

TEST(Gltf, DoubleSidedDefaultsToWhetherTheWeldedMeshHasABoundary) {
  const auto double_sided = [](const RenderMesh& mesh, const GltfOptions& options) {
    const json document = json::parse(format_gltf(mesh, GltfFormat::gltf, options));
    return document["materials"][0].value("doubleSided", false);
  };
  // The cube's 24 render vertices alone leave every edge with one triangle; welded it is closed.
  EXPECT_FALSE(double_sided(cube(), {}));
  EXPECT_TRUE(double_sided(open_square(), {}));
  EXPECT_TRUE(double_sided(grid(3, 4), {}));
  RenderMesh cube_without_a_side = cube();
  cube_without_a_side.indices.resize(cube_without_a_side.indices.size() - 6);
  EXPECT_TRUE(double_sided(cube_without_a_side, {}));
  GltfOptions forced;
  forced.double_sided = true;
  EXPECT_TRUE(double_sided(cube(), forced));
  forced.double_sided = false;
  EXPECT_FALSE(double_sided(open_square(), forced));
}

TEST(Gltf, SceneAndMaterialAreTheDefaults) {
  GltfOptions options;
  options.name = "teapot";
  const json document = json::parse(format_gltf(open_square(), GltfFormat::gltf, options));
  // The open square (0..1, 0..1, 0.25) is (0..1, 0.25, -1..0) in glTF's axes, centred at
  // (0.5, 0.25, -0.5).
  EXPECT_EQ(document["nodes"], json::parse(R"([{"mesh": 0, "name": "teapot", "translation": [0.5, 0.25, -0.5]}])"));
  EXPECT_EQ(document["meshes"][0]["name"], "teapot");
  ASSERT_EQ(document["materials"].size(), 1u);
  const json& pbr = document["materials"][0]["pbrMetallicRoughness"];
  EXPECT_EQ(pbr["baseColorFactor"], json::parse("[0.8, 0.8, 0.8, 1.0]"));
  EXPECT_EQ(pbr["metallicFactor"], 0.0);
  EXPECT_EQ(pbr["roughnessFactor"], 0.5);
  EXPECT_EQ(document["materials"][0].value("alphaMode", "OPAQUE"), "OPAQUE");
}

TEST(Gltf, LevelsOfDetailAreNodesNamedByTheFirstNodesMsftLod) {
  const std::vector<RenderMesh> levels = {grid(8, 8), grid(4, 4), cube()};
  const std::vector<double> coverage = {0.5, 0.125, 0.0};
  GltfOptions options;
  options.name = "teapot";
  const json document = json::parse(format_gltf_levels(levels, coverage, GltfFormat::gltf, options));
  EXPECT_EQ(document["scenes"], json::parse(R"([{"nodes": [0]}])"));
  EXPECT_EQ(document["extensionsUsed"], json::parse(R"(["MSFT_lod"])"));
  EXPECT_FALSE(document.contains("extensionsRequired"));  // a client without MSFT_lod shows level 0
  ASSERT_EQ(document["nodes"].size(), 3u);
  EXPECT_EQ(document["nodes"][0]["extensions"]["MSFT_lod"]["ids"], json::parse("[1, 2]"));
  EXPECT_EQ(document["nodes"][0]["extras"]["MSFT_screencoverage"], json::parse("[0.5, 0.125, 0.0]"));
  // Every level stored from level 0's centre: one translation for the whole chain.
  json lod1 = expected_node(levels[0], 1, "teapot_lod1");
  json lod2 = expected_node(levels[0], 2, "teapot_lod2");
  EXPECT_EQ(document["nodes"][1], lod1);
  EXPECT_EQ(document["nodes"][2], lod2);
  EXPECT_EQ(document["nodes"][2]["translation"], document["nodes"][0]["translation"]);
  ASSERT_EQ(document["meshes"].size(), 3u);
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const json& primitive = document["meshes"][level]["primitives"][0];
    EXPECT_EQ(primitive["material"], 0);
    EXPECT_EQ(document["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"], levels[level].vertex_count());
    EXPECT_EQ(document["accessors"][primitive["indices"].get<int>()]["count"], levels[level].indices.size());
  }
  EXPECT_EQ(document["materials"].size(), 1u);
  // One level is exactly the one-mesh file.
  EXPECT_EQ(format_gltf_levels(std::span<const RenderMesh>(levels.data(), 1), {}, GltfFormat::glb),
            format_gltf(levels[0], GltfFormat::glb));
  // Bad chains are refused.
  const std::vector<double> rising = {0.1, 0.5, 0.0};
  const std::vector<double> short_list = {0.5, 0.0};
  const std::vector<double> above_one = {1.5, 0.1, 0.0};
  for (const auto* bad : {&rising, &short_list, &above_one}) {
    EXPECT_THROW(format_gltf_levels(levels, *bad, GltfFormat::glb), InvalidInput);
  }
  EXPECT_THROW(format_gltf_levels({}, {}, GltfFormat::glb), InvalidInput);
  const std::vector<RenderMesh> with_empty = {cube(), RenderMesh{}};
  EXPECT_THROW(format_gltf_levels(with_empty, std::vector<double>{0.5, 0.0}, GltfFormat::glb), InvalidInput);
}

TEST(Gltf, ZUpIsWrittenAsYUpKeepingTheWinding) {
  const RenderMesh mesh = cube();
  const std::string bytes = format_gltf(mesh, GltfFormat::glb);
  const RenderMesh raw = parse_gltf(bytes, "cube.glb", /*z_up=*/false);
  ASSERT_EQ(raw.vertex_count(), mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    SCOPED_TRACE(v);
    const Vec3& p = mesh.positions[v];
    const Vec3 origin = gltf_origin(mesh);
    EXPECT_EQ(raw.positions[v], stored(p, origin) + origin);
    const Vec3& n = mesh.normals[v];
    EXPECT_EQ(raw.normals[v], Vec3(n.x(), n.z(), -n.y()));
    const Vec4& t = mesh.tangents[v];
    EXPECT_EQ(raw.tangents[v], Vec4(t.x(), t.z(), -t.y(), t.w()));
  }
  // Counter-clockwise seen from the normal's side, in glTF's coordinates too.
  for (std::size_t f = 0; f < raw.triangle_count(); ++f) {
    const Vec3& a = raw.positions[raw.indices[3 * f]];
    const Vec3& b = raw.positions[raw.indices[3 * f + 1]];
    const Vec3& c = raw.positions[raw.indices[3 * f + 2]];
    EXPECT_GT((b - a).cross(c - a).dot(raw.normals[raw.indices[3 * f]]), 0) << "triangle " << f;
  }
  // Written without the map, the coordinates stay.
  GltfOptions y_up;
  y_up.z_up = false;
  const RenderMesh same = parse_gltf(format_gltf(mesh, GltfFormat::glb, y_up), "cube.glb", false);
  EXPECT_EQ(first_difference(same, rounded(mesh, false)), "");
}

TEST(Gltf, NormalsAndTangentsAreUnitAsStoredFloats) {
  // validate() lets lengths be 1e-6 off; the stored floats must be unit to float precision.
  RenderMesh mesh = open_square();
  const double slack = 1 + 9e-7;
  mesh.normals = {Vec3(0.6, 0, 0.8) * slack, Vec3(0, 0, 1) * slack, Vec3(1, 2, 2) / 3 * slack, Vec3(0, 0, 1)};
  mesh.tangents = {Vec4(0, slack, 0, 1), Vec4(0.8 * slack, 0, -0.6 * slack, -1), Vec4(2, -2, 1, 3) / 3,
                   Vec4(1, 0, 0, -1)};
  mesh.tangents[2].w() = 1;
  validate(mesh);
  const RenderMesh raw = parse_gltf(format_gltf(mesh, GltfFormat::glb), "square.glb", false);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    SCOPED_TRACE(v);
    const Vec3 n = mesh.normals[v];
    const Vec3 t = mesh.tangents[v].head<3>();
    EXPECT_NEAR(raw.normals[v].norm(), 1.0, 2e-7);
    EXPECT_NEAR(raw.tangents[v].head<3>().norm(), 1.0, 2e-7);
    EXPECT_LT((raw.normals[v] - Vec3(n.x(), n.z(), -n.y()).normalized()).norm(), 2e-7);
    EXPECT_LT((raw.tangents[v].head<3>() - Vec3(t.x(), t.z(), -t.y()).normalized()).norm(), 2e-7);
    EXPECT_EQ(raw.tangents[v].w(), mesh.tangents[v].w());
  }
}

// ---------------------------------------------------------------------------------------------
// The bytes

// FNV-1a, 64 bits (Fowler, Noll, Vo): a digest that pins a file's bytes in a test.
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325u;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3u;
  }
  return hash;
}

// The meshes whose files are pinned, each with a name: every attribute (the cube, 16-bit
// indices), positions alone (the square), more vertices than write_gltf converts at once (the
// 300 x 300 grid: 90,000 vertices, 32-bit indices), and a level-of-detail chain.
struct PinnedFile {
  std::string name;
  std::vector<RenderMesh> levels;
  std::vector<double> coverage;
};

std::vector<PinnedFile> pinned_files() {
  return {{"cube", {cube()}, {}},
          {"square", {open_square()}, {}},
          {"grid", {grid(300, 300)}, {}},
          {"lod", {grid(8, 8), grid(4, 4), cube()}, {0.5, 0.125, 0.0}}};
}

TEST(Gltf, BytesAreThoseOfTheWriterBeforeStreaming) {
  // Size and FNV-1a digest of each file as the writer of commit 52674cd gave it (tinygltf 2.7.0
  // serialising a model that held the whole buffer): streaming the buffer must not move a byte.
  struct Expected {
    std::size_t size;
    std::uint64_t digest;
  };
  const std::vector<std::pair<Expected, Expected>> expected = {
      {{2504, 0xfaa0943c44422625}, {3909, 0xf1a52f8294bbb80d}},
      {{844, 0x449e61c63e0f4a8c}, {1575, 0x1445aedb0201ccc3}},
      {{6466944, 0xe6874aa1c1a8f93c}, {8623155, 0xc6ca8bbe5e7bed30}},
      {{9072, 0x3f034a1caeabb0f4}, {13634, 0x56c911dd8b7b39d8}}};
  const std::vector<PinnedFile> files = pinned_files();
  ASSERT_EQ(files.size(), expected.size());
  for (std::size_t k = 0; k < files.size(); ++k) {
    for (const GltfFormat format : {GltfFormat::glb, GltfFormat::gltf}) {
      const std::string bytes = format_gltf_levels(files[k].levels, files[k].coverage, format);
      const Expected& pinned = format == GltfFormat::glb ? expected[k].first : expected[k].second;
      EXPECT_EQ(bytes.size(), pinned.size) << files[k].name << (format == GltfFormat::glb ? ".glb" : ".gltf");
      EXPECT_EQ(fnv1a(bytes), pinned.digest) << std::hex << files[k].name << (format == GltfFormat::glb ? ".glb" : ".gltf");
    }
  }
}

TEST(Gltf, TheBytesDoNotDependOnHowManyElementsAreConvertedAtOnce) {
  // Chunks of 1, 2 and 3 elements end inside a vertex's base64 group of 3 bytes and inside a
  // bufferView's padding; 65,536 is write_gltf's (the grid's 90,000 vertices take two).
  for (const PinnedFile& pinned : pinned_files()) {
    for (const GltfFormat format : {GltfFormat::glb, GltfFormat::gltf}) {
      SCOPED_TRACE(pinned.name + (format == GltfFormat::glb ? ".glb" : ".gltf"));
      const std::string bytes = format_gltf_levels(pinned.levels, pinned.coverage, format);
      const std::vector<std::size_t> chunks = pinned.name == "grid" ? std::vector<std::size_t>{7, 4096, 65536}
                                                                    : std::vector<std::size_t>{1, 2, 3, 5, 64};
      for (const std::size_t chunk : chunks) {
        EXPECT_EQ(detail::format_gltf_levels_in_chunks(pinned.levels, pinned.coverage, format, {}, chunk), bytes)
            << "chunk " << chunk;
      }
    }
  }
  EXPECT_THROW(detail::format_gltf_levels_in_chunks(pinned_files()[0].levels, {}, GltfFormat::glb, {}, 0), InvalidInput);
}

TEST_F(GltfFile, WriteGltfWritesTheBytesOfFormatGltf) {
  // write_gltf streams the buffer into the file; format_gltf returns the same bytes: a mesh with
  // normals, uvs and tangents in more than one chunk, a level-of-detail chain, both containers.
  for (const PinnedFile& pinned : pinned_files()) {
    for (const char* extension : {".glb", ".gltf"}) {
      SCOPED_TRACE(pinned.name + extension);
      const GltfFormat format = std::string(extension) == ".glb" ? GltfFormat::glb : GltfFormat::gltf;
      const fs::path path = file(pinned.name + extension);
      const GltfEncoding encoding = encode_gltf_levels(pinned.levels, pinned.coverage, format);
      const std::vector<double> rounding =
          pinned.levels.size() == 1 ? std::vector<double>{write_gltf(path, pinned.levels[0])}
                                    : write_gltf_levels(path, pinned.levels, pinned.coverage);
      EXPECT_EQ(rounding, encoding.position_rounding);
      const std::string written = read_file(path);
      ASSERT_EQ(written.size(), encoding.bytes.size());
      const auto [at, _] = std::mismatch(written.begin(), written.end(), encoding.bytes.begin());
      EXPECT_EQ(at, written.end()) << "first difference at byte " << (at - written.begin());
    }
  }
  // The grid reads back as its float-rounded self (the second chunk's vertices included).
  EXPECT_EQ(first_difference(read_gltf(file("grid.glb")), rounded(grid(300, 300))), "");
  EXPECT_EQ(first_difference(read_gltf(file("grid.gltf")), rounded(grid(300, 300))), "");
}

// ---------------------------------------------------------------------------------------------
// What is refused

TEST(Gltf, RefusesWhatGltfCannotHold) {
  RenderMesh no_triangles = open_square();
  no_triangles.indices.clear();
  EXPECT_THROW(format_gltf(no_triangles, GltfFormat::glb), InvalidInput);
  EXPECT_THROW(format_gltf(RenderMesh{}, GltfFormat::glb), InvalidInput);
  RenderMesh out_of_range = open_square();
  out_of_range.indices[5] = 4;
  EXPECT_THROW(format_gltf(out_of_range, GltfFormat::glb), InvalidInput);
  RenderMesh tangents_only = open_square();
  tangents_only.tangents.assign(4, Vec4(1, 0, 0, 1));
  EXPECT_THROW(format_gltf(tangents_only, GltfFormat::glb), InvalidInput);
  RenderMesh too_far = open_square();
  too_far.positions[2].x() = 1e39;
  try {
    format_gltf(too_far, GltfFormat::glb);
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("position of vertex 2"), std::string::npos) << e.what();
  }
  RenderMesh huge_uv = open_square();
  huge_uv.uvs.assign(4, Vec2(0, 0));
  huge_uv.uvs[1].y() = -1e300;
  EXPECT_THROW(format_gltf(huge_uv, GltfFormat::gltf), InvalidInput);
}

TEST_F(GltfFile, FailedWritesLeaveNothingBehind) {
  const fs::path missing = file("no such folder") / "cube.glb";
  try {
    write_gltf(missing, cube());
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), missing.string());
  }
  EXPECT_FALSE(fs::exists(file("no such folder")));
  // The target is a folder: the rename fails and the temporary file goes.
  fs::create_directory(file("taken.glb"));
  EXPECT_THROW(write_gltf(file("taken.glb"), cube()), IoError);
  // A mesh glTF cannot hold, and an unknown extension: nothing written, an older file intact.
  write_gltf(file("kept.gltf"), open_square());
  const std::string before = read_file(file("kept.gltf"));
  RenderMesh empty = open_square();
  empty.indices.clear();
  EXPECT_THROW(write_gltf(file("kept.gltf"), empty), InvalidInput);
  EXPECT_EQ(read_file(file("kept.gltf")), before);
  for (const char* name : {"cube.obj", "cube", "cube.glb.tmp"}) {
    SCOPED_TRACE(name);
    try {
      write_gltf(file(name), cube());
      ADD_FAILURE() << "no IoError";
    } catch (const IoError& e) {
      EXPECT_EQ(e.path(), file(name).string());
    }
  }
  EXPECT_EQ(entries(), (std::vector<std::string>{"kept.gltf", "taken.glb"}));
  EXPECT_TRUE(fs::is_empty(file("taken.glb")));
}

TEST_F(GltfFile, ReadErrorsNameTheFile) {
  try {
    read_gltf(file("missing.glb"));
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), file("missing.glb").string());
  }
  write_file_atomically(file("text.gltf"), "hello");
  expect_parse_error(file("text.gltf"), "not a glTF 2.0 file");
  const std::string glb = format_gltf(cube(), GltfFormat::glb);
  write_file_atomically(file("truncated.glb"), glb.substr(0, glb.size() / 2));
  expect_parse_error(file("truncated.glb"), "not a glTF 2.0 file");

  const auto primitive = [](json& document) -> json& { return document["meshes"][0]["primitives"][0]; };
  expect_parse_error(edited(open_square(), [&](json& d) { primitive(d)["mode"] = 0; }), "mode 0");
  expect_parse_error(edited(open_square(), [&](json& d) { d["meshes"][0]["primitives"].push_back(primitive(d)); }),
                     "2 primitives");
  // Two vertices left for indices up to 3.
  expect_parse_error(edited(open_square(), [&](json& d) { d["accessors"][0]["count"] = 2; }), "uses vertex 2 of 2");
  // An accessor reaching past its bufferView.
  expect_parse_error(edited(open_square(), [&](json& d) { d["accessors"][0]["byteOffset"] = 4; }),
                     "outside its bufferView");
  expect_parse_error(edited(cube(), [&](json& d) { d["accessors"][primitive(d)["attributes"]["NORMAL"].get<int>()]["count"] = 23; }),
                     "NORMAL has 23 elements for 24 vertices");
  expect_parse_error(edited(open_square(), [&](json& d) { d["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
                     "KHR_draco_mesh_compression");
}

TEST_F(GltfFile, ReadsATrianglePrimitiveWithoutIndices) {
  RenderMesh triangle = open_square();
  triangle.positions.pop_back();
  triangle.position_ids.pop_back();
  triangle.indices = {0, 1, 2};
  const fs::path path = edited(triangle, [](json& d) { d["meshes"][0]["primitives"][0].erase("indices"); });
  EXPECT_FALSE(json::parse(read_file(path))["meshes"][0]["primitives"][0].contains("indices"));
  EXPECT_EQ(first_difference(read_gltf(path), rounded(triangle)), "");
}

// ---------------------------------------------------------------------------------------------
// Node transforms (glTF 2.0, 3.5): the scene graph placed around the written node

// One triangle (0, 0, 0) (1, 0, 0) (0, 1, 1), its normal (0, -1, 1)/sqrt 2 and tangent (+x, +1):
// coordinates floats hold, and so does the centre of its box.
RenderMesh slanted_triangle() {
  RenderMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1)};
  mesh.normals.assign(3, Vec3(0, -1, 1) / std::sqrt(2.0));
  mesh.tangents.assign(3, Vec4(1, 0, 0, 1));
  mesh.indices = {0, 1, 2};
  mesh.position_ids = {0, 1, 2};
  return mesh;
}

// The triangle written to `path` in glTF's axes (z_up off), its node 0 then placed by `edit`.
template <class Edit>
const fs::path& write_placed(const fs::path& path, Edit edit) {
  GltfOptions y_up;
  y_up.z_up = false;
  json document = json::parse(format_gltf(slanted_triangle(), GltfFormat::gltf, y_up));
  edit(document);
  write_file_atomically(path, document.dump());
  return path;
}

// The file write_placed writes, read back (in glTF's axes unless `z_up`).
template <class Edit>
RenderMesh read_placed(const fs::path& path, Edit edit, bool z_up = false) {
  return read_gltf(write_placed(path, edit), z_up);
}

// Node 0 (the written one) made the child of a new node `parent`, the scene's one root.
void wrap(json& document, json parent) {
  parent["children"] = {0};
  document["nodes"].push_back(parent);
  document["scenes"][0]["nodes"] = {document["nodes"].size() - 1};
}

std::vector<Vec3> mapped(const std::function<Vec3(const Vec3&)>& f) {
  std::vector<Vec3> out;
  for (const Vec3& p : slanted_triangle().positions) out.push_back(f(p));
  return out;
}

void expect_directions(const RenderMesh& mesh, const Vec3& normal, const Vec4& tangent) {
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_LT((mesh.normals[v] - normal).norm(), 2e-7) << v << ": " << mesh.normals[v].transpose();
    EXPECT_LT((mesh.tangents[v].head<3>() - tangent.head<3>()).norm(), 2e-7) << v;
    EXPECT_EQ(mesh.tangents[v].w(), tangent.w()) << v;
  }
}

TEST_F(GltfFile, NodeScaleRotationTranslationAndMatrixArePlacedExactly) {
  // Scale (2, 3, 4): positions (2x, 3y, 4z); the normal by the inverse transpose,
  // diag(1/2, 1/3, 1/4) (0, -1, 1) ~ (0, -1/3, 1/4), unit (0, -0.8, 0.6): the normal of the scaled
  // triangle (2, 0, 0) x (0, 3, 4) = (0, -8, 6).
  RenderMesh scaled = read_placed(file("scale.gltf"), [](json& d) { wrap(d, {{"scale", {2, 3, 4}}}); });
  EXPECT_EQ(scaled.positions, mapped([](const Vec3& p) { return Vec3(2 * p.x(), 3 * p.y(), 4 * p.z()); }));
  expect_directions(scaled, Vec3(0, -0.8, 0.6), Vec4(1, 0, 0, 1));
  EXPECT_EQ(scaled.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  // Rotation by 180 degrees about z, quaternion (0, 0, 1, 0): (-x, -y, z), exactly.
  RenderMesh turned = read_placed(file("turn.gltf"), [](json& d) { wrap(d, {{"rotation", {0, 0, 1, 0}}}); });
  EXPECT_EQ(turned.positions, mapped([](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); }));
  expect_directions(turned, Vec3(0, 1, 1) / std::sqrt(2.0), Vec4(-1, 0, 0, 1));
  // 90 degrees about z, (0, 0, sqrt 1/2, sqrt 1/2): (-y, x, z) to rounding.
  const double h = std::sqrt(0.5);
  RenderMesh quarter = read_placed(file("quarter.gltf"), [&](json& d) { wrap(d, {{"rotation", {0, 0, h, h}}}); });
  const std::vector<Vec3> quarter_expected = mapped([](const Vec3& p) { return Vec3(-p.y(), p.x(), p.z()); });
  for (std::size_t v = 0; v < 3; ++v) EXPECT_LT((quarter.positions[v] - quarter_expected[v]).norm(), 1e-15) << v;
  expect_directions(quarter, Vec3(1, 0, 1) / std::sqrt(2.0), Vec4(0, 1, 0, 1));
  // Translation (10, 20, 30).
  RenderMesh moved = read_placed(file("move.gltf"), [](json& d) { wrap(d, {{"translation", {10, 20, 30}}}); });
  EXPECT_EQ(moved.positions, mapped([](const Vec3& p) { return Vec3(p.x() + 10, p.y() + 20, p.z() + 30); }));
  // A matrix, column-major: (x, y, z) -> (1 - 2 y, 2 + x, 3 + 3 z).
  const json matrix = {0, 1, 0, 0, -2, 0, 0, 0, 0, 0, 3, 0, 1, 2, 3, 1};
  RenderMesh affine = read_placed(file("matrix.gltf"), [&](json& d) { wrap(d, {{"matrix", matrix}}); });
  EXPECT_EQ(affine.positions, mapped([](const Vec3& p) { return Vec3(1 - 2 * p.y(), 2 + p.x(), 3 + 3 * p.z()); }));
  // Read Z-up, the node's transform acts in glTF's axes first: (X, Y, Z) -> (X, -Z, Y) after it.
  RenderMesh z_up = read_placed(file("scale_z.gltf"), [](json& d) { wrap(d, {{"scale", {2, 3, 4}}}); }, true);
  EXPECT_EQ(z_up.positions, mapped([](const Vec3& p) { return Vec3(2 * p.x(), -4 * p.z(), 3 * p.y()); }));
}

TEST_F(GltfFile, NestedNodesComposeParentTimesChild) {
  // Root: translation (1, 0, 0) and scale 2; its child: 180 degrees about z; then node 0.
  // World = T S R: (x, y, z) -> (1 - 2 x, -2 y, 2 z).
  const RenderMesh mesh = read_placed(file("nested.gltf"), [](json& d) {
    d["nodes"].push_back({{"rotation", {0, 0, 1, 0}}, {"children", {0}}});
    d["nodes"].push_back({{"translation", {1, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}});
    d["scenes"][0]["nodes"] = {2};
  });
  EXPECT_EQ(mesh.positions, mapped([](const Vec3& p) { return Vec3(1 - 2 * p.x(), -2 * p.y(), 2 * p.z()); }));
  // Without a scene, the roots are the nodes that are nobody's child: the same.
  const RenderMesh sceneless = read_placed(file("sceneless.gltf"), [](json& d) {
    d["nodes"].push_back({{"rotation", {0, 0, 1, 0}}, {"children", {0}}});
    d["nodes"].push_back({{"translation", {1, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}});
    d.erase("scenes");
    d.erase("scene");
  });
  EXPECT_EQ(sceneless.positions, mesh.positions);
  // The default scene is the one "scene" names.
  const RenderMesh second = read_placed(file("second.gltf"), [](json& d) {
    d["nodes"].push_back({{"translation", {0, 0, 7}}, {"children", {0}}});
    d["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1}}}};
    d["scene"] = 1;
  });
  EXPECT_EQ(second.positions, mapped([](const Vec3& p) { return Vec3(p.x(), p.y(), p.z() + 7); }));
}

TEST_F(GltfFile, AMeshInTwoNodesAppearsTwice) {
  const RenderMesh mesh = read_placed(file("twice.gltf"), [](json& d) {
    const json written = d["nodes"][0];
    d["nodes"].push_back({{"children", {0}}});                               // 1: identity
    d["nodes"].push_back(written);                                            // 2: node 0 again
    d["nodes"].push_back({{"translation", {5, 0, 0}}, {"children", {2}}});  // 3: moves node 2
    d["scenes"][0]["nodes"] = {1, 3};
  });
  std::vector<Vec3> expected = slanted_triangle().positions;
  for (const Vec3& p : slanted_triangle().positions) expected.push_back(p + Vec3(5, 0, 0));
  EXPECT_EQ(mesh.positions, expected);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.position_ids, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.normals.size(), 6u);
}

TEST_F(GltfFile, AMirrorFlipsTheWindingAndTheTangentSign) {
  // Scale (-1, 1, 1): (-x, y, z); the normal (0, -1, 1)/sqrt 2 keeps (its x is 0); the tangent
  // (1, 0, 0) becomes (-1, 0, 0) and w -1. The triangle's corners 1 and 2 swap, so it still turns
  // counter-clockwise about its normal.
  const RenderMesh mesh = read_placed(file("mirror.gltf"), [](json& d) { wrap(d, {{"scale", {-1, 1, 1}}}); });
  EXPECT_EQ(mesh.positions, mapped([](const Vec3& p) { return Vec3(-p.x(), p.y(), p.z()); }));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 2, 1}));
  expect_directions(mesh, Vec3(0, -1, 1) / std::sqrt(2.0), Vec4(-1, 0, 0, -1));
  const Vec3& a = mesh.positions[mesh.indices[0]];
  const Vec3& b = mesh.positions[mesh.indices[1]];
  const Vec3& c = mesh.positions[mesh.indices[2]];
  EXPECT_GT((b - a).cross(c - a).dot(mesh.normals[0]), 0);
  // A matrix of determinant -1 (x and y swapped) does the same.
  const RenderMesh swapped = read_placed(file("swap.gltf"), [](json& d) {
    wrap(d, {{"matrix", {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
  });
  EXPECT_EQ(swapped.positions, mapped([](const Vec3& p) { return Vec3(p.y(), p.x(), p.z()); }));
  EXPECT_EQ(swapped.indices, (std::vector<std::uint32_t>{0, 2, 1}));
  const Vec3& p = swapped.positions[0];
  const Vec3& q = swapped.positions[2];
  const Vec3& r = swapped.positions[1];
  EXPECT_GT((q - p).cross(r - p).dot(swapped.normals[0]), 0);
}

TEST_F(GltfFile, NodeGraphsThatCannotBeHonouredAreRefusedNamingTheNode) {
  const auto expect_refused = [&](const std::string& name, const std::function<void(json&)>& edit,
                                  const std::string& part) {
    SCOPED_TRACE(name);
    expect_parse_error(write_placed(file(name), edit), part);
  };
  expect_refused("cycle.gltf", [](json& d) {
    d["nodes"].push_back({{"name", "a"}, {"children", {2}}});
    d["nodes"].push_back({{"name", "b"}, {"children", {1}}});
  }, "node 1 ('a') is its own ancestor (a cycle in the node hierarchy)");
  expect_refused("self.gltf", [](json& d) { d["nodes"][0]["children"] = {0}; }, "node 0 ('patchwork') is its own ancestor");
  expect_refused("parents.gltf", [](json& d) {
    d["nodes"].push_back({{"children", {0}}});
    d["nodes"].push_back({{"children", {0}}});
  }, "node 0 ('patchwork') has two parents (1 and 2)");
  expect_refused("flat.gltf", [](json& d) { wrap(d, {{"name", "flat"}, {"scale", {1, 0, 1}}}); },
                 "node 1 ('flat'): transform is singular (determinant 0)");
  expect_refused("zeros.gltf", [](json& d) { wrap(d, {{"matrix", std::vector<double>(16, 0.0)}}); },
                 "node 1: matrix is not affine");
  expect_refused("singular.gltf", [](json& d) {
    wrap(d, {{"matrix", {1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});  // columns (1, 0, 0) and (2, 0, 0)
  }, "node 1: transform is singular");
  expect_refused("tiny.gltf", [](json& d) {
    // Each determinant 1e-180; composed, 1e-360 underflows to 0.
    d["nodes"].push_back({{"scale", {1e-60, 1e-60, 1e-60}}, {"children", {0}}});
    d["nodes"].push_back({{"scale", {1e-60, 1e-60, 1e-60}}, {"children", {1}}});
    d["scenes"][0]["nodes"] = {2};
  }, "node 1: transform composed with its ancestors' is singular (determinant 0)");
  expect_refused("projective.gltf", [](json& d) {
    wrap(d, {{"matrix", {1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
  }, "node 1: matrix is not affine");
  expect_refused("quaternion.gltf", [](json& d) { wrap(d, {{"rotation", {0, 0, 0, 0}}}); },
                 "node 1: rotation is the zero quaternion");
  expect_refused("child.gltf", [](json& d) { d["nodes"][0]["children"] = {9}; },
                 "node 0 ('patchwork'): child 9 does not exist");
  expect_refused("root.gltf", [](json& d) {
    wrap(d, json::object());
    d["scenes"][0]["nodes"] = {1, 0};
  }, "scene 0 lists node 0 ('patchwork'), a child of node 1, as a root");
  expect_refused("nomesh.gltf", [](json& d) { d["nodes"][0].erase("mesh"); }, "no node of the scene holds the mesh");
  // Not silently scene 0: the file names a scene it does not have.
  expect_refused("scene.gltf", [](json& d) { d["scene"] = 3; }, "the default scene 3 does not exist (the file has 1 scenes)");
  expect_refused("skin.gltf", [](json& d) {
    d["nodes"][0]["skin"] = 0;
    d["skins"] = json::array({{{"joints", {0}}}});
  }, "node 0 ('patchwork') is skinned (skin 0)");
  expect_refused("morph.gltf", [](json& d) {
    d["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", 0}}});
  }, "the primitive has morph targets");
  // A vertex that overflows under its node's world transform (here its parent's scale and
  // translation) names the node that holds the mesh.
  expect_refused("huge.gltf",
                 [](json& d) { wrap(d, {{"name", "far"}, {"scale", {1e308, 1, 1}}, {"translation", {1e308, 0, 0}}}); },
                 "POSITION of vertex 1 is not finite after the transform of node 0 ('patchwork')");
}

TEST_F(GltfFile, PlacementsBeyondTheMemoryLimitAreRefusedBeforeExpanding) {
  // A mesh of 120,000 vertices (1.4 MB of floats) under 3,000 nodes of a few bytes each would
  // expand to 360 M vertices, 12 GiB as doubles with their ids and indices: refused from the
  // counts alone.
  RenderMesh strip;
  for (int k = 0; k < 120000; ++k) strip.positions.emplace_back(k, k % 2, 0.0);
  for (std::uint32_t k = 0; k + 2 < 120000; k += 3) strip.indices.insert(strip.indices.end(), {k, k + 1, k + 2});
  strip.position_ids.resize(strip.positions.size());
  std::iota(strip.position_ids.begin(), strip.position_ids.end(), 0u);
  json document = json::parse(format_gltf(strip, GltfFormat::gltf));
  const json written = document["nodes"][0];
  std::vector<int> roots;
  for (int k = 0; k < 3000; ++k) {
    if (k > 0) document["nodes"].push_back(written);
    roots.push_back(k);
  }
  document["scenes"][0]["nodes"] = roots;
  const fs::path path = file("placed.gltf");
  write_file_atomically(path, document.dump());
  expect_parse_error(path, "3000 instances of a mesh of 120000 vertices and 40000 triangles would take");
  // The same mesh under 10 nodes is read (1.2 M vertices).
  json ten = json::array();
  for (int k = 0; k < 10; ++k) ten.push_back(written);
  document["nodes"] = ten;
  document["scenes"][0]["nodes"] = std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  write_file_atomically(path, document.dump());
  EXPECT_EQ(read_gltf(path).vertex_count(), 1200000u);
}

// A buffer in a file of its own: the cube's .glb JSON with buffers[0].uri = `uri`, in folder
// inner/ of the test's folder, and the BIN chunk written to `bin` (relative to the test's folder).
struct ExternalBuffer {
  json document;
  std::string bin;
};

ExternalBuffer external_buffer(const RenderMesh& mesh) {
  const std::string glb = format_gltf(mesh, GltfFormat::glb);
  ExternalBuffer external;
  external.document = parse_glb(glb).document;
  const std::size_t bin_header = 20 + u32_at(glb, 12);
  external.bin = glb.substr(bin_header + 8, u32_at(glb, bin_header));
  external.bin.resize(external.document["buffers"][0]["byteLength"].get<std::size_t>());
  return external;
}

TEST_F(GltfFile, BufferUrisAreReadOnlyInsideTheFilesFolder) {
  const RenderMesh mesh = cube();
  const ExternalBuffer external = external_buffer(mesh);
  fs::create_directories(file("inner") / "sub");
  fs::create_directories(file("outside"));
  write_file_atomically(file("inner") / "sub" / "data.bin", external.bin);
  write_file_atomically(file("outside") / "data.bin", external.bin);
  fs::create_symlink(file("outside") / "data.bin", file("inner") / "link.bin");
  fs::create_symlink(fs::path("sub") / "data.bin", file("inner") / "inside_link.bin");
  const auto with_uri = [&](const std::string& uri) {
    json document = external.document;
    document["buffers"][0]["uri"] = uri;
    const fs::path path = file("inner") / "mesh.gltf";
    write_file_atomically(path, document.dump());
    return path;
  };
  // Inside the folder: read, as the .glb reads.
  const RenderMesh expected = parse_gltf(format_gltf(mesh, GltfFormat::glb), "cube.glb");
  for (const std::string uri : {"sub/data.bin", "sub%2Fdata.bin", "./sub/data.bin", "inside_link.bin"}) {
    SCOPED_TRACE(uri);
    EXPECT_EQ(first_difference(read_gltf(with_uri(uri)), expected), "");
  }
  // Anywhere else: a ParseError naming the file and the (decoded) URI, though the data is there.
  struct Refused {
    std::string uri, decoded, reason;
  };
  const std::vector<Refused> refused = {
      {"../outside/data.bin", "../outside/data.bin", "goes up out of the folder with '..'"},
      {"sub/../../outside/data.bin", "sub/../../outside/data.bin", "goes up out of the folder with '..'"},
      {"%2e%2e/outside/data.bin", "../outside/data.bin", "goes up out of the folder with '..'"},
      {"%2E%2E%2Foutside%2Fdata.bin", "../outside/data.bin", "goes up out of the folder with '..'"},
      {(file("outside") / "data.bin").string(), (file("outside") / "data.bin").string(), "is an absolute path"},
      {"link.bin", "link.bin", "leads out of the folder through a symbolic link"},
  };
  for (const Refused& r : refused) {
    SCOPED_TRACE(r.uri);
    expect_parse_error(with_uri(r.uri), "'" + r.decoded + "'", r.reason);
  }
  // An image file is opened too (though not decoded): its URI is held to the same rule.
  {
    json document = external.document;
    document["buffers"][0]["uri"] = "sub/data.bin";
    document["images"] = {{{"uri", "../outside/data.bin"}}};
    const fs::path path = file("inner") / "image.gltf";
    write_file_atomically(path, document.dump());
    expect_parse_error(path, "'../outside/data.bin'");
    document["images"] = {{{"uri", "sub/data.bin"}}};  // inside: read (and not decoded)
    write_file_atomically(path, document.dump());
    EXPECT_EQ(first_difference(read_gltf(path), expected), "");
  }
  // A .glb whose buffer is an outside file is refused the same way.
  json document = external.document;
  document["buffers"][0]["uri"] = "../outside/data.bin";
  {
    const std::string text = document.dump();
    std::string padded = text + std::string((4 - text.size() % 4) % 4, ' ');
    std::string glb(12, '\0');
    const auto put = [&](std::uint32_t x) { glb.append(reinterpret_cast<const char*>(&x), 4); };
    put(static_cast<std::uint32_t>(padded.size()));
    put(0x4E4F534Au);
    glb += padded;
    const std::uint32_t header[3] = {0x46546C67u, 2u, static_cast<std::uint32_t>(glb.size())};
    std::memcpy(glb.data(), header, sizeof header);
    write_file_atomically(file("inner") / "mesh.glb", glb);
    expect_parse_error(file("inner") / "mesh.glb", "'../outside/data.bin'");
  }
}

// ---------------------------------------------------------------------------------------------
// The Khronos glTF validator (tools/gltf-validate, installed by scripts/setup)

TEST_F(GltfFile, KhronosValidatorReportsNoErrorAndNoWarning) {
  const fs::path tool = fs::path(PATCHWORK_SOURCE_DIR) / "tools" / "gltf-validate";
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    PATCHWORK_SKIP_UNLESS_CI("node is not installed (scripts/setup installs nodejs and the validator)");
  }
  if (!fs::exists(tool / "node_modules" / "gltf-validator")) {
    PATCHWORK_SKIP_UNLESS_CI("the validator is not installed: run npm ci in " + tool.string());
  }
  RenderMesh uvs_only = open_square();
  uvs_only.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  RenderMesh odd = open_square();
  odd.indices.resize(3);
  odd.positions.pop_back();
  odd.position_ids.pop_back();
  const std::vector<std::pair<std::string, RenderMesh>> files = {
      {"cube.glb", cube()},         {"cube.gltf", cube()},      {"square.glb", open_square()},
      {"square.gltf", open_square()}, {"uvs.glb", uvs_only},    {"triangle.glb", odd},
      {"grid65535.glb", grid(255, 257)}, {"grid65536.glb", grid(256, 256)}};
  // The exit status of validate.js on `path`, and what it printed.
  const auto validate_file = [&](const fs::path& path) {
    const fs::path log = path.string() + ".log";
    const std::string command = "node " + shell_quoted((tool / "validate.js").string()) + " " +
                                shell_quoted(path.string()) + " > " + shell_quoted(log.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    return std::pair{status, read_file(log)};
  };
  for (const auto& [name, mesh] : files) {
    SCOPED_TRACE(name);
    write_gltf(file(name), mesh);
    const auto [status, report] = validate_file(file(name));
    EXPECT_EQ(status, 0) << report;
    EXPECT_NE(report.find("0 errors, 0 warnings"), std::string::npos) << report;
    std::cout << report;
  }
  // A level-of-detail chain (MSFT_lod): the validator does not know the extension (an info).
  const std::vector<RenderMesh> levels = {grid(8, 8), grid(4, 4), cube()};
  for (const std::string name : {"lod.glb", "lod.gltf"}) {
    SCOPED_TRACE(name);
    write_gltf_levels(file(name), levels, std::vector<double>{0.5, 0.125, 0.0});
    const auto [status, report] = validate_file(file(name));
    EXPECT_EQ(status, 0) << report;
    EXPECT_NE(report.find("0 errors, 0 warnings"), std::string::npos) << report;
  }
  // The check can fail: a wrong POSITION max is an error, tangents without normals a warning.
  const auto [error_status, error_report] = validate_file(edited(cube(), [](json& d) {
    d["accessors"][0]["max"][0] = 1.0;
  }));
  EXPECT_NE(error_status, 0) << error_report;
  EXPECT_NE(error_report.find("ACCESSOR_MAX_MISMATCH"), std::string::npos) << error_report;
  const auto [warning_status, warning_report] = validate_file(edited(cube(), [](json& d) {
    d["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  }));
  EXPECT_NE(warning_status, 0) << warning_report;
  EXPECT_NE(warning_report.find("0 errors, 1 warnings"), std::string::npos) << warning_report;
}

}  // namespace
}  // namespace patchwork
