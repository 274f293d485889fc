#pragma once
// What the commands share about files of patches: BPT files and OBJ files of free-form geometry
// (NURBS and Bezier surfaces, io/freeform_surfaces.h), read into one PatchSet.

#include <string>

#include "surfaces/patch_set.h"

namespace patchwork::tools {

/// Whether `path` is a file of patches: a .bpt file, or a .obj file whose text holds free-form
/// statements (a polygon .obj is a mesh). \throws IoError if a .obj file cannot be read.
bool is_patch_file(const std::string& path);

/// \throws InvalidInput, saying to tessellate it, if `path` is a file of patches: for the
///         commands that read meshes (`command` names the one in the message).
void refuse_patch_file_as_mesh(const std::string& command, const std::string& path);

/// The patch set of a .bpt file, or of every surface of a free-form .obj file (each over its
/// range, joined where their edges meet).
/// \throws IoError, ParseError naming the file; InvalidInput for any other extension.
PatchSet read_patch_set(const std::string& path);

}  // namespace patchwork::tools
