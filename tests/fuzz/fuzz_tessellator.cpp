// libFuzzer target: small patch sets from arbitrary bytes (1 to 3 patches of degrees 1 to 3,
// control points on a coarse lattice so that shared, collapsed and touching edges occur) through
// the tessellator at a tolerance or a segment count from the bytes. The mesh must be valid, its
// measured error (measured on every input) within its bound and the bound within the tolerance
// plus the weld gap; the welded mesh must have the patch set's boundary loops and its
// edge-connected components; and one Tessellation reused from input to input (its arrays and
// scratch keep their storage) must give each input's fresh result exactly.

#include <algorithm>
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
    if (meshed[shared.first.patch] && meshed[shared.second.patch]) components.unite(shared.first.patch, shared.second.patch);
  }
  Count roots = 0;
  for (std::uint32_t p = 0; p < count; ++p) roots += meshed[p] && components.find(p) == p;
  return roots;
}

// Whether the welded mesh's boundary loops must be the patch set's. The tessellator joins
// corners only through shared and collapsed edges; PatchSet chains open edges into loops by
// their end points. The two agree unless
//   - a loop is not closed (an open end, a non-manifold corner or an orientation flip);
//   - a patch has no triangle (two collapsed edges that meet, at one segment);
//   - two corners the tessellator does not weld are at one point (a touching point, or a patch
//     whose edge is a closed curve): PatchSet may chain through it, the mesh does not;
//   - two edges (not collapsed) join the same two welded corners, or one joins a welded corner
//     to itself: at one segment they are one mesh edge, which then is no boundary.
bool boundary_loops_comparable(const PatchSet& set, const std::vector<bool>& meshed) {
  if (!std::all_of(set.boundary_loops().begin(), set.boundary_loops().end(),
                   [](const BoundaryLoop& loop) { return loop.closed; }) ||
      std::find(meshed.begin(), meshed.end(), false) != meshed.end())
    return false;
  const auto corner = [&](std::uint32_t p, int c) {
    const BezierPatch3& patch = set.patches()[p];
    const int n = patch.degree_u(), m = patch.degree_v();
    const int i = c == 1 || c == 2 ? n : 0, j = c >= 2 ? m : 0;  // (0,0), (n,0), (n,m), (0,m)
    return patch.control_points()[i + (n + 1) * j];
  };
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
  const std::uint32_t slots = 4 * static_cast<std::uint32_t>(set.patches().size());
  for (std::uint32_t x = 0; x < slots; ++x) {
    for (std::uint32_t y = 0; y < slots; ++y) {
      if (welded.find(x) != welded.find(y) && (corner(x / 4, x % 4) - corner(y / 4, y % 4)).norm() <= set.tolerance())
        return false;
    }
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
    PATCHWORK_FUZZ_CHECK(report.components == patch_components(set, meshed));
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
