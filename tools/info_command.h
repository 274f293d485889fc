#pragma once
// `patchwork info FILE [--json]`: the topology of a mesh file (OBJ, OFF, PLY): V, E, F,
// components, boundary loops, closed, orientable, manifold, chi, genus (null where undefined),
// and the non-manifold elements if any.

#include <iosfwd>
#include <string>

namespace patchwork::tools {

/// Reads `path` and writes its topology report to `out`. \throws on unreadable or bad input.
void run_info(std::ostream& out, const std::string& path, bool json);

}  // namespace patchwork::tools
