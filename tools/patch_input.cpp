#include "tools/patch_input.h"

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/bpt.h"
#include "io/freeform_surfaces.h"
#include "tools/output_files.h"

namespace patchwork::tools {

bool is_patch_file(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".bpt") return true;
  return extension == ".obj" && is_obj_freeform(read_file(path));
}

void refuse_patch_file_as_mesh(const std::string& command, const std::string& path) {
  if (is_patch_file(path)) {
    throw InvalidInput(detail::message(command, " reads meshes; this is a file of patches (curved surfaces): ",
                                       "'patchwork tessellate' makes a mesh of it"));
  }
}

PatchSet read_patch_set(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".bpt") return PatchSet(read_bpt(path));
  if (extension == ".obj") return freeform_patch_set(read_obj_freeform(path));
  throw InvalidInput(detail::message("a file of patches is .bpt or free-form .obj, not '", extension, "'"));
}

}  // namespace patchwork::tools
