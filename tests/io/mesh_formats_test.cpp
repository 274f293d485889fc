// OBJ, OFF and PLY (ascii, binary little and big endian): exact round trips, hand-written files
// with their exact content, and every kind of malformed file as a ParseError at the right place.

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"
#include "tests/support/extreme_doubles.h"
#include "tests/support/parse_errors.h"
#include "tests/support/temporary_directory.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "io/obj.h"
#include "io/off.h"
#include "io/ply.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;

// ---------------------------------------------------------------------------------------------
// Helpers

enum class Format { obj, off, ply_ascii, ply_little, ply_big };
constexpr Format all_formats[] = {Format::obj, Format::off, Format::ply_ascii, Format::ply_little, Format::ply_big};

const char* label(Format format) {
  switch (format) {
    case Format::obj:
      return "obj";
    case Format::off:
      return "off";
    case Format::ply_ascii:
      return "ply ascii";
    case Format::ply_little:
      return "ply binary little endian";
    case Format::ply_big:
      return "ply binary big endian";
  }
  return "?";
}

std::string format_as(const FaceVertexMesh& mesh, Format format) {
  switch (format) {
    case Format::obj:
      return format_obj(mesh);
    case Format::off:
      return format_off(mesh);
    case Format::ply_ascii:
      return format_ply(mesh, PlyFormat::ascii);
    case Format::ply_little:
      return format_ply(mesh, PlyFormat::binary_little_endian);
    case Format::ply_big:
      return format_ply(mesh, PlyFormat::binary_big_endian);
  }
  return {};
}

FaceVertexMesh parse_as(std::string_view text, Format format, const std::string& name) {
  switch (format) {
    case Format::obj:
      return parse_obj(text, name);
    case Format::off:
      return parse_off(text, name);
    default:
      return parse_ply(text, name);
  }
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Whether two meshes are equal bit for bit (operator== would call -0 and +0 equal).
bool bit_identical(const FaceVertexMesh& a, const FaceVertexMesh& b) {
  if (a.vertex_count() != b.vertex_count() || a.face_sizes() != b.face_sizes() ||
      a.face_indices() != b.face_indices()) {
    return false;
  }
  for (Eigen::Index v = 0; v < a.positions().rows(); ++v) {
    for (int c = 0; c < 3; ++c) {
      if (bits(a.positions()(v, c)) != bits(b.positions()(v, c))) return false;
    }
  }
  return true;
}

FaceVertexMesh make_mesh(const std::vector<Vec3>& points, const std::vector<std::vector<std::uint32_t>>& faces) {
  Positions positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) positions.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  for (const auto& face : faces) {
    sizes.push_back(static_cast<std::uint32_t>(face.size()));
    indices.insert(indices.end(), face.begin(), face.end());
  }
  return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
}

// The unit tetrahedron, faces oriented outward.
FaceVertexMesh tetrahedron() {
  return make_mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                   {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

using testing::Malformed;

// The ParseError that parsing `text` throws, or nothing (then the test has failed).
std::optional<ParseError> parse_error(std::string_view text, Format format, const std::string& name) {
  return testing::parse_error_of([&] { parse_as(text, format, name); });
}

void expect_malformed(Format format, const std::vector<Malformed>& cases) {
  testing::expect_parse_errors(cases, "bad.mesh", [&](const std::string& text, const std::string& name) {
    parse_as(text, format, name);
  });
}

// The lines joined with '\n', line `line` (1-based) replaced; an empty replacement removes it.
std::string with_line(const std::vector<std::string>& lines, std::size_t line, const std::string& replacement) {
  std::string text;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (k + 1 == line) {
      if (!replacement.empty()) text += replacement + "\n";
    } else {
      text += lines[k] + "\n";
    }
  }
  return text;
}

// Seconds spent by `work`.
template <class Work>
double seconds(Work work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Binary PLY data built byte by byte in either byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_endian_(big_endian) {}
  Bytes& text(std::string_view s) {
    data_.append(s);
    return *this;
  }
  template <class T>
  Bytes& put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    using Raw =
        std::conditional_t<sizeof(T) == 1, std::uint8_t,
                           std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                              std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    const auto raw = static_cast<std::uint64_t>(std::bit_cast<Raw>(value));
    for (std::size_t k = 0; k < sizeof(T); ++k) {
      const std::size_t shift = 8 * (big_endian_ ? sizeof(T) - 1 - k : k);
      data_ += static_cast<char>(static_cast<unsigned char>((raw >> shift) & 0xff));
    }
    return *this;
  }
  const std::string& data() const noexcept { return data_; }
  std::size_t size() const noexcept { return data_.size(); }

 private:
  bool big_endian_;
  std::string data_;
};

// Every test folder is named after this test program.
struct TemporaryDirectory : testing::TemporaryDirectory {
  TemporaryDirectory() : testing::TemporaryDirectory("patchwork_io_mesh_test") {}
};

std::string file_content(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

// ---------------------------------------------------------------------------------------------
// Generators (drawn inside properties)

// Finite doubles of every kind: raw bit patterns (all exponents, subnormals), the extremes,
// signed zeros, and ordinary decimals.
rc::Gen<double> finite_double() {
  const rc::Gen<double> from_bits =
      rc::gen::map(rc::gen::suchThat(rc::gen::arbitrary<std::uint64_t>(),
                                     [](std::uint64_t b) { return std::isfinite(std::bit_cast<double>(b)); }),
                   [](std::uint64_t b) { return std::bit_cast<double>(b); });
  const rc::Gen<double> special =
      rc::gen::element(0.0, -0.0, std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                       std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                       std::numeric_limits<double>::lowest(), 0.1, 1.0 / 3.0, -2.5, 1e22);
  const rc::Gen<double> decimal = rc::gen::map(rc::gen::inRange(-100000, 100001), [](int k) { return k / 1000.0; });
  return rc::gen::oneOf(from_bits, special, decimal);
}

// A polygon soup: any finite positions, faces of 3 to 8 corners (repeated vertices included),
// vertices that no face uses.
FaceVertexMesh random_mesh(int min_vertices) {
  const int vertex_count = *rc::gen::inRange(min_vertices, 20);
  Positions positions(vertex_count, 3);
  for (int v = 0; v < vertex_count; ++v) {
    for (int c = 0; c < 3; ++c) positions(v, c) = *finite_double();
  }
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  const int face_count = vertex_count == 0 ? 0 : *rc::gen::inRange(0, 12);
  for (int f = 0; f < face_count; ++f) {
    const auto size = *rc::gen::inRange<std::uint32_t>(3, 9);
    sizes.push_back(size);
    for (std::uint32_t k = 0; k < size; ++k)
      indices.push_back(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(vertex_count)));
  }
  return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
}

