#include "io/patch_file.h"

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/bpt.h"
#include "io/freeform_surfaces.h"
#include "io/mesh_file.h"
#include "io/obj_freeform.h"

namespace patchwork {

bool is_patch_file(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".bpt") return true;
  return extension == ".obj" && is_obj_freeform(read_file(path));
}

PatchSet read_patch_set(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".bpt") return PatchSet(read_bpt(path));
  if (extension == ".obj") return freeform_patch_set(read_obj_freeform(path));
  throw InvalidInput(detail::message("a file of patches is .bpt or free-form .obj, not '", extension, "'"));
}

}  // namespace patchwork
