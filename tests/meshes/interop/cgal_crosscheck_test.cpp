// Cross-checks of every topology answer of analyze() and orient() against CGAL on the same
// meshes, and the Surface_mesh / polygon soup conversions. The only CGAL test translation unit
// (CGAL headers are slow to compile on 2 cores).
//
// Where CGAL's conventions differ from ours, the tests pin the difference:
//   - CGAL::Polygon_mesh_processing::connected_components on a Surface_mesh joins faces through
//     edges, as we do; a Surface_mesh holds no edge with three faces, so the difference shows
//     after orient_polygon_soup, which cuts every non-manifold edge and duplicates every
//     non-manifold vertex: the book's three pages are 3 components there, 1 for us.
//   - Border cycles on a Surface_mesh follow next() around the outer face; at a bowtie vertex
//     add_face links the two fans' borders into one cycle through the vertex twice, where we
//     count two loops (one per component; our file comment leaves the pairing at a
//     non-manifold vertex arbitrary, and ours closes each loop at its start vertex).
//   - CGAL's num_vertices counts every vertex, our V only vertices used by a face:
//     chi_CGAL = chi + isolated_vertices; and CGAL::is_valid_polygon_mesh fails on an isolated
//     vertex (no half-edge), which a Surface_mesh and our FaceVertexMesh both hold.
//   - is_polygon_soup_a_polygon_mesh is stricter than "manifold": it also wants the faces
//     oriented as given (no edge walked twice in one direction). So it is true exactly when our
//     report says manifold and orientable and orient() flips no face, which is exactly when a
//     HalfedgeMesh can be built.
//   - orient_polygon_soup keeps the first polygon of each component and flips the rest to agree,
//     as orient() does, but reverses a polygon whole where we keep its first corner first. Its
//     result says whether it had to duplicate vertices: false on any non-manifold or
//     non-orientable soup (it cuts a Moebius band open), where our orient() leaves the vertices
//     alone and reports the component non-orientable with a cycle of faces.
//   - is_outward_oriented decides by the component holding the extreme vertex only; our
//     orient_outward() flips each closed component by the sign of its own signed volume.

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"
#include "meshes/halfedge_mesh.h"
#include "meshes/interop/cgal.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/meshes/interop/grid_pieces.h"
#include "tests/meshes/interop/interop_test_meshes.h"

