#include "report/occt_peer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "surfaces/surface_normal.h"

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

}  // namespace
}  // namespace patchwork::performance
