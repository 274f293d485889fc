// libFuzzer target: face lists from arbitrary bytes (up to 12 vertices, 16 faces of 1 to 6
// corners, any indices) through the topology report, orientation and the half-edge structure:
// whatever analyze() calls a consistently oriented manifold must build, validate, and convert
// back to the same faces.

#include "meshes/halfedge_mesh.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader bytes(data, size);
  // Up to 12 vertices and 16 faces of 1 to 6 corners; one index past the vertices occurs.
  const fuzz::FaceListBytes list = fuzz::face_list(bytes, 1, 12, 0, 17, 1, 6, 1);
  fuzz::expect_documented_errors_only([&] {
    const FaceVertexMesh mesh(list.positions, list.sizes, list.indices);
    const TopologyReport report = analyze(mesh);
    const Orientation oriented = orient(mesh);
    PATCHWORK_FUZZ_CHECK(oriented.non_orientable_cycles.size() == report.non_orientable_cycles.size());
    if (!report.manifold || !report.orientable) return;
    const FaceVertexMesh& consistent = oriented.mesh;
    const HalfedgeMesh halfedges(consistent);
    halfedges.validate();
    PATCHWORK_FUZZ_CHECK(halfedges.face_count() == consistent.face_count());
    const TopologyReport again = analyze(to_face_vertex_mesh(halfedges));
    PATCHWORK_FUZZ_CHECK(again.euler == report.euler && again.boundary_loops == report.boundary_loops);
  });
  return 0;
}
