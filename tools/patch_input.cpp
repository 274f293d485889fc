#include "tools/patch_input.h"

#include "core/errors.h"

namespace patchwork::tools {

void refuse_patch_file_as_mesh(const std::string& command, const std::string& path) {
  if (is_patch_file(path)) {
    throw InvalidInput(detail::message(command, " reads meshes; this is a file of patches (curved surfaces): ",
                                       "'patchwork tessellate' makes a mesh of it"));
  }
}

}  // namespace patchwork::tools
