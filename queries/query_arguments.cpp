#include "queries/query_arguments.h"

#include <cmath>
#include <sstream>

#include "core/errors.h"

namespace patchwork {
namespace {

template <int Dim>
std::string coordinates(const Point<Dim>& point) {
  std::ostringstream out;
  out.precision(17);
  out << '(';
  for (int c = 0; c < Dim; ++c) out << (c ? ", " : "") << point[c];
  out << ')';
  return out.str();
}

}  // namespace

template <int Dim>
void require_finite(const Point<Dim>& point, std::string_view function, std::string_view argument) {
  if (!point.allFinite())
    throw InvalidInput(detail::message(function, ": argument '", argument, "' is not finite ", coordinates(point)));
}

template <int Dim>
void require_direction(const Point<Dim>& direction, std::string_view function, std::string_view argument) {
  require_finite(direction, function, argument);
  if (direction.cwiseAbs().maxCoeff() == 0.0)
    throw InvalidInput(detail::message(function, ": argument '", argument, "' is the zero vector"));
}

void require_positive(double value, std::string_view function, std::string_view argument) {
  if (!(std::isfinite(value) && value > 0.0))
    throw InvalidInput(detail::message(function, ": argument '", argument, "' must be finite and positive, not ", value));
}

template void require_finite<2>(const Point<2>&, std::string_view, std::string_view);
template void require_finite<3>(const Point<3>&, std::string_view, std::string_view);
template void require_direction<2>(const Point<2>&, std::string_view, std::string_view);
template void require_direction<3>(const Point<3>&, std::string_view, std::string_view);

}  // namespace patchwork
