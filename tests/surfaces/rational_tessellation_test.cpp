// Rational patches in a PatchSet and through the tessellator: adjacency with weights, the
// guarantee against the exact quadrics (distance to the implicit form), closed meshes, exact
// normals at the poles.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/errors.h"
#include "meshes/topology.h"
#include "surfaces/patch_set.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/rational_shapes.h"

namespace patchwork {
namespace {

std::vector<AnyBezierPatch> any(const std::vector<RationalBezierPatch>& patches) {
  return {patches.begin(), patches.end()};
}

// Every vertex, edge midpoint and triangle centroid of the mesh is within `bound` of the
// surface whose distance function is given, and every normal is the exact one.
void expect_on_surface(const RenderMesh& mesh, double bound, const std::function<double(const Vec3&)>& distance,
                       const std::function<Vec3(const Vec3&)>& exact_normal) {
  double worst = 0.0, worst_angle = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    worst = std::max(worst, distance(mesh.positions[v]));
    const Vec3 n = exact_normal(mesh.positions[v]);
    worst_angle = std::max(worst_angle, std::atan2(n.cross(mesh.normals[v]).norm(), n.dot(mesh.normals[v])));
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    for (const Vec3& p : {Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2), Vec3((a + b + c) / 3)}) {
      worst = std::max(worst, distance(p));
    }
  }
  EXPECT_LE(worst, bound);
  // The vertices lie on the surface to rounding, where the exact normal is defined.
  EXPECT_LT(worst_angle, 1e-7);
}

TEST(RationalPatchSet, SphereOctantsCloseUp) {
  const PatchSet set(any(testing::unit_sphere_octants()));
  const PatchSetReport r = report(set);
  EXPECT_EQ(r.patches, 8u);
  EXPECT_EQ(r.rational_patches, 8u);
  EXPECT_EQ(r.shared_edges, 12u);
  EXPECT_EQ(r.collapsed_edges, 8u);
  EXPECT_EQ(r.open_edges, 0u);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.consistently_oriented);
  // The octants meet with tangent continuity (one sphere) and, in their homogeneous nets, C^0
  // at least; the edges are the same rational curves, so there is no gap.
  EXPECT_EQ(r.g1_edges, 12u);
  EXPECT_GE(r.min_ck, 0);
  for (const SharedEdge& s : set.shared_edges()) EXPECT_LT(s.continuity.gap, 1e-15);
  EXPECT_THROW((void)set.patches(), InvalidInput);
  EXPECT_EQ(set.control_nets().size(), 8u);
}

TEST(RationalPatchSet, WeightsDecideWhetherAnEdgeIsShared) {
  // A quarter cylinder (the arc along u, weights 1, 1/sqrt2, 1; height along v) and the
  // polynomial patch on the same control points across the arc edge: the points agree, the
  // curves do not (a parabola is not the arc), so the edge must stay open on both sides.
  std::vector<Vec3> points;
  std::vector<double> weights;
  const auto arc = testing::quarter_circle(0.0);
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i <= 2; ++i) {
      points.emplace_back(arc[i].first.x(), arc[i].first.y(), static_cast<double>(j));
      weights.push_back(arc[i].second);
    }
  }
  const RationalBezierPatch cylinder(2, 1, points, weights);
  // Below the arc edge v0: the polynomial patch whose v1 edge has the arc's control points.
  std::vector<Vec3> below;
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i <= 2; ++i) below.push_back(Vec3(arc[i].first.x(), arc[i].first.y(), j - 1.0));
  }
  const BezierPatch3 parabolic(2, 1, below);
  const PatchSet apart(std::vector<AnyBezierPatch>{cylinder, parabolic});
  EXPECT_EQ(apart.shared_edges().size(), 0u);
  EXPECT_EQ(apart.rational_count(), 1u);
  // The straight edge u0 (weights 1, 1) against a flat polynomial patch is shared, without gap.
  const BezierPatch3 wall(1, 1, {Vec3(1, -1, 0), Vec3(1, 0, 0), Vec3(1, -1, 1), Vec3(1, 0, 1)});
  const PatchSet joined(std::vector<AnyBezierPatch>{cylinder, wall});
  ASSERT_EQ(joined.shared_edges().size(), 1u);
  const SharedEdge& s = joined.shared_edges().front();
  EXPECT_EQ(s.first.edge, PatchEdge::u0);
  EXPECT_EQ(s.second.edge, PatchEdge::u1);
  EXPECT_EQ(s.continuity.gap, 0.0);
  // The same rational patch with its weights scaled by 3 is the same surface: its edges are
  // shared with the original's copy moved onto it (weights proportional).
  std::vector<double> tripled = weights;
  for (double& w : tripled) w *= 3;
  const PatchSet scaled(std::vector<AnyBezierPatch>{cylinder, RationalBezierPatch(2, 1, points, tripled)});
  EXPECT_EQ(scaled.shared_edges().size(), 4u);  // each edge of the one with the same edge of the other
}

