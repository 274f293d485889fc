#pragma once
// The rules a free-form OBJ record obeys (io/obj_freeform.h), shared by the reader, which turns
// a problem into a place in the file, and by validate() and the writer, which name it in an
// InvalidInput. Internal: not installed.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include "io/obj_freeform.h"

namespace patchwork::detail {

/// The part of a record a problem is in.
enum class FreeformPart { degree, parameter, parameter_count, range, point_count, point, weight };

/// What is wrong with a record, and in which part.
struct FreeformProblem {
  FreeformPart part;
  int direction;      // 0: u (a curve's only direction), 1: v
  std::size_t index;  // the parameter, the end of the range (0 start, 1 end) or the control point
  std::string message;
};

/// A curve or a surface as the checks and the writer see it: one or two directions.
struct FreeformRecordView {
  const char* keyword;  // "curv" or "surf"
  FreeformBasis basis;
  bool rational;
  int directions;
  std::array<int, 2> degrees;
  std::array<std::span<const double>, 2> parameters;
  std::array<double, 4> range;  // start and end of u, then of v
  std::span<const Vec3> points;
  std::span<const double> weights;
};

/// "bezier" or "bspline", as cstype writes it.
const char* basis_name(FreeformBasis basis);

/// "u" for direction 0, "v" for 1.
const char* direction_name(int direction);

/// The view of a curve (one direction: u).
FreeformRecordView view_of(const FreeformCurve& curve);

/// The view of a surface (u and v).
FreeformRecordView view_of(const FreeformSurface& surface);

/// The first rule the record breaks, in the order degree, parameters, range (per direction),
/// control-point count, points and weights; nothing if it obeys them all.
std::optional<FreeformProblem> record_problem(const FreeformRecordView& record);

}  // namespace patchwork::detail