// ---------------------------------------------------------------------------------------------
// Round trips

RC_GTEST_PROP(MeshFormats, RoundTripIsBitExactInEveryFormat, ()) {
  const FaceVertexMesh mesh = random_mesh(1);
  for (Format format : all_formats) {
    const std::string text = format_as(mesh, format);
    const FaceVertexMesh read = parse_as(text, format, "roundtrip");
    RC_ASSERT(bit_identical(read, mesh));
    RC_ASSERT(format_as(read, format) == text);
  }
}

TEST(MeshFormats, RoundTripKeepsSignedZeroSubnormalsAndExtremes) {
  std::vector<Vec3> points;
  for (double x : testing::extreme_doubles()) points.emplace_back(x, -x, x * 0.5);
  const FaceVertexMesh mesh = make_mesh(points, {{0, 1, 2}, {3, 4, 5, 6, 7, 8, 9}, {9, 9, 0}});
  for (Format format : all_formats) {
    SCOPED_TRACE(label(format));
    const FaceVertexMesh read = parse_as(format_as(mesh, format), format, "extremes");
    EXPECT_TRUE(bit_identical(read, mesh));
    EXPECT_TRUE(std::signbit(read.positions()(0, 0)));
    EXPECT_FALSE(std::signbit(read.positions()(0, 1)));
  }
}

TEST(MeshFormats, EmptyMeshRoundTripsExceptInObj) {
  const FaceVertexMesh empty;
  for (Format format : {Format::off, Format::ply_ascii, Format::ply_little, Format::ply_big}) {
    SCOPED_TRACE(label(format));
    EXPECT_EQ(parse_as(format_as(empty, format), format, "empty"), empty);
  }
  EXPECT_THROW(format_obj(empty), InvalidInput);  // an OBJ file without a vertex is refused by the reader
  const FaceVertexMesh points_only = make_mesh({Vec3(1, 2, 3)}, {});
  for (Format format : all_formats) EXPECT_EQ(parse_as(format_as(points_only, format), format, "points"), points_only);
}

TEST(MeshFormats, FacesAboveTwoHundredFiftyFiveCornersUseAWiderPlyCount) {
  std::vector<Vec3> points;
  std::vector<std::uint32_t> ring;
  for (std::uint32_t k = 0; k < 300; ++k) {
    points.emplace_back(std::cos(k * 0.02), std::sin(k * 0.02), 0.0);
    ring.push_back(k);
  }
  const FaceVertexMesh mesh = make_mesh(points, {ring, {0, 1, 2}});
  const std::string ascii = format_ply(mesh, PlyFormat::ascii);
  EXPECT_NE(ascii.find("property list uint int vertex_indices\n"), std::string::npos);
  for (Format format : all_formats) {
    SCOPED_TRACE(label(format));
    EXPECT_TRUE(bit_identical(parse_as(format_as(mesh, format), format, "ring"), mesh));
  }
}

// ---------------------------------------------------------------------------------------------
// Exact content of hand-written and written files

TEST(Obj, WritesTheTetrahedronExactly) {
  const std::string expected =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  EXPECT_EQ(format_obj(tetrahedron()), expected);
  EXPECT_EQ(parse_obj(expected, "tetra.obj"), tetrahedron());
  EXPECT_EQ(format_obj(make_mesh({Vec3(0.1, -2.5e-7, 1e300)}, {})), "v 0.1 -2.5e-07 1e+300\n");
}

TEST(Obj, ReadsCornersWithTextureAndNormalIndicesAndRelativeIndices) {
  const std::string text =
      "# a unit quad with texture coordinates and normals\r\n"
      "mtllib quad.mtl\r\n"
      "o quad\r\n"
      "v 0 0 0 1\r\n"        // w is ignored
      "v 1.5 0 0 1 0 0\r\n"  // a vertex colour is ignored
      "v 1.5 2 0\r\n"
      "v +0 2 -0.25   # trailing comment\r\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 0 1\n"
      "g front\nusemtl red\ns off\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
      "f -4//-1 -3//1 -2//1\n"  // relative: -1 is vertex 4, the last so far
      "f 1/1 3/3 4/4\n"
      "f 2 2 3\n"  // a repeated vertex is kept for topology analysis to report
      "l 1 2\n"
      "\n\t\n";
  const FaceVertexMesh mesh = parse_obj(text, "quad.obj");
  const FaceVertexMesh expected = make_mesh({Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(1.5, 2, 0), Vec3(0, 2, -0.25)},
                                            {{0, 1, 2, 3}, {0, 1, 2}, {0, 2, 3}, {1, 1, 2}});
  EXPECT_EQ(mesh, expected);
  mesh.validate();
}

TEST(Obj, AbsoluteIndicesMayReferToLaterVertices) {
  const FaceVertexMesh mesh = parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "forward.obj");
  EXPECT_EQ(mesh, make_mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}));
}

TEST(Off, WritesTheTetrahedronExactly) {
  const std::string expected =
      "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  EXPECT_EQ(format_off(tetrahedron()), expected);
  EXPECT_EQ(parse_off(expected, "tetra.off"), tetrahedron());
}

