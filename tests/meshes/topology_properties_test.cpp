// RapidCheck properties of analyze() (seed 3.1, Def 46-51, Satz 19 with b boundary loops): on
// surfaces whose chi, b, orientability and genus are known from their construction, and under
// every change that must not alter them (relabelling, face order, flips, edge flips, edge and
// face splits, subdivision).

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <tuple>

#include "core/errors.h"
#include "meshes/edge_list_mesh.h"
#include "meshes/halfedge_mesh.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/meshes/mesh_generators.h"
#include "tests/meshes/reference_topology.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

// Every answer of a report, components in a canonical order (their numbering follows face order).
struct Answers {
  std::tuple<Count, Count, Count, Count, Count, Count, Count, bool, bool, bool, std::optional<Count>> whole;
  std::vector<std::tuple<Count, Count, Count, Count, Count, bool, bool, std::optional<Count>>> components;
  bool operator==(const Answers&) const = default;
};

Answers answers(const TopologyReport& r) {
  Answers a{{r.vertices, r.edges, r.faces, r.isolated_vertices, r.components, r.boundary_loops, r.euler, r.closed,
             r.orientable, r.manifold, r.genus},
            {}};
  for (const ComponentTopology& c : r.per_component) {
    a.components.emplace_back(c.vertices, c.edges, c.faces, c.euler, c.boundary_loops, c.orientable, c.manifold,
                              c.genus);
  }
  std::sort(a.components.begin(), a.components.end());
  return a;
}

// Every answer analyze() gives for a mesh.
Answers topology_of(const FaceVertexMesh& mesh) { return answers(analyze(mesh)); }

// A random edge {a, b} of the mesh (as the corner pair of a random face).
std::pair<std::uint32_t, std::uint32_t> random_edge(const FaceVertexMesh& mesh, Random& random) {
  const auto face = mesh.face(random.below(mesh.face_count()));
  const std::size_t k = random.below(face.size());
  return {face[k], face[(k + 1) % face.size()]};
}

RC_GTEST_PROP(TopologyProperties, KnownSurfacesGetTheirAnswers, ()) {
  Random random(*seed());
  const KnownSurface surface = any_surface(random, 3);
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const TopologyReport report = analyze(mesh);
  // The generator's claims, checked from scratch first: chi = V - E + F and the boundary loops.
  const ElementCounts counts = count_elements(mesh);
  RC_ASSERT(counts.euler() == surface.euler);
  RC_ASSERT(reference_boundary_loops(mesh) == surface.boundary_loops);
  RC_ASSERT(report.vertices == counts.vertices);
  RC_ASSERT(report.edges == counts.edges);
  RC_ASSERT(report.faces == counts.faces);
  RC_ASSERT(report.isolated_vertices == 0);
  RC_ASSERT(report.euler == surface.euler);
  RC_ASSERT(report.boundary_loops == surface.boundary_loops);
  RC_ASSERT(report.closed == surface.closed());
  RC_ASSERT(report.components == surface.components);
  RC_ASSERT(report.orientable == surface.orientable);
  RC_ASSERT(report.manifold);
  RC_ASSERT(report.non_manifold_edges.empty());
  RC_ASSERT(report.non_manifold_vertices.empty());
  RC_ASSERT(report.faces_repeating_a_vertex.empty());
  RC_ASSERT(report.genus == surface.genus);
  // Boundary edges are the edges of exactly one face.
  Count single_use_edges = 0;
  for (const auto& [key, walks] : edge_walks(mesh)) single_use_edges += walks.size() == 1 ? 1 : 0;
  RC_ASSERT(report.boundary_edges == single_use_edges);
}

RC_GTEST_PROP(TopologyProperties, ChiIsTwoMinusTwoGenusMinusHolesPerOrientableComponent, ()) {
  Random random(*seed());
  KnownSurface surface = orientable_surface(random, 2);
  for (int extra = random_int(random, 0, 2); extra > 0; --extra) {
    surface = disjoint_union(surface, orientable_surface(random, 2), Vec3(0, 0, 50.0 * extra));
  }
  const TopologyReport report = analyze(scrambled(surface.mesh, random));
  RC_ASSERT(report.components == surface.components);
  Count genus = 0;
  for (const ComponentTopology& c : report.per_component) {
    RC_ASSERT(c.orientable);
    RC_ASSERT(c.genus.has_value());
    RC_ASSERT(*c.genus >= 0);
    RC_ASSERT(c.euler == 2 - 2 * *c.genus - c.boundary_loops);
    RC_ASSERT(c.euler == c.vertices - c.edges + c.faces);
    genus += *c.genus;
  }
  RC_ASSERT(report.genus == std::optional<Count>(genus));
  RC_ASSERT(report.genus == surface.genus);
}

