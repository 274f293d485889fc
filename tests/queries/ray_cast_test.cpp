// Ray casting against closed forms (sphere, torus: roots counted independently), the tessellated
// teapot, shared edges and tangent rays.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "queries/patch_bvh.h"
#include "queries/ray_cast.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/tessellator.h"
#include "tests/queries/query_fixtures.h"

namespace ray_cast_test {
namespace {

using namespace patchwork;

const auto& set_from = patchwork::testing::nurbs_patch_set;

const PatchSet& sphere() {
  static const PatchSet set = set_from(nurbs_sphere(Vec3(0.25, -0.5, 1.0), 1.5));
  return set;
}

const PatchSet& torus() {
  static const PatchSet set = set_from(nurbs_torus(Vec3::Zero(), 2.0, 0.75));
  return set;
}

const auto& teapot = patchwork::testing::teapot_set;

// Every hit on the ray and on the surface, in increasing t.
void expect_consistent(const RayHits& result, const Vec3& o, const Vec3& d, double size) {
  for (std::size_t k = 0; k < result.hits.size(); ++k) {
    const RayHit& hit = result.hits[k];
    EXPECT_LE((o + hit.t * d - hit.point).norm(), 1e-12 * size);
    EXPECT_NEAR(hit.normal.norm(), 1.0, 1e-14);
    if (k > 0) {
      EXPECT_LT(result.hits[k - 1].t, hit.t);
    }
  }
}

RC_GTEST_PROP(RayCast, SphereHitsAreTheQuadraticsRoots, ()) {
  static const PatchBvh bvh(sphere());
  const Vec3 c(0.25, -0.5, 1.0);
  const double r = 1.5;
  const Vec3 o(*rc::gen::inRange(-400, 400) / 100.0, *rc::gen::inRange(-400, 400) / 100.0, *rc::gen::inRange(-400, 400) / 100.0);
  const Vec3 target = c + Vec3(*rc::gen::inRange(-200, 200), *rc::gen::inRange(-200, 200), *rc::gen::inRange(-200, 200)) / 100.0;
  const Vec3 d = target - o;
  RC_PRE(d.norm() > 1e-3);
  // |o + t d - c|^2 = r^2: a t^2 + 2 b t + k = 0.
  const double a = d.squaredNorm(), b = d.dot(o - c), k = (o - c).squaredNorm() - r * r;
  const double disc = b * b - a * k;
  RC_PRE(std::abs(disc) > 1e-6 * a);  // tangent rays have their own test
  std::vector<double> roots;
  if (disc > 0) {
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    for (double t : {q / a, k / q})
      if (t >= 0) roots.push_back(t);
    std::sort(roots.begin(), roots.end());
  }
  const RayHits result = ray_cast(bvh, o, d);
  RC_ASSERT(result.hits.size() == roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) {
    RC_ASSERT(std::abs(result.hits[i].t - roots[i]) <= 1e-12 * (1 + roots[i]));
    const Vec3 radial = (result.hits[i].point - c) / r;
    RC_ASSERT(std::abs(std::abs(result.hits[i].normal.dot(radial)) - 1.0) <= 1e-12);
    RC_ASSERT(!result.hits[i].grazing);
  }
}

TEST(RayCast, TangentRayTouchesTheSphereOnceAndIsFlagged) {
  const PatchBvh bvh(sphere());
  const Vec3 c(0.25, -0.5, 1.0);
  for (const auto& [offset, direction] : {std::pair{Vec3(1.5, 0, 0), Vec3(0, 1, 0)}, std::pair{Vec3(0, 0, 1.5), Vec3(1, 0, 0)},
                                          std::pair{Vec3(0, -1.5, 0), Vec3(0, 0, 1)}}) {
    const RayHits result = ray_cast(bvh, c + offset - 3 * direction, direction);
    ASSERT_EQ(result.hits.size(), 1u) << offset.transpose();
    EXPECT_TRUE(result.hits[0].grazing);
    EXPECT_NEAR(result.hits[0].t, 3.0, 1e-6);
    EXPECT_LE((result.hits[0].point - (c + offset)).norm(), 1e-6);
  }
}

// The torus's implicit function along the ray, (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2): its
// sign changes on a fine sampling, each refined by bisection (an independent root count).
std::vector<double> torus_roots(const Vec3& o, const Vec3& d, double major, double minor, double t_end) {
  const auto f = [&](double t) {
    const Vec3 p = o + t * d;
    const double s = p.squaredNorm() + major * major - minor * minor;
    return s * s - 4 * major * major * (p.x() * p.x() + p.y() * p.y());
  };
  std::vector<double> roots;
  const int samples = 20000;
  for (int i = 0; i < samples; ++i) {
    double lo = t_end * i / samples, hi = t_end * (i + 1) / samples;
    if ((f(lo) > 0) == (f(hi) > 0)) continue;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((f(mid) > 0) == (f(lo) > 0) ? lo : hi) = mid;
    }
    roots.push_back(0.5 * (lo + hi));
  }
  return roots;
}

TEST(RayCast, TorusHitsAreTheQuarticsRoots) {
  const PatchBvh bvh(torus());
  int rays = 0, hits = 0;
  for (int i = 0; i < 60; ++i) {
    const double phi = 0.37 * i, z = -0.7 + 0.023 * i;
    const Vec3 o(6 * std::cos(phi), 6 * std::sin(phi), 2.0 * std::sin(1.3 * i));
    const Vec3 target(1.7 * std::cos(2.1 * i), 1.7 * std::sin(2.1 * i), z);
    const Vec3 d = target - o;
    const std::vector<double> roots = torus_roots(o, d, 2.0, 0.75, 3.0);
    const RayHits result = ray_cast(bvh, o, d);
    expect_consistent(result, o, d, bvh.size());
    ASSERT_EQ(result.hits.size(), roots.size()) << "ray " << i;
    for (std::size_t k = 0; k < roots.size(); ++k) EXPECT_NEAR(result.hits[k].t, roots[k], 1e-10);
    ++rays;
    hits += static_cast<int>(roots.size());
  }
  EXPECT_GE(hits, 2 * rays);  // most rays cross the tube twice or four times
}

TEST(RayCast, ThroughSharedEdgesAndCornersOnce) {
  const PatchSet& set = teapot();
  const PatchBvh bvh(set);
  int checked = 0;
  for (const SharedEdge& edge : set.shared_edges()) {
    const BezierPatch3& patch = set.control_nets()[edge.first.patch];
    const double u = edge.first.edge == PatchEdge::u0 ? 0.0 : edge.first.edge == PatchEdge::u1 ? 1.0 : 0.5;
    const double v = edge.first.edge == PatchEdge::v0 ? 0.0 : edge.first.edge == PatchEdge::v1 ? 1.0 : 0.5;
    for (const auto& [su, sv] : {std::pair{u, v}, std::pair{u == 0.5 ? 0.0 : u, v == 0.5 ? 0.0 : v}}) {
      const Vec3 point = patch.evaluate(su, sv);
      const Vec3 d = Vec3(0.3, -0.2, 1.0);
      const RayHits result = ray_cast(bvh, point - 2 * d, d);
      expect_consistent(result, point - 2 * d, d, bvh.size());
      int at_point = 0;
      // A tangent contact (the spout's rim meets this ray at a grazing angle) is located only to
      // about the square root of the rounding level.
      for (const RayHit& hit : result.hits) at_point += (hit.point - point).norm() <= (hit.grazing ? 1e-6 : 1e-9);
      EXPECT_EQ(at_point, 1) << "edge of patch " << edge.first.patch;
      ++checked;
    }
  }
  EXPECT_GE(checked, 100);
}

// Moeller-Trumbore hits of a triangle mesh, both sides.
std::vector<double> mesh_hits(const RenderMesh& mesh, const Vec3& o, const Vec3& d) {
  std::vector<double> ts;
  for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
    const Vec3& a = mesh.positions[mesh.indices[3 * k]];
    const Vec3 e1 = mesh.positions[mesh.indices[3 * k + 1]] - a, e2 = mesh.positions[mesh.indices[3 * k + 2]] - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (det == 0) continue;
    const Vec3 s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(q) / det;
    if (t >= 0) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

TEST(RayCast, TeapotAgainstTheTessellatedMesh) {
  const PatchSet& set = teapot();
  const PatchBvh bvh(set);
  TessellationOptions options;
  options.tolerance = 1e-4;
  const Tessellation mesh = tessellate(set, options);
  int compared = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec3 o(5 * std::cos(0.7 * i), 5 * std::sin(0.7 * i), 1.5 + 1.4 * std::sin(0.9 * i));
    const Vec3 target(0.6 * std::cos(1.9 * i), 0.6 * std::sin(1.9 * i), 0.2 + 0.1 * i);
    const Vec3 d = (target - o).normalized();
    const RayHits result = ray_cast(bvh, o, d);
    expect_consistent(result, o, d, bvh.size());
    const std::vector<double> reference = mesh_hits(mesh.mesh, o, d);
    // Where every hit crosses at a clear angle, the mesh (within 1e-4 of the surface) crosses
    // the ray as often, each crossing within 1e-4 / |cos| of the exact one; rays that graze or
    // pass where two mesh crossings merge (a seam) are left out.
    bool clear = true;
    for (const RayHit& hit : result.hits) clear = clear && std::abs(hit.normal.dot(d)) > 0.2;
    for (std::size_t k = 1; k < reference.size(); ++k) clear = clear && reference[k] - reference[k - 1] > 1e-3;
    if (!clear) continue;
    ASSERT_EQ(result.hits.size(), reference.size()) << "ray " << i;
    for (std::size_t k = 0; k < reference.size(); ++k)
      EXPECT_NEAR(result.hits[k].t, reference[k], 2 * mesh.error_bound / std::abs(result.hits[k].normal.dot(d)));
    ++compared;
  }
  EXPECT_GE(compared, 25);
}

// A small scene far from the origin: the pieces' boxes are widened by a rounding margin that
// grows with their coordinates and depth, larger than the scene's resolution; a piece is tiny by
// its own size. (Compared widened, such pieces halved until memory ran out: std::bad_alloc.)
TEST(RayCast, SmallSceneFarFromTheOriginSettles) {
  for (const double scale : {1e-5, 1e-6}) {
    const PatchSet set = set_from(nurbs_torus(Vec3(100, 37, -61), 2.0 * scale, 0.75 * scale));
    const PatchBvh bvh(set);
    // A ray through the tube, and the reviewer's rays that grazed it.
    const Vec3 o(100 + 2.0 * scale, 37, -61 - 5 * scale);
    const RayHits through = ray_cast(bvh, o, Vec3(0, 0, 1));
    ASSERT_EQ(through.hits.size(), 2u) << scale;
    EXPECT_NEAR(through.hits[0].point.z(), -61 - 0.75 * scale, 1e-9 * scale);
    EXPECT_NEAR(through.hits[1].point.z(), -61 + 0.75 * scale, 1e-9 * scale);
    const Vec3 grazing_o = scale == 1e-5 ? Vec3(99.999926760337218, 36.999928083914291, -60.999995777250646)
                                         : Vec3(99.999991561565267, 36.999996116163899, -61.000006350084853);
    const Vec3 grazing_d = scale == 1e-5 ? Vec3(5.9286262342084228e-05, 7.1098243175526932e-05, 2.1943854804362672e-06)
                                         : Vec3(6.3669138938848846e-06, 1.6421924371456953e-06, 6.2667744060718178e-06);
    const RayHits grazing = ray_cast(bvh, grazing_o, grazing_d);
    EXPECT_LE(grazing.pieces, 100000) << scale;
  }
}

// A ray down the axis onto a sphere's pole far from the origin: F_u there is rounding of the
// coordinates' size, which must not be taken for a tangent (the normal would be that noise's);
// the hit's normal is the pole's, +z, as near the origin.
TEST(RayCast, PoleNormalFarFromTheOrigin) {
  for (const Vec3& centre : {Vec3(0.25, -0.5, 1.0), Vec3(1e6 + 0.1, 7e5 + 0.3, -3e5 + 0.7),
                             Vec3(1e8 + 0.1, 7e7 + 0.3, -3e7 + 0.7), Vec3(1e9 + 0.1, 7e8 + 0.3, -3e8 + 0.7)}) {
    const PatchSet set = set_from(nurbs_sphere(centre, 1.5));
    const RayHits result = ray_cast(set, centre + Vec3(0, 0, 5), Vec3(0, 0, -1));
    ASSERT_FALSE(result.hits.empty()) << centre.transpose();
    const RayHit& top = result.hits.front();
    EXPECT_NEAR(top.point.z() - centre.z(), 1.5, 1e-12 * centre.norm() + 1e-12) << centre.transpose();
    EXPECT_LT((top.normal - Vec3(0, 0, 1)).norm(), centre.norm() > 1e8 ? 1e-5 : 1e-6) << centre.transpose();
  }
}

TEST(RayCast, LimitsAndBadInput) {
  const PatchBvh bvh(sphere());
  const Vec3 o(0.25, -0.5, -5.0), d(0, 0, 1);
  EXPECT_EQ(ray_cast(bvh, o, d).hits.size(), 2u);
  RayOptions first_only;
  first_only.t_max = 4.5;
  EXPECT_EQ(ray_cast(bvh, o, d, first_only).hits.size(), 1u);
  EXPECT_EQ(ray_cast(bvh, o, -d).hits.size(), 0u);
  try {
    ray_cast(bvh, o, Vec3::Zero());
    FAIL();
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()), "ray_cast: argument 'direction' is the zero vector");
  }
  EXPECT_THROW(ray_cast(bvh, Vec3(std::nan(""), 0, 0), d), InvalidInput);
  RayOptions backwards;
  backwards.t_min = 2;
  backwards.t_max = 1;
  EXPECT_THROW(ray_cast(bvh, o, d, backwards), InvalidInput);
}

}  // namespace
}  // namespace ray_cast_test
