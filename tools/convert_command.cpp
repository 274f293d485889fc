#include "tools/convert_command.h"

#include "core/errors.h"
#include "io/bpt.h"
#include "io/freeform_surfaces.h"
#include "io/gltf.h"
#include "io/mesh_file.h"
#include "tools/output_files.h"
#include "tools/patch_input.h"

namespace patchwork::tools {
namespace {

// Patches to BPT (polynomial ones only) or to free-form OBJ (a Bezier record per BPT patch; a
// free-form file written again as it was read).
void convert_patches(const std::string& input, const std::string& output) {
  if (lower_extension(output) == ".bpt") {
    const PatchSet set = read_patch_set(input);
    if (set.rational_count() > 0) {
      throw InvalidInput(detail::message(set.rational_count(), " of its ", set.count(),
                                         " Bezier patches are rational; BPT holds polynomial patches only"));
    }
    write_bpt(output, set.patches());
    return;
  }
  if (lower_extension(input) == ".obj") {
    write_obj_freeform(output, read_obj_freeform(input));
    return;
  }
  FreeformDocument document;
  const std::vector<BezierPatch3> patches = read_bpt(input);
  for (std::size_t k = 0; k < patches.size(); ++k) {
    document.surfaces.push_back(freeform_surface(patches[k], detail::message("patch", k)));
  }
  write_obj_freeform(output, document);
}

}  // namespace

void run_convert(const std::string& input, const std::string& output) {
  const std::string to = lower_extension(output);
  if ((to == ".bpt" || to == ".obj") && is_patch_file(input)) {
    convert_patches(input, output);
    return;
  }
  // The output's extension is checked before anything is read.
  check_mesh_output("convert", output);
  refuse_patch_file_as_mesh("convert to a mesh format", input);
  const FaceVertexMesh mesh = read_polygon_mesh(input);
  // What the mesh cannot be written as (a face that is not simple) is the input's fault: the
  // CLI names the input file before every library error (tools/patchwork.cpp).
  write_polygon_mesh(output, mesh);
}

}  // namespace patchwork::tools
