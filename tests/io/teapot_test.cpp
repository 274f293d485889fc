// The Utah teapot as data/README.md documents it: every fact asserted here comes from that
// documentation or from the control points themselves, and is computed by the code under test
// and, where possible, a second time by a simpler independent computation in this file.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_grid.h"
#include "surfaces/patch_set.h"
#include "surfaces/surface_integrals.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

const char* const teapot_path = PATCHWORK_DATA_DIR "/teapot.bpt";

const std::vector<BezierPatch3>& teapot() {
  static const std::vector<BezierPatch3> patches = read_bpt(teapot_path);
  return patches;
}

// The parts of the table in data/README.md.
enum class Part { rim, body, handle, spout, lid, bottom };

Part part_of(std::uint32_t patch) {
  if (patch < 4) return Part::rim;
  if (patch < 12) return Part::body;
  if (patch < 16) return Part::handle;
  if (patch < 20) return Part::spout;
  if (patch < 28) return Part::lid;
  return Part::bottom;
}

const char* part_name(Part part) {
  switch (part) {
    case Part::rim: return "rim";
    case Part::body: return "body";
    case Part::handle: return "handle";
    case Part::spout: return "spout";
    case Part::lid: return "lid";
    case Part::bottom: return "bottom";
  }
  return "?";
}

// The control points of an edge in the direction of boundary_curve (written out here from the
// index rule P_ij at i + 4 j, not taken from the library).
std::vector<Vec3> edge_points(const BezierPatch3& patch, PatchEdge edge) {
  std::vector<Vec3> points;
  for (int k = 0; k <= 3; ++k) {
    switch (edge) {
      case PatchEdge::v0: points.push_back(patch.control_point(k, 0)); break;
      case PatchEdge::u1: points.push_back(patch.control_point(3, k)); break;
      case PatchEdge::v1: points.push_back(patch.control_point(k, 3)); break;
      case PatchEdge::u0: points.push_back(patch.control_point(0, k)); break;
    }
  }
  return points;
}

constexpr PatchEdge all_edges[4] = {PatchEdge::v0, PatchEdge::u1, PatchEdge::v1, PatchEdge::u0};

// Meridian coordinates (r, z) of a point: distance from the z axis and height.
Vec2 meridian(const Vec3& x) { return {std::hypot(x.x(), x.y()), x.z()}; }

// ---------------------------------------------------------------------------------------------

TEST(Teapot, FileHoldsThirtyTwoBicubicPatchesInShortestForm) {
  const std::vector<BezierPatch3>& patches = teapot();
  ASSERT_EQ(patches.size(), 32U);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    EXPECT_EQ(patches[p].degree_u(), 3) << "patch " << p;
    EXPECT_EQ(patches[p].degree_v(), 3) << "patch " << p;
  }
  std::ifstream in(teapot_path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 545);  // 1 + 32 * (1 + 16) lines
  // The README: numbers are written in the shortest form that reads back exactly, which is
  // what format_bpt writes, so the file is reproduced byte for byte.
  EXPECT_EQ(format_bpt(patches), text);
}

TEST(Teapot, ControlPointBoxIsTheDocumentedOne) {
  Eigen::AlignedBox3d box;
  Eigen::AlignedBox3d boxes;
  for (const BezierPatch3& patch : teapot()) {
    for (const Vec3& p : patch.control_points()) box.extend(p);
    boxes.extend(control_box(patch));
  }
  // Exact: the box corners are control-point values read from the same decimals.
  EXPECT_EQ(box.min(), Vec3(-3, -2, 0));
  EXPECT_EQ(box.max(), Vec3(3.525, 2, 3.15));
  EXPECT_EQ(boxes.min(), box.min());
  EXPECT_EQ(boxes.max(), box.max());
}

