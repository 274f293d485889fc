// Uniform subdivision of a 10,000-quad torus cage to levels 3 and 4: patchwork's refine_uniform
// (OpenSubdiv inside) against OpenMesh's uniform subdividers, the same cage in the same run.
//
//   Catmull-Clark  refine_uniform, scheme catmull_clark   vs  CatmullClarkT on a PolyMesh
//   Loop           refine_uniform, scheme loop            vs  LoopT on a TriMesh
//
// The cage is the cross-checks' 100 x 100 quad torus (R = 2, r = 1); Loop gets the same grid
// with each quad split along its diagonal (a, c): 20,000 triangles, every vertex of valence 6.
// Level k has 10,000 * 4^k quads (Catmull-Clark) or 20,000 * 4^k triangles (Loop).
//
// What each benchmark times (per iteration):
//
//   patchwork_refine     the whole refine_uniform(cage, level) call, which is what a user gets:
//                        validate_cage, the OpenSubdiv topology refinement (full topology in the
//                        last level only when the cage has tags), positions level by level, the
//                        level-k FaceVertexMesh and tags, the TopologyReport of the result
//                        (analyze() of the cage and refined_topology(): the closed forms), and
//                        freeing it all
//   openmesh_subdivide   attach + subdivide(level) + detach of a Subdivider on a fresh copy of
//                        the cage as an OpenMesh mesh, and freeing the refined mesh. The copy is
//                        made with the timer paused: OpenMesh refines in place, refine_uniform
//                        leaves its input alone and returns a new mesh, so each side is timed
//                        from "cage in memory" to "refined mesh in memory, then freed"
//   patchwork_report_only  what a report by analyze() of the level-k result would cost (refine_uniform
//                        derives it from the cage's instead): the part OpenMesh does not do
//   openmesh_end_to_end  excludes nothing on the OpenMesh side either: FaceVertexMesh cage in,
//                        FaceVertexMesh out, as refine_uniform takes and returns it. to_openmesh
//                        (plus TriMesh::assign for Loop) + subdivide + reading the result back
//                        (from_openmesh; for the TriMesh a loop of the same shape below, since
//                        from_openmesh takes the PolyMesh type)
//
// faces/s is output faces over wall time. After the runs the program prints, for each scheme
// and level, faces/s(patchwork) / faces/s(OpenMesh) = time(OpenMesh) / time(patchwork), in CPU
// and wall time: above 1 means patchwork is faster.
//
// Before a configuration is timed, its results are checked once (untimed): patchwork and OpenMesh
// must give the same number of faces and vertices, and the same points (every point of each side
// within 1e-9 x bbox diagonal of a point of the other side, so also the same bounding box). The
// torus has no boundary, so the known differences do not arise: OpenMesh's CatmullClarkT moves a
// boundary vertex to the mean of itself and its two boundary edge midpoints, (4v + v1 + v2) / 6,
// and has no creases or corners (its crease weights stay 0); OpenSubdiv uses the B-spline rule
// (6v + v1 + v2) / 8 and keeps corners of valence 2 (BoundaryInterpolation::edges_and_corners).
// On closed meshes both use the textbook Catmull-Clark and Loop rules (Loop's weights for any
// valence: alpha(n) = 5/8 - (3/8 + cos(2 pi / n) / 4)^2), so the points agree up to rounding.
// A failed check reports an error instead of a time.
//
// At these sizes a large share of both sides' time is the kernel handing out fresh pages (page
// faults), so the times depend on the heap that earlier benchmarks left behind: compare numbers
// from one run of the whole program (whose order is fixed), preferably with repetitions.
//
//   build/release/bench/subdivision_bench                        (about 40 s on 2 cores)
//   build/release/bench/subdivision_bench --benchmark_filter=loop/
//   build/release/bench/subdivision_bench --benchmark_repetitions=3   (ratios from the medians)

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench/timing_reporter.h"
#include "meshes/interop/openmesh.h"
#include "meshes/topology.h"
#include "subdivision/cage.h"
#include "subdivision/refine.h"
#include "tests/meshes/interop/interop_test_meshes.h"

