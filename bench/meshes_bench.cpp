// Half-edge construction plus whole-mesh topology on a 1M-triangle torus: patchwork against
// OpenMesh and CGAL's Surface_mesh, the same work in the same run.
//
//   patchwork  HalfedgeMesh(mesh) (validates manifoldness and orientation while building) +
//              analyze(mesh): V E F, chi, components, boundary edges and loops, closed,
//              orientable, manifold (edges and vertex fans), genus per component
//   OpenMesh   add_vertex/add_face from the same arrays (refusing what is not an oriented
//              manifold, as our constructor does) + boundary half-edges and their cycles,
//              face components by a flood fill through edges, is_manifold per vertex, chi
//   CGAL       Surface_mesh add_vertex/add_face from the same arrays + CGAL::is_closed,
//              PMP::connected_components, PMP::extract_boundary_cycles, border half-edges, chi
//
// The mesh (the cross-checks' 500 x 1000 quad torus split into 1,000,000 triangles) is built
// once, outside the timing. Items are triangles, so items/s compare directly. After the runs the
// program prints time(OpenMesh) / time(patchwork) and time(CGAL) / time(patchwork), in CPU and
// wall time: a ratio above 1 means patchwork is faster. patchwork_halfedge_only and
// patchwork_analyze_only split our time between the two steps. Each benchmark checks its answers
// (one component, closed, chi = 0) and reports an error instead of a time if they are wrong.
//
//   build/release/bench/meshes_bench                       (about 15 s on 2 cores)
//   build/release/bench/meshes_bench --benchmark_filter=cgal

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/boost/graph/helpers.h>
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "bench/timing_reporter.h"
#include "meshes/halfedge_mesh.h"
#include "meshes/interop/cgal.h"
#include "meshes/interop/openmesh.h"
#include "meshes/topology.h"
#include "tests/meshes/interop/interop_test_meshes.h"

namespace {

using patchwork::Count;
using patchwork::FaceVertexMesh;

constexpr std::uint32_t major_segments = 500;
constexpr std::uint32_t minor_segments = 1000;

const FaceVertexMesh& torus() {
  // The cross-checks' torus (R = 2, r = 1), each quad split into two triangles, normals out.
  static const FaceVertexMesh mesh = patchwork::test::torus(major_segments, minor_segments, true);
  return mesh;
}

// The answers every library must give on the torus.
struct Answers {
  Count euler;
  Count components;
  Count boundary_halfedges;
  Count boundary_loops;
  Count non_manifold_vertices;
};

bool expected(const Answers& a) {
  return a.euler == 0 && a.components == 1 && a.boundary_halfedges == 0 && a.boundary_loops == 0 &&
         a.non_manifold_vertices == 0;
}

void finish(benchmark::State& state, const Answers& answers) {
  if (!expected(answers)) state.SkipWithError("wrong topology for the torus");
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(torus().face_count()));
}

// --- patchwork ---------------------------------------------------------------------------

Answers patchwork_answers(const patchwork::TopologyReport& r) {
  return {r.euler, r.components, r.boundary_edges, r.boundary_loops,
          static_cast<Count>(r.non_manifold_vertices.size() + r.non_manifold_edges.size())};
}

void patchwork_halfedge_and_analyze(benchmark::State& state) {
  const FaceVertexMesh& mesh = torus();
  Answers answers{};
  for (auto _ : state) {
    const patchwork::HalfedgeMesh halfedges(mesh);
    const patchwork::TopologyReport report = patchwork::analyze(mesh);
    benchmark::DoNotOptimize(halfedges.halfedge_count());
    answers = patchwork_answers(report);
    if (report.genus != 1 || !report.orientable || !report.closed) answers.components = -1;
  }
  finish(state, answers);
}

void patchwork_halfedge_only(benchmark::State& state) {
  const FaceVertexMesh& mesh = torus();
  for (auto _ : state) {
    const patchwork::HalfedgeMesh halfedges(mesh);
    benchmark::DoNotOptimize(halfedges.halfedge_count());
  }
  finish(state, patchwork_answers(patchwork::analyze(mesh)));
}

void patchwork_analyze_only(benchmark::State& state) {
  const FaceVertexMesh& mesh = torus();
  Answers answers{};
  for (auto _ : state) answers = patchwork_answers(patchwork::analyze(mesh));
  finish(state, answers);
}

// --- OpenMesh ----------------------------------------------------------------------------

using OmMesh = patchwork::OpenMeshPolyMesh;

Answers openmesh_topology(const OmMesh& om) {
  Answers a{};
  a.euler = static_cast<Count>(om.n_vertices()) - static_cast<Count>(om.n_edges()) + static_cast<Count>(om.n_faces());
  std::vector<bool> seen(om.n_halfedges(), false);
  for (const auto h : om.halfedges()) {
    if (!om.is_boundary(h)) continue;
    ++a.boundary_halfedges;
    if (seen[static_cast<std::size_t>(h.idx())]) continue;
    ++a.boundary_loops;
    auto g = h;
    do {
      seen[static_cast<std::size_t>(g.idx())] = true;
      g = om.next_halfedge_handle(g);
    } while (g != h);
  }
  std::vector<bool> reached(om.n_faces(), false);
  std::vector<OmMesh::FaceHandle> stack;
  for (const auto f : om.faces()) {
    if (reached[static_cast<std::size_t>(f.idx())]) continue;
    ++a.components;
    reached[static_cast<std::size_t>(f.idx())] = true;
    stack.push_back(f);
    while (!stack.empty()) {
      const auto g = stack.back();
      stack.pop_back();
      for (const auto neighbour : om.ff_range(g)) {
        if (reached[static_cast<std::size_t>(neighbour.idx())]) continue;
        reached[static_cast<std::size_t>(neighbour.idx())] = true;
        stack.push_back(neighbour);
      }
    }
  }
  for (const auto v : om.vertices()) a.non_manifold_vertices += om.is_manifold(v) ? 0 : 1;
  return a;
}