// The largest value of direction . F over the patch, found with evaluate() alone: a 17 x 17
// grid, then 40 rounds of a 5 x 5 grid around the best point so far, the window halved each
// round (to 2^-44). A lower bound of the true maximum, and equal to it up to rounding when the
// grid starts in the right basin (a bicubic has few; a wrong start would show as a failure).
double sampled_max(const BezierPatch3& patch, const Vec3& direction) {
  constexpr int coarse = 16;
  double best = -std::numeric_limits<double>::infinity();
  double best_u = 0.0;
  double best_v = 0.0;
  const auto visit = [&](double u, double v) {
    const double value = direction.dot(patch.evaluate(u, v));
    if (value > best) {
      best = value;
      best_u = u;
      best_v = v;
    }
  };
  for (int a = 0; a <= coarse; ++a) {
    for (int b = 0; b <= coarse; ++b) visit(static_cast<double>(a) / coarse, static_cast<double>(b) / coarse);
  }
  double h = 1.0 / coarse;
  for (int round = 0; round < 40; ++round) {
    const double u0 = best_u;
    const double v0 = best_v;
    for (int a = -2; a <= 2; ++a) {
      for (int b = -2; b <= 2; ++b) visit(std::clamp(u0 + a * h / 2, 0.0, 1.0), std::clamp(v0 + b * h / 2, 0.0, 1.0));
    }
    h /= 2;
  }
  return best;
}

TEST(Teapot, SurfaceBoxIsTightAndTheDocumentedOne) {
  constexpr double tolerance = 1e-10;
  Eigen::AlignedBox3d surface_box;
  Vec3 sampled_max_corner = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 sampled_min_corner = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t p = 0; p < teapot().size(); ++p) {
    const BezierPatch3& patch = teapot()[p];
    const Eigen::AlignedBox3d box = bounding_box(patch, tolerance);
    surface_box.extend(box);
    for (int c = 0; c < 3; ++c) {
      const Vec3 axis = Vec3::Unit(c);
      const double high = sampled_max(patch, axis);
      const double low = -sampled_max(patch, -axis);
      sampled_max_corner[c] = std::max(sampled_max_corner[c], high);
      sampled_min_corner[c] = std::min(sampled_min_corner[c], low);
      // The box contains every surface point (up to the rounding of evaluate, 1e-14 at this
      // scale) and each face is within `tolerance` of the extreme, which the search finds
      // to ~1e-15; 1e-9 leaves room for both.
      EXPECT_LE(high, box.max()[c] + 1e-14) << "patch " << p << " axis " << c;
      EXPECT_GE(low, box.min()[c] - 1e-14) << "patch " << p << " axis " << c;
      EXPECT_LE(box.max()[c] - high, 1e-9) << "patch " << p << " axis " << c;
      EXPECT_LE(low - box.min()[c], 1e-9) << "patch " << p << " axis " << c;
    }
  }
  std::cout << std::setprecision(17) << "teapot surface box: [" << surface_box.min().transpose() << "] .. ["
            << surface_box.max().transpose() << "]\n";
  // data/README.md: surface box x [-3, 3.43408], y [-2, 2], z [0, 3.15]. All but x max are
  // control points on the surface (corners and poles), exact up to the box tolerance; x max is
  // quoted to 5 decimals from 400 x 400 samples.
  EXPECT_NEAR(surface_box.min().x(), -3.0, 1e-9);
  EXPECT_NEAR(surface_box.max().x(), 3.43408, 1e-5);
  EXPECT_NEAR(surface_box.min().y(), -2.0, 1e-9);
  EXPECT_NEAR(surface_box.max().y(), 2.0, 1e-9);
  EXPECT_NEAR(surface_box.min().z(), 0.0, 1e-9);
  EXPECT_NEAR(surface_box.max().z(), 3.15, 1e-9);
  // The spout tip keeps the surface inside x = 3.525, its inner control point.
  EXPECT_LT(surface_box.max().x(), 3.525 - 0.05);
  // Whole-teapot cross-check by sampling: below the box, and within 1e-6 of it.
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(sampled_max_corner[c], surface_box.max()[c] + 1e-14);
    EXPECT_GE(sampled_max_corner[c], surface_box.max()[c] - 1e-6);
    EXPECT_GE(sampled_min_corner[c], surface_box.min()[c] - 1e-14);
    EXPECT_LE(sampled_min_corner[c], surface_box.min()[c] + 1e-6);
  }
}

// ---------------------------------------------------------------------------------------------
// Adjacency

