#pragma once
// What every fuzz target shares: bad input may only be answered by patchwork's documented
// exceptions. Anything else escapes, and libFuzzer reports it as a crash with the input: a
// std::logic_error from an invariant check, std::bad_alloc from an allocation a size field asked
// for, an out_of_range, a sanitizer report.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <vector>

#include "core/errors.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork::fuzz {

/// Runs body(); the documented answers to bad input (InvalidInput with TopologyError,
/// ParseError, IoError, NumericalError) end the case, everything else goes through.
template <class Body>
void expect_documented_errors_only(const Body& body) {
  try {
    body();
  } catch (const InvalidInput&) {
  } catch (const ParseError&) {
  } catch (const IoError&) {
  } catch (const NumericalError&) {
  }
}

/// The fuzzer's bytes as text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Reads small numbers from the fuzzer's bytes, then zeros when they run out.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  /// A number in [0, n), n > 0.
  std::uint32_t below(std::uint32_t n) { return next() % n; }
  /// A coordinate on a coarse lattice (coincident points and edges are likely): k / 4, |k| <= 8.
  double coordinate() { return (static_cast<int>(below(17)) - 8) / 4.0; }
  bool empty() const { return position_ >= size_; }

 private:
  std::uint32_t next() { return position_ < size_ ? data_[position_++] : 0u; }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

/// A face list drawn from the bytes, before FaceVertexMesh checks it.
struct FaceListBytes {
  Positions positions;
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
};

/// min_vertices + below(vertex_range) points on the lattice, min_faces + below(face_range)
/// faces of min_corners + below(corner_range) corners; indices below the vertex count plus
/// `out_of_range` (so out-of-range indices occur when it is positive).
inline FaceListBytes face_list(ByteReader& bytes, std::uint32_t min_vertices, std::uint32_t vertex_range,
                               std::uint32_t min_faces, std::uint32_t face_range, std::uint32_t min_corners,
                               std::uint32_t corner_range, std::uint32_t out_of_range) {
  FaceListBytes list;
  const std::uint32_t vertices = min_vertices + bytes.below(vertex_range);
  list.positions.resize(vertices, 3);
  for (std::uint32_t v = 0; v < vertices; ++v) {
    for (int k = 0; k < 3; ++k) list.positions(v, k) = bytes.coordinate();
  }
  const std::uint32_t faces = min_faces + bytes.below(face_range);
  for (std::uint32_t f = 0; f < faces; ++f) {
    list.sizes.push_back(min_corners + bytes.below(corner_range));
    for (std::uint32_t k = 0; k < list.sizes.back(); ++k) list.indices.push_back(bytes.below(vertices + out_of_range));
  }
  return list;
}

}  // namespace patchwork::fuzz

/// Makes an assertion that stays on in every build of the fuzz targets.
#define PATCHWORK_FUZZ_CHECK(condition) \
  do {                                  \
    if (!(condition)) __builtin_trap(); \
  } while (false)
