#include "tools/default_tolerance.h"

#include "core/errors.h"

namespace patchwork::tools {

std::optional<double> relative_tolerance_or_default(const std::optional<double>& given, bool no_mode_given) {
  if (no_mode_given) return default_relative_tolerance;
  return given;
}

std::string tolerance_summary(double tolerance, const std::optional<double>& relative, bool is_default) {
  if (is_default) {
    return detail::message(tolerance, " (the default: ", default_relative_tolerance,
                           " of the box diagonal; --tolerance, --relative-tolerance or --segments choose another)");
  }
  if (relative) return detail::message(tolerance, " (", *relative, " of the box diagonal)");
  return detail::message(tolerance);
}

}  // namespace patchwork::tools