RC_GTEST_PROP(TopologyProperties, AnswersSurviveRelabellingReorderingAndFlips, ()) {
  Random random(*seed());
  const KnownSurface surface = any_surface(random, 2);
  const Answers expected = topology_of(surface.mesh);
  RC_ASSERT(topology_of(scrambled(surface.mesh, random)) == expected);
  RC_ASSERT(topology_of(flip_faces(surface.mesh, random_flags(surface.mesh.face_count(), random))) == expected);
  RC_ASSERT(topology_of(relabel_vertices(surface.mesh, random_permutation(surface.mesh.vertex_count(), random))) ==
            expected);
}

RC_GTEST_PROP(TopologyProperties, AnswersSurviveEdgeAndFaceSplits, ()) {
  Random random(*seed());
  const KnownSurface surface = any_surface(random, 2);
  FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const Answers before = topology_of(mesh);
  ElementCounts expected = count_elements(mesh);
  for (int step = random_int(random, 1, 8); step > 0; --step) {
    switch (random.below(3)) {
      case 0: {  // one new vertex and one new edge: chi kept
        const auto [a, b] = random_edge(mesh, random);
        mesh = split_edge(mesh, a, b);
        expected.vertices += 1;
        expected.edges += 1;
        break;
      }
      case 1: {  // a k-gon into k triangles: V + 1, E + k, F + k - 1
        const std::size_t f = random.below(mesh.face_count());
        const auto k = static_cast<Count>(mesh.face(f).size());
        mesh = split_face_at_centre(mesh, f);
        expected.vertices += 1;
        expected.edges += k;
        expected.faces += k - 1;
        break;
      }
      default: {  // a quad into two triangles: E + 1, F + 1
        const auto split = split_quad(mesh, random.below(mesh.face_count()), random_int(random, 0, 1));
        if (!split) break;
        mesh = *split;
        expected.edges += 1;
        expected.faces += 1;
      }
    }
  }
  const ElementCounts counts = count_elements(mesh);
  RC_ASSERT(counts.vertices == expected.vertices);
  RC_ASSERT(counts.edges == expected.edges);
  RC_ASSERT(counts.faces == expected.faces);
  const Answers after = topology_of(mesh);
  // Components, boundary loops, chi, closedness, orientability, manifoldness and genus agree.
  RC_ASSERT(std::get<4>(after.whole) == std::get<4>(before.whole));
  RC_ASSERT(std::get<5>(after.whole) == std::get<5>(before.whole));
  RC_ASSERT(std::get<6>(after.whole) == surface.euler);
  RC_ASSERT(std::get<7>(after.whole) == std::get<7>(before.whole));
  RC_ASSERT(std::get<8>(after.whole) == surface.orientable);
  RC_ASSERT(std::get<9>(after.whole));
  RC_ASSERT(std::get<10>(after.whole) == surface.genus);
}

RC_GTEST_PROP(TopologyProperties, AnswersSurviveEdgeFlips, ()) {
  Random random(*seed());
  // Any surface but the hemi-cube, whose triangulation would repeat a triangle.
  KnownSurface surface = random.coin() ? orientable_surface(random, 2) : non_orientable_surface(random);
  surface = triangulated(surface.name == "hemi-cube" ? klein_bottle(3, 4) : surface, random);
  FaceVertexMesh mesh = surface.mesh;
  const Answers before = topology_of(mesh);
  int flips = 0;
  for (int attempt = 0; attempt < 20; ++attempt) {
    // A random interior edge: the two faces walking it.
    const auto walks = edge_walks(mesh);
    auto it = walks.begin();
    std::advance(it, random.below(walks.size()));
    if (it->second.size() != 2) continue;
    const auto flipped = flip_edge(mesh, it->second[0].face, it->second[1].face);
    if (!flipped) continue;
    mesh = *flipped;
    ++flips;
  }
  RC_TAG(flips > 0);
  // An edge flip keeps V, E and F, and every answer with them.
  RC_ASSERT(topology_of(mesh) == before);
}

