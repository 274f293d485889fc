#pragma once
// Checks of a query's arguments, shared by every query: a point, a direction or a tolerance that
// a query cannot use is an InvalidInput naming the function and the argument, for example
//   "closest_point: argument 'point' is not finite (1, nan, 0)".

#include <string_view>

#include "core/types.h"

namespace patchwork {

/// \throws InvalidInput naming `function` and `argument` if a coordinate of `point` is not finite.
template <int Dim>
void require_finite(const Point<Dim>& point, std::string_view function, std::string_view argument);

/// \throws InvalidInput naming `function` and `argument` if `direction` is not finite or is the
/// zero vector (a ray or a plane normal needs a direction).
template <int Dim>
void require_direction(const Point<Dim>& direction, std::string_view function, std::string_view argument);

/// \throws InvalidInput naming `function` and `argument` unless `value` is finite and > 0.
void require_positive(double value, std::string_view function, std::string_view argument);

}  // namespace patchwork