TEST(Teapot, EdgesCountedByExactComparisonMatchTheDocumentation) {
  // Independent of PatchSet: the README says shared edges coincide exactly, collapsed edges
  // are single points, so exact comparison of the 4 edge control points is the whole story.
  const auto& patches = teapot();
  int collapsed = 0;
  int shared_ends = 0;
  int open = 0;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    for (PatchEdge e : all_edges) {
      const std::vector<Vec3> points = edge_points(patches[p], e);
      if (std::all_of(points.begin(), points.end(), [&](const Vec3& x) { return x == points[0]; })) {
        ++collapsed;
        continue;
      }
      int matches = 0;
      for (std::size_t q = 0; q < patches.size(); ++q) {
        for (PatchEdge f : all_edges) {
          if (q == p && f == e) continue;
          std::vector<Vec3> other = edge_points(patches[q], f);
          if (other == points) ++matches;
          std::reverse(other.begin(), other.end());
          if (other == points) ++matches;
        }
      }
      EXPECT_LE(matches, 1) << "patch " << p << " edge " << edge_name(e) << " shared by more than 2 patches";
      (matches == 1 ? shared_ends : open) += 1;
    }
  }
  EXPECT_EQ(collapsed, 8);
  EXPECT_EQ(shared_ends, 2 * 52);
  EXPECT_EQ(open, 16);
}

TEST(Teapot, PatchSetFindsTheDocumentedAdjacency) {
  const PatchSet set(teapot());
  const PatchSetReport summary = report(set);
  std::cout << "teapot: " << summary.shared_edges << " shared, " << summary.open_edges << " open, "
            << summary.collapsed_edges << " collapsed edges, " << summary.boundary_loops << " boundary loops, "
            << summary.touching_points << " touching point\n";
  EXPECT_EQ(summary.patches, 32U);
  EXPECT_EQ(summary.shared_edges, 52U);
  EXPECT_EQ(summary.open_edges, 16U);
  EXPECT_EQ(summary.collapsed_edges, 8U);
  EXPECT_EQ(summary.boundary_loops, 6U);
  EXPECT_EQ(summary.touching_points, 1U);
  EXPECT_TRUE(summary.consistently_oriented);
  EXPECT_FALSE(summary.closed);

  // Shared pairs by part, and the 4 reversed ones are body/bottom (README "Checks").
  std::map<std::pair<Part, Part>, int> pairs;
  int reversed = 0;
  for (const SharedEdge& shared : set.shared_edges()) {
    Part a = part_of(shared.first.patch);
    Part b = part_of(shared.second.patch);
    if (b < a) std::swap(a, b);
    ++pairs[{a, b}];
    EXPECT_TRUE(shared.consistently_oriented) << "patches " << shared.first.patch << ", " << shared.second.patch;
    EXPECT_EQ(shared.continuity.gap, 0.0);  // the data repeat the same decimals
    if (shared.reversed) {
      ++reversed;
      EXPECT_EQ(a, Part::body);
      EXPECT_EQ(b, Part::bottom);
    }
  }
  const std::map<std::pair<Part, Part>, int> expected_pairs = {
      {{Part::rim, Part::rim}, 4},       {{Part::rim, Part::body}, 4},        {{Part::body, Part::body}, 12},
      {{Part::body, Part::bottom}, 4},   {{Part::bottom, Part::bottom}, 4},   {{Part::lid, Part::lid}, 12},
      {{Part::handle, Part::handle}, 6}, {{Part::spout, Part::spout}, 6}};
  EXPECT_EQ(pairs, expected_pairs);
  EXPECT_EQ(reversed, 4);

  // Collapsed: row 0 (edge v0) of the knob 20-23 and of the bottom 28-31.
  std::set<std::pair<std::uint32_t, PatchEdge>> collapsed;
  for (const EdgeRef& e : set.collapsed_edges()) collapsed.insert({e.patch, e.edge});
  std::set<std::pair<std::uint32_t, PatchEdge>> expected_collapsed;
  for (std::uint32_t p : {20U, 21U, 22U, 23U, 28U, 29U, 30U, 31U}) expected_collapsed.insert({p, PatchEdge::v0});
  EXPECT_EQ(collapsed, expected_collapsed);

  // Open: the rim's row 0, the lid flange's bottom row, and the tube ends (the rows at the body
  // and at the free ends, read off the control points: handle 12-13 and spout 16-17 start at
  // the body with row 0; handle 14-15 and spout tip 18-19 end with row 3).
  std::set<std::pair<std::uint32_t, PatchEdge>> open;
  for (const EdgeRef& e : set.open_edges()) open.insert({e.patch, e.edge});
  std::set<std::pair<std::uint32_t, PatchEdge>> expected_open;
  for (std::uint32_t p : {0U, 1U, 2U, 3U, 12U, 13U, 16U, 17U}) expected_open.insert({p, PatchEdge::v0});
  for (std::uint32_t p : {24U, 25U, 26U, 27U, 14U, 15U, 18U, 19U}) expected_open.insert({p, PatchEdge::v1});
  EXPECT_EQ(open, expected_open);

  // Six closed loops: rim top, lid flange, two handle ends, two spout ends.
  std::set<std::set<std::uint32_t>> loops;
  for (const BoundaryLoop& loop : set.boundary_loops()) {
    EXPECT_TRUE(loop.closed);
    std::set<std::uint32_t> patches;
    for (const EdgeRef& e : loop.edges) patches.insert(e.patch);
    loops.insert(patches);
  }
  const std::set<std::set<std::uint32_t>> expected_loops = {{0, 1, 2, 3}, {24, 25, 26, 27}, {12, 13},
                                                            {14, 15},     {16, 17},         {18, 19}};
  EXPECT_EQ(loops, expected_loops);

  // The handle's lower end touches the body at (-2, 0, 0.9): the groups are the handle's lower
  // patches and the body patches there; together they are exactly the patches with a corner at
  // that point (found here from the control points).
  ASSERT_EQ(set.touching_points().size(), 1U);
  const TouchingPoint& touching = set.touching_points()[0];
  const Vec3 point(-2.0, 0.0, 0.9);
  EXPECT_LE((touching.point - point).norm(), 1e-12);
  std::set<std::uint32_t> with_corner;
  for (std::uint32_t p = 0; p < 32; ++p) {
    const BezierPatch3& patch = teapot()[p];
    for (const auto& [i, j] : {std::pair{0, 0}, std::pair{3, 0}, std::pair{0, 3}, std::pair{3, 3}}) {
      if (patch.control_point(i, j) == point) with_corner.insert(p);
    }
  }
  std::set<std::uint32_t> in_groups;
  bool handle_group = false;
  ASSERT_GE(touching.groups.size(), 2U);
  for (const auto& group : touching.groups) {
    const std::set<std::uint32_t> members(group.begin(), group.end());
    in_groups.insert(members.begin(), members.end());
    if (members == std::set<std::uint32_t>{14, 15}) {
      handle_group = true;
    } else {
      for (std::uint32_t p : members) EXPECT_EQ(part_of(p), Part::body) << "patch " << p << " in a touching group";
    }
  }
  EXPECT_TRUE(handle_group);
  EXPECT_EQ(in_groups, with_corner);
}