RC_GTEST_PROP(TopologyProperties, AnswersSurviveSubdivision, ()) {
  Random random(*seed());
  const KnownSurface surface = any_surface(random, 2);
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const FaceVertexMesh finer = subdivided(mesh);
  const ElementCounts before = count_elements(mesh), after = count_elements(finer);
  const auto corners = static_cast<Count>(mesh.face_indices().size());
  // Catmull-Clark's counts: V' = V + E + F, E' = 2E + sum k, F' = sum k.
  RC_ASSERT(after.vertices == before.vertices + before.edges + before.faces);
  RC_ASSERT(after.edges == 2 * before.edges + corners);
  RC_ASSERT(after.faces == corners);
  const Answers coarse = topology_of(mesh), fine = topology_of(finer);
  RC_ASSERT(std::get<4>(fine.whole) == std::get<4>(coarse.whole));  // components
  RC_ASSERT(std::get<5>(fine.whole) == surface.boundary_loops);
  RC_ASSERT(std::get<6>(fine.whole) == surface.euler);
  RC_ASSERT(std::get<8>(fine.whole) == surface.orientable);
  RC_ASSERT(std::get<9>(fine.whole));
  RC_ASSERT(std::get<10>(fine.whole) == surface.genus);
}

RC_GTEST_PROP(TopologyProperties, NonOrientableInputsAreAlwaysDetected, ()) {
  Random random(*seed());
  KnownSurface surface = non_orientable_surface(random);
  if (random.coin()) surface = disjoint_union(orientable_surface(random, 1), surface);
  const FaceVertexMesh mesh = scrambled(surface.mesh, random);
  const TopologyReport report = analyze(mesh);
  RC_ASSERT(!report.orientable);
  RC_ASSERT(!report.genus.has_value());
  RC_ASSERT(report.euler == surface.euler);
  // Exactly one component is non-orientable, and its cycle proves it.
  RC_ASSERT(std::count_if(report.per_component.begin(), report.per_component.end(),
                          [](const ComponentTopology& c) { return !c.orientable; }) == 1);
  RC_ASSERT(report.non_orientable_cycles.size() == 1u);
  RC_ASSERT(proves_non_orientable(mesh, report.non_orientable_cycles[0]));
  // No flips make it buildable, whatever its faces' orientation.
  RC_ASSERT_THROWS_AS(HalfedgeMesh{mesh}, TopologyError);
  RC_ASSERT_THROWS_AS(EdgeListMesh{mesh}, TopologyError);
  RC_ASSERT_THROWS_AS(HalfedgeMesh{orient(mesh).mesh}, TopologyError);
}

RC_GTEST_PROP(TopologyProperties, FaceListEdgeListHalfedgeRoundTripPreservesEverything, ()) {
  Random random(*seed());
  const KnownSurface surface = orientable_surface(random, 2);
  const FaceVertexMesh mesh = orient(scrambled(surface.mesh, random)).mesh;
  const EdgeListMesh edges(mesh);
  edges.validate();
  const HalfedgeMesh halfedges = to_halfedge_mesh(edges);
  halfedges.validate();
  const FaceVertexMesh back = to_face_vertex_mesh(halfedges);
  back.validate();
  // The same faces with the same first corners, the same positions: equal as values.
  RC_ASSERT(to_face_vertex_mesh(edges) == mesh);
  RC_ASSERT(back == mesh);
  RC_ASSERT(topology_of(back) == topology_of(mesh));
  // And back again through the half-edge mesh's own edge list.
  RC_ASSERT(to_face_vertex_mesh(to_edge_list(halfedges)) == mesh);
  RC_ASSERT(halfedges.edge_count() == edges.edge_count());
  RC_ASSERT(static_cast<Count>(halfedges.edge_count()) == count_elements(mesh).edges);
}

// Pinched vertices (closed fans sharing a vertex), crowded edges, faces repeating a vertex,
// inconsistent orientation: on any soup, every answer is the element-by-element reference's.
RC_GTEST_PROP(TopologyProperties, EveryAnswerIsTheReferencesOnAnySoup, ()) {
  Random random(*seed());
  const FaceVertexMesh mesh = any_soup(random);
  const TopologyReport report = analyze(mesh);
  RC_CLASSIFY(!report.non_manifold_vertices.empty(), "non-manifold vertices");
  RC_CLASSIFY(!report.non_manifold_edges.empty(), "non-manifold edges");
  RC_CLASSIFY(!report.orientable, "non-orientable");
  RC_ASSERT(to_json(report) == to_json(reference_analyze(mesh)));
}

}  // namespace
}  // namespace patchwork
