#pragma once
// `patchwork patches FILE [--json]`: reads a BPT patch set and prints its adjacency and
// continuity report (shared, open and collapsed edges, boundary loops, touching points, C^k and
// G^1 per shared edge), with the surface area and the pole normals found on the way.

#include <iosfwd>
#include <string>

namespace patchwork::tools {

/// Reads `path` and writes the report to `out`, as text or JSON. \throws on bad input.
void run_patches_report(std::ostream& out, const std::string& path, bool json);

}  // namespace patchwork::tools
