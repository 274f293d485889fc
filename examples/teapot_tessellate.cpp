// examples/teapot_tessellate.cpp: read Bezier patches, find their adjacency, tessellate them within a
// tolerance and write glTF. Usage: teapot_tessellate data/teapot.bpt teapot.glb
#include <exception>
#include <iostream>

#include "check.h"
#include "io/bpt.h"
#include "io/gltf.h"
#include "meshes/topology.h"
#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"

int main(int argc, char** argv) {
  using examples::check;
  if (argc != 3) {
    std::cerr << "usage: teapot_tessellate PATCHES.bpt OUT.glb\n";
    return 2;
  }
  try {
    // Adjacency comes from the geometry: edges with the same control points are shared.
    const patchwork::PatchSet set(patchwork::read_bpt(argv[1]));
    const patchwork::PatchSetReport facts = patchwork::report(set);
    std::cout << facts.patches << " patches, " << facts.shared_edges << " shared edges, " << facts.open_edges
              << " open edges, " << facts.boundary_loops << " boundary loops, lowest C^" << facts.min_ck << '\n';

    // Mesh and surface within 1e-3 of the surface's bounding-box diagonal of each other.
    patchwork::TessellationOptions options;
    options.relative_tolerance = 1e-3;
    const patchwork::Tessellation result = patchwork::tessellate(set, options);
    const patchwork::RenderMesh& mesh = result.mesh;
    std::cout << mesh.triangle_count() << " triangles, " << mesh.vertex_count() << " vertices; tolerance "
              << result.tolerance << ", a-priori bound " << result.error_bound << ", measured " << result.measured_error
              << '\n';
    check(result.error_bound <= result.tolerance, "the a-priori bound meets the tolerance");
    check(result.measured_error <= result.error_bound, "the measured error is within the bound");

    // Shared edges are welded, so the mesh has the patch set's boundary.
    const patchwork::TopologyReport topology = patchwork::analyze(patchwork::welded_faces(mesh));
    std::cout << "welded mesh: " << topology.components << " components, " << topology.boundary_loops
              << " boundary loops, chi " << topology.euler << '\n';
    check(topology.manifold && topology.orientable, "the welded mesh is an oriented manifold");
    check(static_cast<std::size_t>(topology.boundary_loops) == facts.boundary_loops,
          "the mesh has the patch set's boundary loops");

    // glTF stores floats, relative to the node's translation (the centre of the box): reading the
    // file back gives every position within the rounding bound write_gltf returns.
    const double rounding = patchwork::write_gltf(argv[2], mesh);
    const patchwork::RenderMesh back = patchwork::read_gltf(argv[2]);
    bool same = back.triangle_count() == mesh.triangle_count() && back.vertex_count() == mesh.vertex_count();
    for (std::size_t i = 0; same && i < mesh.vertex_count(); ++i) {
      same = (back.positions[i] - mesh.positions[i]).norm() <= rounding;
    }
    std::cout << "wrote " << argv[2] << ", positions within " << rounding << " of the mesh's\n";
    check(same, "the file reads back as the mesh, positions within the float rounding bound");
  } catch (const std::exception& error) {
    std::cerr << error.what() << '\n';
    return 1;
  }
  return examples::exit_code();
}
