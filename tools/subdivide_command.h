#pragma once
// `patchwork subdivide IN.(obj|off|ply) --scheme S --levels K -o OUT`: uniform subdivision
// through OpenSubdiv (subdivision/refine.h), written as a polygon mesh (glTF: faces triangulated,
// with normals); with --limit the limit surface tessellated within a tolerance instead
// (subdivision/limit_tessellator.h; relative tolerance 1e-3 unless a mode is given), a render-ready
// mesh like the teapot's.

#include <iosfwd>
#include <optional>
#include <string>

namespace patchwork::tools {

struct SubdivideArguments {
  std::string input;
  std::string output;
  std::string scheme = "catmull-clark";
  /// Default: 1, or 0 with --limit.
  std::optional<int> levels;
  /// none, edges or edges-and-corners.
  std::string boundary = "edges-and-corners";
  /// Edges whose faces meet at more than this angle (degrees) become infinitely sharp creases.
  std::optional<double> sharp_angle_degrees;
  bool limit = false;
  std::optional<double> tolerance;
  std::optional<double> relative_tolerance;
  std::optional<int> segments;
  int isolation_level = 4;
  bool json = false;
};

/// Runs the command; the summary goes to `out`, and to `notes` (stderr) one line each when faces
/// were flipped to orient the cage consistently (subdivision/orient_cage.h) or the cage is not
/// orientable (refined with its seams; --limit refuses it).
/// \throws InvalidInput for bad arguments or a cage that cannot be subdivided (TopologyError),
///         IoError/ParseError for bad files (nothing written).
void run_subdivide(std::ostream& out, std::ostream& notes, const SubdivideArguments& arguments);

}  // namespace patchwork::tools
