#pragma once
// One section of docs/performance.md (scripts/report): its Markdown and the gnuplot commands
// that draw its plots. Plots and data files are written into the report's output folder; the
// gnuplot commands run with that folder as the working directory and name files relative to it.

#include <string>

namespace patchwork::performance {

struct ReportSection {
  /// Markdown, starting with a "## " heading; images referenced as performance/NAME.png.
  std::string markdown;
  /// gnuplot commands (set terminal pngcairo / set output 'NAME.png' / plot ...), or empty.
  std::string gnuplot;
};

}  // namespace patchwork::performance
