// analyze() on meshes whose every answer is known by hand (the worked examples of topology.h,
// seed Def 46-51 and Satz 19), non-manifold input, and the text and JSON forms of the report.

#include "meshes/topology.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

using namespace patchwork::testing;

TEST(Topology, Tetrahedron) {
  const TopologyReport r = analyze(tetrahedron());
  EXPECT_EQ(r.vertices, 4);
  EXPECT_EQ(r.edges, 6);
  EXPECT_EQ(r.faces, 4);
  EXPECT_EQ(r.euler, 2);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.boundary_loops, 0);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.orientable);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.edge_manifold);
  EXPECT_TRUE(r.vertex_manifold);
  EXPECT_EQ(r.genus, std::optional<Count>(0));
  ASSERT_EQ(r.per_component.size(), 1u);
  EXPECT_EQ(r.per_component[0].euler, 2);
  EXPECT_EQ(r.per_component[0].genus, std::optional<Count>(0));
  EXPECT_TRUE(r.non_orientable_cycles.empty());
}

TEST(Topology, SingleTriangleIsADisk) {
  const TopologyReport r = analyze(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}));
  EXPECT_EQ(r.euler, 1);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.genus, std::optional<Count>(0));  // (2 - 1 - 1) / 2
}

TEST(Topology, BoxAndPlateCountsFollowTheirClosedForms) {
  // A box of x by y by z unit quads: F = 2(xy + yz + zx), E = 2F (four edges per quad, two quads
  // per edge), V = F + 2 (chi = 2).
  for (const Resolution res : {Resolution{1, 1, 1}, Resolution{2, 3, 4}, Resolution{5, 1, 2}}) {
    const TopologyReport r = analyze(sphere(res).mesh);
    const Count F = 2 * (res.x * res.y + res.y * res.z + res.z * res.x);
    EXPECT_EQ(r.faces, F);
    EXPECT_EQ(r.edges, 2 * F);
    EXPECT_EQ(r.vertices, F + 2);
    EXPECT_EQ(r.genus, std::optional<Count>(0));
  }
  // The genus-g plate at resolution 1: 5g + 3 cells; top and bottom 2(5g + 3) quads, outer sides
  // 2((2g + 1) + 3), hole walls 4g: F = 18g + 14, E = 2F, V = F + 2 - 2g = 16g + 16.
  for (Count g = 0; g <= 5; ++g) {
    const TopologyReport r = analyze(genus_surface(static_cast<int>(g), {}).mesh);
    EXPECT_EQ(r.faces, 18 * g + 14) << g;
    EXPECT_EQ(r.edges, 2 * (18 * g + 14)) << g;
    EXPECT_EQ(r.vertices, 16 * g + 16) << g;
    EXPECT_EQ(r.euler, 2 - 2 * g) << g;
    EXPECT_EQ(r.genus, std::optional<Count>(g)) << g;
  }
}

TEST(Topology, TorusAnnulusAndMoebiusBand) {
  // The 3 x 3 quad torus: V = 9, E = 18, F = 9.
  const TopologyReport torus_report = analyze(torus(3, 3).mesh);
  EXPECT_EQ(torus_report.vertices, 9);
  EXPECT_EQ(torus_report.edges, 18);
  EXPECT_EQ(torus_report.faces, 9);
  EXPECT_EQ(torus_report.euler, 0);
  EXPECT_EQ(torus_report.genus, std::optional<Count>(1));
  // An open cylinder of 2 x 5 quads: V = 15, E = 25, F = 10, two boundary loops of 5 edges.
  const TopologyReport annulus_report = analyze(annulus(2, 5).mesh);
  EXPECT_EQ(annulus_report.vertices, 15);
  EXPECT_EQ(annulus_report.edges, 25);
  EXPECT_EQ(annulus_report.euler, 0);
  EXPECT_EQ(annulus_report.boundary_edges, 10);
  EXPECT_EQ(annulus_report.boundary_loops, 2);
  EXPECT_EQ(annulus_report.genus, std::optional<Count>(0));
  // The Moebius band of 1 x 3 quads: V = 6, E = 9, F = 3; one boundary loop of 6 edges.
  const TopologyReport band = analyze(mobius_band(1, 3).mesh);
  EXPECT_EQ(band.vertices, 6);
  EXPECT_EQ(band.edges, 9);
  EXPECT_EQ(band.euler, 0);
  EXPECT_EQ(band.boundary_edges, 6);
  EXPECT_EQ(band.boundary_loops, 1);
  EXPECT_FALSE(band.orientable);
  EXPECT_TRUE(band.manifold);
  EXPECT_FALSE(band.genus.has_value());
  ASSERT_EQ(band.per_component.size(), 1u);
  EXPECT_FALSE(band.per_component[0].genus.has_value());
  ASSERT_EQ(band.non_orientable_cycles.size(), 1u);
  // The band's three quads, each sharing an edge with the next: the cycle is all of them.
  EXPECT_EQ(band.non_orientable_cycles[0].size(), 3u);
}

