// The 4-wide float-box tree never drops a piece the ray reaches: its candidates against every
// piece box tested in long double, on random rays and on rays made to touch boxes at a corner or
// run in a face's plane; and ray casting through it against the patches cast one at a time.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "queries/patch_bvh.h"
#include "queries/ray_cast.h"
#include "queries/wide_bvh.h"
#include "surfaces/nurbs_shapes.h"
#include "tests/queries/query_fixtures.h"

namespace wide_bvh_test {
namespace {

using namespace patchwork;

const auto& teapot = patchwork::testing::teapot_set;

const PatchSet& torus() {
  static const PatchSet set = patchwork::testing::nurbs_patch_set(nurbs_torus(Vec3::Zero(), 2.0, 0.75));
  return set;
}

// Whether o + t d (t_min <= t <= t_max) meets the box, in long double (64-bit significands: its
// rounding is far below the float tree's pad, so a box this reaches the tree must keep).
bool reaches_box(const Eigen::AlignedBox3d& box, const Vec3& o, const Vec3& d, double t_min, double t_max) {
  long double t0 = t_min, t1 = t_max;
  for (int c = 0; c < 3; ++c) {
    const long double lo = box.min()[c], hi = box.max()[c], oc = o[c], dc = d[c];
    if (dc == 0) {
      if (oc < lo || oc > hi) return false;
      continue;
    }
    const long double a = (lo - oc) / dc, b = (hi - oc) / dc;
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  return t0 <= t1;
}

// Every piece whose box the ray reaches is among the tree's candidates (or the tree declines the
// ray, and the double tree answers). Returns whether the tree answered.
bool expect_candidates_cover(const PatchBvh& bvh, const Vec3& o, const Vec3& d, double t_min, double t_max) {
  std::vector<std::uint32_t> candidates;
  const bool answered = bvh.wide().reaches(o, d, t_min, t_max, candidates);
  if (!answered) {
    EXPECT_TRUE(candidates.empty());
    return false;
  }
  std::sort(candidates.begin(), candidates.end());
  EXPECT_TRUE(std::adjacent_find(candidates.begin(), candidates.end()) == candidates.end()) << "a piece twice";
  for (std::uint32_t p = 0; p < bvh.piece_boxes().size(); ++p) {
    if (!reaches_box(bvh.piece_boxes()[p], o, d, t_min, t_max)) continue;
    EXPECT_TRUE(std::binary_search(candidates.begin(), candidates.end(), p))
        << "piece " << p << " missed; o = " << o.transpose() << ", d = " << d.transpose() << ", t in [" << t_min << ", " << t_max << "]";
  }
  return true;
}

Vec3 random_vec(double low, double high) {
  const auto coordinate = [&] { return low + (high - low) * *rc::gen::inRange(0, 1 << 20) / double(1 << 20); };
  return {coordinate(), coordinate(), coordinate()};
}

RC_GTEST_PROP(WideBvh, CandidatesCoverRandomRays, ()) {
  static const PatchBvh bvh(teapot());
  const Vec3 o = random_vec(-9, 9), target = random_vec(-3.5, 3.5);
  RC_PRE((target - o).norm() > 1e-6);
  RC_ASSERT(expect_candidates_cover(bvh, o, target - o, 0.0, std::numeric_limits<double>::infinity()));
  RC_ASSERT(!::testing::Test::HasFailure());
}

// Rays that touch a piece's box at a corner, with the ray's end (t_max) exactly there or its
// start (t_min), or that run in the plane of a face along the other axes: the float test's
// hardest cases.
RC_GTEST_PROP(WideBvh, CandidatesCoverRaysTouchingBoxes, ()) {
  static const PatchBvh bvh(teapot());
  const auto piece = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, bvh.piece_boxes().size()));
  const Eigen::AlignedBox3d& box = bvh.piece_boxes()[piece];
  const auto corner_kind = *rc::gen::inRange(0, 8);
  const Vec3 corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner_kind));
  const int shape = *rc::gen::inRange(0, 4);
  if (shape < 3) {
    const Vec3 o = random_vec(-9, 9);
    RC_PRE((corner - o).norm() > 1e-6);
    const Vec3 d = corner - o;
    // The ray to the corner: whole, ending there (t = 1), or starting there.
    const double t_min = shape == 2 ? 1.0 : 0.0, t_max = shape == 1 ? 1.0 : std::numeric_limits<double>::infinity();
    expect_candidates_cover(bvh, o, d, t_min, t_max);
  } else {
    // In the face's plane through the corner, along the other two axes (one of them may be 0).
    const int axis = *rc::gen::inRange(0, 3);
    Vec3 d = random_vec(-1, 1);
    d[axis] = 0.0;
    RC_PRE(d.norm() > 1e-3);
    Vec3 o = corner - 5 * d;
    o[axis] = corner[axis];
    expect_candidates_cover(bvh, o, d, 0.0, std::numeric_limits<double>::infinity());
  }
  RC_ASSERT(!::testing::Test::HasFailure());
}

