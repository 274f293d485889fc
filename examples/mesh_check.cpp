// examples/mesh_check.cpp: build face lists, ask analyze() what they are, and walk a half-edge mesh.
#include <iostream>
#include <vector>

#include "check.h"
#include "core/errors.h"
#include "meshes/face_vertex_mesh.h"
#include "meshes/halfedge_mesh.h"
#include "meshes/topology.h"

namespace {

// The unit cube's corners, numbered as in data/cube.obj: the bottom square, then the top.
patchwork::Positions cube_corners() {
  patchwork::Positions positions(8, 3);
  positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return positions;
}

}  // namespace

int main() {
  using examples::check;
  using patchwork::FaceVertexMesh;
  // Six quads, counter-clockwise seen from outside: a closed surface of genus 0.
  const std::vector<std::uint32_t> quads = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
  const FaceVertexMesh cube = FaceVertexMesh::uniform(cube_corners(), 4, quads);
  const patchwork::TopologyReport report = patchwork::analyze(cube);
  std::cout << "cube: V " << report.vertices << ", E " << report.edges << ", F " << report.faces << ", chi "
            << report.euler << ", genus " << report.genus.value_or(-1) << '\n';
  check(report.vertices == 8 && report.edges == 12 && report.faces == 6, "V = 8, E = 12, F = 6");
  check(report.euler == 2 && report.genus == 0, "chi = V - E + F = 2 = 2 - 2g with g = 0");
  check(report.closed && report.orientable && report.manifold && report.components == 1,
        "one closed, orientable, manifold component");

  // A HalfedgeMesh exists only for an oriented manifold: building it is the check.
  const patchwork::HalfedgeMesh halfedges(cube);
  halfedges.validate();
  bool valence_three = true;
  for (std::uint32_t v = 0; v < halfedges.vertex_count(); ++v) {
    valence_three &= halfedges.vertex_neighbours(patchwork::VertexId(v)).size() == 3;
  }
  std::cout << "half-edge mesh: " << halfedges.halfedge_count() << " half-edges, neighbours of v0:";
  for (const patchwork::VertexId v : halfedges.vertex_neighbours(patchwork::VertexId(0))) std::cout << ' ' << v;
  std::cout << '\n';
  check(halfedges.edge_count() == 12 && valence_three, "12 edges, three at every corner");

  // Without its last face the box is open: one boundary loop, chi = 1, still genus 0.
  const std::vector<std::uint32_t> open_quads(quads.begin(), quads.end() - 4);
  const patchwork::TopologyReport open = patchwork::analyze(FaceVertexMesh::uniform(cube_corners(), 4, open_quads));
  std::cout << "open box: chi " << open.euler << ", boundary loops " << open.boundary_loops << '\n';
  check(!open.closed && open.boundary_loops == 1 && open.euler == 1 && open.genus == 0,
        "open box: one boundary loop, g = (2 - chi - b) / 2 = 0");

  // Three triangles on the edge (0, 1): analyze() explains, HalfedgeMesh refuses.
  const FaceVertexMesh fin = FaceVertexMesh::uniform(cube_corners(), 3, {0, 1, 2, 1, 0, 4, 0, 1, 7});
  const patchwork::TopologyReport fin_report = patchwork::analyze(fin);
  check(!fin_report.edge_manifold && fin_report.non_manifold_edges.size() == 1, "one edge with three faces");
  bool refused = false;
  try {
    const patchwork::HalfedgeMesh not_built(fin);
  } catch (const patchwork::TopologyError& error) {
    std::cout << "HalfedgeMesh refused: " << error.what() << '\n';
    refused = true;
  }
  check(refused, "HalfedgeMesh throws TopologyError on a non-manifold edge");
  return examples::exit_code();
}