namespace {

using patchwork::Count;
using patchwork::FaceVertexMesh;
using patchwork::SubdivisionCage;
using patchwork::SubdivisionScheme;
using patchwork::Vec3;

constexpr std::uint32_t major_segments = 100;
constexpr std::uint32_t minor_segments = 100;
constexpr int levels[] = {3, 4};

const SubdivisionCage& cage(SubdivisionScheme scheme) {
  const auto make = [](bool triangles, SubdivisionScheme s) {
    SubdivisionCage c;
    c.mesh = patchwork::test::torus(major_segments, minor_segments, triangles);
    c.options.scheme = s;
    return c;
  };
  static const SubdivisionCage quads = make(false, SubdivisionScheme::catmull_clark);
  static const SubdivisionCage triangles = make(true, SubdivisionScheme::loop);
  return scheme == SubdivisionScheme::loop ? triangles : quads;
}

std::int64_t output_faces(SubdivisionScheme scheme, int level) {
  return patchwork::refined_face_count(cage(scheme).mesh, scheme, level);
}

// --- OpenMesh, one side per scheme ----------------------------------------------------------

using OmPoly = patchwork::OpenMeshPolyMesh;
using OmTri = OpenMesh::TriMesh_ArrayKernelT<patchwork::OpenMeshTraits>;

struct CatmullClarkSide {
  static constexpr SubdivisionScheme scheme = SubdivisionScheme::catmull_clark;
  using Mesh = OmPoly;
  using Subdivider = OpenMesh::Subdivider::Uniform::CatmullClarkT<OmPoly>;
  static Mesh build(const FaceVertexMesh& mesh) { return patchwork::to_openmesh(mesh); }
  static FaceVertexMesh read(const Mesh& om) { return patchwork::from_openmesh(om); }
};

struct LoopSide {
  static constexpr SubdivisionScheme scheme = SubdivisionScheme::loop;
  using Mesh = OmTri;
  using Subdivider = OpenMesh::Subdivider::Uniform::LoopT<OmTri>;
  // to_openmesh builds the PolyMesh (checking the faces); assign keeps the numbering (and would
  // fan-triangulate other polygons: the cage has triangles only).
  static Mesh build(const FaceVertexMesh& mesh) {
    Mesh om;
    om.assign(patchwork::to_openmesh(mesh));
    return om;
  }
  // from_openmesh for the TriMesh type: vertices and faces in handle order, each face from the
  // target of its stored half-edge (a fresh subdivided mesh has nothing deleted).
  static FaceVertexMesh read(const Mesh& om) {
    patchwork::Positions positions(static_cast<Eigen::Index>(om.n_vertices()), 3);
    for (const auto v : om.vertices()) {
      const auto& p = om.point(v);
      positions.row(v.idx()) << p[0], p[1], p[2];
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * om.n_faces());
    for (const auto f : om.faces()) {
      for (const auto v : om.fv_range(f)) indices.push_back(static_cast<std::uint32_t>(v.idx()));
    }
    return FaceVertexMesh::uniform(std::move(positions), 3, std::move(indices));
  }
};

template <class Side>
const typename Side::Mesh& openmesh_cage() {
  static const typename Side::Mesh mesh = Side::build(cage(Side::scheme).mesh);
  return mesh;
}

// Refines `mesh` in place: what openmesh_subdivide times.
template <class Side>
void openmesh_refine(typename Side::Mesh& mesh, int level) {
  typename Side::Subdivider subdivider;
  subdivider.attach(mesh);
  subdivider(static_cast<std::size_t>(level));
  subdivider.detach();
}

// --- the untimed check ----------------------------------------------------------------------

std::vector<Vec3> points_of(const FaceVertexMesh& mesh) {
  std::vector<Vec3> points(mesh.vertex_count());
  for (std::size_t v = 0; v < points.size(); ++v) points[v] = mesh.position(v);
  return points;
}

template <class Mesh>
std::vector<Vec3> points_of(const Mesh& om) {
  std::vector<Vec3> points;
  points.reserve(om.n_vertices());
  for (const auto v : om.vertices()) points.emplace_back(om.point(v)[0], om.point(v)[1], om.point(v)[2]);
  return points;
}

// The largest distance from a point of `from` to the nearest point of `to`, infinite if some
// point has none within `reach`. The points of `to` are hashed by cells of size 64 * reach into
// chained buckets (two flat arrays; a collision only adds candidates), so a query looks at one
// cell, or at two to eight near a cell border.
double farthest_nearest(const std::vector<Vec3>& from, const std::vector<Vec3>& to, double reach) {
  constexpr std::uint32_t none = UINT32_MAX;
  const double size = 64 * reach;
  const std::size_t mask = std::bit_ceil(2 * to.size()) - 1;
  const auto cell = [size](double c) { return static_cast<std::uint64_t>(std::llround(std::floor(c / size))); };
  const auto bucket = [mask](std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    std::uint64_t h = x * 0x9e3779b97f4a7c15ull ^ y * 0xbf58476d1ce4e5b9ull ^ z * 0x94d049bb133111ebull;
    h ^= h >> 31;  // splitmix64's finaliser: the low bits depend on all three cells
    h *= 0xbf58476d1ce4e5b9ull;
    return static_cast<std::size_t>(h ^ (h >> 29)) & mask;
  };
  std::vector<std::uint32_t> head(mask + 1, none);
  std::vector<std::uint32_t> next(to.size(), none);
  for (std::uint32_t k = 0; k < to.size(); ++k) {
    const std::size_t b = bucket(cell(to[k].x()), cell(to[k].y()), cell(to[k].z()));
    next[k] = head[b];
    head[b] = k;
  }
  double farthest = 0;
  for (const Vec3& p : from) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint64_t x = cell(p.x() - reach); x != cell(p.x() + reach) + 1; ++x) {
      for (std::uint64_t y = cell(p.y() - reach); y != cell(p.y() + reach) + 1; ++y) {
        for (std::uint64_t z = cell(p.z() - reach); z != cell(p.z() + reach) + 1; ++z) {
          for (std::uint32_t k = head[bucket(x, y, z)]; k != none; k = next[k]) {
            nearest = std::min(nearest, (to[k] - p).norm());
          }
        }
      }
    }
    farthest = std::max(farthest, nearest <= reach ? nearest : std::numeric_limits<double>::infinity());
  }
  return farthest;
}

