#pragma once
// Internal to subdivision/: the bridge to OpenSubdiv. Only the subdivision .cpp files include
// this header; no public header names an OpenSubdiv type.

#include <memory>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefiner.h>

#include "core/types.h"
#include "subdivision/cage.h"

namespace patchwork::detail {

/// A validated cage as an OpenSubdiv topology refiner (not yet refined). OpenSubdiv's errors
/// become TopologyError. \throws what validate_cage() throws.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_refiner(const SubdivisionCage& cage);

/// One row of a row-major array of doubles, as OpenSubdiv's primvar interpolation wants it.
struct PrimvarRow {
  double* values;
  int size;
  void Clear() {
    for (int k = 0; k < size; ++k) values[k] = 0.0;
  }
  void AddWithWeight(const PrimvarRow& source, double weight) {
    for (int k = 0; k < size; ++k) values[k] += weight * source.values[k];
  }
};

/// A row-major array of rows of `size` doubles; operator[] hands out rows.
struct PrimvarRows {
  double* base;
  int size;
  PrimvarRow operator[](int index) const { return {base + static_cast<std::ptrdiff_t>(index) * size, size}; }
};

/// A point as OpenSubdiv's interpolation and stencils want it.
struct OsdPoint {
  double x[3];
  void Clear() { x[0] = x[1] = x[2] = 0.0; }
  void AddWithWeight(const OsdPoint& source, double weight) {
    x[0] += weight * source.x[0];
    x[1] += weight * source.x[1];
    x[2] += weight * source.x[2];
  }
  Vec3 vec() const { return {x[0], x[1], x[2]}; }
};

/// Rows of a compile-time width (the positions: 3), unrolled.
template <int Width>
struct FixedRow {
  double* values;
  void Clear() {
    for (int k = 0; k < Width; ++k) values[k] = 0.0;
  }
  void AddWithWeight(const FixedRow& source, double weight) {
    for (int k = 0; k < Width; ++k) values[k] += weight * source.values[k];
  }
};
template <int Width>
struct FixedRows {
  double* base;
  FixedRow<Width> operator[](int index) const { return {base + static_cast<std::ptrdiff_t>(index) * Width}; }
};

using PrimvarRefiner = OpenSubdiv::Far::PrimvarRefinerReal<double>;

}  // namespace patchwork::detail
