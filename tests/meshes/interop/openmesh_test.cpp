// OpenMesh interop: exact round trips, OpenMesh's own counts and circulators against analyze(),
// refusals named by face. The topology on OpenMesh's side is computed here from its half-edge
// structure (boundary half-edges and their next() cycles, a face flood fill through edges,
// is_manifold per vertex), independently of meshes/topology.cpp.
//
// Where OpenMesh's conventions differ from ours: n_vertices() counts every vertex (ours only
// those used by a face), and at a bowtie vertex add_face links the two fans' boundaries into
// one cycle through the vertex twice, where we count a loop per fan.

#include "meshes/interop/openmesh.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "core/errors.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "tests/meshes/interop/grid_pieces.h"
#include "tests/meshes/interop/interop_test_meshes.h"

namespace patchwork {
namespace {

using test::crosscheck_meshes;
using test::NamedMesh;

// What OpenMesh's structure says, counted with OpenMesh's handles and circulators.
struct OpenMeshAnswers {
  Count isolated_vertices = 0;
  Count boundary_halfedges = 0;
  Count boundary_cycles = 0;             // cycles of next_halfedge_handle over boundary half-edges
  std::vector<std::uint32_t> component;  // per face: flood fill through ff_range, by smallest face
  Count components = 0;
  std::vector<std::uint32_t> non_manifold_vertices;  // !is_manifold(v)
};

OpenMeshAnswers ask_openmesh(const OpenMeshPolyMesh& om) {
  OpenMeshAnswers a;
  for (const auto v : om.vertices()) {
    if (om.is_isolated(v)) ++a.isolated_vertices;
    if (!om.is_manifold(v)) a.non_manifold_vertices.push_back(static_cast<std::uint32_t>(v.idx()));
  }
  std::vector<bool> seen(om.n_halfedges(), false);
  for (const auto h : om.halfedges()) {
    if (!om.is_boundary(h)) continue;
    ++a.boundary_halfedges;
    if (seen[static_cast<std::size_t>(h.idx())]) continue;
    ++a.boundary_cycles;
    auto g = h;
    do {
      seen[static_cast<std::size_t>(g.idx())] = true;
      g = om.next_halfedge_handle(g);
    } while (g != h);
  }
  constexpr std::uint32_t none = 0xffffffffu;
  a.component.assign(om.n_faces(), none);
  for (const auto f : om.faces()) {
    if (a.component[static_cast<std::size_t>(f.idx())] != none) continue;
    const auto number = static_cast<std::uint32_t>(a.components++);
    std::vector<OpenMeshPolyMesh::FaceHandle> stack{f};
    a.component[static_cast<std::size_t>(f.idx())] = number;
    while (!stack.empty()) {
      const auto g = stack.back();
      stack.pop_back();
      for (const auto neighbour : om.ff_range(g)) {
        if (a.component[static_cast<std::size_t>(neighbour.idx())] != none) continue;
        a.component[static_cast<std::size_t>(neighbour.idx())] = number;
        stack.push_back(neighbour);
      }
    }
  }
  return a;
}

// The faces as point sequences (first corner first), sorted: the mesh up to renumbering.
std::vector<std::vector<std::array<double, 3>>> faces_by_points(const FaceVertexMesh& mesh) {
  std::vector<std::vector<std::array<double, 3>>> faces;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    auto& points = faces.emplace_back();
    for (std::uint32_t v : mesh.face(f))
      points.push_back({mesh.position(v).x(), mesh.position(v).y(), mesh.position(v).z()});
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

TEST(OpenMeshInterop, RoundTripIsExact) {
  int checked = 0;
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    if (!test::add_face_accepts(c.mesh)) continue;
    const OpenMeshPolyMesh om = to_openmesh(c.mesh);
    // OpenMesh's own face circulator lists each face's corners as given, first corner first.
    ASSERT_EQ(om.n_faces(), c.mesh.face_count());
    for (std::size_t f = 0; f < c.mesh.face_count(); ++f) {
      std::vector<std::uint32_t> corners;
      for (const auto v : om.fv_range(om.face_handle(static_cast<int>(f))))
        corners.push_back(static_cast<std::uint32_t>(v.idx()));
      const auto face = c.mesh.face(f);
      EXPECT_EQ(corners, std::vector<std::uint32_t>(face.begin(), face.end())) << "face " << f;
    }
    const FaceVertexMesh back = from_openmesh(om);
    back.validate();
    EXPECT_EQ(back, c.mesh);
    ++checked;
  }
  EXPECT_EQ(checked, 10);  // every mesh but the book, the flipped cube and the Moebius bands
}

TEST(OpenMeshInterop, CountsAndTopologyMatchAnalyze) {
  for (const NamedMesh& c : crosscheck_meshes()) {
    SCOPED_TRACE(c.name);
    if (!test::add_face_accepts(c.mesh)) continue;
    const OpenMeshPolyMesh om = to_openmesh(c.mesh);
    const TopologyReport r = analyze(c.mesh);
    const OpenMeshAnswers a = ask_openmesh(om);
    EXPECT_EQ(static_cast<Count>(om.n_vertices()), r.vertices + r.isolated_vertices);
    EXPECT_EQ(a.isolated_vertices, r.isolated_vertices);
    EXPECT_EQ(static_cast<Count>(om.n_edges()), r.edges);
    EXPECT_EQ(static_cast<Count>(om.n_faces()), r.faces);
    EXPECT_EQ(static_cast<Count>(om.n_vertices() - om.n_edges() + om.n_faces()), r.euler + r.isolated_vertices);
    EXPECT_EQ(a.boundary_halfedges, r.boundary_edges);
    EXPECT_EQ(a.boundary_halfedges == 0, r.closed);
    EXPECT_EQ(a.components, r.components);
    EXPECT_EQ(a.component, face_components(c.mesh));
    EXPECT_EQ(a.non_manifold_vertices, r.non_manifold_vertices);
    if (r.manifold) {
      EXPECT_EQ(a.boundary_cycles, r.boundary_loops);
    } else {
      // The bowtie: one boundary cycle through vertex 0 twice in OpenMesh, a loop per fan for us.
      EXPECT_EQ(a.non_manifold_vertices, std::vector<std::uint32_t>{0});
      EXPECT_EQ(a.boundary_cycles, 1);
      EXPECT_EQ(r.boundary_loops, 2);
    }
  }
}

TEST(OpenMeshInterop, RefusedFacesAreNamed) {
  const auto message = [](const FaceVertexMesh& mesh) {
    return testing::error_message<TopologyError>([&] { to_openmesh(mesh); });
  };
  EXPECT_EQ(message(test::book()),
            "to_openmesh: OpenMesh cannot add face 2 (0 4 1): edge (1,0) is already walked from 1 to 0 by face 0 (an "
            "edge with three faces, or inconsistent orientation)");
  EXPECT_EQ(message(test::reversed(test::cube(), {0})),
            "to_openmesh: OpenMesh cannot add face 2 (0 1 5 4): edge (0,1) is already walked from 0 to 1 by face 0 (an "
            "edge with three faces, or inconsistent orientation)");
  // The band closes on its last quad, which walks the rung (1,0) as quad 0 does.
  EXPECT_EQ(message(test::moebius_band(8, 1)),
            "to_openmesh: OpenMesh cannot add face 7 (14 1 0 15): edge (1,0) is already walked from 1 to 0 by face 0 "
            "(an edge with three faces, or inconsistent orientation)");
  EXPECT_EQ(message(test::cone_with_extra_face()),
            "to_openmesh: OpenMesh cannot add face 4 (0 5 6): vertex 0 is already surrounded by faces (a non-manifold "
            "vertex)");
  // Checked before OpenMesh sees it (its add_face asserts on such a face).
  EXPECT_EQ(message(test::face_repeating_a_vertex()), "to_openmesh: face 0 (0 1 2 1) uses vertex 1 more than once");
}

TEST(OpenMeshInterop, DeletedElementsAreSkippedAndTheRestRenumbered) {
  OpenMeshPolyMesh om = to_openmesh(test::two_cubes());
  om.request_vertex_status();
  om.request_edge_status();
  om.request_halfedge_status();
  om.request_face_status();
  for (int f = 0; f < 6; ++f) om.delete_face(om.face_handle(f), true);
  const FaceVertexMesh expected = test::cube(Vec3(3, 0, 0));
  const FaceVertexMesh before_collection = from_openmesh(om);
  before_collection.validate();
  EXPECT_EQ(before_collection, expected);
  // Garbage collection fills the holes from the back, so it renumbers: the same faces by points.
  om.garbage_collection();
  ASSERT_EQ(om.n_vertices(), 8u);
  EXPECT_EQ(faces_by_points(from_openmesh(om)), faces_by_points(expected));
}

// Random pieces of a triangulated grid (with non-manifold vertices where pieces touch at a
// corner): to_openmesh takes every piece (a vertex never gets more triangles than its closed
// grid fan, so OpenMesh can always link the fans), keeps every face exactly and agrees with
// analyze(), non-manifold vertices included.
RC_GTEST_PROP(OpenMeshInterop, GridPiecesComeBackExactly, ()) {
  const FaceVertexMesh mesh = test::drawn_grid_pieces();
  const TopologyReport r = analyze(mesh);
  RC_TAG(r.manifold ? "manifold" : "non-manifold vertices");
  const OpenMeshPolyMesh om = to_openmesh(mesh);
  RC_ASSERT(from_openmesh(om) == mesh);
  const OpenMeshAnswers a = ask_openmesh(om);
  RC_ASSERT(static_cast<Count>(om.n_edges()) == r.edges);
  RC_ASSERT(a.boundary_halfedges == r.boundary_edges);
  RC_ASSERT(a.component == face_components(mesh));
  RC_ASSERT(a.non_manifold_vertices == r.non_manifold_vertices);
  if (r.manifold) RC_ASSERT(a.boundary_cycles == r.boundary_loops);
}

}  // namespace
}  // namespace patchwork