TEST(Off, ReadsHeaderVariantsCommentsAndColours) {
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::vector<std::string> texts = {
      "4 4 6\n" + body,      // no header
      "OFF 4 4 6\n" + body,  // counts on the header line
      "OFF\n4 4\n" + body,   // no edge count
      "# made by hand\nOFF # header\n\n  4 4 6  # counts\r\n" + body,
      "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 9\n"
      "3 0 2 1 1 0 0\n3 0 1 3 0.5 0.5 0.5 1\n3 0 3 2 7\n3 1 2 3\n",
      "NOFF\n4 4 6\n0 0 0 -1 -1 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
      "STCNOFF\n4 4 6\n" + body,
  };
  for (const std::string& text : texts) {
    SCOPED_TRACE(text);
    EXPECT_EQ(parse_off(text, "variant.off"), tetrahedron());
  }
  // A quad and a face with a repeated vertex, kept as they are.
  const FaceVertexMesh mesh = parse_off("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 0 1\n", "quad.off");
  EXPECT_EQ(mesh, make_mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, {{0, 1, 2, 3}, {0, 0, 1}}));
}

TEST(Ply, WritesTheTetrahedronExactly) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string expected = header + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  EXPECT_EQ(format_ply(tetrahedron(), PlyFormat::ascii), expected);
  EXPECT_EQ(parse_ply(expected, "tetra.ply"), tetrahedron());

  // Binary: the same header with another format line, then doubles and (uchar, int...) records.
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    Bytes bytes(big);
    std::string binary_header = header;
    binary_header.replace(binary_header.find("ascii"), 5, big ? "binary_big_endian" : "binary_little_endian");
    bytes.text(binary_header);
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)})
      bytes.put(p.x()).put(p.y()).put(p.z());
    for (const auto& face : {std::vector<int>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
      bytes.put(std::uint8_t{3});
      for (int index : face) bytes.put(static_cast<std::int32_t>(index));
    }
    const PlyFormat format = big ? PlyFormat::binary_big_endian : PlyFormat::binary_little_endian;
    EXPECT_EQ(format_ply(tetrahedron(), format), bytes.data());
    EXPECT_EQ(bytes.size(), binary_header.size() + 4 * 24 + 4 * 13);
    EXPECT_EQ(parse_ply(bytes.data(), "tetra.ply"), tetrahedron());
  }
}

TEST(Ply, AsciiWithExtraPropertiesAndElements) {
  const std::string text =
      "ply\r\n"
      "format ascii 1.0\r\n"
      "comment exported by hand\n"
      "obj_info any text\n"
      "element vertex 4\n"
      "property float32 nx\n"
      "property float x\n"
      "property double y\n"
      "property int z\n"  // coordinates of any scalar type
      "property float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property list uchar float weights\n"
      "element face 2\n"
      "property uchar flags\n"
      "property list ushort uint vertex_index\n"
      "property list uchar float texcoord\n"
      "element edge 3\n"
      "property int vertex1\nproperty int vertex2\nproperty char crease\n"
      "element empty 1000000000000\n"  // no properties: no data, whatever the count
      "end_header\n"
      "0 0.5 -1.25 7 0 1 255 0 0 0\n"
      "0 1e-3 2 -8 0 1 0 255 0 2 0.5 0.5\n"
      "nan 3 0 0 0 1 0 0 255 1 1\n"  // a nan normal is not a coordinate: read past
      "0 -0 -0 0 0 1 1 2 3 0\n"
      "  1 4 0 1 2 3 6 0 0 1 0 1 1\n"
      "0 3 3 2 1 0\r\n"
      "0 1 0\n1 2 -1\n2 3 127\n";
  const FaceVertexMesh mesh = parse_ply(text, "extra.ply");
  const FaceVertexMesh expected =
      make_mesh({Vec3(0.5, -1.25, 7), Vec3(static_cast<float>(1e-3), 2, -8), Vec3(3, 0, 0), Vec3(-0.0, -0.0, 0)},
                {{0, 1, 2, 3}, {3, 2, 1}});
  EXPECT_TRUE(bit_identical(mesh, expected));
  EXPECT_TRUE(std::signbit(mesh.positions()(3, 0)));
}

TEST(Ply, BigEndianBinaryBuiltByteByByte) {
  Bytes bytes(true);
  bytes.text(
      "ply\nformat binary_big_endian 1.0\ncomment every type\n"
      "element vertex 3\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property char c\nproperty short s\nproperty ushort us\nproperty uint u\nproperty double d\n"
      "property list int int8 ids\n"
      "element material 2\n"
      "property list uint32 float64 values\nproperty uint8 id\n"
      "element face 2\n"
      "property int16 tag\n"
      "property list char uint16 vertex_indices\n"
      "end_header\n");
  const float xs[] = {1.5f, -2.25f, 0.1f};
  for (int v = 0; v < 3; ++v) {
    bytes.put(xs[v]).put(static_cast<float>(v)).put(-0.0f);
    bytes.put(std::int8_t{-7})
        .put(std::int16_t{-300})
        .put(std::uint16_t{65535})
        .put(std::uint32_t{4000000000u})
        .put(1e300);
    bytes.put(std::int32_t{2}).put(std::int8_t{-1}).put(std::int8_t{1});
  }
  bytes.put(std::uint32_t{1}).put(2.5).put(std::uint8_t{9});
  bytes.put(std::uint32_t{0}).put(std::uint8_t{10});
  bytes.put(std::int16_t{-1}).put(std::int8_t{3}).put(std::uint16_t{2}).put(std::uint16_t{1}).put(std::uint16_t{0});
  bytes.put(std::int16_t{5})
      .put(std::int8_t{4})
      .put(std::uint16_t{0})
      .put(std::uint16_t{1})
      .put(std::uint16_t{2})
      .put(std::uint16_t{2});
  const FaceVertexMesh mesh = parse_ply(bytes.data(), "big.ply");
  const FaceVertexMesh expected = make_mesh(
      {Vec3(1.5, 0, -0.0), Vec3(-2.25, 1, -0.0), Vec3(static_cast<double>(0.1f), 2, -0.0)}, {{2, 1, 0}, {0, 1, 2, 2}});
  EXPECT_TRUE(bit_identical(mesh, expected));
  EXPECT_EQ(mesh.positions()(2, 0), static_cast<double>(0.1f));  // float data read as float
}

