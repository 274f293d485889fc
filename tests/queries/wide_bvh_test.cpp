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

#include "queries/double_box_walk.h"
#include "queries/patch_bvh.h"
#include "queries/ray_cast.h"
#include "queries/wide_bvh.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_transform.h"
#include "surfaces/rational_bezier_patch.h"
#include "surfaces/nurbs_shapes.h"
#include "tests/queries/query_fixtures.h"

namespace wide_bvh_test {
namespace {

using namespace patchwork;
using detail::WideBvh;

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

// The double tree's walk, which answers the rays the float tree declines, keeps every piece box
// a long-double slab test reaches, on rays from 10^3 to 10^15 away to a box's corner (ending
// there or passing it): its slab test is widened by its own rounding.
RC_GTEST_PROP(WideBvh, DoubleBoxWalkCoversFarRaysToCorners, ()) {
  static const PatchBvh bvh(teapot());
  const auto piece = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, bvh.piece_boxes().size()));
  const Eigen::AlignedBox3d& box = bvh.piece_boxes()[piece];
  const Vec3 corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(*rc::gen::inRange(0, 8)));
  const Vec3 towards = random_vec(-1, 1);
  RC_PRE(towards.norm() > 1e-3);
  const double far = std::pow(10.0, *rc::gen::inRange(3, 16));
  const Vec3 o = corner + far * towards.normalized(), d = corner - o;
  const double t_max = *rc::gen::arbitrary<bool>() ? 1.0 : std::numeric_limits<double>::infinity();
  std::vector<std::uint32_t> pieces;
  detail::double_box_pieces(bvh, o, d, 0.0, t_max, pieces);
  std::sort(pieces.begin(), pieces.end());
  for (std::uint32_t p = 0; p < bvh.piece_boxes().size(); ++p) {
    if (reaches_box(bvh.piece_boxes()[p], o, d, 0.0, t_max)) RC_ASSERT(std::binary_search(pieces.begin(), pieces.end(), p));
  }
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


// A float in [-2^k, 2^k] on a grid of 2^-10 of that (k in [-3, 3]), or 0.
float random_float() {
  if (*rc::gen::inRange(0, 8) == 0) return 0.0f;
  const int k = *rc::gen::inRange(-3, 4);
  return std::ldexp(static_cast<float>(*rc::gen::inRange(-1024, 1025)), k - 10);
}

// The slab test alone, without the pad (the boxes are exactly the floats given): a float ray
// q + s e that passes through a point p = q + s1 e inside box k (a box that may be flat, with p
// on its faces, its corner or its edge, and s1 the far end) is reported by both the SSE and the
// scalar test, which agree on every box. Without pbrt's stretch the far end rounds below the
// near one on such rays.
RC_GTEST_PROP(WideBvh, NodeMaskKeepsRaysEndingOnABox, ()) {
  float q[3], e[3], inverse[3];
  int negative[3];
  for (int c = 0; c < 3; ++c) {
    q[c] = random_float();
    e[c] = random_float();
    inverse[c] = 1.0f / e[c];
    negative[c] = std::signbit(e[c]) ? 1 : 0;
  }
  RC_PRE(e[0] != 0.0f || e[1] != 0.0f || e[2] != 0.0f);
  const float s1 = std::ldexp(static_cast<float>(*rc::gen::inRange(1, 1 << 12)), -*rc::gen::inRange(4, 12));
  WideBvh::Node node;
  const auto box_slot = static_cast<int>(*rc::gen::inRange(0, 4));
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      // The point of the ray at s1, in long double (exact here: 24-bit values on nearby scales),
      // rounded outward to floats, and the box grown from it by 0 or a random amount each side.
      const long double p = static_cast<long double>(q[c]) + static_cast<long double>(s1) * e[c];
      float low = static_cast<float>(p), high = low;
      if (static_cast<long double>(low) > p) low = std::nextafter(low, -1e30f);
      if (static_cast<long double>(high) < p) high = std::nextafter(high, 1e30f);
      if (k != box_slot) {
        low = random_float(), high = random_float();
        if (low > high) std::swap(low, high);
      } else {
        if (*rc::gen::inRange(0, 3) == 0) low -= std::abs(random_float());
        if (*rc::gen::inRange(0, 3) == 0) high += std::abs(random_float());
      }
      node.bounds[0][c][k] = low;
      node.bounds[1][c][k] = high;
    }
    node.child[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(k);
  }
  const unsigned simd = detail::node_mask(node, q, inverse, negative, s1);
  const unsigned scalar = detail::node_mask_scalar(node, q, inverse, negative, s1);
  RC_ASSERT(simd == scalar);
  RC_ASSERT((simd >> box_slot) & 1u);
}