struct Check {
  bool ok = false;
  std::string summary;  // one line, printed after the runs
  // The level-k result, for patchwork_report_only.
  patchwork::UniformRefinement refined;
};

template <class Side>
Check run_check(int level) {
  Check check;
  check.refined = patchwork::refine_uniform(cage(Side::scheme), level);
  typename Side::Mesh om = openmesh_cage<Side>();
  openmesh_refine<Side>(om, level);

  const FaceVertexMesh& ours = check.refined.cage.mesh;
  const patchwork::TopologyReport& report = check.refined.topology;
  const std::vector<Vec3> a = points_of(ours);
  const std::vector<Vec3> b = points_of(om);
  Eigen::AlignedBox3d box;
  for (const Vec3& p : a) box.extend(p);
  const double tolerance = 1e-9 * box.diagonal().norm();
  const bool counts = static_cast<std::int64_t>(ours.face_count()) == output_faces(Side::scheme, level) &&
                      ours.face_count() == om.n_faces() && a.size() == b.size() && report.closed && report.euler == 0 &&
                      report.components == 1;
  const double distance = std::max(farthest_nearest(a, b, tolerance), farthest_nearest(b, a, tolerance));
  check.ok = counts && distance <= tolerance;

  std::ostringstream out;
  out << patchwork::scheme_name(Side::scheme) << " level " << level << ": faces " << ours.face_count() << " / "
      << om.n_faces() << ", vertices " << a.size() << " / " << b.size() << ", farthest point from the other side "
      << std::scientific << std::setprecision(1);
  if (std::isinf(distance)) {
    out << "beyond the tolerance " << tolerance;
  } else {
    out << distance << " (tolerance " << tolerance << ")";
  }
  out << (check.ok ? "" : "  FAILED");
  check.summary = out.str();
  return check;
}

std::map<std::pair<SubdivisionScheme, int>, Check>& checks() {
  static std::map<std::pair<SubdivisionScheme, int>, Check> done;
  return done;
}

// The check of one scheme and level, run the first time a benchmark of it asks.
const Check& checked(SubdivisionScheme scheme, int level) {
  auto& done = checks();
  const auto it = done.find({scheme, level});
  if (it != done.end()) return it->second;
  Check check = scheme == SubdivisionScheme::loop ? run_check<LoopSide>(level) : run_check<CatmullClarkSide>(level);
  return done.emplace(std::pair(scheme, level), std::move(check)).first->second;
}

bool skipped(benchmark::State& state, SubdivisionScheme scheme, int level) {
  const Check& check = checked(scheme, level);
  if (!check.ok) state.SkipWithError(check.summary.c_str());
  return !check.ok;
}

