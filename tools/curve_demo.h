#pragma once
// `patchwork curve-demo`: what the curves module does, with speed and error printed. It stands
// in for the main job (tessellating the teapot) until the tessellator exists.

#include <iosfwd>

namespace patchwork::tools {

/// Runs the demo: accuracy of plain vs compensated de Casteljau on a hard case, arc length of
/// an exact circle, and evaluation speed; writes a report to `out`.
void run_curve_demo(std::ostream& out, int degree, long evaluations);

}  // namespace patchwork::tools