TEST(Topology, ClosedNonOrientableSurfaces) {
  // Hemi-cube V=4 E=6 F=3; Klein bottle of 3 x 4 quads V=12 E=24 F=12; projective plane of a
  // 1 x 3 band (V=6 E=9 F=3) and a 6-triangle cap (V+1, E+6, F+6).
  const TopologyReport hemi = analyze(hemi_cube().mesh);
  EXPECT_EQ(hemi.vertices, 4);
  EXPECT_EQ(hemi.edges, 6);
  EXPECT_EQ(hemi.euler, 1);
  EXPECT_TRUE(hemi.closed);
  EXPECT_TRUE(hemi.manifold);
  EXPECT_FALSE(hemi.orientable);
  const TopologyReport klein = analyze(klein_bottle(3, 4).mesh);
  EXPECT_EQ(klein.vertices, 12);
  EXPECT_EQ(klein.edges, 24);
  EXPECT_EQ(klein.euler, 0);
  EXPECT_TRUE(klein.closed);
  EXPECT_FALSE(klein.orientable);
  EXPECT_TRUE(klein.manifold);
  const TopologyReport plane = analyze(projective_plane(1, 3).mesh);
  EXPECT_EQ(plane.vertices, 7);
  EXPECT_EQ(plane.edges, 15);
  EXPECT_EQ(plane.faces, 9);
  EXPECT_EQ(plane.euler, 1);
  EXPECT_TRUE(plane.closed);
  EXPECT_FALSE(plane.orientable);
  EXPECT_FALSE(plane.genus.has_value());
}

TEST(Topology, ComponentsAddUpAndIsolatedVerticesStandApart) {
  // Two tetrahedra and an unused position: chi = 4, genus 0 + 0, one isolated vertex.
  KnownSurface two = disjoint_union({"tetrahedron", tetrahedron(), 2, 0, 1, true, 0, std::nullopt},
                                    {"tetrahedron", tetrahedron(), 2, 0, 1, true, 0, std::nullopt});
  std::vector<Vec3> points = points_of(two.mesh);
  points.emplace_back(50, 50, 50);
  const TopologyReport r = analyze(make_mesh(points, faces_of(two.mesh)));
  EXPECT_EQ(r.vertices, 8);
  EXPECT_EQ(r.isolated_vertices, 1);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.euler, 4);
  EXPECT_EQ(r.genus, std::optional<Count>(0));
  // A sphere and a torus: genus 0 + 1.
  const TopologyReport mixed = analyze(disjoint_union(sphere({}), torus(3, 4)).mesh);
  EXPECT_EQ(mixed.components, 2);
  EXPECT_EQ(mixed.euler, 2);
  EXPECT_EQ(mixed.genus, std::optional<Count>(1));
}

TEST(Topology, EdgeWithThreeFaces) {
  // A book of three triangles on edge (0,1).
  const TopologyReport r = analyze(book());
  EXPECT_FALSE(r.edge_manifold);
  EXPECT_FALSE(r.manifold);
  ASSERT_EQ(r.non_manifold_edges.size(), 1u);
  EXPECT_EQ(r.non_manifold_edges[0], (std::array<std::uint32_t, 2>{0, 1}));
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.vertices - r.edges + r.faces, r.euler);
  EXPECT_EQ(r.euler, 5 - 7 + 3);
  EXPECT_FALSE(r.genus.has_value());
  ASSERT_EQ(r.per_component.size(), 1u);
  EXPECT_FALSE(r.per_component[0].manifold);
}

