#include "surfaces/prepared_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "io/freeform_surfaces.h"
#include "io/obj_freeform.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_transform.h"
#include "surfaces/tessellator_stages.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/patch_set_fixtures.h"
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
#ifdef PATCHWORK_ENABLE_ASSERTS
  // The sanitizer build measures only the first frame: the meter's sampling under the sanitizers
  // was most of these tests' 80 s there; the Release build measures every frame, and the
  // meter has tests of its own in both builds.
  for (std::size_t k = 1; k < list.size(); ++k) list[k].options.measure = false;
#endif
  return list;
}

// One prepared surface and one Tessellation reused frame after frame give, at every frame, the
// tessellation of the plain call on the set (which prepares afresh): nothing a frame keeps leaks
// into the next.
TEST(PreparedSurface, ReusedFrameAfterFrameEqualsAFreshTessellation) {
  // The bulged cube is a solid: automatic back-face culling culls its far faces.
  const PatchSet cube(testing::bulged_cube(std::vector<double>(24, 0.2)));
  for (const PatchSet* set : {&teapot(), &torus(), &cube}) {
    const PreparedSurface prepared(*set);
    Tessellation reused;
    for (const Named& frame : frames(*set)) {
      SCOPED_TRACE(frame.name + (set == &teapot() ? " (teapot)" : set == &torus() ? " (torus)" : " (cube)"));
      tessellate(prepared, frame.options, reused);
      const Tessellation fresh = tessellate(*set, frame.options);
      ASSERT_GT(fresh.mesh.triangle_count(), 0u);
      testing::expect_identical_tessellations(reused, fresh);
      testing::expect_identical_tessellations(tessellate(prepared, frame.options), fresh);
    }
  }
}

// A result keeps what the grid searches learnt for the surface it was last made from, and only
// for that one: one Tessellation reused across two prepared surfaces (and a prepared surface
// made again at the address of one gone) gives each frame as a fresh tessellation.
TEST(PreparedSurface, OneResultAcrossSurfacesKeepsNoOtherSurfacesMemos) {
  // The teapot and the teapot a little larger: the same pieces and grids asked about, with
  // other bounds, at the same absolute tolerances.
  const PatchSet larger = transform(teapot(), Eigen::Affine3d(Eigen::Scaling(1.07))).set;
  Tessellation reused;
  const std::vector<TessellationOptions> options = {absolute(0.008), absolute(0.004), absolute(0.008),
                                                    looking(teapot(), Vec3(0.73, -0.55, 0.49), BackFaceCulling::never)};
  for (int round = 0; round < 2; ++round) {
    // Made in the other order the second time: each may take the address the other had.
    std::optional<PreparedSurface> first, second;
    if (round == 0) {
      first.emplace(teapot()), second.emplace(larger);
    } else {
      second.emplace(larger), first.emplace(teapot());
    }
    for (const TessellationOptions& o : options) {
      for (const PreparedSurface* pair : {&*first, &*second}) {
        tessellate(*pair, o, reused);
        testing::expect_identical_tessellations(reused, tessellate(pair->set(), o));
      }
    }
  }
}

// A long frame sequence through one result, so that what one frame's searches learnt is used by
// later ones: tolerances drifting up and down by a few percent (relative and absolute), coming
// back, a camera circling with a drifting pixel tolerance, split on and off, uniform grids
// between (a stitched pattern's cell bound asked for after a search stopped on that grid), on
// the teapot and on a teapot whose edges join with weld gaps (the planning reserves them). Each
// frame equals a fresh tessellation.
TEST(PreparedSurface, DriftingFramesThroughOneResultEqualFreshTessellations) {
  std::vector<BezierPatch3> noisy = teapot().patches();
  for (std::size_t p = 0; p < noisy.size(); ++p) {
    std::vector<Vec3> points = noisy[p].control_points();
    for (std::size_t k = 0; k < points.size(); ++k) points[k] += 2e-5 * Vec3(std::sin(7.0 * p + k), std::cos(3.0 * k + p), std::sin(1.0 * k * p));
    noisy[p] = BezierPatch3(noisy[p].degree_u(), noisy[p].degree_v(), points);
  }
  const PatchSet gapped(noisy, 1e-4);
  ASSERT_EQ(gapped.shared_edges().size(), teapot().shared_edges().size());  // joined, with gaps
#ifdef PATCHWORK_ENABLE_ASSERTS
  const int count = 40;  // the sanitizer build: fewer frames, the same kinds
#else
  const int count = 160;
#endif
  for (const PatchSet* set : {&teapot(), &gapped}) {
    const PreparedSurface prepared(*set);
    Tessellation reused;
    double r = 1e-3;
    for (int frame = 0; frame < count; ++frame) {
      TessellationOptions o;
      const int kind = frame % 8;
      r *= 1.0 + 0.06 * std::sin(1.3 * frame);  // drifting, coming back
      r = std::clamp(r, 2e-4, 3e-2);
      if (kind < 3) {
        o = relative(r);
      } else if (kind == 3) {
        o = absolute(8.2 * r);
      } else if (kind == 4) {
        o.segments = 1 + frame % 6;
      } else if (kind == 5) {
        o = relative(r);
        o.split_patches = false;
      } else {
        o = looking(*set, Vec3(std::cos(0.05 * frame), std::sin(0.05 * frame), 0.5), BackFaceCulling::never);
        o.pixel_tolerance = 0.5 + 0.4 * std::sin(0.7 * frame);
      }
      o.measure = false;
      SCOPED_TRACE("frame " + std::to_string(frame) + (set == &teapot() ? " (teapot)" : " (gapped)"));
      tessellate(prepared, o, reused);
      testing::expect_identical_tessellations(reused, tessellate(*set, o));
      if (::testing::Test::HasFailure()) return;
    }
  }
}