// ---------------------------------------------------------------------------------------------
// Normals

TEST(Teapot, PoleNormalsPointUpAtTheLidAndDownAtTheBottom) {
  // Knob and bottom rows 1 lie at the pole's height (z 3.15 and 0), so the tangent plane at the
  // poles is horizontal; outward is up at the lid top and down under the pot.
  for (std::uint32_t p = 20; p < 24; ++p) {
    for (double u : {0.0, 0.125, 0.3, 0.5, 0.77, 1.0}) {
      EXPECT_LE((teapot()[p].evaluate(u, 0.0) - Vec3(0, 0, 3.15)).norm(), 1e-14);  // rounding of (1-u) a + u a
      EXPECT_LE((unit_normal(teapot()[p], u, 0.0) - Vec3(0, 0, 1)).norm(), 1e-12) << "patch " << p << " u " << u;
    }
  }
  for (std::uint32_t p = 28; p < 32; ++p) {
    for (double u : {0.0, 0.125, 0.3, 0.5, 0.77, 1.0}) {
      EXPECT_EQ(teapot()[p].evaluate(u, 0.0), Vec3(0, 0, 0));  // exact: all terms are 0
      EXPECT_LE((unit_normal(teapot()[p], u, 0.0) - Vec3(0, 0, -1)).norm(), 1e-12) << "patch " << p << " u " << u;
    }
  }
}

