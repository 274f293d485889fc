#pragma once
// What is this mesh? One report with every topological answer (seed 3.1, Def 41-51, Satz 19).
//
// Conventions (libigl and geometry-central differ on some of these; these are ours):
//   V   vertices referenced by at least one face (unreferenced rows of positions are counted
//       apart, as isolated_vertices, and belong to no component)
//   E   distinct undirected edges {a, b} of the faces
//   F   faces
//   chi = V - E + F, for the whole mesh and per component (a vertex shared by two components,
//       where they touch, counts in each of them, so the components' chi need not add up)
//   components: faces connected through shared edges (touching at a vertex does not connect)
//   boundary edge: used by exactly one face; boundary loops: the cycles the boundary edges form
//       (well defined on a manifold; at a non-manifold boundary vertex the pairing is arbitrary)
//   closed (Def 46): no boundary edge
//   orientable (Def 47): faces can be flipped so every edge with two faces is walked both ways
//   manifold: every edge has at most two faces, no face repeats a vertex, and the faces around
//       every vertex form a single fan (connected through edges at that vertex)
//   genus g = (2 - chi - b) / 2 per component with b boundary loops, defined for orientable
//       manifold components only (Satz 19 is b = 0: chi = 2 - 2g); the mesh's genus is the sum
//       over its components, undefined (nullopt) if any component's is.
// Worked examples: a tetrahedron V=4 E=6 F=4 chi=2 g=0 b=0; a single triangle chi=1 b=1 g=0;
// a quad-mesh torus chi=0 g=1; an open cylinder (annulus) chi=0 b=2 g=0; a Moebius band chi=0
// b=1, not orientable, genus undefined; two tetrahedra chi=4, 2 components, genus 0 + 0 = 0.

#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// The topology of one edge-connected component.
struct ComponentTopology {
  Count vertices;
  Count edges;
  Count faces;
  Count euler;
  Count boundary_loops;
  bool orientable;
  bool manifold;
  /// (2 - chi - b)/2 for an orientable manifold component, else nullopt.
  std::optional<Count> genus;
};

struct TopologyReport {
  Count vertices;
  Count edges;
  Count faces;
  Count isolated_vertices;
  Count components;
  Count boundary_edges;
  Count boundary_loops;
  bool closed;
  bool orientable;
  bool edge_manifold;
  bool vertex_manifold;
  bool manifold;
  Count euler;
  std::optional<Count> genus;
  std::vector<ComponentTopology> per_component;
  /// Edges with more than two faces, as vertex pairs.
  std::vector<std::array<std::uint32_t, 2>> non_manifold_edges;
  /// Vertices whose faces form more than one fan.
  std::vector<std::uint32_t> non_manifold_vertices;
  /// Faces that use a vertex more than once.
  std::vector<std::uint32_t> faces_repeating_a_vertex;
  /// One cycle of faces per non-orientable component (see orient()).
  std::vector<std::vector<FaceId>> non_orientable_cycles;
};

/// The topology of any face list (non-manifold input included), in O(corners + vertices) time.
TopologyReport analyze(const FaceVertexMesh& mesh);

/// The report as text, one fact per line.
std::ostream& operator<<(std::ostream& out, const TopologyReport& report);

/// The report as JSON with the keys vertices, edges, faces, components, boundary_loops, closed,
/// orientable, manifold, euler, genus (null where undefined), plus the non-manifold elements.
std::string to_json(const TopologyReport& report);

}  // namespace patchwork
