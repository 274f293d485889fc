#include "surfaces/patch_set.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <nlohmann/json.hpp>
#include <algorithm>
#include <numeric>
#include <random>
#include <sstream>

#include "core/errors.h"
#include "io/bpt.h"
#include "surfaces/patch_transform.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/rational_shapes.h"

namespace patchwork {
namespace {

using testing::bilinear;
using testing::coordinate;

// A rows x cols grid of unit bilinear squares in the plane z = 0, all with normal +z.
std::vector<BezierPatch3> square_grid(int rows, int cols) {
  std::vector<BezierPatch3> patches;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      patches.push_back(bilinear(Vec3(c, r, 0), Vec3(c + 1, r, 0), Vec3(c, r + 1, 0), Vec3(c + 1, r + 1, 0)));
    }
  }
  return patches;
}

// The unit cube as six outward bilinear faces (see surface_integrals_test.cpp).
std::vector<BezierPatch3> unit_cube() {
  const auto face = [](Vec3 origin, Vec3 a, Vec3 b) { return bilinear(origin, origin + a, origin + b, origin + a + b); };
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ(), o = Vec3::Zero();
  return {face(o, y, x), face(z, x, y), face(o, x, z), face(y, z, x), face(o, z, y), face(x, y, z)};
}

// The same surface with u reversed (P_ij -> P_{n-i,j}): the orientation flips.
BezierPatch3 reversed_u(const BezierPatch3& patch) {
  std::vector<Vec3> points;
  for (int j = 0; j <= patch.degree_v(); ++j) {
    for (int i = patch.degree_u(); i >= 0; --i) points.push_back(patch.control_point(i, j));
  }
  return BezierPatch3(patch.degree_u(), patch.degree_v(), points);
}

// The bottom half of a curved patch against its top half cut at u = 0.3 (subpatch, so the
// pieces' edges are the long edge's de Casteljau pieces up to rounding): one T-junction, the
// long edge and its two parts no longer open, one boundary loop around the whole.
TEST(PatchSet, TJunctionIsFound) {
  const PatchSet set(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}));
  ASSERT_EQ(set.t_junctions().size(), 1u);
  const TJunction& t = set.t_junctions()[0];
  EXPECT_EQ(t.edge, (EdgeRef{0, PatchEdge::v1}));
  EXPECT_EQ(t.parts, (std::vector<EdgeRef>{{1, PatchEdge::v0}, {2, PatchEdge::v0}}));
  ASSERT_EQ(t.breaks.size(), 2u);
  EXPECT_NEAR(t.breaks[0], 0.3, 1e-12);
  EXPECT_EQ(t.breaks[1], 1.0);
  EXPECT_EQ(t.reversed, (std::vector<bool>{false, false}));
  EXPECT_TRUE(t.consistently_oriented);
  EXPECT_LT(t.gap, 1e-14);
  EXPECT_EQ(set.shared_edges().size(), 1u);  // between the two top pieces
  EXPECT_EQ(set.open_edges().size(), 7u);
  ASSERT_EQ(set.boundary_loops().size(), 1u);
  EXPECT_TRUE(set.boundary_loops()[0].closed);
  EXPECT_EQ(set.boundary_loops()[0].edges.size(), 7u);
  EXPECT_TRUE(set.touching_points().empty());
  const PatchSetReport r = report(set);
  EXPECT_EQ(r.t_junctions, 1u);
  EXPECT_TRUE(r.consistently_oriented);
  const nlohmann::json json = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(json["t_junctions"], 1);
  EXPECT_EQ(json["junctions"][0]["parts"][1]["edge"], "v0");
}

