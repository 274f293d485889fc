// Properties of the tessellator on generated patch sets (tests/surfaces/patch_set_fixtures.h):
// exact normals at poles that are not on an axis, the patch set's topology on sets with poles,
// turned and degree-elevated patches and closed sets, and output that does not depend on the
// thread count in any mode.

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "io/bpt.h"
#include "meshes/topology.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/patch_set_fixtures.h"
#include "tests/surfaces/tessellation_checks.h"

// A named namespace: the test programs are unity builds, and tessellator_test.cpp's helpers live
// in patchwork's anonymous namespace.
namespace patchwork::tessellator_properties {
namespace {

using testing::net_unit_normal;

// The sanitizer build runs the coarser tolerances only: the same paths (split patches from 1e-2
// on the teapot), a few times fewer triangles.
#ifdef PATCHWORK_ENABLE_ASSERTS
rc::Gen<double> relative_tolerance() { return rc::gen::element(3e-2, 1e-2); }
constexpr double fine_tolerance = 1e-2;
constexpr int uniform_segments = 6;
constexpr double pixel_tolerance = 3.0;
#else
rc::Gen<double> relative_tolerance() { return rc::gen::element(3e-2, 1e-2, 3e-3); }
constexpr double fine_tolerance = 1e-3;
constexpr int uniform_segments = 12;
constexpr double pixel_tolerance = 1.0;
#endif

// The unit normal a vertex must carry: exact(patch, u, v).
using ExactNormal = std::function<Vec3(std::uint32_t, double, double)>;

// (u, v) lies on a collapsed edge of patch p.
bool on_collapsed_edge(const PatchSet& set, std::uint32_t p, double u, double v) {
  for (const EdgeRef& e : set.collapsed_edges()) {
    if (e.patch != p) continue;
    if ((e.edge == PatchEdge::v0 && v == 0) || (e.edge == PatchEdge::v1 && v == 1) ||
        (e.edge == PatchEdge::u0 && u == 0) || (e.edge == PatchEdge::u1 && u == 1))
      return true;
  }
  return false;
}

// The unit normal of the triangle's chord plane.
Vec3 face_normal(const RenderMesh& mesh, std::size_t t) {
  const Vec3& a = mesh.positions[mesh.indices[3 * t]];
  return (mesh.positions[mesh.indices[3 * t + 1]] - a).cross(mesh.positions[mesh.indices[3 * t + 2]] - a).normalized();
}

struct NormalCheck {
  // Largest |normal - exact| over all vertices of all triangles, and over those at the pole.
  double worst = 0.0;
  double worst_at_pole = 0.0;
  std::size_t pole_vertices = 0;
  // Largest distance between two unit normals at the pole.
  double pole_spread = 0.0;
  // Largest |average - exact| at the pole for the averages of the unit face normals of the
  // triangles using the vertex, and of those around its welded point.
  double vertex_average_error = 0.0;
  double point_average_error = 0.0;
};

// Every vertex normal against exact() at the vertex's (u, v) in its triangle's patch
// (UvMode::patch); the pole's vertices are those at `pole`.
NormalCheck check_normals(const PatchSet& set, const Tessellation& result, const Vec3& pole, const ExactNormal& exact) {
  const RenderMesh& mesh = result.mesh;
  NormalCheck check;
  std::vector<Vec3> vertex_sum(mesh.vertex_count(), Vec3::Zero()), point_sum(mesh.vertex_count(), Vec3::Zero());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      vertex_sum[v] += face_normal(mesh, t);
      point_sum[mesh.position_ids[v]] += face_normal(mesh, t);
    }
  }
  std::vector<Vec3> pole_normals;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t p = result.triangle_patches[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      const Vec3 expected = exact(p, mesh.uvs[v].x(), mesh.uvs[v].y());
      const double error = (mesh.normals[v] - expected).norm();
      check.worst = std::max(check.worst, error);
      if ((mesh.positions[v] - pole).norm() > 1e-12 * set.size()) continue;
      ++check.pole_vertices;
      check.worst_at_pole = std::max(check.worst_at_pole, error);
      pole_normals.push_back(mesh.normals[v]);
      check.vertex_average_error =
          std::max(check.vertex_average_error, (vertex_sum[v].normalized() - expected).norm());
      check.point_average_error =
          std::max(check.point_average_error, (point_sum[mesh.position_ids[v]].normalized() - expected).norm());
    }
  }
  for (const Vec3& a : pole_normals) {
    for (const Vec3& b : pole_normals) check.pole_spread = std::max(check.pole_spread, (a - b).norm());
  }
  return check;
}

