#pragma once
// The BPT text format for Bezier patch sets (R. Holmes' patchoff format, data/README.md):
//
//   32                  number of patches
//   3 3                 per patch: degrees n m
//   x y z               then (n+1)(m+1) points, the first index (u) varying fastest:
//   ...                 point k = i + (n+1) j is P_ij
//
// Reading is strict: every line holds exactly the numbers it should, numbers are finite,
// degrees are within [0, max_bpt_degree], and the patch count matches the data; anything else
// is a ParseError with the file, the line and column, and what was expected. Blank lines are
// skipped and '\r' counts as white space (Windows line endings read). A missing value is reported
// just after the last token before it (at the end of the data: after its last token). Nothing is
// allocated for a count before the data for it has been read.
// Writing uses the shortest decimal form that reads back to the same double, whole or not at all,
// and writes only what the reader accepts.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "surfaces/bezier_patch.h"

namespace patchwork {

/// The largest degree a BPT file may declare.
inline constexpr int max_bpt_degree = 64;

/// Parses BPT text; `name` is used in error messages. \throws ParseError.
std::vector<BezierPatch3> parse_bpt(std::string_view text, const std::string& name);

/// Reads a BPT file. \throws IoError if it cannot be read, ParseError if it is malformed.
std::vector<BezierPatch3> read_bpt(const std::filesystem::path& path);

/// The BPT text of the patches.
/// \throws InvalidInput if there is no patch or a degree exceeds max_bpt_degree (unreadable).
std::string format_bpt(std::span<const BezierPatch3> patches);

/// Writes a BPT file atomically. \throws InvalidInput as format_bpt (nothing written), IoError.
void write_bpt(const std::filesystem::path& path, std::span<const BezierPatch3> patches);

}  // namespace patchwork
