#include "tools/convert_command.h"

#include "io/gltf.h"
#include "io/mesh_file.h"
#include "tools/output_files.h"

namespace patchwork::tools {

void run_convert(const std::string& input, const std::string& output) {
  // The output's extension is checked before anything is read.
  check_mesh_output("convert", output);
  const FaceVertexMesh mesh = is_gltf(input) ? welded_faces(read_gltf(input)) : read_mesh(input);
  // What the mesh cannot be written as (a face that is not simple) is the input's fault: the
  // CLI names the input file before every library error (tools/patchwork.cpp).
  write_polygon_mesh(output, mesh);
}

}  // namespace patchwork::tools