TessellationOptions exact_normal_options(double relative) {
  TessellationOptions options;
  options.relative_tolerance = relative;
  options.crease_angle = 0.0;
  options.uv = UvMode::patch;
  return options;
}

// R'(u) x (A - R(u)) / |...| for the curve R of `row` (the normal of the cone from R to A, the
// limit normal at A of a patch whose row next to the collapsed edge is R): F_u x F_v of the
// patch (1 - v) R(u) + v A at v = 0.
Vec3 cone_normal(const std::vector<Vec3>& row, const Vec3& apex, double u) {
  std::vector<Vec3> points = row;
  points.insert(points.end(), row.size(), apex);
  return net_unit_normal(BezierPatch3(static_cast<int>(row.size()) - 1, 1, points), u, 0.0);
}

// The control points of row j of a patch.
std::vector<Vec3> net_row(const BezierPatch3& patch, int j) {
  const auto begin = patch.control_points().begin() + (patch.degree_u() + 1) * j;
  return {begin, begin + patch.degree_u() + 1};
}

// The asserts every pole check makes: the normals are exact (1e-9) everywhere and at the pole,
// and the averages of face normals around the pole vertices would not be.
void assert_exact_normals(const NormalCheck& check, std::size_t patches) {
  RC_LOG() << "pole vertices " << check.pole_vertices << ", worst " << check.worst << ", at the pole "
           << check.worst_at_pole << ", averages " << check.vertex_average_error << " " << check.point_average_error
           << "\n";
  RC_ASSERT(check.pole_vertices >= 2 * patches);  // at least two corners per patch
  RC_ASSERT(check.worst <= 1e-9);
  RC_ASSERT(check.worst_at_pole <= 1e-9);
  RC_ASSERT(check.vertex_average_error > 1e-6);
  RC_ASSERT(check.point_average_error > 1e-6);
}

// (a) A dome whose row next to the pole lies in a tilted plane through it, uneven around it,
// moved by a rigid motion: the limit normal at the pole is the plane's normal, on no axis.
RC_GTEST_PROP(TessellatorPoleNormals, ATiltedDomeHasItsPlanesNormalAtThePole, ()) {
  const int n = *rc::gen::inRange(1, 4);
  const int m = *rc::gen::inRange(2, 4);
  const int k = *rc::gen::inRange(n >= 2 ? 2 : 3, 5);
  const testing::TiltedDome dome = *testing::tilted_dome(k, n, m);
  // The fixture is what it says: the cone normal of every patch's row m-1 is the plane's.
  for (const BezierPatch3& patch : dome.patches) {
    for (double u : {0.0, 0.3, 0.7, 1.0}) RC_ASSERT((cone_normal(net_row(patch, m - 1), dome.pole, u) - dome.normal).norm() < 1e-12);
  }
  RC_ASSERT(std::acos(dome.normal.z()) > 0.19);  // before the motion, no axis either
  const Eigen::Isometry3d motion = *testing::random_rigid_motion();
  std::vector<BezierPatch3> patches;
  for (const BezierPatch3& patch : dome.patches) patches.push_back(testing::transformed(patch, Eigen::Affine3d(motion)));
  const PatchSet set(patches);
  RC_ASSERT(set.collapsed_edges().size() == static_cast<std::size_t>(k));
  const Vec3 pole = motion * dome.pole;
  const Vec3 normal = motion.linear() * dome.normal;
  const Tessellation result = tessellate(set, exact_normal_options(*relative_tolerance()));
  const NormalCheck check = check_normals(set, result, pole, [&](std::uint32_t p, double u, double v) {
    return on_collapsed_edge(set, p, u, v) ? normal : net_unit_normal(set.patches()[p], u, v);
  });
  assert_exact_normals(check, patches.size());
  RC_ASSERT(check.pole_spread <= 2e-9);
}