// Three parts, one of them turned by 180 degrees (it meets the long edge with its v1 edge,
// running the other way) and one of higher degree along the edge; and the orientation flip of a
// part mirrored in u is reported.
TEST(PatchSet, TJunctionWithReversedAndElevatedParts) {
  std::vector<BezierPatch3> patches = testing::t_junction_pieces(testing::wavy_bicubic(), {0.25, 0.6});
  patches[2] = testing::turned_half(patches[2]);
  patches[3] = elevate_degree(patches[3], 2, 0);
  const PatchSet set(patches);
  ASSERT_EQ(set.t_junctions().size(), 1u);
  const TJunction& t = set.t_junctions()[0];
  EXPECT_EQ(t.parts, (std::vector<EdgeRef>{{1, PatchEdge::v0}, {2, PatchEdge::v1}, {3, PatchEdge::v0}}));
  EXPECT_EQ(t.reversed, (std::vector<bool>{false, true, false}));
  EXPECT_NEAR(t.breaks[0], 0.25, 1e-12);
  EXPECT_NEAR(t.breaks[1], 0.6, 1e-12);
  EXPECT_TRUE(t.consistently_oriented);
  EXPECT_EQ(set.open_edges().size(), 8u);  // bottom v0, u0, u1; three tops; two outer sides
  patches[1] = reversed_u(patches[1]);
  const PatchSet flipped(patches);
  ASSERT_EQ(flipped.t_junctions().size(), 1u);
  EXPECT_FALSE(flipped.t_junctions()[0].consistently_oriented);
  EXPECT_FALSE(report(flipped).consistently_oriented);
  // A piece that does not follow the long edge (moved off it by 1e-3) is no part: no junction.
  std::vector<BezierPatch3> apart = testing::t_junction_pieces(testing::wavy_bicubic(), {0.3});
  std::vector<Vec3> points = apart[1].control_points();
  points[1].z() += 1e-3;
  apart[1] = BezierPatch3(3, 3, points);
  EXPECT_TRUE(PatchSet(apart).t_junctions().empty());
}

TEST(PatchSet, GridOfSquares) {
  const PatchSet set(square_grid(2, 3));
  // Interior edges of a 2 x 3 grid: 2 * 2 vertical + 1 * 3 horizontal = 7; boundary 2 * (2 + 3) = 10.
  EXPECT_EQ(set.shared_edges().size(), 7u);
  EXPECT_EQ(set.open_edges().size(), 10u);
  EXPECT_TRUE(set.collapsed_edges().empty());
  ASSERT_EQ(set.boundary_loops().size(), 1u);
  EXPECT_TRUE(set.boundary_loops()[0].closed);
  EXPECT_EQ(set.boundary_loops()[0].edges.size(), 10u);
  EXPECT_TRUE(set.touching_points().empty());
  const PatchSetReport r = report(set);
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_FALSE(r.closed);
  // Bilinear squares of one plane: the parametrisations continue C^1 (same spacing), G^1 everywhere.
  EXPECT_EQ(r.min_ck, 1);
  EXPECT_EQ(r.g1_edges, 7u);
}

TEST(PatchSet, CubeIsClosedAndOriented) {
  const PatchSet set(unit_cube());
  EXPECT_EQ(set.shared_edges().size(), 12u);
  EXPECT_TRUE(set.open_edges().empty());
  EXPECT_TRUE(set.boundary_loops().empty());
  const PatchSetReport r = report(set);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_EQ(r.g1_edges, 0u);  // cube edges are creases of 90 degrees
  for (const SharedEdge& e : set.shared_edges()) EXPECT_NEAR(e.continuity.max_normal_angle, std::acos(0.0), 1e-12);
  // Flipping one face breaks the orientation of its four edges only.
  std::vector<BezierPatch3> flipped = unit_cube();
  flipped[2] = reversed_u(flipped[2]);
  const PatchSet broken(flipped);
  EXPECT_EQ(broken.shared_edges().size(), 12u);
  EXPECT_EQ(std::count_if(broken.shared_edges().begin(), broken.shared_edges().end(),
                          [](const SharedEdge& e) { return !e.consistently_oriented; }), 4);
  EXPECT_FALSE(report(broken).consistently_oriented);
}