namespace patchwork {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using test::crosscheck_meshes;
using test::NamedMesh;
using FaceIndex = CgalSurfaceMesh::Face_index;
using HalfedgeIndex = CgalSurfaceMesh::Halfedge_index;
using VertexIndex = CgalSurfaceMesh::Vertex_index;

// What CGAL says about a Surface_mesh, computed with CGAL's own functions and structure.
struct CgalAnswers {
  Count vertices;  // num_vertices: every vertex, isolated ones included
  Count isolated_vertices;
  Count edges;
  Count faces;
  bool closed;
  std::vector<std::uint32_t> component;  // per face, from PMP::connected_components
  Count components;
  Count border_halfedges;
  Count border_cycles;  // PMP::extract_boundary_cycles
  // Per component: vertices, edges, faces, border cycles (counted from the half-edges).
  std::vector<Count> component_vertices, component_edges, component_faces, component_cycles;
  std::vector<std::uint32_t> non_manifold_vertices;  // PMP::non_manifold_vertices, ascending
};

CgalAnswers ask_cgal(CgalSurfaceMesh sm) {
  CgalAnswers a{};
  a.vertices = static_cast<Count>(num_vertices(sm));
  a.edges = static_cast<Count>(num_edges(sm));
  a.faces = static_cast<Count>(num_faces(sm));
  for (VertexIndex v : sm.vertices()) a.isolated_vertices += sm.is_isolated(v) ? 1 : 0;
  a.closed = CGAL::is_closed(sm);
  auto fcm = sm.add_property_map<FaceIndex, std::size_t>("f:component", 0).first;
  a.components = static_cast<Count>(PMP::connected_components(sm, fcm));
  for (FaceIndex f : sm.faces()) a.component.push_back(static_cast<std::uint32_t>(fcm[f]));
  for (HalfedgeIndex h : sm.halfedges()) a.border_halfedges += sm.is_border(h) ? 1 : 0;
  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  a.border_cycles = static_cast<Count>(cycles.size());

  const auto c = static_cast<std::size_t>(a.components);
  a.component_vertices.assign(c, 0);
  a.component_edges.assign(c, 0);
  a.component_faces.assign(c, 0);
  a.component_cycles.assign(c, 0);
  for (FaceIndex f : sm.faces()) ++a.component_faces[fcm[f]];
  for (auto e : sm.edges()) {
    const HalfedgeIndex h = sm.halfedge(e);
    const FaceIndex f = sm.is_border(h) ? sm.face(sm.opposite(h)) : sm.face(h);
    ++a.component_edges[fcm[f]];
  }
  std::set<std::pair<std::size_t, std::size_t>> vertex_in_component;  // (vertex, component)
  for (HalfedgeIndex h : sm.halfedges()) {
    if (!sm.is_border(h)) vertex_in_component.emplace(static_cast<std::size_t>(sm.target(h)), fcm[sm.face(h)]);
  }
  for (const auto& [v, k] : vertex_in_component) ++a.component_vertices[k];
  for (HalfedgeIndex h : cycles) ++a.component_cycles[fcm[sm.face(sm.opposite(h))]];
  std::vector<HalfedgeIndex> umbrellas;  // one half-edge per fan of each non-manifold vertex
  PMP::non_manifold_vertices(sm, std::back_inserter(umbrellas));
  std::set<std::uint32_t> singular;
  for (HalfedgeIndex h : umbrellas) singular.insert(static_cast<std::uint32_t>(sm.target(h)));
  a.non_manifold_vertices.assign(singular.begin(), singular.end());
  return a;
}

// Whether two polygons are the same cycle up to rotation and reversal.
bool same_cycle_up_to_reversal(std::vector<std::uint32_t> a, std::vector<std::uint32_t> b) {
  if (a.size() != b.size()) return false;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t shift = 0; shift < a.size(); ++shift) {
      std::rotate(a.begin(), a.begin() + 1, a.end());
      if (a == b) return true;
    }
    std::reverse(a.begin(), a.end());
  }
  return false;
}

bool halfedge_mesh_builds(const FaceVertexMesh& mesh) {
  try {
    HalfedgeMesh(mesh).validate();
    return true;
  } catch (const TopologyError&) {
    return false;
  }
}

std::vector<std::uint32_t> as_indices(const std::vector<std::size_t>& polygon) {
  return {polygon.begin(), polygon.end()};
}

TEST(CgalCrosscheck, AnalyzeMatchesTheClosedForms) {
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    c.mesh.validate();
    const TopologyReport r = analyze(c.mesh);
    EXPECT_EQ(r.vertices, c.expected.vertices);
    EXPECT_EQ(r.edges, c.expected.edges);
    EXPECT_EQ(r.faces, c.expected.faces);
    EXPECT_EQ(r.components, c.expected.components);
    EXPECT_EQ(r.boundary_loops, c.expected.boundary_loops);
    EXPECT_EQ(r.closed, c.expected.closed);
    EXPECT_EQ(r.orientable, c.expected.orientable);
    EXPECT_EQ(r.manifold, c.expected.manifold);
    EXPECT_EQ(orient(c.mesh).flipped.empty(), c.expected.oriented);
  }
}

// is_polygon_soup_a_polygon_mesh(polygons) checks: no polygon with fewer than 3 corners or a
// repeated vertex, no directed edge (a, b) used twice (so at most two faces per edge, walking
// it in opposite directions: orientation as given, not mere orientability), no edge CGAL would
// have to cut, and no vertex whose faces form several fans. In our terms that is
// manifold && orientable && orient() flips nothing, the precondition of HalfedgeMesh.
TEST(CgalCrosscheck, PolygonSoupIsAPolygonMeshExactlyWhenOrientedManifold) {
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    const TopologyReport r = analyze(c.mesh);
    const bool ours = r.manifold && r.orientable && orient(c.mesh).flipped.empty();
    const CgalPolygonSoup soup = to_cgal_polygon_soup(c.mesh);
    EXPECT_EQ(PMP::is_polygon_soup_a_polygon_mesh(soup.polygons), ours);
    EXPECT_EQ(halfedge_mesh_builds(c.mesh), ours);
    EXPECT_EQ(ours, c.expected.manifold && c.expected.oriented);
  }
}

