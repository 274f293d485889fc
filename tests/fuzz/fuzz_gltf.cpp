// libFuzzer target: the glTF reader (.glb bytes, or JSON text when they do not start with the
// GLB magic) on arbitrary bytes; a mesh that parses must pass validate().

#include "io/gltf.h"
#include "meshes/render_mesh.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool glb = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  fuzz::expect_documented_errors_only([&] {
    const RenderMesh mesh = parse_gltf(fuzz::as_text(data, size), glb ? "fuzz.glb" : "fuzz.gltf");
    validate(mesh);
  });
  return 0;
}
