#pragma once
// `patchwork curve-demo`: what the curves module does, with speed and error printed: plain and
// compensated de Casteljau near a root of high multiplicity, the arc length of an exact rational
// circle, and evaluation speed. The main job, tessellating patch sets, is `patchwork tessellate`.

#include <iosfwd>

namespace patchwork::tools {

/// Runs the demo: accuracy of plain vs compensated de Casteljau on a hard case, arc length of
/// an exact circle, and evaluation speed; writes a report to `out`.
void run_curve_demo(std::ostream& out, int degree, long evaluations);

}  // namespace patchwork::tools