// On every mesh CGAL's add_face accepts: is_closed, connected_components (the partition, not
// only the count), border half-edges and cycles, Euler characteristic, and per component V, E,
// F and border cycles counted on CGAL's half-edges.
TEST(CgalCrosscheck, SurfaceMeshTopologyMatchesAnalyze) {
  int checked = 0;
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    const TopologyReport r = analyze(c.mesh);
    if (!test::add_face_accepts(c.mesh)) {
      EXPECT_THROW(to_cgal_surface_mesh(c.mesh), TopologyError);
      continue;
    }
    const CgalSurfaceMesh sm = to_cgal_surface_mesh(c.mesh);
    // CGAL's validity check wants a half-edge at every vertex: isolated vertices fail it.
    EXPECT_EQ(CGAL::is_valid_polygon_mesh(sm), r.isolated_vertices == 0);
    const CgalAnswers a = ask_cgal(sm);
    ++checked;
    EXPECT_EQ(a.vertices - a.isolated_vertices, r.vertices);
    EXPECT_EQ(a.isolated_vertices, r.isolated_vertices);
    EXPECT_EQ(a.edges, r.edges);
    EXPECT_EQ(a.faces, r.faces);
    EXPECT_EQ(a.vertices - a.edges + a.faces, r.euler + r.isolated_vertices);
    EXPECT_EQ(a.closed, r.closed);
    EXPECT_EQ(a.components, r.components);
    EXPECT_EQ(a.component, face_components(c.mesh));  // both number components by smallest face
    EXPECT_EQ(a.border_halfedges, r.boundary_edges);
    EXPECT_EQ(a.non_manifold_vertices, r.non_manifold_vertices);
    ASSERT_EQ(a.component_faces.size(), r.per_component.size());
    for (std::size_t k = 0; k < r.per_component.size(); ++k) {
      EXPECT_EQ(a.component_vertices[k], r.per_component[k].vertices) << "component " << k;
      EXPECT_EQ(a.component_edges[k], r.per_component[k].edges) << "component " << k;
      EXPECT_EQ(a.component_faces[k], r.per_component[k].faces) << "component " << k;
      EXPECT_EQ(a.component_vertices[k] - a.component_edges[k] + a.component_faces[k], r.per_component[k].euler);
    }
    if (r.manifold) {
      EXPECT_EQ(a.border_cycles, r.boundary_loops);
      for (std::size_t k = 0; k < r.per_component.size(); ++k) {
        EXPECT_EQ(a.component_cycles[k], r.per_component[k].boundary_loops) << "component " << k;
      }
    } else {
      // The bowtie: CGAL links both triangles' borders into one cycle through vertex 0.
      EXPECT_EQ(r.boundary_loops, 2);
      EXPECT_EQ(a.border_cycles, 1);
    }
  }
  EXPECT_EQ(checked, 10);  // every mesh but the book, the flipped cube and the Moebius bands
}

// orient_polygon_soup returns true when it needed no vertex duplication. On an orientable
// manifold it then orients like orient(): both keep the first face of each component and flip
// whatever disagrees with it, so the polygons agree face by face (CGAL reverses a polygon whole,
// we keep its first corner first: compare as cycles).
TEST(CgalCrosscheck, OrientPolygonSoupAgreesWithOrient) {
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    const TopologyReport r = analyze(c.mesh);
    CgalPolygonSoup soup = to_cgal_polygon_soup(c.mesh);
    const bool unchanged_vertices = PMP::orient_polygon_soup(soup.points, soup.polygons);
    EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(soup.polygons));  // CGAL's promise
    if (!(r.manifold && r.orientable)) {
      EXPECT_GT(soup.points.size(), c.mesh.vertex_count());
      EXPECT_FALSE(unchanged_vertices);
      continue;
    }
    EXPECT_TRUE(unchanged_vertices);
    const Orientation ours = orient(c.mesh);
    ASSERT_EQ(soup.polygons.size(), ours.mesh.face_count());
    for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
      const auto face = ours.mesh.face(f);
      EXPECT_TRUE(same_cycle_up_to_reversal(as_indices(soup.polygons[f]), {face.begin(), face.end()})) << "face " << f;
    }
    // Same cycle up to reversal does not say which way: both must walk every shared edge both
    // ways, and face 0 keeps its orientation in both.
    const FaceVertexMesh cgal_oriented = from_cgal_polygon_soup(soup);
    EXPECT_TRUE(halfedge_mesh_builds(cgal_oriented));
    const auto first = c.mesh.face(0);
    EXPECT_EQ(as_indices(soup.polygons[0]), std::vector<std::uint32_t>(first.begin(), first.end()));
  }
}