// Rim, body, lid and bottom are surfaces of revolution up to the quarter-circle approximation:
// row j is r_j times one arc C(u) at height z_j, so F(u, v) = (rho(v) C(u), zeta(v)) and a
// point's azimuth depends on u alone. Their outside is read off the meridian profile (r, z):
//   - rim + body + bottom are one sheet. Walk its profile from the rim's inner top edge, over
//     the lip, down the body and in along the bottom to the axis. On the body (walking down)
//     the outside faces away from the axis, i.e. to the left of the walk in the (r, z) plane;
//     the sheet is smooth, so the outside stays on the left all the way: up on top of the lip,
//     towards the axis on the lip's inner side (the lip folds over), down under the bottom.
//   - the lid is a cap: walk from the knob's top pole out to the flange edge. On top of the
//     knob (walking outward) the outside is up: the left again, and so all along, also under
//     the knob's overhang where it points down.
// Which way v walks is decided from the geometry of each patch's end rows (not its normal):
// the rim's inner edge has the smaller radius, the body goes down, the bottom goes in to the
// axis, the lid goes out from it. The profile tangent is a central difference of evaluate().
TEST(Teapot, NormalsPointOutwardOnTheRotationalParts) {
  constexpr int samples = 8;
  constexpr double h = 1e-6;  // central difference: truncation ~h^2, rounding ~1e-16/h, both << 1
  double worst = 1.0;
  for (std::uint32_t p = 0; p < 32; ++p) {
    const Part part = part_of(p);
    if (part == Part::handle || part == Part::spout) continue;
    const BezierPatch3& patch = teapot()[p];
    const Vec2 start = meridian(patch.evaluate(0.5, 0.0));
    const Vec2 end = meridian(patch.evaluate(0.5, 1.0));
    bool forward = false;
    switch (part) {
      case Part::rim: forward = end.x() > start.x(); break;
      case Part::body: forward = end.y() < start.y(); break;
      case Part::bottom: forward = end.x() < start.x(); break;
      default: forward = end.x() > start.x(); break;  // lid
    }
    const double walk = forward ? 1.0 : -1.0;
    for (int a = 0; a < samples; ++a) {
      for (int b = 0; b < samples; ++b) {
        const double u = (a + 0.5) / samples;
        const double v = (b + 0.5) / samples;
        const Vec3 x = patch.evaluate(u, v);
        const Vec2 tangent = walk * (meridian(patch.evaluate(u, v + h)) - meridian(patch.evaluate(u, v - h)));
        ASSERT_GT(tangent.norm(), 1e-9) << "patch " << p << " (" << u << ", " << v << ")";
        const Vec2 left = Vec2(-tangent.y(), tangent.x()).normalized();
        const Vec3 n = unit_normal(patch, u, v);
        const Vec3 radial = Vec3(x.x(), x.y(), 0.0).normalized();
        const Vec2 n_meridian(n.dot(radial), n.z());
        // The normal lies in the meridian plane but for the arc's small non-circularity (and
        // the knob's row 1, scaled 0.5625 instead of 0.56), so its projection is nearly unit
        // and along `left`; 0.9 only asks for the sign with a clear margin.
        const double agreement = n_meridian.dot(left) / n_meridian.norm();
        worst = std::min(worst, agreement);
        EXPECT_GT(agreement, 0.9) << part_name(part) << " patch " << p << " (" << u << ", " << v << ")";
        // Plain signs where the control rows make them obvious (rows r_j, z_j from the file):
        switch (part) {
          case Part::body:  // z falls strictly (2.4 .. 0.15): the wall faces away from the axis
            EXPECT_GT(n.dot(radial), 0.0) << "patch " << p;
            break;
          case Part::bottom:  // r grows strictly to the rim of the base: faces down
            EXPECT_LT(n.z(), 0.0) << "patch " << p;
            break;
          case Part::rim:  // z rows 2.4, 2.53125, 2.53125, 2.4: the lip's inner half (v < 1/2)
                           // faces the axis, its outer half faces away
            EXPECT_GT((v - 0.5) * n.dot(radial), 0.0) << "patch " << p << " v " << v;
            break;
          case Part::lid:
            // Flange: r grows strictly to the edge, so it faces up. Knob: r rows 0, 0.8, 0, 0.2
            // give r' ~ 0.8 - 3.2 v + 2.6 v^2, positive for v < 0.349 (the top, facing up) and
            // v > 0.882 (the neck flaring into the flange, up), negative between: the
            // underside of the overhang, facing down.
            if (p >= 24) {
              EXPECT_GT(n.z(), 0.0) << "patch " << p;
            } else if (v < 0.3 || v > 0.92) {
              EXPECT_GT(n.z(), 0.0) << "patch " << p << " v " << v;
            } else if (v > 0.4 && v < 0.85) {
              EXPECT_LT(n.z(), 0.0) << "patch " << p << " v " << v;
            }
            break;
          default: break;
        }
      }
    }
  }
  std::cout << std::setprecision(17) << "rotational parts: smallest agreement of normal and outward profile normal " << worst << "\n";
}

