#include "surfaces/batched_tessellation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "meshes/topology.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_transform.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator_stages.h"
#include "tests/surfaces/rational_shapes.h"
#include "tests/surfaces/tessellation_checks.h"

namespace patchwork {
namespace batched_tessellation_test {

using testing::absolute;
using testing::relative;

// A scene of separate objects: five teapots, each turned and moved (each teapot is several
// shells, one of them touching another at the handle), and a rational sphere of eight octants
// between them. 168 patches.
const PatchSet& scene() {
  static const PatchSet set = [] {
    const std::vector<BezierPatch3> teapot = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
    std::vector<AnyBezierPatch> patches;
    for (int copy = 0; copy < 5; ++copy) {
      const Eigen::Affine3d map = Eigen::Translation3d(9.0 * copy, 2.0 * copy, -1.0 * copy) *
                                  Eigen::AngleAxisd(0.4 + 0.9 * copy, Vec3(1.0, copy, 2.0).normalized());
      for (const BezierPatch3& patch : teapot) patches.emplace_back(transform(patch, map));
      if (copy == 2) {
        for (const RationalBezierPatch& octant : testing::unit_sphere_octants()) {
          patches.emplace_back(transform(octant, Eigen::Affine3d(Eigen::Translation3d(20, -8, 0) * Eigen::Scaling(2.5))));
        }
      }
    }
    return PatchSet(patches);
  }();
  return set;
}

// The options the tests run with, by name (every mode that batches, and the attributes).
std::vector<std::pair<std::string, TessellationOptions>> batching_options() {
  TessellationOptions tangents = relative(2e-3);
  tangents.tangents = true;
  tangents.uv = UvMode::none;
  TessellationOptions segments;
  segments.segments = 3;
  TessellationOptions unsplit = absolute(0.01);
  unsplit.split_patches = false;
  return {{"absolute 0.004", absolute(0.004)},
          {"relative 1e-3", relative(1e-3)},
          {"relative 2e-3, tangents, no uv", tangents},
          {"segments 3", segments},
          {"absolute 0.01 unsplit", unsplit}};
}

// Every patch in exactly one batch, each batch whole shells in increasing order, all batches
// but the last at least batch_patches patches.
TEST(TessellationBatches, AreWholeShellsInOrder) {
  const PatchSet& set = scene();
  const std::vector<Shell> parts = shells(set);
  ASSERT_GT(parts.size(), 10u);
  for (const std::size_t size : {std::size_t{1}, std::size_t{7}, std::size_t{40}, std::size_t{100}, set.count()}) {
    SCOPED_TRACE(size);
    const std::vector<std::vector<std::uint32_t>> batches = tessellation_batches(set, size);
    std::vector<std::int64_t> batch_of(set.count(), -1);
    for (std::size_t b = 0; b < batches.size(); ++b) {
      ASSERT_FALSE(batches[b].empty());
      EXPECT_TRUE(std::is_sorted(batches[b].begin(), batches[b].end()));
      if (b + 1 < batches.size()) { EXPECT_GE(batches[b].size(), size); }
      for (const std::uint32_t p : batches[b]) {
        EXPECT_EQ(batch_of[p], -1) << "patch " << p << " twice";
        batch_of[p] = static_cast<std::int64_t>(b);
      }
    }
    EXPECT_EQ(std::count(batch_of.begin(), batch_of.end(), -1), 0);
    for (const Shell& shell : parts) {
      for (const std::uint32_t p : shell.patches) EXPECT_EQ(batch_of[p], batch_of[shell.patches.front()]);
    }
    // Shells in their order: batch numbers never go down from shell to shell.
    for (std::size_t k = 1; k < parts.size(); ++k) {
      EXPECT_LE(batch_of[parts[k - 1].patches.front()], batch_of[parts[k].patches.front()]);
    }
    if (size == 1) { EXPECT_EQ(batches.size(), parts.size()); }
    if (size == set.count()) { EXPECT_EQ(batches.size(), 1u); }
  }
  EXPECT_THROW((void)tessellation_batches(set, 0), InvalidInput);
}

// The batched mesh is each batch's tessellation of its subset, bit for bit, end to end: indices
// and position ids shifted past the batches before, triangle_patches the set's patches; the
// numbers the largest (bounds) or the sums (counts) of the batches'.
TEST(TessellateInBatches, IsEachBatchsTessellationEndToEnd) {
  const PatchSet& set = scene();
  const double diagonal = bounding_box(set, 1e-6 * set.size()).diagonal().norm();
  const std::size_t batch_patches = 40;
  const std::vector<std::vector<std::uint32_t>> batches = tessellation_batches(set, batch_patches);
  ASSERT_GE(batches.size(), 3u);
  for (const auto& [name, options] : batching_options()) {
    SCOPED_TRACE(name);
    const Tessellation batched = tessellate_in_batches(set, options, batch_patches);
    TessellationOptions each = options;
    if (options.relative_tolerance) {
      each.relative_tolerance.reset();
      each.tolerance = *options.relative_tolerance * diagonal;
    }
    RenderMesh expected;
    std::vector<std::uint32_t> patches;
    double error_bound = 0.0, measured = 0.0, weld_gap = 0.0, tolerance = 0.0;
    std::size_t welded = 0;
    for (const std::vector<std::uint32_t>& batch : batches) {
      const Tessellation part = tessellate(set.subset(batch), each);
      const auto first_vertex = static_cast<std::uint32_t>(expected.positions.size());
      const auto first_id = static_cast<std::uint32_t>(welded);
      expected.positions.insert(expected.positions.end(), part.mesh.positions.begin(), part.mesh.positions.end());
      expected.normals.insert(expected.normals.end(), part.mesh.normals.begin(), part.mesh.normals.end());
      expected.uvs.insert(expected.uvs.end(), part.mesh.uvs.begin(), part.mesh.uvs.end());
      expected.tangents.insert(expected.tangents.end(), part.mesh.tangents.begin(), part.mesh.tangents.end());
      for (const std::uint32_t i : part.mesh.indices) expected.indices.push_back(i + first_vertex);
      for (const std::uint32_t id : part.mesh.position_ids) expected.position_ids.push_back(id + first_id);
      for (const std::uint32_t p : part.triangle_patches) patches.push_back(batch[p]);
      error_bound = std::max(error_bound, part.error_bound);
      measured = std::max(measured, part.measured_error);
      weld_gap = std::max(weld_gap, part.weld_gap);
      tolerance = std::max(tolerance, part.tolerance);
      welded += part.welded_vertices;
    }
    EXPECT_EQ(batched.mesh.positions, expected.positions);
    EXPECT_EQ(batched.mesh.normals, expected.normals);
    EXPECT_EQ(batched.mesh.uvs, expected.uvs);
    EXPECT_EQ(batched.mesh.tangents, expected.tangents);
    EXPECT_EQ(batched.mesh.indices, expected.indices);
    EXPECT_EQ(batched.mesh.position_ids, expected.position_ids);
    EXPECT_EQ(batched.triangle_patches, patches);
    EXPECT_EQ(batched.error_bound, error_bound);
    EXPECT_EQ(batched.measured_error, measured);
    EXPECT_EQ(batched.weld_gap, weld_gap);
    EXPECT_EQ(batched.tolerance, tolerance);
    EXPECT_EQ(batched.welded_vertices, welded);
    EXPECT_TRUE(batched.mesh.tangents.empty() == !options.tangents);
  }
}

// What the batches make is the whole set's surface within the tolerance, welded as the whole
// set's tessellation is: the same components, boundary loops, Euler characteristic and manifold
// topology (not the same boundary edges: a batch may split its patches otherwise than the whole
// set, and an open edge's rate with them), the same tolerance (a relative one is of the whole
// set's box), and the bound met everywhere.
TEST(TessellateInBatches, KeepsTheWholeSetsToleranceAndTopology) {
  const PatchSet& set = scene();
  for (const auto& [name, options] : batching_options()) {
    SCOPED_TRACE(name);
    const Tessellation whole = tessellate(set, options);
    const Tessellation batched = tessellate_in_batches(set, options, 40);
    ASSERT_NO_THROW(validate(batched.mesh));
    EXPECT_EQ(batched.tolerance, whole.tolerance);
    if (!options.segments) {
      EXPECT_LE(batched.error_bound, batched.tolerance);
    }
    EXPECT_LE(batched.measured_error, batched.error_bound);
    const TopologyReport a = analyze(welded_faces(batched.mesh));
    const TopologyReport b = analyze(welded_faces(whole.mesh));
    EXPECT_EQ(a.components, b.components);
    EXPECT_EQ(a.boundary_loops, b.boundary_loops);
    EXPECT_EQ(a.euler, b.euler);
    EXPECT_EQ(a.manifold, b.manifold);
    EXPECT_EQ(a.orientable, b.orientable);
    EXPECT_EQ(a.isolated_vertices, 0u);
    // Every triangle's patch: each patch of the set has triangles, in the batched mesh as in the
    // whole set's, and as many (at a uniform grid) or about as many.
    std::vector<std::size_t> per_patch_batched(set.count(), 0), per_patch_whole(set.count(), 0);
    for (const std::uint32_t p : batched.triangle_patches) ++per_patch_batched[p];
    for (const std::uint32_t p : whole.triangle_patches) ++per_patch_whole[p];
    EXPECT_EQ(std::count(per_patch_batched.begin(), per_patch_batched.end(), 0u), 0);
    if (options.segments) { EXPECT_EQ(per_patch_batched, per_patch_whole); }
  }
}

// Where the batches cannot differ from the whole set, or must not, the result is exactly
// tessellate(set, options): one batch, a camera, atlas UVs.
TEST(TessellateInBatches, IsThePlainTessellationWhereItCannotBatch) {
  const PatchSet& set = scene();
  testing::expect_identical_tessellations(tessellate_in_batches(set, absolute(0.004), set.count()),
                                          tessellate(set, absolute(0.004)));
  const Eigen::AlignedBox3d box = bounding_box(set, 1e-6 * set.size());
  TessellationOptions camera;
  camera.camera = Camera{box.center() + 0.6 * box.diagonal(), box.center(), Vec3::UnitZ(), 40.0, 640, 480};
  testing::expect_identical_tessellations(tessellate_in_batches(set, camera, 40), tessellate(set, camera));
  TessellationOptions atlas = relative(1e-3);
  atlas.uv = UvMode::atlas;
  testing::expect_identical_tessellations(tessellate_in_batches(set, atlas, 40), tessellate(set, atlas));
}

TEST(TessellateInBatches, DoesNotDependOnTheThreadCount) {
  TessellationOptions one = relative(1e-3);
  one.threads = 1;
  TessellationOptions two = one;
  two.threads = 2;
  Tessellation a = tessellate_in_batches(scene(), one, 40);
  Tessellation b = tessellate_in_batches(scene(), two, 40);
  testing::expect_identical_tessellations(a, b);
}

// The triangle budget is checked on the tessellator's estimate summed over the batches (each
// batch's from its own run, kept in the scratch): one triangle short of the sum stops the last
// batch, before it is made, with a message naming it; the sum itself passes.
TEST(TessellateInBatches, CountsTheTriangleBudgetOverEveryBatch) {
  const PatchSet& set = scene();
  const std::vector<std::vector<std::uint32_t>> batches = tessellation_batches(set, 40);
  double estimated = 0.0;
  for (const std::vector<std::uint32_t>& batch : batches) {
    const PatchSet subset = set.subset(batch);
    const PreparedSurface prepared(subset);
    Tessellation part;
    tessellate(prepared, absolute(0.004), part);
    estimated += part.scratch.get().estimated_triangles;
  }
  const Tessellation all = tessellate_in_batches(set, absolute(0.004), 40);
  ASSERT_GT(estimated, static_cast<double>(all.mesh.triangle_count()));
  TessellationOptions limited = absolute(0.004);
  limited.max_triangles = static_cast<std::int64_t>(estimated);
  EXPECT_EQ(tessellate_in_batches(set, limited, 40).mesh.triangle_count(), all.mesh.triangle_count());
  limited.max_triangles = static_cast<std::int64_t>(estimated) - 1;
  try {
    (void)tessellate_in_batches(set, limited, 40);
    ADD_FAILURE() << "no error at " << limited.max_triangles << " triangles";
  } catch (const InvalidInput& error) {
    const std::string what = error.what();
    const std::string last = detail::message("tessellate: batch ", batches.size(), " of ", batches.size(), " (");
    EXPECT_EQ(what.rfind(last, 0), 0u) << what;
    EXPECT_NE(what.find("more than the limit"), std::string::npos) << what;
  }
}

// Bad options get the single run's message, not a batch's.
TEST(TessellateInBatches, ReportsBadOptionsAsTheSingleRunDoes) {
  const PatchSet& set = scene();
  TessellationOptions negative = relative(-1e-3);
  TessellationOptions crease = absolute(0.004);
  crease.crease_angle = -1.0;
  TessellationOptions two_modes = absolute(0.004);
  two_modes.segments = 3;
  // Finite, but not times the diagonal: the product is checked as the single run checks it.
  TessellationOptions overflowing = relative(1e308);
  for (const TessellationOptions& options : {negative, crease, two_modes, overflowing}) {
    std::string single, batched;
    try {
      (void)tessellate(set, options);
    } catch (const InvalidInput& error) {
      single = error.what();
    }
    try {
      (void)tessellate_in_batches(set, options, 40);
    } catch (const InvalidInput& error) {
      batched = error.what();
    }
    EXPECT_FALSE(single.empty());
    EXPECT_EQ(batched, single);
  }
}

}  // namespace batched_tessellation_test
}  // namespace patchwork
