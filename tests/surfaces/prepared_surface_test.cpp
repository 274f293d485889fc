#include "surfaces/prepared_surface.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "io/freeform_surfaces.h"
#include "io/obj_freeform.h"
#include "surfaces/patch_bounding_box.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/tessellation_checks.h"

namespace patchwork {
namespace prepared_surface_test {

const PatchSet& teapot() {
  static const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  return set;
}

// The NURBS torus (rational patches, joins known from the knots).
const PatchSet& torus() {
  static const PatchSet set(freeform_patch_set(read_obj_freeform(PATCHWORK_DATA_DIR "/nurbs_torus.obj")));
  return set;
}

struct Named {
  std::string name;
  TessellationOptions options;
};

using testing::absolute;
using testing::relative;

// A camera looking at the centre of the set's box from centre + diagonal * offset.
TessellationOptions looking(const PatchSet& set, const Vec3& offset, BackFaceCulling culling) {
  const Eigen::AlignedBox3d box = bounding_box(set, 1e-6 * set.size());
  const Vec3 centre = box.center();
  TessellationOptions options;
  options.camera = Camera{centre + box.diagonal().norm() * offset, centre, Vec3::UnitZ(), 40.0, 640, 480};
  options.back_face_culling = culling;
  return options;
}

// A frame sequence a renderer might ask for: tolerances that come back, tolerances that change,
// a camera that moves a little (some patches keep their tolerance, some change, some are
// culled), other attributes, uniform grids, and back.
std::vector<Named> frames(const PatchSet& set) {
  std::vector<Named> list = {
      {"relative 1e-2", relative(1e-2)},
      {"relative 1e-3", relative(1e-3)},
      {"relative 1e-3 again", relative(1e-3)},
      {"absolute 0.004", absolute(0.004)},
      {"camera far", looking(set, Vec3(0.98, -0.73, 0.6), BackFaceCulling::automatic)},
      {"camera nearer", looking(set, Vec3(0.73, -0.55, 0.49), BackFaceCulling::automatic)},
      {"camera nearer again", looking(set, Vec3(0.73, -0.55, 0.49), BackFaceCulling::automatic)},
      {"camera inside the box, culling never", looking(set, Vec3(0.05, 0.02, -0.06), BackFaceCulling::never)},
      {"camera always culls", looking(set, Vec3(0.73, -0.55, 0.49), BackFaceCulling::always)}};
  TessellationOptions tangents = relative(1e-3);
  tangents.tangents = true;
  tangents.uv = UvMode::atlas;
  list.push_back({"relative 1e-3 with tangents and atlas", tangents});
  TessellationOptions segments;
  segments.segments = 5;
  list.push_back({"segments 5", segments});
  TessellationOptions unsplit = relative(1e-3);
  unsplit.split_patches = false;
  list.push_back({"relative 1e-3 unsplit", unsplit});
  list.push_back({"relative 1e-3 back", relative(1e-3)});
  return list;
}

// One prepared surface and one Tessellation reused frame after frame give, at every frame, the
// tessellation of the plain call on the set (which prepares afresh): nothing a frame keeps leaks
// into the next.
TEST(PreparedSurface, ReusedFrameAfterFrameEqualsAFreshTessellation) {
  for (const PatchSet* set : {&teapot(), &torus()}) {
    const PreparedSurface prepared(*set);
    Tessellation reused;
    for (const Named& frame : frames(*set)) {
      SCOPED_TRACE(frame.name + (set == &teapot() ? " (teapot)" : " (torus)"));
      tessellate(prepared, frame.options, reused);
      const Tessellation fresh = tessellate(*set, frame.options);
      ASSERT_GT(fresh.mesh.triangle_count(), 0u);
      testing::expect_identical_tessellations(reused, fresh);
      testing::expect_identical_tessellations(tessellate(prepared, frame.options), fresh);
    }
  }
}

// A set with T-junctions is never split; its prepared form says so when asked for split pieces.
TEST(PreparedSurface, TJunctionsKeepThePatchesWhole) {
  const PatchSet set(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}));
  ASSERT_EQ(set.t_junctions().size(), 1u);
  const PreparedSurface prepared(set);
  EXPECT_EQ(prepared.pieces(1, true).count, set.count());
  EXPECT_THROW(prepared.pieces(2, true), InvalidInput);
  EXPECT_THROW(prepared.pieces(3, false), InvalidInput);
  Tessellation reused;
  for (const double tolerance : {3e-2, 1e-3, 3e-2}) {
    tessellate(prepared, absolute(tolerance), reused);
    testing::expect_identical_tessellations(reused, tessellate(set, absolute(tolerance)));
  }
}

