// The measured error (surfaces/tessellator_measure.cpp) against the straightforward reference of
// tests/surfaces/measured_error_reference.h: every sample of every triangle, point by point with
// the patch's own evaluate. The meter evaluates a sample that two triangles share once, skips
// corners that are the piece's own surface points and evaluates with evaluate_points; per piece
// the two agree to the rounding of S and L (a few units in the last place of the coordinates), on
// fixed sets (the teapot, the mixed-degree lens, rational and NURBS shapes, T-junctions; whole
// and split pieces; tolerances, segments and a camera) and on generated ones.

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/bpt.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/measured_error_reference.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/patch_set_fixtures.h"
#include "tests/surfaces/rational_shapes.h"

// A named namespace: the test programs are unity builds.
namespace patchwork::tessellator_measure {
namespace {

using testing::MeasuredErrorComparison;

// The point of piece p of `pieces` (made from `set`) at (u, v): its patch's own evaluate (tensor
// de Casteljau, rational or not) at the piece's parameters in the patch.
testing::PiecePoint own_point(const PatchSet& set, const SurfacePieces& pieces) {
  return [&set, &pieces](std::uint32_t p, double u, double v) {
    std::uint32_t patch = p;
    if (!pieces.domains.empty()) {
      const SurfacePieces::Domain& d = pieces.domains[p];
      patch = d.patch;
      u = d.u0 + d.size * u;
      v = d.v0 + d.size * v;
    }
    const RationalBezierPatch* rational = set.rational(patch);
    return rational != nullptr ? rational->evaluate(u, v) : set.control_nets()[patch].evaluate(u, v);
  };
}

double largest(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

// What differs beyond rounding between the meter and the reference (empty: nothing). Rounding:
// S from two evaluation schemes and L from the same sums, both of the size of the coordinates.
std::string mismatch(const MeasuredErrorComparison& c) {
  std::ostringstream says;
  const double rounding = 1e-13 * std::max(c.scale, 1e-300);
  for (std::size_t p = 0; p < c.meter.size(); ++p) {
    if (!(std::abs(c.meter[p] - c.reference[p]) <= rounding)) {
      says << "piece " << p << ": meter " << c.meter[p] << ", reference " << c.reference[p] << "; ";
    }
  }
  if (!(std::abs(c.measured_error - largest(c.reference)) <= rounding)) {
    says << "measured_error " << c.measured_error << ", reference " << largest(c.reference) << "; ";
  }
  // The run measured the same positions (unless the vertices of unused interior points were
  // dropped, where the reference puts the piece's own point for them).
  if (!c.unused_interior && c.measured_error != largest(c.meter)) {
    says << "measured_error " << c.measured_error << " is not the largest piece's " << largest(c.meter) << "; ";
  }
  return says.str();
}

// |a - b| in units in the last place of b.
double ulps(double a, double b) {
  const double ulp = std::nextafter(b, std::numeric_limits<double>::infinity()) - b;
  return std::abs(a - b) / ulp;
}

TEST(TessellatorMeasure, MatchesTheReferenceOnFixedSets) {
  struct Set {
    const char* name;
    PatchSet set;
  };
  std::vector<Set> sets;
  sets.push_back({"teapot", PatchSet(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"))});
  sets.push_back({"mixed-degree lens", PatchSet(testing::mixed_degree_lens())});
  sets.push_back({"rational sphere", PatchSet(testing::as_any(testing::unit_sphere_octants()))});
  sets.push_back({"rational torus", PatchSet(testing::as_any(testing::torus_patches(2.0, 0.5)))});
  sets.push_back({"wedge (rational and polynomial)", PatchSet(testing::wedge(1.0, 0.4, Vec3(0.1, 0.2, 0.3)))});
  sets.push_back({"NURBS sphere", PatchSet(bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0)).patches)});
  sets.push_back({"NURBS cone", PatchSet(bezier_patches(nurbs_cone(Vec3::Zero(), 1.0, 1.5)).patches)});
  sets.push_back({"T-junctions", PatchSet(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3, 0.55}))});
  TessellationOptions camera;
  camera.camera = Camera{Vec3(8, -6, 5), Vec3(0, 0, 1.5), Vec3::UnitZ(), 40.0, 640, 480};
  camera.pixel_tolerance = 1.0;
  camera.back_face_culling = BackFaceCulling::always;
  // A relative tolerance or segments.
  const auto mode = [](std::optional<double> relative_tolerance, std::optional<int> segments) {
    TessellationOptions options;
    options.relative_tolerance = relative_tolerance;
    options.segments = segments;
    return options;
  };
#ifdef PATCHWORK_ENABLE_ASSERTS
  const std::vector<TessellationOptions> modes = {mode(1e-2, {}), mode({}, 3), mode({}, 5)};
#else
  const std::vector<TessellationOptions> modes = {mode(1e-2, {}), mode(1e-3, {}), mode({}, 3), mode({}, 8)};
#endif
  double worst_ulps = 0.0;
  double worst_coordinate_ulps = 0.0;
  for (const Set& s : sets) {
    const bool splits = s.set.t_junctions().empty();
    for (const int k : {1, 2, 4}) {
      if (k > 1 && !splits) continue;
      const SurfacePieces pieces = k == 1 ? surface_pieces(s.set) : split_surface_pieces(s.set, k);
      std::vector<TessellationOptions> runs = modes;
      // The camera mode needs whole patches; the teapot's view culls some.
      if (k == 1 && std::string(s.name) == "teapot") runs.push_back(camera);
#ifndef PATCHWORK_ENABLE_ASSERTS
      // Rows of 16 cells and more: the inner cells are evaluated a row at a time.
      if (k == 1) runs.push_back(mode({}, 20));
#endif
      for (TessellationOptions& options : runs) {
        options.threads = 2;
        const MeasuredErrorComparison c = testing::compare_measured_error(pieces, options, own_point(s.set, pieces));
        SCOPED_TRACE(::testing::Message() << s.name << ", " << k << " x " << k << " pieces, "
                                          << (options.camera     ? "camera"
                                              : options.segments ? "segments"
                                                                 : "tolerance"));
        EXPECT_EQ(mismatch(c), "");
        EXPECT_GT(c.triangles, 0u);
        const double reference = largest(c.reference);
        // The same difference in units of the coordinates' last place (the rounding of S and L).
        const double coordinate_ulps = std::abs(c.measured_error - reference) / (std::ldexp(1.0, -52) * c.scale);
        if (reference > 0.0) worst_ulps = std::max(worst_ulps, ulps(c.measured_error, reference));
        worst_coordinate_ulps = std::max(worst_coordinate_ulps, coordinate_ulps);
        std::cout << s.name << ", " << k << " x " << k << ", " << (options.camera ? "camera" : "")
                  << (options.segments ? "segments " + std::to_string(*options.segments) : "")
                  << (options.relative_tolerance ? "relative " + std::to_string(*options.relative_tolerance) : "")
                  << ": " << c.triangles << " triangles, measured " << c.measured_error << ", reference " << reference
                  << ", " << ulps(c.measured_error, reference) << " ulps of the error apart (" << coordinate_ulps
                  << " of the coordinates)\n";
      }
    }
  }
  std::cout << "the meter and the reference differ by at most " << worst_ulps << " ulps of the error, "
            << worst_coordinate_ulps << " ulps of the coordinates\n";
}

// Welding gives a point the position of one side of a shared edge; where the sides differ (here
// the right patch's corner control point lies delta above the left's), the other side's mesh
// point is off its own surface point, and the corner sample measures it: the largest sampled
// distance of the right patch is at that corner, delta (its edge midpoints move by less).
TEST(TessellatorMeasure, SamplesTheCornersThatWeldingMoved) {
  const double delta = 2e-3;
  const auto [left, right] =
      testing::height_fields_side_by_side([delta](int j) { return Vec3(0, 0, j == 0 ? delta : 0.0); });
  const PatchSet set({left, right}, 1e-3);
  ASSERT_EQ(set.shared_edges().size(), 1u);
  TessellationOptions options;
  options.tolerance = 1e-4;
  for (const int k : {1, 2}) {
    SCOPED_TRACE(::testing::Message() << k << " x " << k << " pieces");
    const SurfacePieces pieces = k == 1 ? surface_pieces(set) : split_surface_pieces(set, k);
    const MeasuredErrorComparison c = testing::compare_measured_error(pieces, options, own_point(set, pieces));
    EXPECT_EQ(mismatch(c), "");
    // Whole, the corner's delta is the largest; split, a sample beside it adds a little chord error.
    if (k == 1) {
      EXPECT_NEAR(c.measured_error, delta, 1e-15);
    }
    EXPECT_GE(c.measured_error, delta * (1 - 1e-12));
    EXPECT_LE(c.measured_error, 1.01 * delta);
  }
}

// A camera that sees the set from a random direction, 1.5 to 3 box diagonals from its centre.
Camera random_camera(const PatchSet& set) {
  Eigen::AlignedBox3d box;
  for (const BezierPatch3& net : set.control_nets()) {
    for (const Vec3& x : net.control_points()) box.extend(x);
  }
  Vec3 direction(*testing::coordinate(-1, 1), *testing::coordinate(-1, 1), *testing::coordinate(-1, 1));
  if (direction.norm() < 0.1) direction = Vec3(1, -0.5, 0.3);
  direction.normalize();
  const Vec3 up = std::abs(direction.z()) > 0.9 ? Vec3::UnitX() : Vec3::UnitZ();
  const double distance = *testing::coordinate(1.5, 3.0) * box.diagonal().norm();
  return Camera{box.center() + distance * direction, box.center(), up, 40.0, 640, 480};
}

// Generated sets (grids, fans, lenses, cubes; turned, elevated, moved; sometimes two), whole or
// split, in every mode, on 1 to 3 threads.
RC_GTEST_PROP(TessellatorMeasure, MatchesTheReferenceOnGeneratedSets, ()) {
  const testing::PatchSetFixture fixture = *testing::any_patch_set();
  RC_TAG(fixture.kind);
  const PatchSet set(fixture.patches);
  const int k = set.t_junctions().empty() ? *rc::gen::element(1, 2, 4) : 1;
  const SurfacePieces pieces = k == 1 ? surface_pieces(set) : split_surface_pieces(set, k);
  TessellationOptions options;
  const int mode = *rc::gen::inRange(0, k == 1 ? 3 : 2);
  if (mode == 0) {
    options.relative_tolerance = *rc::gen::element(3e-2, 1e-2, 3e-3);
  } else if (mode == 1) {
    options.segments = *rc::gen::inRange(2, 7);
  } else {
    options.camera = random_camera(set);
    options.pixel_tolerance = *rc::gen::element(1.0, 3.0);
  }
  options.threads = *rc::gen::inRange(1, 4);
  RC_LOG() << fixture.kind << ", " << k << " x " << k << " pieces, mode " << mode << ", " << options.threads
           << " threads";
  const MeasuredErrorComparison c = testing::compare_measured_error(pieces, options, own_point(set, pieces));
  const std::string says = mismatch(c);
  RC_LOG() << says;
  RC_ASSERT(says.empty());
}

}  // namespace
}  // namespace patchwork::tessellator_measure