TEST(RationalPatchSet, EqualWeightsArePolynomial) {
  const BezierPatch3 wall(1, 1, {Vec3(1, -1, 0), Vec3(1, 0, 0), Vec3(1, -1, 1), Vec3(1, 0, 1)});
  const PatchSet set(std::vector<AnyBezierPatch>{RationalBezierPatch(1, 1, wall.control_points(), {2, 2, 2, 2})});
  EXPECT_EQ(set.rational_count(), 0u);
  EXPECT_EQ(set.patches().front().control_points(), wall.control_points());
}

class RationalTessellation : public ::testing::TestWithParam<double> {};

TEST_P(RationalTessellation, SphereIsClosedAndWithinTheTolerance) {
  const double tolerance = GetParam();
  const PatchSet set(any(testing::unit_sphere_octants()));
  TessellationOptions options;
  options.tolerance = tolerance;
  const Tessellation result = tessellate(set, options);
  EXPECT_LE(result.error_bound, tolerance);
  EXPECT_GT(result.measured_error, 0.0);
  EXPECT_LE(result.measured_error, result.error_bound);
  expect_on_surface(
      result.mesh, result.error_bound, [](const Vec3& p) { return std::abs(p.norm() - 1.0); },
      [](const Vec3& p) { return p.normalized(); });
  const TopologyReport topology = analyze(welded_faces(result.mesh));
  EXPECT_TRUE(topology.closed);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.components, 1);
  EXPECT_EQ(topology.euler, 2);
  // Each pole is one vertex position with the exact normal.
  for (const Vec3& pole : {Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
    int found = 0;
    for (std::size_t v = 0; v < result.mesh.vertex_count(); ++v) {
      if ((result.mesh.positions[v] - pole).norm() > 1e-12) continue;
      ++found;
      EXPECT_LT((result.mesh.normals[v] - pole).norm(), 1e-12);
    }
    EXPECT_GE(found, 1);
  }
}

TEST_P(RationalTessellation, TorusIsClosedAndWithinTheTolerance) {
  const double tolerance = GetParam();
  const double R = 2.0, r = 0.5;
  const PatchSet set(any(testing::torus_patches(R, r)));
  const PatchSetReport patches = report(set);
  EXPECT_EQ(patches.shared_edges, 32u);
  EXPECT_TRUE(patches.closed);
  EXPECT_TRUE(patches.consistently_oriented);
  TessellationOptions options;
  options.tolerance = tolerance;
  const Tessellation result = tessellate(set, options);
  EXPECT_LE(result.error_bound, tolerance);
  EXPECT_LE(result.measured_error, result.error_bound);
  expect_on_surface(
      result.mesh, result.error_bound, [&](const Vec3& p) { return testing::torus_distance(p, R, r); },
      [&](const Vec3& p) { return testing::torus_normal(p, R); });
  const TopologyReport topology = analyze(welded_faces(result.mesh));
  EXPECT_TRUE(topology.closed);
  EXPECT_EQ(topology.components, 1);
  EXPECT_EQ(topology.euler, 0);
}

// 1e-4 (0.2 M and 0.4 M triangles) is left to the Release build.
#ifdef PATCHWORK_ENABLE_ASSERTS
INSTANTIATE_TEST_SUITE_P(Tolerances, RationalTessellation, ::testing::Values(1e-2, 1e-3));
#else
INSTANTIATE_TEST_SUITE_P(Tolerances, RationalTessellation, ::testing::Values(1e-2, 1e-3, 1e-4));
#endif

TEST(RationalTessellation, UniformAndCameraModesTakeRationalPieces) {
  const PatchSet set(any(testing::unit_sphere_octants()));
  TessellationOptions uniform;
  uniform.segments = 3;
  const Tessellation grid = tessellate(set, uniform);
  EXPECT_EQ(grid.mesh.triangle_count(), 8u * 3 * 3 * 2 - 8u * 3);  // a collapsed row of triangles per octant
  TessellationOptions view;
  view.camera = Camera{Vec3(0, -6, 0), Vec3::Zero(), Vec3::UnitZ(), 45.0, 800, 600};
  view.pixel_tolerance = 0.5;
  const Tessellation seen = tessellate(set, view);
  // Rational pieces are not culled as back-facing: all 8 octants are tessellated.
  EXPECT_EQ(seen.culled_patches, 0u);
  EXPECT_LE(seen.measured_error, seen.error_bound);
}

}  // namespace
}  // namespace patchwork
