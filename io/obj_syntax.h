#pragma once
// What the two OBJ readers share (io/obj.cpp for polygons, io/obj_freeform.cpp for free-form
// geometry): vertex references and the set of free-form statements. Internal: not installed.
//
//   v          a vertex index: 1-based, or negative, relative: -1 is the last vertex so far
//   v/vt       with a texture coordinate index
//   v//vn      with a normal index
//   v/vt/vn    with both; every index written is a nonzero integer

#include <cstdint>
#include <string_view>

#include "io/mesh_file.h"

namespace patchwork::detail {

/// The indices of an OBJ vertex reference as written, 0 where a part is absent.
struct ObjReference {
  std::int64_t vertex = 0;
  std::int64_t texture = 0;
  std::int64_t normal = 0;
};

/// Parses a reference v, v/vt, v//vn or v/vt/vn; `what` names it in messages ("a face corner").
/// \throws ParseError at the token for any other form or a zero index.
ObjReference parse_obj_reference(const TextLines& reader, const TextToken& token, std::string_view what);

/// The 0-based index an OBJ index stands for among the `defined` elements read so far: a
/// positive index as it is (it may be >= defined: the caller checks forward references), a
/// negative one counted back from the last; `element` and `elements` name them in messages
/// ("vertex", "vertices"). \pre index != 0.
/// \throws ParseError at the token for a relative index before the first element.
std::int64_t resolve_obj_index(const TextLines& reader, const TextToken& token, std::int64_t index,
                               std::int64_t defined, std::string_view element, std::string_view elements);

/// Whether the keyword is a statement of OBJ's free-form geometry (cstype ... end, and the
/// connectivity, trimming and basis-matrix statements that go with it).
bool is_obj_freeform_statement(std::string_view keyword);

}  // namespace patchwork::detail