// The tree's boxes are relative to the scene's centre: a scene moved far from the origin keeps
// the pad of the scene at the origin (it grew with |coordinates| before, and the tree pruned
// nothing out there) and its rays are answered by the float tree.
TEST(WideBvh, PadDoesNotGrowWithTheSceneDistance) {
  const PatchBvh here(teapot());
  const Vec3 offset(3e6, -1e6, 2e6);
  const TransformedPatchSet moved = transform(teapot(), Eigen::Affine3d(Eigen::Translation3d(offset)));
  const PatchBvh there(moved.set);
  EXPECT_NEAR(there.wide().pad(), here.wide().pad(), 1e-6 * here.wide().pad());
  std::vector<std::uint32_t> near_pieces, far_pieces;
  const Vec3 o(-8, 0.3, 1.2), d(1, 0.05, 0.02);
  ASSERT_TRUE(here.wide().reaches(o, d, 0.0, std::numeric_limits<double>::infinity(), near_pieces));
  ASSERT_TRUE(there.wide().reaches(o + offset, d, 0.0, std::numeric_limits<double>::infinity(), far_pieces));
  EXPECT_LE(far_pieces.size(), near_pieces.size() + 4);
  expect_candidates_cover(there, o + offset, d, 0.0, std::numeric_limits<double>::infinity());
}

// Scaling by a power of two is exact on control points, rays and every product: the hits of the
// teapot scaled by 2^k (k up to +-66, about 1e+-20) are the original's, t for t, point for point.
TEST(RayCast, PowerOfTwoScaledScenesHitAsTheOriginal) {
  const PatchBvh original(teapot());
  const std::vector<std::pair<Vec3, Vec3>> rays = rays_through_seams(teapot(), 30);
  for (const int k : {-66, -20, 20, 66}) {
    const double scale = std::ldexp(1.0, k);
    const TransformedPatchSet scaled = transform(teapot(), Eigen::Affine3d(Eigen::Scaling(scale)));
    const PatchBvh bvh(scaled.set);
    for (const auto& [o, d] : rays) {
      const RayHits truth = ray_cast(original, o, d);
      const RayHits hits = ray_cast(bvh, scale * o, scale * d);
      ASSERT_EQ(hits.hits.size(), truth.hits.size()) << "2^" << k << ", o = " << o.transpose() << ", d = " << d.transpose();
      for (std::size_t h = 0; h < truth.hits.size(); ++h) {
        EXPECT_NEAR(hits.hits[h].t, truth.hits[h].t, 1e-9 * (1 + truth.hits[h].t)) << "2^" << k;
        EXPECT_LE((hits.hits[h].point / scale - truth.hits[h].point).norm(), 1e-9) << "2^" << k;
      }
    }
  }
}

// A ray aimed from far away at a point in the middle of a patch hits the patch there, from 10^3
// to 10^12 scene sizes out (the far ones walk the double tree, whose slab test is widened by its
// rounding): the rounded direction passes within 2u |o| of the aimed point, so at an angle of
// more than 0.2 to the surface the hit is within 32 eps |o| of it.
TEST(RayCast, RaysFromFarAwayHitWhatTheyAimAt) {
  const PatchBvh bvh(teapot());
  int aimed = 0;
  for (std::uint32_t p = 0; p < teapot().count(); ++p) {
    const AnyBezierPatch patch = teapot().patch(p);
    // Plain variables, not a structured binding: lambdas below capture them (clang 14).
    const std::pair<Vec3, Vec3> at = std::visit(
        [&](const auto& f) {
          const auto D = partial_derivatives(f, 0.37, 0.61, 1);
          return std::pair<Vec3, Vec3>{Vec3(D.at(0, 0)), Vec3(D.at(1, 0)).cross(Vec3(D.at(0, 1))).normalized()};
        },
        patch);
    const Vec3 target = at.first, normal = at.second;
    const Vec3 towards = Vec3(std::cos(1.7 * p), std::sin(1.7 * p), 0.3 * std::cos(0.3 * p)).normalized();
    if (!(std::abs(towards.dot(normal)) > 0.2)) continue;
    for (const double far : {1e3, 1e6, 1e9, 1e12}) {
      const Vec3 o = target + far * towards;
      const RayHits result = ray_cast(bvh, o, target - o);
      const double slack = 1e-9 + 32 * std::numeric_limits<double>::epsilon() * far;
      const bool found = std::any_of(result.hits.begin(), result.hits.end(), [&](const RayHit& h) {
        return h.patch == p && (h.point - target).norm() <= slack;
      });
      double nearest = std::numeric_limits<double>::infinity();
      for (const RayHit& h : result.hits) nearest = std::min(nearest, (h.point - target).norm());
      EXPECT_TRUE(found) << "patch " << p << " from " << far << " away: " << result.hits.size() << " hits, nearest " << nearest << " pieces " << result.pieces;
      ++aimed;
    }
  }
  EXPECT_GE(aimed, 40);
}