// What CGAL makes of the soups that are no polygon mesh: orient_polygon_soup cuts non-manifold
// edges and the edges where orientation conflicts, then duplicates the vertices whose faces no
// longer form one fan. Values from the construction of each mesh.
TEST(CgalCrosscheck, CgalCutsNonManifoldAndNonOrientableSoups) {
  struct Cut {
    FaceVertexMesh mesh;
    std::size_t points;  // after duplication
    Count components;
    Count euler;
    Count border_cycles;
  };
  const std::vector<std::pair<std::string, Cut>> cases = {
      // Each page keeps its own copy of the spine (0,1): 3 triangles apart, ours is 1 component.
      {"book", {test::book(), 9, 3, 3, 3}},
      // Vertex 0 is duplicated: 2 triangles, as our 2 components.
      {"bowtie", {test::bowtie(), 6, 2, 2, 2}},
      // The band cut open along its conflicting rung: a strip (a disk), chi 1, one border.
      {"moebius 8x1", {test::moebius_band(8, 1), 18, 1, 1, 1}},
  };
  for (const auto& [name, cut] : cases) {
    SCOPED_TRACE(name);
    CgalPolygonSoup soup = to_cgal_polygon_soup(cut.mesh);
    EXPECT_FALSE(PMP::orient_polygon_soup(soup.points, soup.polygons));
    EXPECT_EQ(soup.points.size(), cut.points);
    ASSERT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(soup.polygons));
    CgalSurfaceMesh sm;
    PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, sm);
    const CgalAnswers a = ask_cgal(sm);
    EXPECT_EQ(a.components, cut.components);
    EXPECT_EQ(a.vertices - a.edges + a.faces, cut.euler);
    EXPECT_EQ(a.border_cycles, cut.border_cycles);
    // Our analyze() of CGAL's result agrees with CGAL: it is a manifold now.
    const TopologyReport r = analyze(from_cgal(sm));
    EXPECT_TRUE(r.manifold);
    EXPECT_EQ(r.components, cut.components);
    EXPECT_EQ(r.euler, cut.euler);
    EXPECT_EQ(r.boundary_loops, cut.border_cycles);
  }
}

// Closed meshes: PMP::is_outward_oriented agrees with the sign of our signed_volume, holds after
// orient_outward() and fails after reversing every face; CGAL's volume equals ours.
TEST(CgalCrosscheck, OutwardOrientationMatchesSignedVolume) {
  int checked = 0;
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    const TopologyReport r = analyze(c.mesh);
    if (!r.closed || !r.manifold || !r.orientable) continue;
    const FaceVertexMesh outward = orient_outward(c.mesh).mesh;
    const double diagonal = (c.mesh.positions().colwise().maxCoeff() - c.mesh.positions().colwise().minCoeff()).norm();
    for (const auto& [label, mesh] : {std::pair{"outward", outward}, std::pair{"reversed", test::reversed(outward)}}) {
      SCOPED_TRACE(label);
      const FaceVertexMesh triangles = test::triangulated(mesh);
      const CgalSurfaceMesh sm = to_cgal_surface_mesh(triangles);
      const double volume = signed_volume(mesh);
      // For two cubes is_outward_oriented looks at the component with the extreme vertex only;
      // the volume sign covers both.
      EXPECT_EQ(PMP::is_outward_oriented(sm), volume > 0);
      EXPECT_EQ(std::string(label) == "outward", volume > 0);
      EXPECT_NEAR(PMP::volume(sm), volume, 1e-14 * std::pow(diagonal, 3));
    }
    if (c.expected.oriented) {
      const CgalSurfaceMesh input = to_cgal_surface_mesh(test::triangulated(c.mesh));
      EXPECT_EQ(PMP::is_outward_oriented(input), signed_volume(c.mesh) > 0);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 7);
}