TEST(Topology, VertexWithTwoFans) {
  // A bowtie: triangles (0,1,2) and (0,3,4) touch at vertex 0 only. Touching at a vertex does not
  // connect: two components, each V=3 E=3 F=1 (vertex 0 counted in both, so 1 + 1 != chi = 1).
  const TopologyReport r = analyze(bowtie());
  EXPECT_TRUE(r.edge_manifold);
  EXPECT_FALSE(r.vertex_manifold);
  EXPECT_FALSE(r.manifold);
  EXPECT_EQ(r.non_manifold_vertices, std::vector<std::uint32_t>{0});
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.euler, 5 - 6 + 2);
  ASSERT_EQ(r.per_component.size(), 2u);
  for (const ComponentTopology& c : r.per_component) {
    EXPECT_EQ(c.vertices, 3);
    EXPECT_EQ(c.euler, 1);
    EXPECT_EQ(c.boundary_loops, 1);
    EXPECT_FALSE(c.manifold);
    EXPECT_FALSE(c.genus.has_value());
  }
  // Two closed fans at one vertex: two tetrahedra sharing vertex 0.
  const TopologyReport pinched = analyze(pinched_tetrahedra());
  EXPECT_EQ(pinched.non_manifold_vertices, std::vector<std::uint32_t>{0});
  EXPECT_TRUE(pinched.closed);
  EXPECT_EQ(pinched.euler, 7 - 12 + 8);
}

TEST(Topology, FaceRepeatingAVertex) {
  const TopologyReport r = analyze(make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 3, 0, 3}}));
  EXPECT_EQ(r.faces_repeating_a_vertex, std::vector<std::uint32_t>{1});
  EXPECT_FALSE(r.vertex_manifold);
  EXPECT_FALSE(r.manifold);
  EXPECT_FALSE(r.genus.has_value());
}

TEST(Topology, TextNamesEveryFact) {
  std::ostringstream out;
  out << analyze(mobius_band(1, 3).mesh);
  const std::string text = out.str();
  for (const char* line :
       {"vertices: 6", "edges: 9", "faces: 3", "components: 1", "boundary loops: 1", "closed: no", "orientable: no",
        "manifold: yes", "euler characteristic: 0", "genus: undefined", "non-orientable along faces"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << "\n" << text;
  }
}

TEST(Topology, JsonCarriesTheReport) {
  const auto document = nlohmann::json::parse(to_json(analyze(disjoint_union(torus(3, 4), sphere({})).mesh)));
  EXPECT_EQ(document.at("vertices"), 12 + 8);
  EXPECT_EQ(document.at("edges"), 24 + 12);
  EXPECT_EQ(document.at("faces"), 12 + 6);
  EXPECT_EQ(document.at("components"), 2);
  EXPECT_EQ(document.at("boundary_loops"), 0);
  EXPECT_EQ(document.at("closed"), true);
  EXPECT_EQ(document.at("orientable"), true);
  EXPECT_EQ(document.at("manifold"), true);
  EXPECT_EQ(document.at("euler"), 2);
  EXPECT_EQ(document.at("genus"), 1);
  ASSERT_EQ(document.at("per_component").size(), 2u);
  EXPECT_EQ(document.at("per_component")[0].at("genus"), 1);  // the torus has the smallest face
  EXPECT_EQ(document.at("per_component")[1].at("euler"), 2);
  const auto band = nlohmann::json::parse(to_json(analyze(mobius_band(1, 3).mesh)));
  EXPECT_TRUE(band.at("genus").is_null());
  EXPECT_EQ(band.at("orientable"), false);
  ASSERT_EQ(band.at("non_orientable_cycles").size(), 1u);
  EXPECT_EQ(band.at("non_orientable_cycles")[0].size(), 3u);
}

}  // namespace
}  // namespace patchwork