TEST(Ply, LittleEndianBinaryWithUintCountsAndFaceFirst) {
  Bytes bytes(false);
  bytes.text(
      "ply\nformat binary_little_endian 1.0\n"
      "element face 1\nproperty list uint int vertex_indices\n"
      "element vertex 3\nproperty double z\nproperty double y\nproperty double x\n"
      "end_header\r\n");
  bytes.put(std::uint32_t{3}).put(std::int32_t{0}).put(std::int32_t{1}).put(std::int32_t{2});
  for (int v = 0; v < 3; ++v) bytes.put(10.0 * v).put(1.0 * v).put(0.5);
  const FaceVertexMesh mesh = parse_ply(bytes.data(), "little.ply");
  EXPECT_EQ(mesh, make_mesh({Vec3(0.5, 0, 0), Vec3(0.5, 1, 10), Vec3(0.5, 2, 20)}, {{0, 1, 2}}));
}

// ---------------------------------------------------------------------------------------------
// Malformed files: every case is a ParseError at the right place, naming what was wrong.

const std::vector<std::string> obj_lines = {
    "# a square of two triangles", "v 0 0 0", "v 1 0 0", "v 1 1 0", "v 0 1 0", "f 1 2 3", "f 1 3 4"};

TEST(Obj, MalformedTextIsAParseErrorAtTheRightPlace) {
  const auto edit = [](std::size_t line, const std::string& replacement) {
    return with_line(obj_lines, line, replacement);
  };
  expect_malformed(
      Format::obj,
      {
          {"empty file", "", 1, 1, {"no vertex"}},
          {"comments only", "# nothing here\n\n", 1, 1, {"no vertex"}},
          {"two coordinates", edit(3, "v 0 0"), 3, 6, {"'v x y z'", "found 2 numbers"}},
          {"nan", edit(3, "v 1 0 nan"), 3, 7, {"finite coordinate", "'nan'"}},
          {"-inf", edit(3, "v 1 0 -inf"), 3, 7, {"finite coordinate", "'-inf'"}},
          {"overflow", edit(3, "v 1e999 0 0"), 3, 3, {"finite coordinate", "'1e999'"}},
          {"too many numbers", edit(3, "v 1 0 0 1 2 3 4 5"), 3, 17, {"at most 4 more numbers", "found 8"}},
          {"a word after xyz", edit(3, "v 1 0 0 red"), 3, 9, {"expected a number", "'red'"}},
          {"face with 2 vertices", edit(6, "f 1 2"), 6, 3, {"at least 3 corners", "found 2"}},
          {"face without vertices", edit(6, "f"), 6, 2, {"at least 3 corners", "found 0"}},
          {"index out of range", edit(6, "f 1 2 5"), 6, 7, {"uses vertex 5", "defines 4 vertices"}},
          {"index 2^32", edit(6, "f 1 2 4294967296"), 6, 7, {"uses vertex 4294967296"}},
          {"index overflows", edit(6, "f 1 2 99999999999999999999"), 6, 7, {"face corner", "'99999999999999999999'"}},
          {"index 0", edit(6, "f 0 1 2"), 6, 3, {"nonzero integers", "'0'"}},
          {"relative index before the first vertex",
           edit(6, "f -5 1 2"),
           6,
           3,
           {"relative index -5", "4 vertices defined so far"}},
          {"most negative index", edit(6, "f -9223372036854775808 1 2"), 6, 3, {"relative index -9223372036854775808"}},
          {"relative index before any vertex", "f -1 -2 -3\nv 0 0 0\n", 1, 3, {"relative index -1", "0 vertices"}},
          {"forward reference beyond the end",
           "f 1 2 3\nv 0 0 0\nv 1 0 0\n",
           1,
           7,
           {"uses vertex 3", "defines 2 vertices"}},
          {"four parts", edit(7, "f 1/1/1/1 3 4"), 7, 3, {"v/vt/vn", "'1/1/1/1'"}},
          {"empty texture index", edit(7, "f 1/ 3 4"), 7, 3, {"'1/'"}},
          {"bad normal index", edit(7, "f 1//2 3/x 4"), 7, 8, {"'3/x'"}},
          {"word as index", edit(7, "f a b c"), 7, 3, {"'a'"}},
          {"unknown statement", edit(2, "vx 1 2 3"), 2, 1, {"unknown OBJ statement", "'vx'"}},
          {"binary garbage",
           "\x7f"
           "ELF\x02\x01\x00\xff\n"s,
           1,
           1,
           {"unknown OBJ statement", "'\\x7fELF\\x02\\x01\\x00\\xff'"}},
          {"latin-1 byte", edit(4, "v 1 1 0\xe9"), 4, 7, {"'0\\xe9'"}},
          {"error after CRLF lines", "v 0 0 0\r\nv 1 0 0\r\nf 1 2\r\n", 3, 3, {"found 2"}},
      });
}

TEST(Obj, RefusesFreeformStatementsPointingToTheFreeformReader) {
  const std::string polygons = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (const char* keyword : {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
                              "sp", "end", "con"}) {
    SCOPED_TRACE(keyword);
    const auto error = testing::parse_error_of([&] { parse_obj(polygons + "  " + keyword + " 1\n", "mixed.obj"); });
    ASSERT_TRUE(error);
    EXPECT_EQ(error->line(), 5);
    EXPECT_EQ(error->column(), 3);
    const std::string message = error->what();
    EXPECT_NE(message.find(std::string("free-form statement '") + keyword + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("read_obj_freeform"), std::string::npos) << message;
  }
  // Its rendering hints stay read past.
  EXPECT_EQ(parse_obj(polygons + "ctech cparm 1\nstech cparma 1 1\n", "hints.obj").face_count(), 1u);
}

TEST(Obj, ContinuationLinesJoinIntoTheStatementWhereTheyStart) {
  const FaceVertexMesh mesh = parse_obj("v 0 0 0\nv 1 0 \\\n 0\nv 0 1 0\nf 1 \\\n 2 \\  # comment\n 3\n", "continued.obj");
  EXPECT_EQ(mesh, make_mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}));
  // An error in a continuation line names the line the statement starts in and its own.
  const auto error = parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n   x\n", Format::obj, "continued.obj");
  ASSERT_TRUE(error);
  EXPECT_EQ(error->line(), 4);
  EXPECT_EQ(error->column(), 4);
  EXPECT_NE(std::string(error->what()).find("(in continuation line 5)"), std::string::npos) << error->what();
}

