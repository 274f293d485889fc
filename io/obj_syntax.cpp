#include "io/obj_syntax.h"

#include <algorithm>
#include <array>
#include <iterator>

#include "core/errors.h"

namespace patchwork::detail {

ObjReference parse_obj_reference(const TextLines& reader, const TextToken& token, std::string_view what) {
  // Split "v", "v/vt", "v//vn" or "v/vt/vn" into its parts.
  std::array<std::string_view, 3> parts;
  std::size_t count = 0;
  std::string_view rest = token.text;
  while (true) {
    const std::size_t slash = rest.find('/');
    if (count == parts.size()) {
      reader.fail(token, message("expected ", what, " v, v/vt, v//vn or v/vt/vn, found ", quoted(token.text)));
    }
    parts[count++] = rest.substr(0, slash);
    if (slash == std::string_view::npos) break;
    rest.remove_prefix(slash + 1);
  }
  std::array<std::int64_t, 3> values{};
  for (std::size_t k = 0; k < count; ++k) {
    if (parts[k].empty() && k == 1 && count == 3) continue;  // v//vn
    if (!parse_integer(parts[k], values[k]) || values[k] == 0) {
      reader.fail(token, message("expected ", what, " v, v/vt, v//vn or v/vt/vn of nonzero integers, found ",
                                 quoted(token.text)));
    }
  }
  return {values[0], values[1], values[2]};
}

std::int64_t resolve_obj_index(const TextLines& reader, const TextToken& token, std::int64_t index,
                               std::int64_t defined, std::string_view element, std::string_view elements) {
  if (index > 0) return index - 1;
  if (index < -defined) {  // not -index > defined: -INT64_MIN overflows
    reader.fail(token, message("relative index ", index, " reaches before the first ", element, " (", defined, " ",
                               elements, " defined so far)"));
  }
  return defined + index;
}

bool is_obj_freeform_statement(std::string_view keyword) {
  static constexpr std::string_view statements[] = {"cstype", "deg",  "bmat", "step", "curv", "curv2", "surf",
                                                    "parm",   "trim", "hole", "scrv", "sp",   "end",   "con"};
  return std::find(std::begin(statements), std::end(statements), keyword) != std::end(statements);
}

}  // namespace patchwork::detail