// A set with T-junctions is never split; its prepared form says so when asked for split pieces.
TEST(PreparedSurface, TJunctionsKeepThePatchesWhole) {
  const PatchSet set(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}));
  ASSERT_EQ(set.t_junctions().size(), 1u);
  const PreparedSurface prepared(set);
  EXPECT_EQ(prepared.pieces(1).count, set.count());
  EXPECT_THROW(prepared.pieces(2), InvalidInput);
  EXPECT_THROW(prepared.pieces(3), InvalidInput);
  Tessellation reused;
  for (const double tolerance : {3e-2, 1e-3, 3e-2}) {
    tessellate(prepared, absolute(tolerance), reused);
    testing::expect_identical_tessellations(reused, tessellate(set, absolute(tolerance)));
  }
}

// What preparing computes is what the set says: one set of cell bounds per patch, the control
// points' diagonal, the tight box's diagonal, k x k pieces per patch, the solids.
TEST(PreparedSurface, HoldsTheSetsBoundsAndPieces) {
  const PreparedSurface prepared(teapot());
  EXPECT_EQ(&prepared.set(), &teapot());
  ASSERT_EQ(prepared.cell_bounds().size(), teapot().count());
  for (const auto& cells : prepared.cell_bounds()) EXPECT_EQ(cells.size(), 16u);
  EXPECT_EQ(prepared.control_diagonal(), teapot().size());
  EXPECT_EQ(prepared.tight_diagonal(), bounding_box(teapot(), 1e-6 * teapot().size()).diagonal().norm());
  for (const int k : {1, 2, 4}) {
    const SurfacePieces& pieces = prepared.pieces(k);
    EXPECT_EQ(pieces.count, teapot().count() * static_cast<std::size_t>(k * k));
    EXPECT_EQ(pieces.diagonal, prepared.control_diagonal());
    EXPECT_TRUE(pieces.solids.empty());
    // Made once: the same object every time.
    EXPECT_EQ(&prepared.pieces(k), &pieces);
  }
  // The teapot is open: no solid. The bulged cube is one.
  ASSERT_EQ(prepared.solids().size(), teapot().count());
  for (const std::int32_t solid : prepared.solids()) EXPECT_EQ(solid, -1);
  const PatchSet cube(testing::bulged_cube(std::vector<double>(24, 0.2)));
  const PreparedSurface prepared_cube(cube);
  for (const std::int32_t solid : prepared_cube.solids()) EXPECT_EQ(solid, 0);
  // A set without a surface cannot be prepared.
  const std::vector<Vec3> point(16, Vec3(1, 2, 3));
  const PatchSet dot({BezierPatch3(3, 3, point)});
  EXPECT_THROW(PreparedSurface{dot}, InvalidInput);
}

// The prepared path against the tessellator on pieces made without a PreparedSurface
// (surface_pieces: whole patches, the solids, the diagonal the mode asks for): equal bit for bit
// wherever the patches are not split, so preparing changes nothing of the old computation.
TEST(PreparedSurface, EqualsTheTessellatorOnPiecesMadeWithoutIt) {
  const PatchSet cube(testing::bulged_cube(std::vector<double>(24, 0.2)));
  for (const PatchSet* set : {&teapot(), &torus(), &cube}) {
    const PreparedSurface prepared(*set);
    Tessellation reused;
    for (Named frame : frames(*set)) {
      frame.options.split_patches = false;
      SCOPED_TRACE(frame.name);
      const bool relative_mode = frame.options.relative_tolerance.has_value();
      tessellate(prepared, frame.options, reused);
      testing::expect_identical_tessellations(reused, tessellate(surface_pieces(*set, relative_mode), frame.options));
    }
  }
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

// The camera's tolerances are on the ladder 2^(k/16): each is the largest ladder value at most
// the tolerance asked for (tau z_min / f_px), so a moving camera's plans repeat from frame to
// frame. Over tolerances from 1e-300 to 1e300: at most t, within a step of it, a ladder value
// maps to itself, and the ladder keeps the order.
TEST(PreparedSurface, CameraTolerancesLieOnTheLadderJustBelowTheirOwn) {
  const double step = std::exp2(-1.0 / 16);
  double previous_t = 0.0;
  double previous = 0.0;
  for (double t = 1e-300; t < 1e300; t *= 1.0137) {
    const double on = detail::tolerance_on_ladder(t);
    ASSERT_LE(on, t) << t;
    ASSERT_GT(on, t * step * (1.0 - 1e-12)) << t;
    ASSERT_EQ(detail::tolerance_on_ladder(on), on) << t;
    ASSERT_GE(on, previous) << previous_t << " then " << t;
    previous = on;
    previous_t = t;
  }
  EXPECT_EQ(detail::tolerance_on_ladder(1.0), 1.0);
  EXPECT_EQ(detail::tolerance_on_ladder(0.5), 0.5);
  EXPECT_EQ(detail::tolerance_on_ladder(std::nextafter(1.0, 0.0)), std::nextafter(std::exp2(-1.0 / 16), 0.0));
  // A camera's run reports the largest of its patches' tolerances: a ladder value below the
  // largest tau z_min / f_px, and every patch meets its own.
  const TessellationOptions options = looking(teapot(), Vec3(0.73, -0.55, 0.49), BackFaceCulling::automatic);
  const Tessellation result = tessellate(teapot(), options);
  EXPECT_EQ(detail::tolerance_on_ladder(result.tolerance), result.tolerance);
  EXPECT_LE(result.error_bound, result.tolerance);
}

}  // namespace prepared_surface_test
}  // namespace patchwork