// (b) Cones F = A + (1 - v)(C(u) - A) over non-planar cubics C around A (a fan of k patches of
// degree (3, 1)), elevated in v to degree 2 or 3: the normal is normalize(C'(u) x (A - C(u))) on
// each whole ruling, the apex included, so at A it varies with u and from patch to patch.
RC_GTEST_PROP(TessellatorPoleNormals, ConesHaveTheirRulingsNormalAtTheApex, ()) {
  const int k = *rc::gen::inRange(2, 5);
  std::vector<double> radii, heights;
  for (int s = 0; s < 3 * k; ++s) {
    radii.push_back(*testing::coordinate(0.6, 1.4));
    heights.push_back(*testing::coordinate(-0.4, 0.4));
  }
  const std::vector<Vec3> rim = testing::fan_net(
      k, 3, 1, [&](int s, int) { return radii[s]; }, [&](int s, int) { return heights[s]; });
  const Eigen::Isometry3d motion = *testing::random_rigid_motion();
  const Vec3 local_apex(0, 0, *testing::coordinate(0.5, 1.5));
  const Vec3 apex = motion * local_apex;
  const int elevations = *rc::gen::inRange(1, 3);
  std::vector<BezierPatch3> cones, patches;
  for (const BezierPatch3& cone : testing::polar_fan(k, 3, 1, rim, local_apex)) {
    cones.push_back(testing::transformed(cone, Eigen::Affine3d(motion)));
    patches.push_back(cones.back());
    for (int e = 0; e < elevations; ++e) patches.back() = testing::elevated_once(patches.back(), false);
  }
  const PatchSet set(patches);
  RC_ASSERT(set.collapsed_edges().size() == static_cast<std::size_t>(k));
  const Tessellation result = tessellate(set, exact_normal_options(*relative_tolerance()));
  const NormalCheck check = check_normals(set, result, apex, [&](std::uint32_t p, double u, double) {
    return cone_normal(net_row(cones[p], 0), apex, u);
  });
  assert_exact_normals(check, patches.size());
  RC_ASSERT(check.pole_spread > 0.1);
}

// (c) A collapsed edge across which the degree is higher than along it: tilted domes of degree
// (2, 4) turned a quarter (or three), so each patch is of degree (4, 2) with its u1 (or u0) edge
// collapsed, some of them elevated once more along the pole.
RC_GTEST_PROP(TessellatorPoleNormals, AMixedDegreePatchCollapsedOnAnUEdgeHasTheExactNormal, ()) {
  const int k = *rc::gen::inRange(2, 5);
  const testing::TiltedDome dome = *testing::tilted_dome(k, 2, 4);
  const int turns = *rc::gen::element(1, 3);
  std::vector<BezierPatch3> patches;
  for (const BezierPatch3& patch : dome.patches) {
    BezierPatch3 turned = testing::turned(patch, turns);
    if (*rc::gen::arbitrary<bool>()) turned = testing::elevated_once(turned, false);
    patches.push_back(turned);
  }
  const PatchSet set(patches);
  RC_ASSERT(set.collapsed_edges().size() == static_cast<std::size_t>(k));
  for (const EdgeRef& e : set.collapsed_edges()) {
    RC_ASSERT(e.edge == (turns == 1 ? PatchEdge::u1 : PatchEdge::u0));
    RC_ASSERT(set.patches()[e.patch].degree_u() == 4);
  }
  const Tessellation result = tessellate(set, exact_normal_options(*relative_tolerance()));
  const NormalCheck check = check_normals(set, result, dome.pole, [&](std::uint32_t p, double u, double v) {
    return on_collapsed_edge(set, p, u, v) ? dome.normal : net_unit_normal(set.patches()[p], u, v);
  });
  assert_exact_normals(check, patches.size());
  RC_ASSERT(check.pole_spread <= 2e-9);
}