const std::vector<std::string> off_lines = {"OFF",   "# tetrahedron", "4 4 6",   "0 0 0",   "1 0 0",  "0 1 0",
                                            "0 0 1", "3 0 2 1",       "3 0 1 3", "3 0 3 2", "3 1 2 3"};

TEST(Off, MalformedTextIsAParseErrorAtTheRightPlace) {
  const auto edit = [](std::size_t line, const std::string& replacement) {
    return with_line(off_lines, line, replacement);
  };
  expect_malformed(
      Format::off,
      {
          {"empty file", "", 1, 1, {"end of file", "'OFF'"}},
          {"header only", "OFF\n", 1, 4, {"end of file", "counts"}},
          {"4D", edit(1, "4OFF"), 1, 1, {"unsupported OFF variant", "'4OFF'"}},
          {"n-dimensional", edit(1, "nOFF"), 1, 1, {"unsupported OFF variant"}},
          {"binary", edit(1, "OFF BINARY"), 1, 5, {"binary OFF"}},
          {"another format", edit(1, "ply"), 1, 1, {"header 'OFF' or the counts", "'ply'"}},
          {"one count", edit(3, "4"), 3, 2, {"'V F E'", "found 1 number"}},
          {"four counts", edit(3, "4 4 6 1"), 3, 7, {"'V F E'", "found 4"}},
          {"negative count", edit(3, "4 -4 6"), 3, 3, {"face count F is negative"}},
          {"count not an integer", edit(3, "4.0 4 6"), 3, 1, {"vertex count V", "'4.0'"}},
          {"vertex count above 32 bits", edit(3, "4294967295 4 6"), 3, 1, {"exceeds the limit"}},
          {"vertex with 2 numbers", edit(5, "1 0"), 5, 4, {"vertex 1 as 'x y z'", "found 2 numbers"}},
          {"nan", edit(6, "0 nan 0"), 6, 3, {"finite coordinate of vertex 2", "'nan'"}},
          {"word after a vertex", edit(6, "0 1 0 red"), 6, 7, {"number after vertex 2", "'red'"}},
          {"face with 2 vertices", edit(8, "2 0 2"), 8, 1, {"face 0 has 2 corners", "at least 3"}},
          {"negative corner count", edit(8, "-3 0 2 1"), 8, 1, {"face 0 has -3 corners"}},
          {"negative index", edit(9, "3 0 1 -3"), 9, 7, {"negative vertex index -3"}},
          {"index out of range", edit(9, "3 0 1 4"), 9, 7, {"face 1 uses vertex 4", "4 vertices"}},
          {"too few indices", edit(9, "4 0 1 3"), 9, 8, {"face 1 has 4 corners but 3 indices follow"}},
          {"huge corner count", edit(9, "1000000000000 0 1 3"), 9, 20, {"1000000000000 corners"}},
          {"too many colour values", edit(9, "3 0 1 3 1 1 1 1 1"), 9, 17, {"5 numbers after its 3 indices"}},
          {"word as colour", edit(9, "3 0 1 3 red"), 9, 9, {"colour value of face 1", "'red'"}},
          {"word as index", edit(9, "3 0 1 x"), 9, 7, {"vertex index of face 1", "'x'"}},
          {"missing face", edit(11, ""), 10, 8, {"end of file", "face 3 of 4"}},
          {"missing vertices", "OFF\n4 4 6\n0 0 0\n", 3, 6, {"end of file", "vertex 1 of 4"}},
          {"trailing data", with_line(off_lines, 0, "") + "3 0 1 2\n", 12, 1, {"after the last of 4 faces"}},
          {"garbage", "\x89PNG\r\n\x1a\n\x00\x00"s, 1, 1, {"'\\x89PNG'"}},
      });
}

const std::vector<std::string> ply_lines = {"ply",
                                            "format ascii 1.0",
                                            "comment made by hand",
                                            "element vertex 4",
                                            "property float x",
                                            "property float y",
                                            "property float z",
                                            "element face 4",
                                            "property list uchar int vertex_indices",
                                            "end_header",
                                            "0 0 0",
                                            "1 0 0",
                                            "0 1 0",
                                            "0 0 1",
                                            "3 0 2 1",
                                            "3 0 1 3",
                                            "3 0 3 2",
                                            "3 1 2 3"};

TEST(Ply, ValidHandWrittenAsciiReads) { EXPECT_EQ(parse_ply(with_line(ply_lines, 0, ""), "tetra.ply"), tetrahedron()); }

