#pragma once
// Files of patches: BPT files and OBJ files of free-form geometry (NURBS and Bezier surfaces,
// io/freeform_surfaces.h), read into one PatchSet. What the CLI's commands and the Python module
// take wherever they take a surface.

#include <filesystem>

#include "surfaces/patch_set.h"

namespace patchwork {

/// Whether `path` is a file of patches: a .bpt file, or a .obj file whose text holds free-form
/// statements (a polygon .obj is a mesh). \throws IoError if a .obj file cannot be read.
bool is_patch_file(const std::filesystem::path& path);

/// The patch set of a .bpt file, or of every surface of a free-form .obj file (each over its
/// range, joined where their edges meet).
/// \throws IoError, ParseError naming the file; InvalidInput for any other extension.
PatchSet read_patch_set(const std::filesystem::path& path);

}  // namespace patchwork