TEST(PatchSet, SplitPatchJoinsWithFullContinuity) {
  // The two halves of one bicubic patch agree in every derivative across the split: C^3.
  std::vector<Vec3> points;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) points.emplace_back(i, j, std::sin(1.0 + i * j) + 0.1 * i * i);
  }
  const BezierPatch3 patch(3, 3, points);
  const auto [left, right] = split_u(patch, 0.5);
  const PatchSet set({left, right});
  ASSERT_EQ(set.shared_edges().size(), 1u);
  const SharedEdge& e = set.shared_edges()[0];
  EXPECT_EQ(e.continuity.ck, 3);
  EXPECT_TRUE(e.continuity.g1);
  EXPECT_LT(e.continuity.max_normal_angle, 1e-12);
  EXPECT_EQ(e.continuity.gap, 0.0);
}

TEST(PatchSet, ContinueAcrossBuildsCkJoins) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Vec3> points;
  for (int k = 0; k < 16; ++k) points.emplace_back(k % 4 + 0.2 * value(random), k / 4 + 0.2 * value(random), value(random));
  const BezierPatch3 patch(3, 3, points);
  for (PatchEdge edge : {PatchEdge::v0, PatchEdge::u1, PatchEdge::v1, PatchEdge::u0}) {
    for (int k = 0; k <= 2; ++k) {
      const auto rows = continue_across(patch, edge, k, 3);
      std::vector<Vec3> net;
      for (int j = 0; j <= 3; ++j) {
        for (int i = 0; i <= 3; ++i) net.push_back(j <= k ? rows[j][i] : Vec3(value(random), value(random), 3.0 + j + value(random)));
      }
      // The neighbour has its v0 edge on `edge`, u along boundary_curve(patch, edge).
      const EdgeContinuity c = edge_continuity(patch, edge, BezierPatch3(3, 3, net), PatchEdge::v0, false);
      EXPECT_EQ(c.gap, 0.0);
      EXPECT_EQ(c.ck, k) << edge_name(edge) << " k=" << k;  // generic free rows: not C^(k+1)
      if (k >= 1) {
        EXPECT_LT(c.max_normal_angle, 1e-9);
      }
    }
  }
  EXPECT_THROW(continue_across(patch, PatchEdge::v0, 4, 3), InvalidInput);
}

TEST(PatchSet, CollapsedEdgesAndTouchingPoints) {
  // A triangle-like patch with edge v0 collapsed, and two squares meeting only at a corner.
  const BezierPatch3 cap = bilinear(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(-1, 1, 0), Vec3(1, 1, 0));
  const BezierPatch3 a = bilinear(Vec3(5, 5, 0), Vec3(6, 5, 0), Vec3(5, 6, 0), Vec3(6, 6, 0));
  const BezierPatch3 b = bilinear(Vec3(6, 6, 0), Vec3(7, 6, 0), Vec3(6, 7, 0), Vec3(7, 7, 0));
  const PatchSet set({cap, a, b});
  ASSERT_EQ(set.collapsed_edges().size(), 1u);
  EXPECT_EQ(set.collapsed_edges()[0], (EdgeRef{0, PatchEdge::v0}));
  ASSERT_EQ(set.touching_points().size(), 1u);
  EXPECT_EQ(set.touching_points()[0].point, Vec3(6, 6, 0));
  EXPECT_EQ(set.touching_points()[0].groups, (std::vector<std::vector<std::uint32_t>>{{1}, {2}}));
  EXPECT_EQ(set.open_edges().size(), 11u);
  EXPECT_EQ(set.boundary_loops().size(), 3u);
}