// Each welded edge that only one triangle uses lies on an open edge of that triangle's patch:
// its corners' patch parameters are on one side of the square, PatchSet lists that side as open,
// and the corners are that patch's points there (up to the weld gap).
bool boundary_lies_on_open_edges(const PatchSet& set, const Tessellation& result) {
  const RenderMesh& mesh = result.mesh;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::size_t, int>>> uses;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      uses[std::minmax(mesh.position_ids[mesh.indices[3 * t + k]], mesh.position_ids[mesh.indices[3 * t + (k + 1) % 3]])]
          .emplace_back(t, k);
    }
  }
  const auto on_side = [](const Vec2& uv, PatchEdge edge) {
    switch (edge) {
      case PatchEdge::v0: return uv.y() == 0;
      case PatchEdge::u1: return uv.x() == 1;
      case PatchEdge::v1: return uv.y() == 1;
      case PatchEdge::u0: return uv.x() == 0;
    }
    return false;
  };
  for (const auto& [edge, triangles] : uses) {
    if (triangles.size() != 1) continue;
    const auto [t, k] = triangles.front();
    const std::uint32_t p = result.triangle_patches[t];
    const Vec2& a = mesh.uvs[mesh.indices[3 * t + k]];
    const Vec2& b = mesh.uvs[mesh.indices[3 * t + (k + 1) % 3]];
    const bool open = std::any_of(set.open_edges().begin(), set.open_edges().end(), [&](const EdgeRef& e) {
      return e.patch == p && on_side(a, e.edge) && on_side(b, e.edge);
    });
    if (!open) return false;
    for (int c : {k, (k + 1) % 3}) {
      const std::uint32_t v = mesh.indices[3 * t + c];
      const Vec3 point = set.patches()[p].evaluate(mesh.uvs[v].x(), mesh.uvs[v].y());
      if ((point - mesh.positions[v]).norm() > result.weld_gap + 1e-12 * set.size()) return false;
    }
  }
  return true;
}

// Sets with poles, turned and degree-elevated patches, closed sets and pairs of sets: the welded
// mesh is a manifold, orientable, with the patch set's boundary loops (none where it is closed),
// the fixture's Euler characteristic and components, its boundary on open edges only, and the
// guarantee holds.
RC_GTEST_PROP(TessellatorTopology, WeldedMeshHasThePatchSetsTopology, ()) {
  const testing::PatchSetFixture fixture = *testing::any_patch_set();
  RC_TAG(fixture.kind);
  RC_LOG() << fixture.kind << ":";
  for (const BezierPatch3& patch : fixture.patches) RC_LOG() << " (" << patch.degree_u() << ", " << patch.degree_v() << ")";
  const PatchSet set(fixture.patches);
  // The fixture is what it says.
  RC_ASSERT(set.open_edges().empty() == fixture.closed);
  RC_ASSERT(static_cast<Count>(set.boundary_loops().size()) == fixture.boundary_loops);
  TessellationOptions options;
  options.crease_angle = *rc::gen::element(0.0, 0.0174532925199432958, 0.5);
  if (*rc::gen::inRange(0, 4) == 0) {
    // Not 1: a fan of two patches then has two chord triangles on the same three points (each
    // patch spans half the pole), which no tolerance mode makes (curved patches get two segments).
    options.segments = *rc::gen::element(2, 3);
  } else {
    options.relative_tolerance = *relative_tolerance();
  }
  const Tessellation result = tessellate(set, options);
  validate(result.mesh);
  const double slack = 1e-12 * set.size();
  if (!options.segments) RC_ASSERT(result.error_bound <= result.tolerance + result.weld_gap + slack);
  RC_ASSERT(result.measured_error <= result.error_bound * (1 + 1e-9) + slack);
  const TopologyReport report = analyze(welded_faces(result.mesh));
  RC_ASSERT(report.manifold);
  RC_ASSERT(report.orientable);
  RC_ASSERT(report.closed == fixture.closed);
  RC_ASSERT(report.euler == fixture.euler);
  RC_ASSERT(report.components == fixture.components);
  RC_ASSERT(report.boundary_loops == static_cast<Count>(set.boundary_loops().size()));
  RC_ASSERT(report.isolated_vertices == 0);
  RC_ASSERT(boundary_lies_on_open_edges(set, result));
}