TEST(Ply, MalformedHeaderOrAsciiDataIsAParseErrorAtTheRightPlace) {
  const auto edit = [](std::size_t line, const std::string& replacement) {
    return with_line(ply_lines, line, replacement);
  };
  std::string unterminated;
  for (std::size_t k = 0; k < 9; ++k) unterminated += ply_lines[k] + "\n";
  expect_malformed(
      Format::ply_ascii,
      {
          {"empty file", "", 1, 1, {"empty file", "'ply'"}},
          {"wrong magic", edit(1, "PLY"), 1, 1, {"magic line 'ply'", "'PLY'"}},
          {"unknown format", edit(2, "format binary 1.0"), 2, 8, {"unknown PLY format 'binary'"}},
          {"version 2.0", edit(2, "format ascii 2.0"), 2, 14, {"unsupported PLY version '2.0'"}},
          {"no format line", edit(2, ""), 9, 1, {"no 'format' line"}},
          {"unknown type", edit(5, "property flot x"), 5, 10, {"unknown PLY type 'flot'"}},
          {"no z", edit(7, "property float w"), 4, 1, {"no property 'z'"}},
          {"z as a list", edit(7, "property list uchar float z"), 7, 1, {"'z' is a list"}},
          {"float indices", edit(9, "property list uchar float vertex_indices"), 9, 1, {"list of an integer type"}},
          {"float list count", edit(9, "property list float int vertex_indices"), 9, 15, {"count type of a list"}},
          {"indices not a list", edit(9, "property int vertex_indices"), 9, 1, {"list of an integer type"}},
          {"no index list", edit(9, "property list uchar int indices"), 8, 1, {"no list property 'vertex_indices'"}},
          {"negative count", edit(4, "element vertex -4"), 4, 16, {"count of element 'vertex'", "'-4'"}},
          {"vertex count above 32 bits", edit(4, "element vertex 4294967295"), 4, 1, {"above the limit"}},
          {"no vertex element", edit(4, "element point 4"), 10, 1, {"no 'element vertex'"}},
          {"property before any element", edit(3, "property float q"), 3, 1, {"before any 'element'"}},
          {"unknown header line", edit(3, "elemnt foo 1"), 3, 1, {"unknown PLY header line", "'elemnt'"}},
          {"property twice", edit(6, "property float x"), 6, 16, {"property 'x' of element 'vertex' declared twice"}},
          {"header never ends", unterminated, 9, 39, {"expected 'end_header'"}},
          {"missing value", edit(12, "1 0"), 12, 4, {"expected property 'z' of vertex 1"}},
          {"extra value", edit(12, "1 0 0 0"), 12, 7, {"vertex 1 has more values"}},
          {"nan", edit(12, "1 nan 0"), 12, 3, {"property 'y' of vertex 1 is not finite"}},
          {"beyond float", edit(12, "1 1e39 0"), 12, 3, {"not finite"}},
          {"word as coordinate", edit(12, "1 zero 0"), 12, 3, {"property 'y' of vertex 1 as float", "'zero'"}},
          {"face with 2 vertices", edit(15, "2 0 2"), 15, 1, {"face 0 has 2 corners"}},
          {"count beyond uchar", edit(15, "256 0 2 1"), 15, 1, {"uchar", "[0, 255]", "'256'"}},
          {"index out of range", edit(15, "3 0 2 4"), 15, 7, {"face 0 uses vertex 4", "4 vertices"}},
          {"negative index", edit(15, "3 0 -2 1"), 15, 5, {"negative vertex index -2"}},
          {"count larger than the line", edit(15, "4 0 2 1"), 15, 8, {"has 4 items but 3 values follow"}},
          {"fractional index", edit(15, "3 0 2 1.5"), 15, 7, {"as int", "'1.5'"}},
          {"missing face", edit(18, ""), 17, 8, {"end of file", "face 3 of 4"}},
          {"trailing data", with_line(ply_lines, 0, "") + "junk\n", 19, 1, {"after the last element", "'junk'"}},
          {"binary garbage", "\x00\x01\x02\xff\xfe"s, 1, 1, {"'\\x00\\x01\\x02\\xff\\xfe'"}},
      });
}

// A binary tetrahedron: float x y z, faces 'list uchar int'; `vertices` and `faces` as declared.
struct BinaryTetra {
  std::string header;
  Bytes bytes;
  std::size_t data_offset;
};

BinaryTetra binary_tetra(bool big, const std::string& vertex_count = "4", const std::string& face_count = "4") {
  BinaryTetra result{"ply\nformat "s + (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\nelement vertex " +
                         vertex_count + "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                         face_count + "\nproperty list uchar int vertex_indices\nend_header\n",
                     Bytes(big), 0};
  result.bytes.text(result.header);
  result.data_offset = result.bytes.size();
  return result;
}

void put_tetra_vertices(Bytes& bytes, float nan_at_second_y = 1.0f) {
  bytes.put(0.0f).put(0.0f).put(0.0f);
  bytes.put(1.0f).put(nan_at_second_y - 1.0f).put(0.0f);
  bytes.put(0.0f).put(1.0f).put(0.0f);
  bytes.put(0.0f).put(0.0f).put(1.0f);
}

void put_face(Bytes& bytes, std::vector<std::int32_t> indices) {
  bytes.put(static_cast<std::uint8_t>(indices.size()));
  for (std::int32_t index : indices) bytes.put(index);
}

TEST(Ply, MalformedBinaryDataIsAParseErrorAtItsByteOffset) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    {  // valid, as the reference for the edits below
      auto t = binary_tetra(big);
      put_tetra_vertices(t.bytes);
      for (const auto& face : {std::vector<std::int32_t>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
        put_face(t.bytes, face);
      EXPECT_EQ(parse_ply(t.bytes.data(), "valid.ply"), tetrahedron());
    }
    std::vector<Malformed> cases;
    {  // the vertices cannot fit: fails before reading any
      auto t = binary_tetra(big);
      t.bytes.put(0.0f).put(0.0f).put(0.0f);
      const auto o = t.data_offset;
      cases.push_back({"truncated vertices",
                       t.bytes.data(),
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"binary data ends early", "element 'vertex' declares 4 records of at least 12 bytes",
                        "from byte offset " + std::to_string(o), "only 12 bytes remain"}});
    }
    {  // 10^12 faces
      auto t = binary_tetra(big, "4", "1000000000000");
      put_tetra_vertices(t.bytes);
      put_face(t.bytes, {0, 2, 1});
      const auto o = t.data_offset + 48;
      cases.push_back({"10^12 faces",
                       t.bytes.data(),
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"element 'face' declares 1000000000000 records of at least 13 bytes", "only 13 bytes remain"}});
    }
    {  // a face list longer than the data
      auto t = binary_tetra(big, "4", "1");
      put_tetra_vertices(t.bytes);
      put_face(t.bytes, {0, 2, 1});
      std::string data = t.bytes.data();
      data[t.data_offset + 48] = 4;  // the count: 4 items, 12 bytes follow
      const auto o = t.data_offset + 49;
      cases.push_back({"list longer than the data",
                       data,
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"property 'vertex_indices' of face 0 has 4 items", "only 12 bytes remain"}});
    }
    {  // data ends inside a record: the check before the element passes (54 bytes for 3 faces of
       // at least 13), the long first face leaves nothing for the third
      auto t = binary_tetra(big, "4", "3");
      put_tetra_vertices(t.bytes);
      put_face(t.bytes, {0, 1, 2, 3, 0, 1, 2, 3, 0, 1});
      put_face(t.bytes, {0, 2, 1});
      const auto o = t.data_offset + 48 + 41 + 13;
      cases.push_back(
          {"truncated record",
           t.bytes.data(),
           0,
           static_cast<std::int64_t>(o) + 1,
           {"binary data ends at byte offset " + std::to_string(o), "inside property 'vertex_indices' of face 2"}});
    }
    {  // nan
      auto t = binary_tetra(big, "4", "0");
      put_tetra_vertices(t.bytes, std::numeric_limits<float>::quiet_NaN());
      const auto o = t.data_offset + 16;
      cases.push_back({"nan",
                       t.bytes.data(),
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"property 'y' of vertex 1 is not finite", "byte offset " + std::to_string(o)}});
    }
    {  // index out of range, negative index, 2 corners
      static const std::pair<std::vector<std::int32_t>, std::string> bad_faces[] = {
          {{0, 2, 4}, "face 1 uses vertex 4 but there are 4 vertices"},
          {{0, -1, 2}, "face 1 has the negative vertex index -1"},
          {{0, 2}, "face 1 has 2 corners"}};
      for (const auto& [face, part] : bad_faces) {
        auto t = binary_tetra(big, "4", "2");
        put_tetra_vertices(t.bytes);
        put_face(t.bytes, {0, 2, 1});
        put_face(t.bytes, face);
        if (face.size() == 2) t.bytes.put(std::int32_t{0});  // the bytes the check before the faces wants
        const std::size_t at = face.size() == 2 ? 0 : face[2] == 4 ? 9 : 5;  // count byte, or the offending index
        const auto o = t.data_offset + 48 + 13 + at;
        cases.push_back({part.c_str(), t.bytes.data(), 0, static_cast<std::int64_t>(o) + 1, {part}});
      }
    }
    {  // trailing bytes
      auto t = binary_tetra(big, "4", "0");
      put_tetra_vertices(t.bytes);
      t.bytes.text("\n");
      const auto o = t.data_offset + 48;
      cases.push_back({"trailing byte",
                       t.bytes.data(),
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"1 bytes of unexpected data after the last element", "from byte offset " + std::to_string(o)}});
    }
    {  // a negative list count of a signed count type
      Bytes bytes(big);
      bytes.text(
          "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
          "property double z\nproperty list char int extra\nend_header\n");
      std::string data = bytes.data();
      if (big) data.replace(data.find("little"), 6, "big");
      const auto o = data.size() + 24;
      Bytes body(big);
      body.put(1.0).put(2.0).put(3.0).put(std::int8_t{-2});
      cases.push_back({"negative list count",
                       data + body.data(),
                       0,
                       static_cast<std::int64_t>(o) + 1,
                       {"property 'extra' of vertex 0 has a negative item count -2"}});
    }
    expect_malformed(big ? Format::ply_big : Format::ply_little, cases);
  }
}