TEST(PatchSet, ToleranceDecidesNearMisses) {
  std::vector<BezierPatch3> patches = square_grid(1, 2);
  std::vector<Vec3> moved = patches[1].control_points();
  for (Vec3& p : moved) p.z() += 1e-12;  // far below the default 1e-9 * diagonal
  const PatchSet close({patches[0], BezierPatch3(1, 1, moved)});
  ASSERT_EQ(close.shared_edges().size(), 1u);
  EXPECT_NEAR(close.shared_edges()[0].continuity.gap, 1e-12, 1e-15);
  for (Vec3& p : moved) p.z() += 1e-6;
  const PatchSet apart({patches[0], BezierPatch3(1, 1, moved)});
  EXPECT_TRUE(apart.shared_edges().empty());
  EXPECT_EQ(apart.open_edges().size(), 8u);
  EXPECT_THROW(PatchSet(std::vector<BezierPatch3>{}), InvalidInput);
  EXPECT_THROW(PatchSet(std::vector<AnyBezierPatch>{}), InvalidInput);
  EXPECT_THROW(PatchSet(patches, -1.0), InvalidInput);
}

RC_GTEST_PROP(PatchSet, AdjacencyIgnoresOrderDirectionAndRigidMotion, ()) {
  std::vector<BezierPatch3> patches = unit_cube();
  const Eigen::Isometry3d motion = *testing::random_rigid_motion();
  for (BezierPatch3& p : patches) p = testing::transformed(p, Eigen::Affine3d(motion));
  const auto order = *rc::gen::container<std::vector<bool>>(6, rc::gen::arbitrary<bool>());
  for (std::size_t k = 0; k < 6; ++k) {
    if (order[k]) patches[k] = reversed_u(patches[k]);
  }
  std::mt19937 random(*rc::gen::inRange(0, 1000));
  std::shuffle(patches.begin(), patches.end(), random);
  const PatchSet set(patches);
  RC_ASSERT(set.shared_edges().size() == 12u);
  RC_ASSERT(set.open_edges().empty());
  const bool all_same = std::all_of(order.begin(), order.end(), [&](bool b) { return b == order[0]; });
  RC_ASSERT(report(set).consistently_oriented == all_same);
}

TEST(PatchSetReport, PrintsTextAndJson) {
  const PatchSet set(square_grid(1, 2));
  std::ostringstream text;
  text << report(set);
  EXPECT_NE(text.str().find("2 patches, 1 shared edges, 6 open edges"), std::string::npos) << text.str();
  const nlohmann::json json = nlohmann::json::parse(to_json(report(set)));
  EXPECT_EQ(json["patches"], 2);
  EXPECT_EQ(json["shared_edges"], 1);
  EXPECT_EQ(json["open_edges"], 6);
  EXPECT_EQ(json["boundary_loops"], 1);
  EXPECT_EQ(json["closed"], false);
  EXPECT_EQ(json["shared"][0]["ck"], 1);
  EXPECT_EQ(json["loops"][0]["edges"].size(), 6u);
}

}  // namespace
}  // namespace patchwork

