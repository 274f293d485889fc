#pragma once
// `patchwork closest FILE X Y Z [--json]` and `patchwork raycast FILE --origin X,Y,Z
// --direction X,Y,Z [--json]`: the modeling queries (queries/) on any file `tessellate` reads.
//
// closest prints the distance, the foot point, its patch and (u, v), and the certified interval
// [lower, upper] that holds the true distance; JSON keys distance, point, patch, u, v, bound
// ([lower, upper]) and attained_more_than_once. raycast prints every hit in order along the ray;
// JSON {"hits": [{t, patch, u, v, point, normal, grazing}]}. Numbers are written so that they
// read back to the same double.

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

namespace patchwork::tools {

/// Reads `path` and writes the closest point of its surface to `point`. \throws on bad input.
void run_closest(std::ostream& out, const std::string& path, const std::array<double, 3>& point, bool json);

/// Reads `path` and writes every hit of the ray. \throws on bad input (a zero direction, too).
void run_raycast(std::ostream& out, const std::string& path, const std::vector<double>& origin,
                 const std::vector<double>& direction, bool json);

}  // namespace patchwork::tools