// A header that claims 10^12 faces fails as soon as the data runs out: nothing is reserved for
// the claim (the sanitizer would abort on such an allocation) and nothing loops over it.
TEST(MeshFormats, AbsurdCountsFailFastWithoutAllocating) {
  std::vector<std::pair<Format, std::string>> texts;
  texts.emplace_back(Format::off, with_line(off_lines, 3, "4 1000000000000 6"));
  texts.emplace_back(Format::off, with_line(off_lines, 3, "4000000000 4 6"));
  texts.emplace_back(Format::ply_ascii, with_line(ply_lines, 8, "element face 1000000000000"));
  texts.emplace_back(Format::ply_ascii, with_line(ply_lines, 4, "element vertex 4294967294"));
  texts.emplace_back(Format::ply_ascii, with_line(ply_lines, 8, "element face 9223372036854775807"));
  for (const bool big : {false, true}) {
    auto t = binary_tetra(big, "4294967294", "1000000000000");
    put_tetra_vertices(t.bytes);
    texts.emplace_back(big ? Format::ply_big : Format::ply_little, t.bytes.data());
    auto u = binary_tetra(big, "4", "1000000000000");
    put_tetra_vertices(u.bytes);
    put_face(u.bytes, {0, 1, 2});
    texts.emplace_back(big ? Format::ply_big : Format::ply_little, u.bytes.data());
  }
  for (const auto& [format, text] : texts) {
    SCOPED_TRACE(label(format));
    const double elapsed =
        seconds([&, format = format, &text = text] { EXPECT_TRUE(parse_error(text, format, "huge")); });
    EXPECT_LT(elapsed, 0.5);
  }
  // The ascii cases fail at the end of the data, where the first missing record was due.
  const auto off = parse_error(texts[0].second, Format::off, "huge.off");
  ASSERT_TRUE(off);
  EXPECT_EQ(off->line(), 11);
  EXPECT_NE(std::string(off->what()).find("face 4 of 1000000000000"), std::string::npos) << off->what();
  const auto ply = parse_error(texts[2].second, Format::ply_ascii, "huge.ply");
  ASSERT_TRUE(ply);
  EXPECT_EQ(ply->line(), 18);
  EXPECT_NE(std::string(ply->what()).find("face 4 of 1000000000000"), std::string::npos) << ply->what();
}

TEST(MeshFormats, EmptyTextIsAParseErrorInEveryFormat) {
  for (Format format : all_formats) {
    SCOPED_TRACE(label(format));
    for (const std::string& text : {""s, "\n\n  \r\n"s}) {
      const auto error = parse_error(text, format, "empty");
      if (!error) continue;
      EXPECT_EQ(error->line(), 1);
      EXPECT_EQ(error->column(), 1);
    }
  }
}

