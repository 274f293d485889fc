// libFuzzer target: small patch sets from arbitrary bytes (1 to 3 patches of degrees 1 to 3,
// control points on a coarse lattice so that shared, collapsed and touching edges occur) through
// the tessellator at a tolerance or a segment count from the bytes. The mesh must be valid, its
// measured error within its bound and the bound within the tolerance; and one Tessellation
// reused from input to input (its arrays and scratch keep their storage) must give each input's
// fresh result exactly.

#include "meshes/render_mesh.h"
#include "meshes/topology.h"
#include "surfaces/tessellator.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

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
  // Small meshes keep the executions fast (coverage instrumentation costs per loop step): every
  // path (stitching, welding, poles, touching points, refusals over the limit) shows at this size.
  options.max_triangles = 1'000;
  options.threads = 1;
  const std::uint32_t mode = bytes.below(4);
  if (mode == 0) {
    options.segments = 1 + static_cast<int>(bytes.below(6));
  } else {
    options.relative_tolerance = 1.0 / (2.0 + bytes.below(30));
  }
  options.uv = static_cast<UvMode>(bytes.below(3));
  options.tangents = bytes.below(2) == 1;
  // The sampled error costs ten evaluations per triangle: one input in four measures it.
  options.measure = bytes.below(4) == 0;
  fuzz::expect_documented_errors_only([&] {
    const PatchSet set(patches);
    const Tessellation result = tessellate(set, options);
    validate(result.mesh);
    (void)analyze(welded_faces(result.mesh));
    // The guarantee, up to rounding (1e-9 of the size).
    const double slack = 1e-9 * std::max(1.0, set.size());
    if (options.measure) PATCHWORK_FUZZ_CHECK(result.measured_error <= result.error_bound + slack);
    if (!options.segments) PATCHWORK_FUZZ_CHECK(result.error_bound <= result.tolerance + slack);
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