namespace patchwork {
namespace {

// Found by fuzzing (tests/fuzz/regressions/fuzz_tessellator): a set whose control points are all
// one point has size 0, and its point grid divided coordinates by a cell of 1e-300 and converted
// the quotient to an integer (undefined behaviour under -fsanitize=undefined).
TEST(PatchSet, ASetOfOnePointIsAnalysedAndRefusedByTheTessellator) {
  const BezierPatch3 point(1, 1, std::vector<Vec3>(4, Vec3(-2, -2, -2)));
  const PatchSet set({point, point});
  EXPECT_EQ(set.size(), 0.0);
  EXPECT_EQ(set.collapsed_edges().size(), 8u);
  TessellationOptions options;
  options.segments = 2;
  EXPECT_THROW(tessellate(set, options), InvalidInput);
}


TEST(RationalPatchSet, SphereOctantsCloseUp) {
  const PatchSet set(testing::as_any(testing::unit_sphere_octants()));
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
  // The homogeneous nets of neighbouring octants join C^0 only (their second rows differ in
  // weight), a lower bound for the surfaces' continuity, which is C^infinity on the sphere.
  EXPECT_EQ(r.min_ck, 0);
  for (const SharedEdge& s : set.shared_edges()) EXPECT_LT(s.continuity.gap, 1e-15);
  EXPECT_EQ(nlohmann::json::parse(to_json(r))["rational_patches"], 8);
  std::ostringstream text;
  text << r;
  EXPECT_NE(text.str().find("8 patches (8 rational)"), std::string::npos);
  EXPECT_TRUE(set.is_rational(7));
  EXPECT_FALSE(set.is_rational(8));
  EXPECT_EQ(set.rational(8), nullptr);
  EXPECT_THROW((void)set.patch(8), InvalidInput);
  EXPECT_THROW((void)set.rational_patch(8), InvalidInput);
  EXPECT_EQ(std::get<RationalBezierPatch>(set.patch(3)).homogeneous().control_points(),
            testing::unit_sphere_octants()[3].homogeneous().control_points());
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
  EXPECT_EQ(apart.open_edges().size(), 8u);
  EXPECT_EQ(apart.rational_count(), 1u);
  // The straight edge u0 (weights 1, 1) against a flat polynomial patch is shared, without gap.
  const BezierPatch3 wall(1, 1, {Vec3(1, -1, 0), Vec3(1, 0, 0), Vec3(1, -1, 1), Vec3(1, 0, 1)});
  const PatchSet joined(std::vector<AnyBezierPatch>{cylinder, wall});
  ASSERT_EQ(joined.shared_edges().size(), 1u);
  const SharedEdge& s = joined.shared_edges().front();
  EXPECT_EQ(s.first.edge, PatchEdge::u0);
  EXPECT_EQ(s.second.edge, PatchEdge::u1);
  EXPECT_EQ(s.continuity.gap, 0.0);
  EXPECT_EQ(joined.open_edges().size(), 6u);
  // The wall continues the cylinder's tangent plane (x = 1 at the arc's start): G^1.
  EXPECT_TRUE(s.continuity.g1);
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


// The gap with weights that are proportional only within the tolerance: the reported bound holds
// the sampled distance of the two curves, and beyond the tolerance the edge is open.
TEST(RationalPatchSet, NearlyProportionalWeightsBoundTheGap) {
  const auto arc = testing::quarter_circle(0.3);
  const auto net = [&](double lift, double delta) {
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int j = 0; j <= 1; ++j) {
      for (int i = 0; i <= 2; ++i) {
        points.emplace_back(2 * arc[i].first.x(), 2 * arc[i].first.y(), lift * j);
        weights.push_back(arc[i].second * (1 + delta * i));
      }
    }
    return RationalBezierPatch(2, 1, points, weights);
  };
  // Below: the same arc as its v0 edge (z = 0), weights scaled by (1 + delta i).
  const RationalBezierPatch above = net(1.0, 0.0);
  for (const double delta : {3e-10, 3e-9}) {
    const RationalBezierPatch below = net(-1.0, delta);
    const PatchSet set(std::vector<AnyBezierPatch>{above, below});
    if (delta > 1e-9) {
      EXPECT_TRUE(set.shared_edges().empty()) << delta;
      continue;
    }
    ASSERT_EQ(set.shared_edges().size(), 1u) << delta;
    const double gap = set.shared_edges().front().continuity.gap;
    EXPECT_GT(gap, 0.0);
    double sampled = 0.0;
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0;
      sampled = std::max(sampled, (above.evaluate(t, 0.0) - below.evaluate(t, 0.0)).norm());
    }
    EXPECT_LE(sampled, gap);
    EXPECT_GT(sampled, 0.1 * gap);  // and the bound is not loose by orders of magnitude
  }
  // An arc against its degree-elevated form, reversed: the same curve, shared without gap.
  const RationalBezierPatch elevated = elevate_degree(above, 1, 0);
  std::vector<Vec4> turned = elevated.homogeneous().control_points();
  for (int j = 0; j <= 1; ++j) std::reverse(turned.begin() + 4 * j, turned.begin() + 4 * j + 4);
  for (Vec4& h : turned) h.z() = -h.z() + 2 * h.w();  // moved up by reflection: its bottom edge is above's top
  const PatchSet pair(std::vector<AnyBezierPatch>{above, RationalBezierPatch(BezierPatch4(3, 1, turned))});
  ASSERT_EQ(pair.shared_edges().size(), 1u);
  EXPECT_TRUE(pair.shared_edges().front().reversed);
  EXPECT_LT(pair.shared_edges().front().continuity.gap, 1e-14);
}

// A rational edge against its two halves (homogeneous de Casteljau): not a T-junction, which
// rational edges take no part in; all three edges stay open.
TEST(RationalPatchSet, RationalEdgesTakeNoPartInTJunctions) {
  const RationalBezierPatch octant = sphere_octant(Vec3::Zero(), 1.0);
  const auto [left, right] = split_u(octant, 0.5);
  // The halves mirrored through z = 0 meet the octant along its equator (edge v0) in halves.
  const auto mirrored = [](const RationalBezierPatch& patch) {
    std::vector<Vec4> H = patch.homogeneous().control_points();
    for (Vec4& h : H) h.z() = -h.z();
    return RationalBezierPatch(BezierPatch4(patch.degree_u(), patch.degree_v(), H));
  };
  const PatchSet set(std::vector<AnyBezierPatch>{octant, mirrored(left), mirrored(right)});
  EXPECT_TRUE(set.t_junctions().empty());
  for (std::uint32_t p : {0u, 1u, 2u}) {
    EXPECT_NE(std::find(set.open_edges().begin(), set.open_edges().end(), EdgeRef{p, PatchEdge::v0}), set.open_edges().end())
        << "patch " << p << ": its equator edge stays open";
  }
  EXPECT_EQ(set.rational_count(), 3u);
}


// --- subsets of whole shells -------------------------------------------------------------------

// The adjacency of `a` and `b` is the same, element for element (touching points' positions
// within `tolerance`: each is one of the corners there).
void expect_same_adjacency(const PatchSet& a, const PatchSet& b, double tolerance) {
  ASSERT_EQ(a.count(), b.count());
  ASSERT_EQ(a.shared_edges().size(), b.shared_edges().size());
  for (std::size_t k = 0; k < a.shared_edges().size(); ++k) {
    const SharedEdge& s = a.shared_edges()[k];
    const SharedEdge& t = b.shared_edges()[k];
    EXPECT_EQ(s.first, t.first) << k;
    EXPECT_EQ(s.second, t.second) << k;
    EXPECT_EQ(s.reversed, t.reversed) << k;
    EXPECT_EQ(s.consistently_oriented, t.consistently_oriented) << k;
    EXPECT_EQ(s.continuity.ck, t.continuity.ck) << k;
    EXPECT_EQ(s.continuity.g1, t.continuity.g1) << k;
    EXPECT_EQ(s.continuity.gap, t.continuity.gap) << k;
  }
  EXPECT_EQ(a.collapsed_edges(), b.collapsed_edges());
  EXPECT_EQ(a.open_edges(), b.open_edges());
  ASSERT_EQ(a.t_junctions().size(), b.t_junctions().size());
  for (std::size_t k = 0; k < a.t_junctions().size(); ++k) {
    EXPECT_EQ(a.t_junctions()[k].edge, b.t_junctions()[k].edge);
    EXPECT_EQ(a.t_junctions()[k].parts, b.t_junctions()[k].parts);
    EXPECT_EQ(a.t_junctions()[k].breaks, b.t_junctions()[k].breaks);
    EXPECT_EQ(a.t_junctions()[k].reversed, b.t_junctions()[k].reversed);
  }
  ASSERT_EQ(a.boundary_loops().size(), b.boundary_loops().size());
  for (std::size_t k = 0; k < a.boundary_loops().size(); ++k) {
    EXPECT_EQ(a.boundary_loops()[k].edges, b.boundary_loops()[k].edges) << k;
    EXPECT_EQ(a.boundary_loops()[k].closed, b.boundary_loops()[k].closed) << k;
  }
  ASSERT_EQ(a.touching_points().size(), b.touching_points().size());
  for (std::size_t k = 0; k < a.touching_points().size(); ++k) {
    EXPECT_EQ(a.touching_points()[k].groups, b.touching_points()[k].groups) << k;
    EXPECT_LE((a.touching_points()[k].point - b.touching_points()[k].point).norm(), tolerance) << k;
  }
}

// The set analysed afresh from the subset's patches with the subset's absolute tolerance: what
// the subset's carried-over adjacency must be.
PatchSet analysed_afresh(const PatchSet& subset) {
  std::vector<AnyBezierPatch> patches;
  for (std::uint32_t p = 0; p < subset.count(); ++p) patches.push_back(subset.patch(p));
  return PatchSet(patches, subset.tolerance() / subset.size());
}

// Shells of a scene (the teapot, a copy of it moved and turned, a T-junction, a rational
// sphere), and subsets of whole shells: each has the adjacency a fresh analysis of its patches
// finds, its own control box and the set's tolerance.
TEST(PatchSet, SubsetOfWholeShellsKeepsTheAdjacency) {
  std::vector<AnyBezierPatch> scene;
  const std::vector<BezierPatch3> teapot = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  const Eigen::Affine3d moved = Eigen::Translation3d(10, -3, 2) * Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized());
  for (const BezierPatch3& patch : teapot) scene.emplace_back(patch);
  for (const BezierPatch3& patch : testing::t_junction_pieces(testing::wavy_bicubic(), {0.3})) {
    scene.emplace_back(transform(patch, Eigen::Affine3d(Eigen::Translation3d(-8, 0, 0))));
  }
  for (const RationalBezierPatch& octant : testing::unit_sphere_octants()) {
    scene.emplace_back(transform(octant, Eigen::Affine3d(Eigen::Translation3d(0, 9, 0))));
  }
  for (const BezierPatch3& patch : teapot) scene.emplace_back(transform(patch, moved));
  const PatchSet set(scene);
  const std::vector<Shell> parts = shells(set);
  ASSERT_GE(parts.size(), 6u);
  ASSERT_EQ(set.t_junctions().size(), 1u);
  ASSERT_EQ(set.touching_points().size(), 2u);  // each teapot's handle on its body
  // Every shell alone, every other shell, and all but the first.
  std::vector<std::vector<std::uint32_t>> subsets;
  for (const Shell& shell : parts) subsets.push_back(shell.patches);
  for (std::size_t start : {0, 1}) {
    std::vector<std::uint32_t> every_other;
    for (std::size_t k = start; k < parts.size(); k += 2) {
      every_other.insert(every_other.end(), parts[k].patches.begin(), parts[k].patches.end());
    }
    std::sort(every_other.begin(), every_other.end());
    subsets.push_back(every_other);
  }
  std::vector<std::uint32_t> all_but_first;
  for (std::size_t k = 1; k < parts.size(); ++k) {
    all_but_first.insert(all_but_first.end(), parts[k].patches.begin(), parts[k].patches.end());
  }
  std::sort(all_but_first.begin(), all_but_first.end());
  subsets.push_back(all_but_first);
  std::size_t with_touching = 0, with_junction = 0, rational = 0;
  for (const std::vector<std::uint32_t>& patches : subsets) {
    SCOPED_TRACE(detail::message("subset of ", patches.size(), " patches from ", patches.front()));
    const PatchSet subset = set.subset(patches);
    ASSERT_EQ(subset.count(), patches.size());
    for (std::size_t k = 0; k < patches.size(); ++k) {
      EXPECT_EQ(subset.control_nets()[k].control_points(), set.control_nets()[patches[k]].control_points());
      EXPECT_EQ(subset.is_rational(static_cast<std::uint32_t>(k)), set.is_rational(patches[k]));
    }
    EXPECT_EQ(subset.tolerance(), set.tolerance());
    const PatchSet fresh = analysed_afresh(subset);
    EXPECT_EQ(subset.size(), fresh.size());
    EXPECT_EQ(subset.rational_count(), fresh.rational_count());
    expect_same_adjacency(subset, fresh, subset.tolerance());
    with_touching += !subset.touching_points().empty();
    with_junction += !subset.t_junctions().empty();
    rational += subset.rational_count() > 0;
  }
  // All shells at once, one subset after the other: each the subset of its shell.
  std::vector<std::vector<std::uint32_t>> each_shell;
  for (const Shell& shell : parts) each_shell.push_back(shell.patches);
  std::size_t handed = 0;
  set.for_each_subset(each_shell, [&](std::size_t k, PatchSet& sub) {
    SCOPED_TRACE(detail::message("for_each_subset part ", k));
    EXPECT_EQ(k, handed++);
    const PatchSet alone = set.subset(each_shell[k]);
    EXPECT_EQ(sub.size(), alone.size());
    EXPECT_EQ(sub.tolerance(), alone.tolerance());
    for (std::uint32_t p = 0; p < sub.count(); ++p) {
      EXPECT_EQ(sub.control_nets()[p].control_points(), alone.control_nets()[p].control_points());
    }
    expect_same_adjacency(sub, alone, 0.0);
  });
  EXPECT_EQ(handed, parts.size());
  // The cases the scene is for did occur.
  EXPECT_GT(with_touching, 0u);
  EXPECT_GT(with_junction, 0u);
  EXPECT_GT(rational, 0u);
  // The whole set as a subset of itself.
  std::vector<std::uint32_t> every(set.count());
  std::iota(every.begin(), every.end(), 0u);
  expect_same_adjacency(set.subset(every), set, 0.0);
}

