#include "report/occt_peer.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "report/nurbs_section.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/surface_normal.h"
#include "tests/surfaces/nurbs_generators.h"

namespace patchwork::performance {
namespace {

const std::vector<BezierPatch3>& teapot() {
  static const std::vector<BezierPatch3> patches = read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt");
  return patches;
}

// Diagonal of the control points' bounding box (it contains every patch).
double diagonal(const std::vector<BezierPatch3>& patches) {
  Eigen::AlignedBox3d box;
  for (const BezierPatch3& patch : patches) {
    for (const Vec3& P : patch.control_points()) box.extend(P);
  }
  return box.diagonal().norm();
}

Vec3 triangle_cross(const PeerMesh& mesh, std::size_t t) {
  const Vec3& a = mesh.positions[mesh.indices[3 * t]];
  const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
  return (b - a).cross(c - a);
}

// The patch owning vertex i (first_vertex is sorted).
std::size_t patch_of(const detail::OcctParametricMesh& result, std::size_t i) {
  std::size_t k = 0;
  while (result.first_vertex[k + 1] <= i) ++k;
  return k;
}

TEST(OcctPeer, VersionIsDebian12s) { EXPECT_EQ(occt_version(), "7.6.3"); }

// OCCT's (U, V) is patchwork's (u, v): every node is F(u, v) at its own UV (a transposed or
// mirrored pole net would put the teapot's nodes far off).
TEST(OcctPeer, NodesLieOnTheirPatchAtTheirParameters) {
  const double tolerance = 1e-9 * diagonal(teapot());
  for (const double deflection : {1e-1, 1e-2}) {
    const detail::OcctParametricMesh result = detail::occt_parametric_mesh(teapot(), deflection, 0.5);
    ASSERT_EQ(result.first_vertex.size(), teapot().size() + 1);
    ASSERT_EQ(result.uv.size(), result.mesh.positions.size());
    for (std::size_t k = 0; k < teapot().size(); ++k) {
      ASSERT_LT(result.first_vertex[k], result.first_vertex[k + 1]) << "patch " << k << " has no vertex";
      for (std::size_t i = result.first_vertex[k]; i < result.first_vertex[k + 1]; ++i) {
        const Vec2& uv = result.uv[i];
        ASSERT_TRUE(uv.x() >= -1e-12 && uv.x() <= 1 + 1e-12 && uv.y() >= -1e-12 && uv.y() <= 1 + 1e-12)
            << "patch " << k << " vertex " << i << " at (" << uv.x() << ", " << uv.y() << ")";
        EXPECT_LE((teapot()[k].evaluate(uv.x(), uv.y()) - result.mesh.positions[i]).norm(), tolerance)
            << "patch " << k << " vertex " << i;
      }
    }
  }
}

// Triangles stay within their patch and are wound along F_u x F_v (checked at the centroid of
// their parameters, with the limit normal where F_u x F_v vanishes).
TEST(OcctPeer, TrianglesAreWoundAlongThePatchNormal) {
  const double min_cross = 1e-12 * std::pow(diagonal(teapot()), 2);
  for (const double angular : {0.5, 10.0}) {
    const detail::OcctParametricMesh result = detail::occt_parametric_mesh(teapot(), 1e-2, angular);
    std::size_t checked = 0;
    for (std::size_t t = 0; t < result.mesh.triangle_count(); ++t) {
      const std::uint32_t* corner = &result.mesh.indices[3 * t];
      const std::size_t k = patch_of(result, corner[0]);
      ASSERT_EQ(patch_of(result, corner[1]), k);
      ASSERT_EQ(patch_of(result, corner[2]), k);
      const Vec3 cross = triangle_cross(result.mesh, t);
      if (cross.norm() <= min_cross) continue;  // degenerate, e.g. at a collapsed edge
      const Vec2 centroid = (result.uv[corner[0]] + result.uv[corner[1]] + result.uv[corner[2]]) / 3.0;
      EXPECT_GT(cross.dot(unit_normal(teapot()[k], centroid.x(), centroid.y())), 0.0)
          << "patch " << k << " triangle " << t << " (angular " << angular << ")";
      ++checked;
    }
    EXPECT_GT(checked, result.mesh.triangle_count() * 9 / 10);
  }
}

// A flat bilinear patch (a trapezoid with parallel sides 4 and 2 at height 2, area 6), moved
// rigidly: its triangles tile it exactly, so both their areas and their areas signed along the
// plane's normal F_u x F_v sum to 6.
TEST(OcctPeer, FlatBilinearPatchHasTheExactArea) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.rotate(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  motion.pretranslate(Vec3(0.5, -1.25, 2));
  const std::vector<BezierPatch3> patch{BezierPatch3(
      1, 1, {motion * Vec3(0, 0, 0), motion * Vec3(4, 0, 0), motion * Vec3(1, 2, 0), motion * Vec3(3, 2, 0)})};
  const Vec3 plane_normal = motion.linear() * Vec3(0, 0, 1);  // F_u x F_v / |F_u x F_v|
  for (const double deflection : {1e-1, 1e-3}) {
    const PeerMesh mesh = occt_tessellate(patch, deflection, 0.5, 1).mesh;
    double area = 0;
    double signed_area = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      area += 0.5 * triangle_cross(mesh, t).norm();
      signed_area += 0.5 * triangle_cross(mesh, t).dot(plane_normal);
    }
    EXPECT_NEAR(area, 6.0, 6e-12) << "deflection " << deflection;
    EXPECT_NEAR(signed_area, 6.0, 6e-12) << "deflection " << deflection;
  }
}

TEST(OcctPeer, SmallerDeflectionNeverGivesFewerTriangles) {
  for (const double angular : {0.5, 10.0}) {
    std::size_t previous = 0;
    for (const double deflection : {3e-1, 1e-1, 3e-2, 1e-2, 3e-3}) {
      const std::size_t count = occt_tessellate(teapot(), deflection, angular, 1).mesh.triangle_count();
      EXPECT_GE(count, previous) << "deflection " << deflection << ", angular " << angular;
      previous = count;
    }
  }
}

// The timed runs mesh afresh each time and return what one untimed meshing gives.
TEST(OcctPeer, RepeatsGiveTheSameMeshAndTimes) {
  const OcctRun run = occt_tessellate(teapot(), 1e-1, 0.5, 3);
  const detail::OcctParametricMesh once = detail::occt_parametric_mesh(teapot(), 1e-1, 0.5);
  EXPECT_EQ(run.repeats, 3);
  EXPECT_GT(run.seconds_min, 0.0);
  EXPECT_LE(run.seconds_min, run.seconds_median);
  EXPECT_EQ(run.mesh.indices, once.mesh.indices);
  EXPECT_EQ(run.mesh.positions, once.mesh.positions);
}

TEST(OcctPeer, BadArgumentsThrow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {0.0, -1e-3, nan, inf}) {
    EXPECT_THROW(occt_tessellate(teapot(), bad, 0.5, 1), InvalidInput) << bad;
    EXPECT_THROW(occt_tessellate(teapot(), 1e-2, bad, 1), InvalidInput) << bad;
    EXPECT_THROW(detail::occt_parametric_mesh(teapot(), bad, 0.5), InvalidInput) << bad;
  }
  EXPECT_THROW(occt_tessellate(teapot(), 1e-2, 0.5, 0), InvalidInput);
  EXPECT_THROW(occt_tessellate(teapot(), 1e-2, 0.5, -2), InvalidInput);
  // Geom_BezierSurface takes degrees 1..25.
  const std::vector<BezierPatch3> flat_in_v{BezierPatch3(1, 0, {Vec3(0, 0, 0), Vec3(1, 0, 0)})};
  EXPECT_THROW(occt_tessellate(flat_in_v, 1e-2, 0.5, 1), InvalidInput);
  const std::vector<BezierPatch3> too_high{BezierPatch3(26, 1, std::vector<Vec3>(54, Vec3(0, 0, 0)))};
  EXPECT_THROW(occt_tessellate(too_high, 1e-2, 0.5, 1), InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// Geom_BSplineSurface against NurbsSurface: two independent evaluators of the same surface.

// The size of the control net: its box's diagonal plus its distance from the origin (what
// absolute rounding scales with; a net collapsed to one point far out still rounds).
double net_size(const NurbsSurface& surface) {
  Eigen::AlignedBox3d box;
  for (int j = 0; j < surface.count_v(); ++j) {
    for (int i = 0; i < surface.count_u(); ++i) box.extend(surface.control_point(i, j));
  }
  return box.diagonal().norm() + box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).norm();
}

// Where patchwork's S, S_u, S_v and OCCT's D0 and D1 disagree at `parameters` (the first three
// places and a count; empty if nowhere): the point beyond 1e-12 of the net's size, a derivative
// beyond 1e-12 of the size over the domain's shortest side (S_u scales as 1 / parameter length)
// plus the derivatives' own size. Both evaluators are backward stable, so their rounding stays far below.
std::string disagreement_with_occt(const NurbsSurface& surface, const std::vector<Vec2>& parameters) {
  const std::vector<SurfaceJet> theirs = occt_evaluate(surface, parameters);
  if (theirs.size() != parameters.size()) return "occt_evaluate returned " + std::to_string(theirs.size()) + " jets";
  const double size = net_size(surface);
  const double side =
      std::min(surface.knots_u().b() - surface.knots_u().a(), surface.knots_v().b() - surface.knots_v().a());
  std::ostringstream out;
  out.precision(17);
  int disagreements = 0;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const double u = parameters[k].x();
    const double v = parameters[k].y();
    const PartialDerivatives<3> ours = partial_derivatives(surface, u, v, 1);
    const double derivative_tolerance = 1e-12 * (size / side + theirs[k].du.norm() + theirs[k].dv.norm());
    const double point = (surface.evaluate(u, v) - theirs[k].point).norm();
    const double du = (ours.at(1, 0) - theirs[k].du).norm();
    const double dv = (ours.at(0, 1) - theirs[k].dv).norm();
    // Written so that a NaN disagrees.
    const bool agree = point <= 1e-12 * size && du <= derivative_tolerance && dv <= derivative_tolerance;
    if (!agree && ++disagreements <= 3) {
      out << "at (" << u << ", " << v << "): |S - D0| = " << point << " (net size " << size << "), |S_u - D1u| = " << du
          << ", |S_v - D1v| = " << dv << " (tolerance " << derivative_tolerance << ")\n";
    }
  }
  if (disagreements > 3) out << "and at " << disagreements - 3 << " more parameters\n";
  return out.str();
}