void count_faces(benchmark::State& state, SubdivisionScheme scheme, int level) {
  state.counters["faces/s"] = benchmark::Counter(static_cast<double>(output_faces(scheme, level)),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

// --- the benchmarks -------------------------------------------------------------------------

void patchwork_refine(benchmark::State& state, SubdivisionScheme scheme, int level) {
  if (skipped(state, scheme, level)) return;
  const SubdivisionCage& input = cage(scheme);
  for (auto _ : state) {
    const patchwork::UniformRefinement refined = patchwork::refine_uniform(input, level);
    benchmark::DoNotOptimize(refined.topology.faces);
  }
  count_faces(state, scheme, level);
}

void patchwork_report_only(benchmark::State& state, SubdivisionScheme scheme, int level) {
  if (skipped(state, scheme, level)) return;
  const SubdivisionCage& refined = checked(scheme, level).refined.cage;
  for (auto _ : state) {
    const patchwork::TopologyReport report = patchwork::analyze(patchwork::surface_faces(refined));
    benchmark::DoNotOptimize(report.faces);
  }
  count_faces(state, scheme, level);
}

template <class Side>
void openmesh_subdivide(benchmark::State& state, int level) {
  if (skipped(state, Side::scheme, level)) return;
  const typename Side::Mesh& input = openmesh_cage<Side>();
  for (auto _ : state) {
    state.PauseTiming();
    typename Side::Mesh mesh = input;
    state.ResumeTiming();
    openmesh_refine<Side>(mesh, level);
    benchmark::DoNotOptimize(mesh.n_faces());
  }  // the refined mesh is freed inside the timing, like patchwork's result
  count_faces(state, Side::scheme, level);
}

template <class Side>
void openmesh_end_to_end(benchmark::State& state, int level) {
  if (skipped(state, Side::scheme, level)) return;
  const FaceVertexMesh& input = cage(Side::scheme).mesh;
  for (auto _ : state) {
    typename Side::Mesh mesh = Side::build(input);
    openmesh_refine<Side>(mesh, level);
    const FaceVertexMesh refined = Side::read(mesh);
    benchmark::DoNotOptimize(refined.face_count());
  }
  count_faces(state, Side::scheme, level);
}

std::string scheme_key(SubdivisionScheme scheme) {
  return scheme == SubdivisionScheme::loop ? "loop" : "catmull_clark";
}

std::string benchmark_name(SubdivisionScheme scheme, const char* method, int level) {
  return scheme_key(scheme) + "/" + method + "/" + std::to_string(level);
}

// Benchmarks are named scheme/method/level, in the order patchwork_refine, openmesh_subdivide,
// patchwork_report_only, openmesh_end_to_end for each scheme and level.
template <class Side>
void register_scheme() {
  for (const int level : levels) {
    const auto add = [level](const char* method, auto function) {
      benchmark::RegisterBenchmark(benchmark_name(Side::scheme, method, level).c_str(), function)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    };
    add("patchwork_refine", [level](benchmark::State& state) { patchwork_refine(state, Side::scheme, level); });
    add("openmesh_subdivide", [level](benchmark::State& state) { openmesh_subdivide<Side>(state, level); });
    add("patchwork_report_only",
        [level](benchmark::State& state) { patchwork_report_only(state, Side::scheme, level); });
    add("openmesh_end_to_end", [level](benchmark::State& state) { openmesh_end_to_end<Side>(state, level); });
  }
}

// CPU time is the fairer measure on a shared machine (each benchmark runs on one thread);
// wall time is printed beside it.
void print_ratios(const patchwork::bench::TimingReporter& timing, std::ostream& out) {
  if (timing.empty()) return;
  out << "\nfaces/s(patchwork_refine) / faces/s(OpenMesh) = time(OpenMesh) / time(patchwork_refine); above 1: "
         "patchwork is faster\n"
      << "\n"
      << "  scheme         level   output faces   patchwork faces/s   OpenMesh faces/s"
      << "   vs subdivide cpu  wall   vs end-to-end cpu  wall\n";
  for (const SubdivisionScheme scheme : {SubdivisionScheme::catmull_clark, SubdivisionScheme::loop}) {
    for (const int level : levels) {
      const patchwork::bench::TimingReporter::Seconds* ours = timing.find(benchmark_name(scheme, "patchwork_refine", level));
      const patchwork::bench::TimingReporter::Seconds* theirs = timing.find(benchmark_name(scheme, "openmesh_subdivide", level));
      if (ours == nullptr || theirs == nullptr) continue;
      const auto faces = static_cast<double>(output_faces(scheme, level));
      out << "  " << std::left << std::setw(15) << scheme_key(scheme) << std::right << std::setw(5) << level
          << std::setw(15) << static_cast<std::int64_t>(faces) << std::scientific << std::setprecision(3)
          << std::setw(20) << faces / ours->wall << std::setw(19) << faces / theirs->wall << std::fixed
          << std::setprecision(2) << std::setw(19) << theirs->cpu / ours->cpu << std::setw(6)
          << theirs->wall / ours->wall;
      if (const patchwork::bench::TimingReporter::Seconds* end_to_end = timing.find(benchmark_name(scheme, "openmesh_end_to_end", level))) {
        out << std::setw(20) << end_to_end->cpu / ours->cpu << std::setw(6) << end_to_end->wall / ours->wall;
      } else {
        out << std::setw(26) << "-";
      }
      out << "\n";
    }
  }
  out << "\nChecks (untimed, once per scheme and level run; patchwork / OpenMesh):\n";
  for (const auto& [key, check] : checks()) out << "  " << check.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  register_scheme<CatmullClarkSide>();
  register_scheme<LoopSide>();
  return patchwork::bench::run_benchmarks(argc, argv, [](const patchwork::bench::TimingReporter& timing) {
    print_ratios(timing, std::cout);
  });
}
