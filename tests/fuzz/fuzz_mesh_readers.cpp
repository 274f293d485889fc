// libFuzzer target: the OBJ, OFF and PLY readers on arbitrary bytes (the first byte picks the
// format). A mesh that parses must survive analyze(), HalfedgeMesh where it is a manifold, and a
// round trip through its own writer unchanged.

#include "io/obj.h"
#include "io/off.h"
#include "io/ply.h"
#include "meshes/halfedge_mesh.h"
#include "meshes/topology.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int format = data[0] % 3;
  const std::string_view text = fuzz::as_text(data + 1, size - 1);
  fuzz::expect_documented_errors_only([&] {
    const FaceVertexMesh mesh = format == 0 ? parse_obj(text, "fuzz.obj")
                                : format == 1 ? parse_off(text, "fuzz.off")
                                              : parse_ply(text, "fuzz.ply");
    mesh.validate();
    const TopologyReport report = analyze(mesh);
    if (report.manifold && report.orientable) {
      fuzz::expect_documented_errors_only([&] { HalfedgeMesh(mesh).validate(); });
    }
    // What the writer makes, the reader reads back as it was (an empty mesh has no OBJ form).
    if (mesh.vertex_count() == 0) return;
    const FaceVertexMesh back = format == 0 ? parse_obj(format_obj(mesh), "back.obj")
                                : format == 1 ? parse_off(format_off(mesh), "back.off")
                                              : parse_ply(format_ply(mesh, PlyFormat::binary_little_endian), "back.ply");
    PATCHWORK_FUZZ_CHECK(back == mesh);
  });
  return 0;
}