// 1, 2, 3 and 7 threads give the same output in every mode of the library: absolute and relative
// tolerance (split patches), uniform segments, and the camera with culling, on the teapot and on
// a set of mixed degrees with poles. (Levels of detail are a loop over tolerances in the CLI,
// tools/tessellate_command.cpp, not a library mode.)
TEST(TessellatorThreads, EveryModeGivesTheSameOutputOnAnyThreadCount) {
  const PatchSet teapot(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  const PatchSet lens(testing::mixed_degree_lens());
  struct Mode {
    const char* name;
    const PatchSet* set;
    TessellationOptions options;
  };
  std::vector<Mode> modes;
  for (const PatchSet* set : {&teapot, &lens}) {
    Mode absolute{"absolute tolerance", set, {}};
    absolute.options.tolerance = 2 * fine_tolerance * set->size();
    absolute.options.tangents = true;
    Mode relative{"relative tolerance", set, {}};
    relative.options.relative_tolerance = fine_tolerance;
    relative.options.uv = UvMode::atlas;
    Mode segments{"segments", set, {}};
    segments.options.segments = uniform_segments;
    segments.options.tangents = true;
    modes.insert(modes.end(), {absolute, relative, segments});
  }
  Mode camera{"camera", &teapot, {}};
  camera.options.camera = Camera{Vec3(8, -6, 5), Vec3(0, 0, 1.5), Vec3::UnitZ(), 40.0, 640, 480};
  camera.options.pixel_tolerance = pixel_tolerance;
  camera.options.tangents = true;
  camera.options.back_face_culling = BackFaceCulling::always;  // the teapot is open: asked for
  modes.push_back(camera);
  // A closed cube culls its back by itself (BackFaceCulling::automatic; the lens has poles, where
  // F_u x F_v vanishes, and no patch of it is back-facing everywhere by the Bernstein test).
  std::vector<double> bulge(24);
  for (std::size_t k = 0; k < bulge.size(); ++k) bulge[k] = 0.1 + 0.02 * static_cast<double>(k % 7);
  const PatchSet cube(testing::bulged_cube(bulge));
  Mode closed_camera{"camera, automatic culling", &cube, {}};
  closed_camera.options.camera = Camera{Vec3(4, -3, 2.5), Vec3(0, 0, 0), Vec3::UnitZ(), 40.0, 640, 480};
  closed_camera.options.pixel_tolerance = pixel_tolerance;
  modes.push_back(closed_camera);
  for (Mode& mode : modes) {
    mode.options.threads = 1;
    const Tessellation one = tessellate(*mode.set, mode.options);
    ASSERT_GT(one.mesh.triangle_count(), 0u);
    if (mode.options.camera) {
      EXPECT_GT(one.culled_patches, 0u);
    }
    for (int threads : {2, 3, 7}) {
      mode.options.threads = threads;
      SCOPED_TRACE(::testing::Message() << mode.name << ", " << threads << " threads");
      testing::expect_identical_tessellations(one, tessellate(*mode.set, mode.options));
    }
  }
}

// A patch whose v0 edge is a closed curve (its corners (0,0) and (1,0) are one point) touches
// itself there. The tessellator welds corners only through shared and collapsed edges, so the
// welded mesh (a manifold disc) has one boundary loop through two vertices at that point, and
// PatchSet chains its loops through the same joins: one loop [v0 u1 v1 u0] (it found two, [v0]
// and [u1 v1 u0], when it chained by end points).
TEST(TessellatorTopology, APatchWhoseEdgeIsAClosedCurveHasThePatchSetsBoundaryLoops) {
  // Degree (3, 1): row v = 0 a closed cubic loop through the origin (P00 = P30), row v = 1 open.
  const BezierPatch3 patch(3, 1, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), Vec3(-1, -1, 1),
                                  Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(-1, 1, 1)});
  const PatchSet set({patch});
  TessellationOptions options;
  options.relative_tolerance = 1e-2;
  const TopologyReport report = analyze(welded_faces(tessellate(set, options).mesh));
  ASSERT_TRUE(report.manifold);
  ASSERT_EQ(set.boundary_loops().size(), 1u);
  EXPECT_TRUE(set.boundary_loops()[0].closed);
  EXPECT_EQ(set.boundary_loops()[0].edges.size(), 4u);
  EXPECT_EQ(report.boundary_loops, static_cast<Count>(set.boundary_loops().size()));
}

}  // namespace
}  // namespace patchwork::tessellator_properties