// Any damage to a valid file either still parses to a valid mesh or is a ParseError: never
// another exception, never a crash (the sanitizer build checks memory and undefined behaviour).
RC_GTEST_PROP(MeshFormats, DamagedFilesParseOrAreAParseError, ()) {
  const Format format =
      *rc::gen::element(Format::obj, Format::off, Format::ply_ascii, Format::ply_little, Format::ply_big);
  std::string text = format_as(random_mesh(1), format);
  const int edits = *rc::gen::inRange(1, 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = *rc::gen::inRange<std::size_t>(0, text.size() + 1);
    switch (*rc::gen::inRange(0, 5)) {
      case 0:
        text.insert(at, 1, *rc::gen::arbitrary<char>());
        break;
      case 1:
        text.erase(at, *rc::gen::inRange<std::size_t>(0, 20));
        break;
      case 2:
        text.insert(at, *rc::gen::element(" "s, "\n"s, "\r\n"s, " 1"s, "nan"s, "-"s, "e999"s, "/"s, "-7"s,
                                          "99999999999"s, "\xff"s, "4294967295"s, "\0"s));
        break;
      case 3:
        if (at < text.size()) text[at] = *rc::gen::arbitrary<char>();
        break;
      default:
        text.resize(at);
        break;
    }
  }
  try {
    const FaceVertexMesh mesh = parse_as(text, format, "damaged");
    mesh.validate();
    RC_ASSERT(bit_identical(parse_as(format_as(mesh, format), format, "again"), mesh));
  } catch (const ParseError& error) {
    RC_ASSERT(error.line() >= 0);
    RC_ASSERT(error.column() >= (error.line() == 0 ? 1 : 0));
  }
}

// ---------------------------------------------------------------------------------------------
// Files

TEST(MeshFile, WriteThenReadByExtensionInEveryFormat) {
  const TemporaryDirectory folder;
  const FaceVertexMesh mesh =
      make_mesh({Vec3(0.1, 0.2, 0.3), Vec3(1, 0, -0.0), Vec3(0, 1e-300, 0), Vec3(7, 7, 7)}, {{0, 1, 2}, {0, 2, 3, 1}});
  for (const char* name : {"a.obj", "b.off", "c.ply", "D.OBJ", "e.Ply"}) {
    SCOPED_TRACE(name);
    write_mesh(folder.path() / name, mesh);
    EXPECT_TRUE(bit_identical(read_mesh(folder.path() / name), mesh));
  }
  EXPECT_EQ(file_content(folder.path() / "a.obj"), format_obj(mesh));
  EXPECT_EQ(file_content(folder.path() / "b.off"), format_off(mesh));
  EXPECT_EQ(file_content(folder.path() / "c.ply"), format_ply(mesh, PlyFormat::binary_little_endian));
  write_mesh(folder.path() / "f.ply", mesh, PlyFormat::ascii);
  EXPECT_EQ(file_content(folder.path() / "f.ply"), format_ply(mesh, PlyFormat::ascii));
  EXPECT_TRUE(bit_identical(read_ply(folder.path() / "f.ply"), mesh));
  EXPECT_TRUE(bit_identical(read_obj(folder.path() / "a.obj"), mesh));
  EXPECT_TRUE(bit_identical(read_off(folder.path() / "b.off"), mesh));
  // No temporary file is left behind.
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"D.OBJ", "a.obj", "b.off", "c.ply", "e.Ply", "f.ply"}));
}

TEST(MeshFile, UnknownExtensionIsAnIoErrorAndWritesNothing) {
  const TemporaryDirectory folder;
  for (const char* name : {"mesh.stl", "mesh", "mesh.obj.bak"}) {
    SCOPED_TRACE(name);
    const fs::path path = folder.path() / name;
    try {
      write_mesh(path, tetrahedron());
      ADD_FAILURE() << "no IoError";
    } catch (const IoError& error) {
      EXPECT_EQ(error.path(), path.string());
      EXPECT_NE(std::string(error.what()).find("expected .obj, .off or .ply"), std::string::npos) << error.what();
    }
    put_file(path, format_obj(tetrahedron()));
    EXPECT_THROW(read_mesh(path), IoError);
    fs::remove(path);
  }
  EXPECT_TRUE(folder.entries().empty());
}

TEST(MeshFile, RefusedObjWriteLeavesNothing) {
  const TemporaryDirectory folder;
  EXPECT_THROW(write_mesh(folder.path() / "empty.obj", FaceVertexMesh()), InvalidInput);
  EXPECT_TRUE(folder.entries().empty());
}

TEST(MeshFile, MissingFileOrDirectoryIsAnIoError) {
  const TemporaryDirectory folder;
  for (const char* name : {"absent.obj", "absent.off", "absent.ply"}) {
    const fs::path missing = folder.path() / name;
    try {
      read_mesh(missing);
      ADD_FAILURE() << "no IoError for " << name;
    } catch (const IoError& error) {
      EXPECT_EQ(error.path(), missing.string());
    }
  }
  for (const char* name : {"dir.obj", "dir.off", "dir.ply"}) {
    const fs::path directory = folder.path() / name;
    fs::create_directory(directory);
    EXPECT_THROW(read_mesh(directory), IoError) << name;
  }
  EXPECT_THROW(read_obj(folder.path()), IoError);
  EXPECT_THROW(read_off(folder.path()), IoError);
  EXPECT_THROW(read_ply(folder.path()), IoError);
}

TEST(MeshFile, ParseErrorsNameTheFileAndLine) {
  const TemporaryDirectory folder;
  const std::pair<const char*, std::string> files[] = {
      {"bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"},
      {"bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"},
      {"bad.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"},
  };
  const std::int64_t lines[] = {3, 6, 13};
  for (std::size_t k = 0; k < std::size(files); ++k) {
    const fs::path path = folder.path() / files[k].first;
    put_file(path, files[k].second);
    try {
      read_mesh(path);
      ADD_FAILURE() << "no ParseError for " << files[k].first;
    } catch (const ParseError& error) {
      EXPECT_EQ(error.path(), path.string());
      EXPECT_EQ(error.line(), lines[k]) << error.what();
      EXPECT_EQ(std::string(error.what()).rfind(path.string() + ":" + std::to_string(lines[k]) + ":", 0), 0U)
          << error.what();
    }
  }
  const fs::path empty = folder.path() / "empty.ply";
  put_file(empty, "");
  EXPECT_THROW(read_mesh(empty), ParseError);
}

}  // namespace
}  // namespace patchwork