// Handle and spout are tubes; each segment is two patches, mirror images in y with u reversed
// (patch q(u, v) = mirror of patch p(1 - u, v)), so a fixed v gives one closed cross-section
// ring made of both halves. The ring is convex and the centroid of points sampled evenly on it
// lies inside, so on the outside of the tube the normal points away from that centroid.
// Not so on the spout's tip (18, 19): it is the spout's mouth and folds over like the pot's rim.
// Its rows run from the ring it shares with the spout base (row 0: x 2.7 .. 3.3, z 2.4) up over
// the lip (z ~2.5) and down inside the mouth to a smaller ring (row 3: x 2.8 .. 3.2, z 2.4), so
// near row 3 the outside faces the spout's axis. There the check is the one for a fold: at fixed
// u the curve v -> F(u, v) is a convex arch (its control polygon with the chord is convex, e.g.
// (2.7, 2.4) (2.8, 2.475) (2.9, 2.475) (2.8, 2.4) in (x, z) at u = 0), and the outside is away
// from the centroid of its points, which lies inside the lip's cross-section.
TEST(Teapot, NormalsPointAwayFromTheTubeCentreOnHandleAndSpout) {
  constexpr int ring_samples = 64;
  constexpr int samples = 8;
  const std::pair<std::uint32_t, std::uint32_t> segments[] = {{12, 13}, {14, 15}, {16, 17}};
  double worst = 1.0;
  for (const auto& [p, q] : segments) {
    const BezierPatch3& first = teapot()[p];
    const BezierPatch3& second = teapot()[q];
    for (int b = 0; b < samples; ++b) {
      const double v = (b + 0.5) / samples;
      Vec3 centre = Vec3::Zero();
      for (int k = 0; k < ring_samples; ++k) {
        const double u = (k + 0.5) / ring_samples;
        const Vec3 x = first.evaluate(u, v);
        const Vec3 y = second.evaluate(1.0 - u, v);
        EXPECT_LE((y - Vec3(x.x(), -x.y(), x.z())).norm(), 1e-12) << "patches " << p << ", " << q << " not mirrored";
        centre += x + y;
      }
      centre /= 2.0 * ring_samples;
      for (const BezierPatch3* patch : {&first, &second}) {
        for (int a = 0; a < samples; ++a) {
          const double u = (a + 0.5) / samples;
          const Vec3 away = (patch->evaluate(u, v) - centre).normalized();
          const double agreement = unit_normal(*patch, u, v).dot(away);
          worst = std::min(worst, agreement);
          // Not 1: the ring is not a circle and the tube bends and tapers; the sign with a
          // margin is the claim.
          EXPECT_GT(agreement, 0.3) << "patch " << (patch == &first ? p : q) << " (" << u << ", " << v << ")";
        }
      }
    }
  }
  double worst_tip = 1.0;
  for (std::uint32_t p : {18U, 19U}) {
    const BezierPatch3& patch = teapot()[p];
    for (int a = 0; a < samples; ++a) {
      const double u = (a + 0.5) / samples;
      Vec3 centre = Vec3::Zero();
      for (int k = 0; k < ring_samples; ++k) centre += patch.evaluate(u, (k + 0.5) / ring_samples);
      centre /= ring_samples;
      for (int b = 0; b < samples; ++b) {
        const double v = (b + 0.5) / samples;
        const Vec3 away = (patch.evaluate(u, v) - centre).normalized();
        const double agreement = unit_normal(patch, u, v).dot(away);
        worst_tip = std::min(worst_tip, agreement);
        // Smaller margin than on the tubes: the lip's arch is flat and long (0.1 high, 0.4 to
        // 0.6 wide) and twists with u, so near its ends the direction away from its centroid is
        // far from the normal; the sign is the claim.
        EXPECT_GT(agreement, 0.1) << "patch " << p << " (" << u << ", " << v << ")";
      }
    }
  }
  std::cout << std::setprecision(17) << "tubes: smallest cosine between normal and direction away from the ring centre "
            << worst << ", on the spout's lip away from the fold's centre " << worst_tip << "\n";
}

