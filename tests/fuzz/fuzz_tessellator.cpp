// libFuzzer target: small patch sets from arbitrary bytes (1 to 3 patches of degrees 1 to 3,
// control points on a coarse lattice so that shared, collapsed and touching edges occur) through
// the tessellator at a tolerance or a segment count from the bytes. The mesh must be valid, its
// measured error (measured on every input) within its bound and the bound within the tolerance
// plus the weld gap; the welded mesh must have the patch set's boundary loops and its
// edge-connected components; and one Tessellation reused from input to input (its arrays and
// scratch keep their storage) must give each input's fresh result exactly.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/union_find.h"
#include "meshes/render_mesh.h"
#include "meshes/topology.h"
#include "surfaces/tessellator.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

namespace {

// The patches with at least one triangle.
std::vector<bool> meshed_patches(const PatchSet& set, const std::vector<std::uint32_t>& triangle_patches) {
  std::vector<bool> meshed(set.patches().size(), false);
  for (const std::uint32_t p : triangle_patches) meshed[p] = true;
  return meshed;
}

// Whether every patch edge is in at most one join (shared edge, T-junction). An edge shared by
// three patches keeps its first pairing for its points, while its corners are welded through
// every pairing (build_edge_classes, number_welded_points): the third patch then joins the mesh
// through an edge only where that edge has one segment, which the set cannot tell. Found by
// fuzzing on 2026-12-04 (a bilinear pair and a cubic patch on one edge, relative 0.25: two
// components where the set has one; at one segment a second input had them joined).
bool components_comparable(const PatchSet& set) {
  std::vector<std::array<int, 4>> joins(set.patches().size(), {0, 0, 0, 0});
  const auto count = [&](const EdgeRef& e) { return ++joins[e.patch][static_cast<std::size_t>(e.edge)]; };
  bool single = true;
  for (const SharedEdge& shared : set.shared_edges()) {
    const bool first = count(shared.first) == 1;  // both counted, always
    const bool second = count(shared.second) == 1;
    single = single && first && second;
  }
  for (const TJunction& t : set.t_junctions()) {
    const bool long_edge = count(t.edge) == 1;
    single = single && long_edge;
    for (const EdgeRef& part : t.parts) {
      const bool alone = count(part) == 1;
      single = single && alone;
    }
  }
  return single;
}

// The components the welded mesh must have, counted on the patch set: patches joined by shared
// edges are one component. The tessellator welds corners only through shared edges and a
// patch's own collapsed edges (surfaces/tessellator.h), so patches that touch at a point, or
// whose poles meet without a shared edge, stay apart; and analyze() joins faces only through
// edges. A patch all of whose triangles were dropped (degenerate at its collapsed edges) is in no
// component.
Count patch_components(const PatchSet& set, const std::vector<bool>& meshed) {
  const std::size_t count = set.patches().size();
  UnionFind components(count);
  for (const SharedEdge& shared : set.shared_edges()) {
    if (meshed[shared.first.patch] && meshed[shared.second.patch])
      components.unite(shared.first.patch, shared.second.patch);
  }
  for (const TJunction& t : set.t_junctions()) {
    for (const EdgeRef& part : t.parts) {
      if (meshed[t.edge.patch] && meshed[part.patch]) components.unite(t.edge.patch, part.patch);
    }
  }
  Count roots = 0;
  for (std::uint32_t p = 0; p < count; ++p) roots += meshed[p] && components.find(p) == p;
  return roots;
}

// Whether the welded mesh's boundary loops must be the patch set's. The tessellator joins
// corners only through shared and collapsed edges and T-junctions, and PatchSet chains open
// edges into loops through the same joins (two corners at one point that nothing joins, as at a
// touching point or a patch whose edge is a closed curve, stay apart in both). The two agree
// unless
//   - a loop is not closed (an open end, a non-manifold corner or an orientation flip);
//   - a patch has no triangle (two collapsed edges that meet, at one segment);
//   - two edges (not collapsed) join the same two welded corners, or one joins a welded corner
//     to itself: at one segment they are one mesh edge, which then is no boundary.
bool boundary_loops_comparable(const PatchSet& set, const std::vector<bool>& meshed) {
  if (!std::all_of(set.boundary_loops().begin(), set.boundary_loops().end(),
                   [](const BoundaryLoop& loop) { return loop.closed; }) ||
      std::find(meshed.begin(), meshed.end(), false) != meshed.end())
    return false;
  // Edge k runs from corner start[k] to end[k] in boundary_curve direction.
  constexpr int start[4] = {0, 1, 3, 0};
  constexpr int end[4] = {1, 2, 2, 3};
  const auto slot = [](std::uint32_t p, int c) { return 4 * p + static_cast<std::uint32_t>(c); };
  UnionFind welded(4 * set.patches().size());
  for (const SharedEdge& e : set.shared_edges()) {
    const int a = static_cast<int>(e.first.edge), b = static_cast<int>(e.second.edge);
    welded.unite(slot(e.first.patch, start[a]), slot(e.second.patch, e.reversed ? end[b] : start[b]));
    welded.unite(slot(e.first.patch, end[a]), slot(e.second.patch, e.reversed ? start[b] : end[b]));
  }
  for (const EdgeRef& e : set.collapsed_edges()) {
    welded.unite(slot(e.patch, start[static_cast<int>(e.edge)]), slot(e.patch, end[static_cast<int>(e.edge)]));
  }
  // A T-junction's parts, end to end along the long edge (part b in the long edge's direction
  // runs from its end corner to its start corner when reversed).
  for (const TJunction& t : set.t_junctions()) {
    const auto from = [&](std::size_t b) {
      const int k = static_cast<int>(t.parts[b].edge);
      return slot(t.parts[b].patch, t.reversed[b] ? end[k] : start[k]);
    };
    const auto to = [&](std::size_t b) {
      const int k = static_cast<int>(t.parts[b].edge);
      return slot(t.parts[b].patch, t.reversed[b] ? start[k] : end[k]);
    };
    const int k = static_cast<int>(t.edge.edge);
    welded.unite(slot(t.edge.patch, start[k]), from(0));
    welded.unite(slot(t.edge.patch, end[k]), to(t.parts.size() - 1));
    for (std::size_t b = 0; b + 1 < t.parts.size(); ++b) welded.unite(to(b), from(b + 1));
  }
  // Each edge once (a shared edge by its first side), as the pair of its welded end corners.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ends;
  const auto add = [&](const EdgeRef& e) {
    const auto a = welded.find(slot(e.patch, start[static_cast<int>(e.edge)]));
    const auto b = welded.find(slot(e.patch, end[static_cast<int>(e.edge)]));
    ends.push_back(std::minmax(a, b));
    return a != b;
  };
  for (const SharedEdge& e : set.shared_edges()) {
    if (!add(e.first)) return false;
  }
  for (const EdgeRef& e : set.open_edges()) {
    if (!add(e)) return false;
  }
  std::sort(ends.begin(), ends.end());
  return std::adjacent_find(ends.begin(), ends.end()) == ends.end();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader bytes(data, size);
  std::vector<BezierPatch3> patches;
  const std::uint32_t count = 1 + bytes.below(3);
  for (std::uint32_t p = 0; p < count; ++p) {
    const int n = 1 + static_cast<int>(bytes.below(3));
    const int m = 1 + static_cast<int>(bytes.below(3));
    std::vector<Vec3> points;
    for (int k = 0; k < (n + 1) * (m + 1); ++k)
      points.emplace_back(bytes.coordinate(), bytes.coordinate(), bytes.coordinate());
    patches.emplace_back(n, m, std::move(points));
  }
  TessellationOptions options;
  // Small meshes keep the executions fast (coverage instrumentation costs per loop step, and
  // every input is measured, ten samples a triangle): every path (stitching, welding, poles,
  // touching points, refusals over the limit) shows at this size.
  options.max_triangles = 500;
  options.threads = 1;
  const std::uint32_t mode = bytes.below(4);
  if (mode == 0) {
    options.segments = 1 + static_cast<int>(bytes.below(6));
  } else {
    options.relative_tolerance = 1.0 / (2.0 + bytes.below(30));
  }
  options.uv = static_cast<UvMode>(bytes.below(3));
  options.tangents = bytes.below(2) == 1;
  fuzz::expect_documented_errors_only([&] {
    const PatchSet set(patches);
    const Tessellation result = tessellate(set, options);
    validate(result.mesh);
    // The guarantee, up to rounding (1e-9 of the size).
    const double slack = 1e-9 * std::max(1.0, set.size());
    PATCHWORK_FUZZ_CHECK(result.measured_error <= result.error_bound + slack);
    if (!options.segments) PATCHWORK_FUZZ_CHECK(result.error_bound <= result.tolerance + result.weld_gap + slack);
    // The patch set's topology: its components, and its boundary loops where they are
    // comparable (boundary_loops_comparable).
    const TopologyReport report = analyze(welded_faces(result.mesh));
    const std::vector<bool> meshed = meshed_patches(set, result.triangle_patches);
    if (boundary_loops_comparable(set, meshed)) {
      PATCHWORK_FUZZ_CHECK(report.boundary_loops == static_cast<Count>(set.boundary_loops().size()));
    }
    if (components_comparable(set)) PATCHWORK_FUZZ_CHECK(report.components == patch_components(set, meshed));
    static Tessellation reused;
    tessellate(set, options, reused);
    const RenderMesh& a = reused.mesh;
    const RenderMesh& b = result.mesh;
    PATCHWORK_FUZZ_CHECK(a.indices == b.indices && a.positions == b.positions && a.normals == b.normals &&
                         a.uvs == b.uvs && a.tangents == b.tangents && a.position_ids == b.position_ids);
    PATCHWORK_FUZZ_CHECK(reused.triangle_patches == result.triangle_patches &&
                         reused.error_bound == result.error_bound && reused.measured_error == result.measured_error &&
                         reused.welded_vertices == result.welded_vertices);
  });
  return 0;
}