// Transversal hits found without any tree, box or net test: Newton on the patch's own
// evaluation from a 12 x 12 grid of starts on every patch, kept where it converges onto the ray
// inside the square at an angle of more than 10^-2 to the surface. Every such hit is one of
// ray_cast's, and every hit of ray_cast's at such an angle is one of these.
std::vector<double> newton_grid_hits(const PatchSet& set, const Vec3& o, const Vec3& d) {
  const Vec3 unit = d.normalized();
  const Vec3 a = unit.cross(std::abs(unit.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY()).normalized(), b = unit.cross(a);
  std::vector<double> ts;
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    const AnyBezierPatch patch = set.patch(p);
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        double u = (i + 0.5) / 12, v = (j + 0.5) / 12;
        bool converged = false;
        for (int iteration = 0; iteration < 40 && !converged; ++iteration) {
          const auto [F, Fu, Fv] = std::visit(
              [&](const auto& f) {
                const auto D = partial_derivatives(f, u, v, 1);
                return std::array<Vec3, 3>{Vec3(D.at(0, 0)), Vec3(D.at(1, 0)), Vec3(D.at(0, 1))};
              },
              patch);
          const double r0 = a.dot(F - o), r1 = b.dot(F - o);
          const double j00 = a.dot(Fu), j01 = a.dot(Fv), j10 = b.dot(Fu), j11 = b.dot(Fv), det = j00 * j11 - j01 * j10;
          if (!(std::abs(det) > 0)) break;
          const double du = (j11 * r0 - j01 * r1) / det, dv = (j00 * r1 - j10 * r0) / det;
          u -= du, v -= dv;
          if (!(u > -0.5 && u < 1.5 && v > -0.5 && v < 1.5)) break;
          converged = std::abs(du) + std::abs(dv) < 1e-14;
        }
        if (!converged || u < 0 || u > 1 || v < 0 || v > 1) continue;
        const auto [F, normal] = std::visit(
            [&](const auto& f) {
              const auto D = partial_derivatives(f, u, v, 1);
              return std::pair<Vec3, Vec3>{Vec3(D.at(0, 0)), Vec3(D.at(1, 0)).cross(Vec3(D.at(0, 1)))};
            },
            patch);
        if (!(std::abs(normal.normalized().dot(unit)) > 1e-2)) continue;
        const double t = d.dot(F - o) / d.squaredNorm();
        if (t >= 0) ts.push_back(t);
      }
    }
  }
  std::sort(ts.begin(), ts.end());
  std::vector<double> distinct;
  for (double t : ts)
    if (distinct.empty() || t - distinct.back() > 1e-7) distinct.push_back(t);
  return distinct;
}

TEST(RayCast, TransversalHitsAsNewtonOnEveryPatch) {
  const PatchBvh bvh(teapot());
  int compared = 0;
  for (const auto& [o, d] : rays_through_seams(teapot(), 24)) {
    const std::vector<double> truth = newton_grid_hits(teapot(), o, d);
    const RayHits result = ray_cast(bvh, o, d);
    for (double t : truth) {
      EXPECT_TRUE(std::any_of(result.hits.begin(), result.hits.end(), [&](const RayHit& h) { return std::abs(h.t - t) <= 1e-7 * (1 + t); }))
          << "missed t = " << t << ", o = " << o.transpose() << ", d = " << d.transpose();
    }
    for (const RayHit& h : result.hits) {
      if (!(std::abs(h.normal.dot(d.normalized())) > 2e-2)) continue;
      EXPECT_TRUE(std::any_of(truth.begin(), truth.end(), [&](double t) { return std::abs(h.t - t) <= 1e-7 * (1 + t); }))
          << "extra t = " << h.t << ", o = " << o.transpose() << ", d = " << d.transpose();
    }
    compared += static_cast<int>(truth.size());
  }
  EXPECT_GE(compared, 40);
}

}  // namespace
}  // namespace wide_bvh_test