// ---------------------------------------------------------------------------------------------
// Area, two independent ways

// Sum of the areas of the two triangles per cell of a uniform n x n grid on every patch
// (Neumaier-compensated: a million terms would otherwise lose ~1e-10 relative).
double tessellated_area(std::size_t n) {
  const PatchGridWeights weights = PatchGridWeights::uniform(3, 3, n, n);
  double sum = 0.0;
  double compensation = 0.0;
  const auto add = [&](double term) {
    const double t = sum + term;
    compensation += std::abs(sum) >= std::abs(term) ? (sum - t) + term : (term - t) + sum;
    sum = t;
  };
  for (const BezierPatch3& patch : teapot()) {
    const PatchGridSamples grid = evaluate_grid(patch, weights);
    const auto at = [&](std::size_t a, std::size_t b) -> const Vec3& { return grid.points[a + grid.count_u * b]; };
    for (std::size_t b = 0; b < n; ++b) {
      for (std::size_t a = 0; a < n; ++a) {
        const Vec3& p00 = at(a, b);
        const Vec3& p10 = at(a + 1, b);
        const Vec3& p11 = at(a + 1, b + 1);
        const Vec3& p01 = at(a, b + 1);
        add(0.5 * (p10 - p00).cross(p11 - p00).norm());
        add(0.5 * (p11 - p00).cross(p01 - p00).norm());
      }
    }
  }
  return sum + compensation;
}

TEST(Teapot, AreaByQuadratureAndByExtrapolatedTessellationsAgree) {
  // Way 1: adaptive Gauss-Legendre of |F_u x F_v| per patch.
  double quadrature = 0.0;
  double error_estimate = 0.0;
  for (const BezierPatch3& patch : teapot()) {
    const SurfaceIntegral a = area(patch, 1e-9);  // 32 patches: <= 3.2e-8 in all, 6e-10 relative
    quadrature += a.value;
    error_estimate += a.error_estimate;
  }
  // Way 2: flat triangles. Each cell's two triangles are symmetric under the point reflection
  // through the cell centre (it maps the diagonal to itself), so the error of a cell is even in
  // the step h and the sum over cells (a midpoint-type sum) adds only even powers:
  //   A(h) = A + c2 h^2 + c4 h^4 + c6 h^6 + ...
  // Richardson removes h^2, h^4, h^6 in turn from N = 16, 32, 64, 128.
  const std::vector<std::size_t> sizes = {16, 32, 64, 128};
  std::vector<double> table;
  for (std::size_t n : sizes) table.push_back(tessellated_area(n));
  // The premise: successive differences shrink by 4 (the h^2 term dominates).
  for (std::size_t k = 0; k + 2 < table.size(); ++k) {
    const double ratio = (table[k + 1] - table[k]) / (table[k + 2] - table[k + 1]);
    EXPECT_NEAR(ratio, 4.0, 0.05) << "N = " << sizes[k];
  }
  std::cout << std::setprecision(17);
  for (std::size_t k = 0; k < sizes.size(); ++k) std::cout << "tessellation N = " << sizes[k] << ": " << table[k] << "\n";
  double factor = 4.0;
  while (table.size() > 1) {
    std::vector<double> next;
    for (std::size_t k = 0; k + 1 < table.size(); ++k) next.push_back((factor * table[k + 1] - table[k]) / (factor - 1.0));
    table = std::move(next);
    factor *= 4.0;
  }
  const double extrapolated = table[0];
  std::cout << "teapot area: quadrature " << quadrature << " (error estimate " << error_estimate
            << "), Richardson-extrapolated tessellation " << extrapolated << ", relative difference "
            << std::abs(quadrature - extrapolated) / quadrature << "\n";
  EXPECT_LE(error_estimate, 32 * 1e-9);
  EXPECT_LE(std::abs(quadrature - extrapolated), 1e-8 * quadrature);
}

}  // namespace
}  // namespace patchwork