TEST(WideBvh, FarAndDegenerateRays) {
  const PatchBvh bvh(teapot());
  const Vec3 c = bvh.nodes().front().box.center();
  // Origins far out (the far ones are left to the double tree), directions with tiny or zero
  // components, a ray along an axis through a box's edge.
  int declined = 0;
  for (const double far : {10.0, 1e3, 1e6, 1e9, 1e15}) {
    for (const Vec3& towards : {Vec3(1, 0, 0), Vec3(0.3, -1, 0.2), Vec3(1e-30, 1, -1e-300)}) {
      const Vec3 o = c + far * towards;
      declined += !expect_candidates_cover(bvh, o, c - o, 0.0, std::numeric_limits<double>::infinity());
    }
  }
  EXPECT_GE(declined, 1);  // 10^15 away: the double tree's turn
  EXPECT_LE(declined, 6);
  const Eigen::AlignedBox3d& box = bvh.piece_boxes()[7];
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 o = box.max();
    o[axis] = -20;
    expect_candidates_cover(bvh, o, Vec3::Unit(axis), 0.0, std::numeric_limits<double>::infinity());
    expect_candidates_cover(bvh, o, Vec3::Unit(axis) * 1e-200, 0.0, std::numeric_limits<double>::infinity());
  }
  EXPECT_TRUE(expect_candidates_cover(bvh, c + Vec3(8, 1, 0.5), Vec3(-1, 0, 0), 0.0, std::numeric_limits<double>::infinity()));
}

// The hits of every patch cast alone (one-patch sets), merged as ray_cast merges them: one point
// seen from two patches (a shared edge), or a tangent contact's candidates within 1e-4 of the size.
std::vector<RayHit> brute_force_hits(const PatchSet& set, const Vec3& o, const Vec3& d, double size) {
  std::vector<RayHit> all;
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    const AnyBezierPatch patch = set.patch(p);
    const PatchSet one(std::span<const AnyBezierPatch>(&patch, 1));
    for (const RayHit& hit : ray_cast(one, o, d).hits) all.push_back(hit);
  }
  std::sort(all.begin(), all.end(), [](const RayHit& x, const RayHit& y) { return x.t < y.t; });
  std::vector<RayHit> merged;
  for (const RayHit& hit : all) {
    if (!merged.empty()) {
      RayHit& last = merged.back();
      const double apart = (hit.point - last.point).norm();
      if (apart <= 1e-9 * size || ((hit.grazing || last.grazing) && apart <= 1e-4 * size)) {
        last.grazing = last.grazing || hit.grazing;
        continue;
      }
    }
    merged.push_back(hit);
  }
  return merged;
}

// The same hits as casting each patch alone (crossings at the same t; a tangent contact, located
// only to about the square root of rounding, within 1e-3), on rays at random and through the ends
// and middles of shared edges (the seams, where a hit lies on two pieces' boxes' faces).
void expect_as_brute_force(const PatchSet& set, const std::vector<std::pair<Vec3, Vec3>>& rays) {
  const PatchBvh bvh(set);
  int grazing = 0;
  for (const auto& [o, d] : rays) {
    const RayHits result = ray_cast(bvh, o, d);
    const std::vector<RayHit> truth = brute_force_hits(set, o, d, bvh.size());
    ASSERT_EQ(result.hits.size(), truth.size()) << "o = " << o.transpose() << ", d = " << d.transpose();
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const bool tangent = truth[k].grazing || result.hits[k].grazing;
      EXPECT_EQ(result.hits[k].grazing, truth[k].grazing);
      EXPECT_NEAR(result.hits[k].t, truth[k].t, (tangent ? 1e-3 : 1e-9) * (1 + truth[k].t));
      grazing += tangent;
    }
  }
  EXPECT_GE(grazing, 1);  // some seam rays are tangent there
}

std::vector<std::pair<Vec3, Vec3>> rays_through_seams(const PatchSet& set, int random_rays) {
  std::vector<std::pair<Vec3, Vec3>> rays;
  for (int i = 0; i < random_rays; ++i) {
    const Vec3 o(7 * std::cos(0.9 * i), 7 * std::sin(0.9 * i), 1 + 3 * std::sin(1.7 * i));
    const Vec3 target(2 * std::cos(2.3 * i), 1.5 * std::sin(1.1 * i), 1.2 + std::cos(0.4 * i));
    rays.emplace_back(o, target - o);
  }
  int k = 0;
  for (const SharedEdge& edge : set.shared_edges()) {
    const double u = edge.first.edge == PatchEdge::u0 ? 0.0 : edge.first.edge == PatchEdge::u1 ? 1.0 : 0.5;
    const double v = edge.first.edge == PatchEdge::v0 ? 0.0 : edge.first.edge == PatchEdge::v1 ? 1.0 : 0.5;
    const AnyBezierPatch patch = set.patch(edge.first.patch);
    const Vec3 point = std::visit([&](const auto& p) { return Vec3(p.evaluate(u, v)); }, patch);
    const Vec3 d(std::cos(1.3 * k), std::sin(1.3 * k), 0.4 * std::sin(0.7 * k));
    rays.emplace_back(point - 6 * d, d);
    ++k;
  }
  return rays;
}

TEST(WideBvh, TeapotHitsAsEachPatchAlone) { expect_as_brute_force(teapot(), rays_through_seams(teapot(), 60)); }

TEST(WideBvh, TorusHitsAsEachPatchAlone) { expect_as_brute_force(torus(), rays_through_seams(torus(), 40)); }

}  // namespace
}  // namespace wide_bvh_test