// What preparing computes is what the set says: one set of cell bounds per patch, the control
// points' diagonal, the tight box's diagonal, k x k pieces per patch.
TEST(PreparedSurface, HoldsTheSetsBoundsAndPieces) {
  const PreparedSurface prepared(teapot());
  EXPECT_EQ(&prepared.set(), &teapot());
  ASSERT_EQ(prepared.cell_bounds().size(), teapot().count());
  for (const auto& cells : prepared.cell_bounds()) EXPECT_EQ(cells.size(), 16u);
  EXPECT_EQ(prepared.control_diagonal(), teapot().size());
  EXPECT_EQ(prepared.tight_diagonal(), bounding_box(teapot(), 1e-6 * teapot().size()).diagonal().norm());
  for (const int k : {1, 2, 4}) {
    const SurfacePieces& pieces = prepared.pieces(k, true);
    EXPECT_EQ(pieces.count, teapot().count() * static_cast<std::size_t>(k * k));
    EXPECT_EQ(pieces.diagonal, prepared.tight_diagonal());
    EXPECT_EQ(prepared.pieces(k, false).diagonal, prepared.control_diagonal());
    // Made once: the same object every time.
    EXPECT_EQ(&prepared.pieces(k, true), &pieces);
  }
  // Only the automatic back-face culling asks for the solids: the teapot is open, none.
  const SurfacePieces& with_solids = prepared.pieces(1, false, true);
  ASSERT_EQ(with_solids.solids.size(), teapot().count());
  for (const std::int32_t solid : with_solids.solids) EXPECT_EQ(solid, -1);
  // A set without a surface cannot be prepared.
  const std::vector<Vec3> point(16, Vec3(1, 2, 3));
  const PatchSet dot({BezierPatch3(3, 3, point)});
  EXPECT_THROW(PreparedSurface{dot}, InvalidInput);
}

// Two threads tessellating one prepared surface at once (each into its own result, the pieces
// made on first use by whichever comes first) get what each would alone.
TEST(PreparedSurface, TwoThreadsShareOnePreparedSurface) {
  const std::vector<Named> list = frames(teapot());
  std::vector<Tessellation> alone;
  for (const Named& frame : list) alone.push_back(tessellate(teapot(), frame.options));
  const PreparedSurface prepared(teapot());
  std::vector<Tessellation> first(list.size());
  std::vector<Tessellation> second(list.size());
  const auto run = [&](std::vector<Tessellation>& into, bool backwards) {
    Tessellation reused;
    for (std::size_t q = 0; q < list.size(); ++q) {
      const std::size_t k = backwards ? list.size() - 1 - q : q;
      tessellate(prepared, list[k].options, reused);
      into[k] = reused;
    }
  };
  std::thread other(run, std::ref(first), false);
  run(second, true);
  other.join();
  for (std::size_t k = 0; k < list.size(); ++k) {
    SCOPED_TRACE(list[k].name);
    testing::expect_identical_tessellations(first[k], alone[k]);
    testing::expect_identical_tessellations(second[k], alone[k]);
  }
}

}  // namespace prepared_surface_test
}  // namespace patchwork