// Random degrees 1..3, clamped knots with interior knots repeated up to the degree, weights in
// [1/4, 4] (or all 1); parameters at breakpoints (one-sided derivatives there: both take the
// span to the right of a knot, the last one at b) and spread over the domain.
RC_GTEST_PROP(OcctBSplineSurface, EvaluationAndFirstDerivativesAgreeWithNurbsSurface, ()) {
  const NurbsSurface surface = *nurbs_gen::nurbs_surface(*rc::gen::arbitrary<bool>(), /*clamped_only=*/true);
  std::vector<Vec2> parameters;
  for (int k = 0; k < 16; ++k) {
    parameters.emplace_back(*bspline_gen::parameter(surface.knots_u()), *bspline_gen::parameter(surface.knots_v()));
  }
  const std::string disagreement = disagreement_with_occt(surface, parameters);
  RC_ASSERT(disagreement == "");
}

// The exact shapes, on a 13 x 13 grid of their domain (with the sphere's poles and the joins of
// the quadratic arcs, C^0 knots of multiplicity 2).
TEST(OcctBSplineSurface, SphereAndTorusAgreeWithNurbsSurface) {
  for (const NurbsSurface& surface :
       {nurbs_sphere(Vec3(0.5, -1, 2), 1.5), nurbs_torus(Vec3(-1, 0.25, 0.5), 2.0, 0.5)}) {
    const KnotVector& U = surface.knots_u();
    const KnotVector& V = surface.knots_v();
    std::vector<Vec2> parameters;
    for (int j = 0; j <= 12; ++j) {
      for (int i = 0; i <= 12; ++i) {
        parameters.emplace_back(U.a() + (U.b() - U.a()) * i / 12.0, V.a() + (V.b() - V.a()) * j / 12.0);
      }
    }
    EXPECT_EQ(disagreement_with_occt(surface, parameters), "");
  }
}

