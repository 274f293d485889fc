#pragma once
// What the commands share about files of patches (reading them is io/patch_file.h).

#include <string>

#include "io/patch_file.h"  // read_patch_set and is_patch_file, which the commands use with this

namespace patchwork::tools {

/// \throws InvalidInput, saying to tessellate it, if `path` is a file of patches: for the
///         commands that read meshes (`command` names the one in the message).
void refuse_patch_file_as_mesh(const std::string& command, const std::string& path);

}  // namespace patchwork::tools