// Random pieces of a triangulated grid (with non-manifold vertices where pieces touch at a
// corner): is_polygon_soup_a_polygon_mesh agrees with our report, and to_cgal_surface_mesh
// takes every piece (a vertex never gets more triangles than its closed grid fan, so CGAL can
// always link the fans), keeps every face exactly and agrees with analyze() on every answer.
RC_GTEST_PROP(CgalCrosscheck, GridPiecesAgreeWithAnalyze, ()) {
  const FaceVertexMesh mesh = test::drawn_grid_pieces();
  const TopologyReport r = analyze(mesh);
  RC_TAG(r.manifold ? "manifold" : "non-manifold vertices");
  RC_ASSERT(PMP::is_polygon_soup_a_polygon_mesh(to_cgal_polygon_soup(mesh).polygons) == r.manifold);
  const CgalSurfaceMesh sm = to_cgal_surface_mesh(mesh);
  RC_ASSERT(from_cgal(sm) == mesh);
  const CgalAnswers a = ask_cgal(sm);
  RC_ASSERT(a.edges == r.edges);
  RC_ASSERT(a.vertices - a.edges + a.faces == r.euler + r.isolated_vertices);
  RC_ASSERT(a.closed == r.closed);
  RC_ASSERT(a.component == face_components(mesh));
  RC_ASSERT(a.border_halfedges == r.boundary_edges);
  RC_ASSERT(a.non_manifold_vertices == r.non_manifold_vertices);
  for (std::size_t k = 0; k < r.per_component.size(); ++k) {
    RC_ASSERT(a.component_vertices[k] - a.component_edges[k] + a.component_faces[k] == r.per_component[k].euler);
  }
  if (r.manifold) RC_ASSERT(a.border_cycles == r.boundary_loops);
}

TEST(CgalInterop, RoundTripsAreExact) {
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(from_cgal_polygon_soup(to_cgal_polygon_soup(c.mesh)), c.mesh);
    if (!test::add_face_accepts(c.mesh)) continue;
    const FaceVertexMesh back = from_cgal(to_cgal_surface_mesh(c.mesh));
    back.validate();
    EXPECT_EQ(back, c.mesh);
  }
}

TEST(CgalInterop, RefusedFacesAreNamed) {
  const auto message = [](const FaceVertexMesh& mesh) {
    return testing::error_message<TopologyError>([&] { to_cgal_surface_mesh(mesh); });
  };
  EXPECT_EQ(message(test::book()),
            "to_cgal_surface_mesh: CGAL cannot add face 2 (0 4 1): edge (1,0) is already walked from 1 to 0 by face 0 "
            "(an edge with three faces, or inconsistent orientation)");
  // Face 0 flipped walks (0,1) as face 2 does.
  EXPECT_EQ(
      message(test::reversed(test::cube(), {0})),
      "to_cgal_surface_mesh: CGAL cannot add face 2 (0 1 5 4): edge (0,1) is already walked from 0 to 1 by face 0 "
      "(an edge with three faces, or inconsistent orientation)");
  EXPECT_EQ(message(test::cone_with_extra_face()),
            "to_cgal_surface_mesh: CGAL cannot add face 4 (0 5 6): vertex 0 is already surrounded by faces (a "
            "non-manifold vertex)");
  EXPECT_EQ(message(test::face_repeating_a_vertex()),
            "to_cgal_surface_mesh: CGAL cannot add face 0 (0 1 2 1): it uses vertex 1 more than once");
}

TEST(CgalInterop, RemovedElementsAreSkippedAndTheRestRenumbered) {
  CgalSurfaceMesh sm = to_cgal_surface_mesh(test::two_cubes());
  for (std::uint32_t f = 0; f < 6; ++f) CGAL::Euler::remove_face(sm.halfedge(FaceIndex(f)), sm);
  ASSERT_EQ(sm.number_of_removed_faces(), 6u);
  ASSERT_EQ(sm.number_of_removed_vertices(), 8u);
  const FaceVertexMesh back = from_cgal(sm);
  back.validate();
  EXPECT_EQ(back, test::cube(Vec3(3, 0, 0)));
}

}  // namespace
}  // namespace patchwork
