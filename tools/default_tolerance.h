#pragma once
// The tolerance `patchwork tessellate` and `patchwork subdivide --limit` use when none of
// --tolerance, --relative-tolerance, --segments (and, for tessellate, --camera) is given: 10^-3
// of the box diagonal relative tolerances refer to (the surface's tight box for tessellate, the
// cage's box for subdivide --limit), the tolerance scripts/demo uses. The summary names it, so a
// user sees which tolerance was chosen for them.

#include <optional>
#include <string>

namespace patchwork::tools {

/// The relative tolerance used when no mode is given (a fraction of the box diagonal).
inline constexpr double default_relative_tolerance = 1e-3;

/// The relative tolerance a command runs with: `given`, or the default when `no_mode_given`.
std::optional<double> relative_tolerance_or_default(const std::optional<double>& given, bool no_mode_given);

/// The summary's tolerance line after its label: the absolute `tolerance`, and how it was chosen
/// ("0.0082 (the default: 1e-3 of the box diagonal; ...)", "0.0082 (1e-3 of the box diagonal)").
std::string tolerance_summary(double tolerance, const std::optional<double>& relative, bool is_default);

}  // namespace patchwork::tools