TEST(PatchSet, SubsetRefusesWhatIsNotWholeShells) {
  const PatchSet set(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}));
  const std::vector<std::uint32_t> none;
  EXPECT_THROW((void)set.subset(none), InvalidInput);
  const std::vector<std::uint32_t> long_edge_alone = {0};  // its parts are patches 1 and 2
  EXPECT_THROW((void)set.subset(long_edge_alone), InvalidInput);
  const std::vector<std::uint32_t> shared_cut = {0, 1};  // 1 shares an edge with 2
  EXPECT_THROW((void)set.subset(shared_cut), InvalidInput);
  const std::vector<std::uint32_t> backwards = {2, 1, 0};
  EXPECT_THROW((void)set.subset(backwards), InvalidInput);
  const std::vector<std::uint32_t> twice = {0, 1, 1, 2};
  EXPECT_THROW((void)set.subset(twice), InvalidInput);
  const std::vector<std::uint32_t> missing = {0, 1, 2, 3};
  EXPECT_THROW((void)set.subset(missing), InvalidInput);
  const std::vector<std::uint32_t> all = {0, 1, 2};
  EXPECT_EQ(set.subset(all).t_junctions().size(), 1u);
  // A shared edge alone (no T-junction): two squares side by side, one of them taken.
  const PatchSet squares(square_grid(1, 2));
  ASSERT_EQ(squares.shared_edges().size(), 1u);
  const std::vector<std::uint32_t> left = {0};
  EXPECT_THROW((void)squares.subset(left), InvalidInput);
  // Two parts, each cutting the pair; a patch in two parts.
  const std::vector<std::vector<std::uint32_t>> apart = {{0}, {1}};
  const std::vector<std::vector<std::uint32_t>> overlapping = {{0, 1}, {0, 1}};  // cuts nothing
  const auto nothing = [](std::size_t, PatchSet&) {};
  EXPECT_THROW(squares.for_each_subset(apart, nothing), InvalidInput);
  try {
    squares.for_each_subset(overlapping, nothing);
    ADD_FAILURE() << "a patch in two parts was taken";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("is in parts 0 and 1"), std::string::npos) << error.what();
  }
  const std::vector<std::vector<std::uint32_t>> whole = {{0, 1}};
  std::size_t made = 0;
  squares.for_each_subset(whole, [&](std::size_t, PatchSet& sub) { made += sub.shared_edges().size(); });
  EXPECT_EQ(made, 1u);
}

}  // namespace
}  // namespace patchwork