void openmesh_build_and_topology(benchmark::State& state) {
  const FaceVertexMesh& mesh = torus();
  const auto& positions = mesh.positions();
  const auto& indices = mesh.face_indices();
  Answers answers{};
  for (auto _ : state) {
    OmMesh om;
    om.reserve(mesh.vertex_count(), indices.size() / 2, mesh.face_count());
    std::vector<OmMesh::VertexHandle> vertices;
    vertices.reserve(mesh.vertex_count());
    for (Eigen::Index v = 0; v < positions.rows(); ++v) {
      vertices.push_back(om.add_vertex(OmMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2))));
    }
    bool refused = false;
    for (std::size_t c = 0; c < indices.size(); c += 3) {
      refused |= !om.add_face(vertices[indices[c]], vertices[indices[c + 1]], vertices[indices[c + 2]]).is_valid();
    }
    answers = openmesh_topology(om);
    if (refused) answers.components = -1;
  }
  finish(state, answers);
}

// --- CGAL Surface_mesh -------------------------------------------------------------------

using Sm = patchwork::CgalSurfaceMesh;

Answers cgal_topology(Sm& sm) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  Answers a{};
  a.euler =
      static_cast<Count>(num_vertices(sm)) - static_cast<Count>(num_edges(sm)) + static_cast<Count>(num_faces(sm));
  const bool closed = CGAL::is_closed(sm);
  auto component = sm.add_property_map<Sm::Face_index, std::size_t>("f:component", 0).first;
  a.components = static_cast<Count>(PMP::connected_components(sm, component));
  sm.remove_property_map(component);
  for (const auto h : sm.halfedges()) a.boundary_halfedges += sm.is_border(h) ? 1 : 0;
  std::vector<Sm::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  a.boundary_loops = static_cast<Count>(cycles.size());
  // The answer CGAL has for non-manifold vertices (a vertex on the border more than once).
  for (const auto v : sm.vertices()) {
    Count border = 0;
    for (const auto h : CGAL::halfedges_around_target(v, sm)) border += sm.is_border(h) ? 1 : 0;
    a.non_manifold_vertices += border > 1 ? 1 : 0;
  }
  if (closed != (a.boundary_halfedges == 0)) a.components = -1;
  return a;
}

void cgal_build_and_topology(benchmark::State& state) {
  const FaceVertexMesh& mesh = torus();
  const auto& positions = mesh.positions();
  const auto& indices = mesh.face_indices();
  Answers answers{};
  for (auto _ : state) {
    Sm sm;
    sm.reserve(static_cast<Sm::size_type>(mesh.vertex_count()), static_cast<Sm::size_type>(indices.size() / 2),
               static_cast<Sm::size_type>(mesh.face_count()));
    for (Eigen::Index v = 0; v < positions.rows(); ++v)
      sm.add_vertex(patchwork::CgalPoint(positions(v, 0), positions(v, 1), positions(v, 2)));
    bool refused = false;
    for (std::size_t c = 0; c < indices.size(); c += 3) {
      refused |= sm.add_face(Sm::Vertex_index(indices[c]), Sm::Vertex_index(indices[c + 1]),
                             Sm::Vertex_index(indices[c + 2])) == Sm::null_face();
    }
    answers = cgal_topology(sm);
    if (refused) answers.components = -1;
  }
  finish(state, answers);
}

// Three timed iterations each: one iteration is 0.3 to 3 s of work, and the ratios need no more.
BENCHMARK(patchwork_halfedge_and_analyze)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(openmesh_build_and_topology)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(cgal_build_and_topology)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(patchwork_halfedge_only)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(patchwork_analyze_only)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// CPU time is the fairer measure on a shared machine (each benchmark runs on one thread);
// wall time is printed beside it.
void print_ratios(const patchwork::bench::TimingReporter& timing, std::ostream& out) {
  const auto* ours = timing.find("patchwork_halfedge_and_analyze");
  if (ours == nullptr) return;
  out << "\nTime per 1M-triangle build + topology relative to patchwork (above 1: patchwork is faster)\n"
      << "  " << std::left << std::setw(30) << ""
      << " cpu ratio  wall ratio   cpu seconds (other / patchwork)\n";
  for (const char* other : {"openmesh_build_and_topology", "cgal_build_and_topology"}) {
    const auto* it = timing.find(other);
    if (it == nullptr) continue;
    out << "  " << std::left << std::setw(30) << other << std::right << std::fixed << std::setprecision(3)
        << std::setw(10) << it->cpu / ours->cpu << std::setw(12) << it->wall / ours->wall
        << std::setw(10) << it->cpu << " / " << ours->cpu << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  return patchwork::bench::run_benchmarks(argc, argv, [](const patchwork::bench::TimingReporter& timing) {
    print_ratios(timing, std::cout);
  });
}