// The NURBS section's meter (report/nurbs_section.h) takes the distance of the mesh to the surface
// as the two-sided one because a closed mesh wraps the surface: OCCT's meshes of the sphere and
// the torus are closed once nodes closer than 1e-9 are welded (the seam's and the poles' nodes
// repeat) and the triangles this collapses are dropped (at the poles), every edge shared by exactly
// two triangles, and their nodes lie on the surface.
TEST(OcctPeer, NurbsSphereAndTorusMeshesAreClosedAndOnTheSurface) {
  for (const ExactShape& shape : exact_shapes()) {
    for (const double deflection : {1e-2, 1e-3}) {
      const PeerMesh mesh = occt_tessellate(shape.surface, deflection, 0.5, 1).mesh;
      std::map<std::array<long long, 3>, std::uint32_t> welded;
      std::vector<std::uint32_t> id;
      for (const Vec3& x : mesh.positions) {
        EXPECT_LE(shape.distance(x), 1e-12) << shape.name;
        const std::array<long long, 3> key{std::llround(x.x() * 1e9), std::llround(x.y() * 1e9),
                                           std::llround(x.z() * 1e9)};
        id.push_back(welded.emplace(key, static_cast<std::uint32_t>(welded.size())).first->second);
      }
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const std::array<std::uint32_t, 3> c{id[mesh.indices[3 * t]], id[mesh.indices[3 * t + 1]],
                                             id[mesh.indices[3 * t + 2]]};
        // Collapsed by the welding (two corners at a pole, at the seam's two copies): no area.
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
        for (int k = 0; k < 3; ++k) ++uses[{std::min(c[k], c[(k + 1) % 3]), std::max(c[k], c[(k + 1) % 3])}];
      }
      std::size_t open = 0;
      for (const auto& [edge, count] : uses) open += count != 2;
      EXPECT_EQ(open, 0u) << shape.name << ", deflection " << deflection << ", " << uses.size() << " edges";
    }
  }
}

TEST(OcctBSplineSurface, ParametersOutsideTheDomainThrow) {
  const NurbsSurface sphere = nurbs_sphere(Vec3(0, 0, 0), 1.0);
  const double b = sphere.knots_u().b();
  for (const Vec2& uv : {Vec2(b + 1e-9, 0.5), Vec2(0.5, -1e-9), Vec2(std::nan(""), 0.5)}) {
    EXPECT_THROW(occt_evaluate(sphere, std::vector<Vec2>{uv}), InvalidInput) << uv.transpose();
  }
}

}  // namespace
}  // namespace patchwork::performance
