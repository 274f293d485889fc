#include "surfaces/tessellator.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/errors.h"
#include "io/bpt.h"
#include "meshes/topology.h"
#include "surfaces/surface_integrals.h"
#include "tests/support/ray_cast.h"
#include "tests/surfaces/patch_fixtures.h"
#include "tests/surfaces/patch_set_fixtures.h"
#include "tests/surfaces/tessellation_checks.h"

namespace patchwork {
namespace {

const PatchSet& teapot() {
  static const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  return set;
}

using testing::relative;

// N x N per patch, in the tessellator's order (no vertex-cache reordering).
TessellationOptions uniform_unordered(int segments) {
  TessellationOptions options;
  options.segments = segments;
  options.optimize = false;
  return options;
}

double triangle_area(const RenderMesh& mesh, std::size_t t) {
  const Vec3& a = mesh.positions[mesh.indices[3 * t]];
  const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
  return 0.5 * (b - a).cross(c - a).norm();
}

// Distance from p to the boundary curve of an edge (dense samples, then golden-section refinement).
double distance_to_edge(const BezierPatch3& patch, PatchEdge edge, const Vec3& p) {
  const BezierCurve<3> curve = boundary_curve(patch, edge);
  constexpr int samples = 256;
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double d = (curve.evaluate(static_cast<double>(k) / samples) - p).norm();
    if (d < best_distance) best_distance = d, best = k;
  }
  double lo = std::max(0.0, (best - 1.0) / samples), hi = std::min(1.0, (best + 1.0) / samples);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double a = lo + (hi - lo) * 0.381966, b = hi - (hi - lo) * 0.381966;
    if ((curve.evaluate(a) - p).norm() < (curve.evaluate(b) - p).norm()) {
      hi = b;
    } else {
      lo = a;
    }
  }
  return std::min(best_distance, (curve.evaluate(0.5 * (lo + hi)) - p).norm());
}

// Welded, crack-free and render-ready: the checks every tessellation must pass.
// At coarse tolerances a chord triangle may tilt away from the normals at its corners (a patch
// cut into 2 x 2 cells at 1e-1); with check_winding the winding must agree with them.
void expect_render_ready(const PatchSet& set, const Tessellation& result, double tolerance, bool check_winding = true) {
  const RenderMesh& mesh = result.mesh;
  ASSERT_NO_THROW(validate(mesh));
  EXPECT_LE(result.error_bound, tolerance);
  EXPECT_LE(result.measured_error, result.error_bound * (1 + 1e-9) + 1e-12 * set.size());
  EXPECT_EQ(result.triangle_patches.size(), mesh.triangle_count());
  const double scale = set.size();
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    // No degenerate triangle, and the winding agrees with the exact normals.
    ASSERT_GT(triangle_area(mesh, t), 1e-12 * scale * scale) << "triangle " << t;
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3 geometric =
        (mesh.positions[mesh.indices[3 * t + 1]] - a).cross(mesh.positions[mesh.indices[3 * t + 2]] - a);
    Vec3 average = Vec3::Zero();
    for (int k = 0; k < 3; ++k) average += mesh.normals[mesh.indices[3 * t + k]];
    if (check_winding) {
      ASSERT_GT(geometric.dot(average), 0.0) << "triangle " << t;
    }
  }
  // The welded mesh is a manifold whose boundary lies on the patch set's open edges only.
  const FaceVertexMesh welded = welded_faces(mesh);
  const TopologyReport report = analyze(welded);
  EXPECT_TRUE(report.manifold);
  EXPECT_TRUE(report.orientable);
  EXPECT_EQ(static_cast<std::size_t>(report.boundary_loops), set.boundary_loops().size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t f = 0; f < welded.face_count(); ++f) {
    const auto face = welded.face(f);
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(face[k], face[(k + 1) % 3])];
  }
  for (const auto& [edge, count] : uses) {
    if (count != 1) continue;
    for (std::uint32_t v : {edge.first, edge.second}) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const EdgeRef& open : set.open_edges()) {
        nearest = std::min(nearest, distance_to_edge(set.patches()[open.patch], open.edge, welded.position(v)));
      }
      ASSERT_LT(nearest, 1e-9 * scale) << "boundary vertex " << v << " is not on an open edge";
    }
  }
}

class TeapotTessellation : public ::testing::TestWithParam<double> {};

TEST_P(TeapotTessellation, IsWatertightWithinItsToleranceWithThePatchSetsTopology) {
  const Tessellation result = tessellate(teapot(), relative(GetParam()));
  expect_render_ready(teapot(), result, result.tolerance, GetParam() <= 1e-2);
  // 4 face-connected components (body, lid, handle, spout), 6 boundary loops, each component
  // a sphere with holes (genus 0); the handle touches the body at one point, which keeps two
  // vertices, so the mesh stays manifold there.
  const TopologyReport report = analyze(welded_faces(result.mesh));
  EXPECT_EQ(report.components, 4);
  EXPECT_EQ(report.boundary_loops, 6);
  EXPECT_EQ(report.genus, 0);
  EXPECT_NEAR(result.tolerance, GetParam() * 8.2048659851356535, 1e-9 * GetParam());
}

// 1e-4 and 1e-5 (90 k and 850 k triangles) are too slow for the sanitizer build, where 1e-1 ..
// 1e-3 run (1e-3 already splits patches 4 x 4, the path the finer ones take).
#ifdef PATCHWORK_ENABLE_ASSERTS
INSTANTIATE_TEST_SUITE_P(Tolerances, TeapotTessellation, ::testing::Values(1e-1, 1e-2, 1e-3));
#else
INSTANTIATE_TEST_SUITE_P(Tolerances, TeapotTessellation, ::testing::Values(1e-1, 1e-2, 1e-3, 1e-4, 1e-5));
#endif

TEST(Tessellator, UniformSegmentsGiveTheClassicCount) {
  TessellationOptions options;
  options.segments = 16;
  const Tessellation result = tessellate(teapot(), options);
  // 32 patches of 16 x 16 cells, 2 triangles each, less one triangle per cell at the 8 collapsed
  // edges (16 cells each).
  EXPECT_EQ(result.mesh.triangle_count(), 32u * 16 * 16 * 2 - 8u * 16);
  // Without a tolerance the bound is still computed; it is no looser than the Filip-Magedson-
  // Markot norm bound (M_uu du^2 + 2 M_uv du dv + M_vv dv^2) / 8 from each whole patch's net,
  // computed here on its own (the tessellator's sub-net, directional and cell bounds are tighter).
  // M from the nets' second differences, written out here: n (n - 1) max |P_{i+2,j} - 2 P_{i+1,j}
  // + P_ij|, n m max |P_{i+1,j+1} - P_{i+1,j} - P_{i,j+1} + P_ij|, m (m - 1) max |P_{i,j+2} - ...|.
  double norm_bound = 0.0;
  const double h = 1.0 / 16;
  for (const BezierPatch3& patch : teapot().patches()) {
    const int n = patch.degree_u();
    const int m = patch.degree_v();
    const auto P = [&](int i, int j) { return patch.control_point(i, j); };
    double uu = 0.0, uv = 0.0, vv = 0.0;
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) {
        if (i + 2 <= n) uu = std::max(uu, n * (n - 1) * (P(i + 2, j) - 2 * P(i + 1, j) + P(i, j)).norm());
        if (j + 2 <= m) vv = std::max(vv, m * (m - 1) * (P(i, j + 2) - 2 * P(i, j + 1) + P(i, j)).norm());
        if (i + 1 <= n && j + 1 <= m) uv = std::max(uv, n * m * (P(i + 1, j + 1) - P(i + 1, j) - P(i, j + 1) + P(i, j)).norm());
      }
    }
    norm_bound = std::max(norm_bound, (uu + 2 * uv + vv) * h * h / 8);
  }
  EXPECT_GT(result.error_bound, 0.0);
  expect_render_ready(teapot(), result, norm_bound);
}

TEST(Tessellator, PolesAreOneVertexWithTheExactLimitNormal) {
  TessellationOptions options = relative(1e-3);
  options.uv = UvMode::none;
  const Tessellation result = tessellate(teapot(), options);
  const RenderMesh& mesh = result.mesh;
  // The lid's top (0, 0, 3.15) and the bottom's centre (0, 0, 0).
  for (const auto& [pole, normal] :
       {std::pair{Vec3(0, 0, 3.15), Vec3(0, 0, 1)}, std::pair{Vec3(0, 0, 0), Vec3(0, 0, -1)}}) {
    std::set<std::uint32_t> ids;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      if ((mesh.positions[v] - pole).norm() > 1e-12) continue;
      ids.insert(mesh.position_ids[v]);
      EXPECT_LT((mesh.normals[v] - normal).norm(), 1e-12) << "at " << pole.transpose();
    }
    EXPECT_EQ(ids.size(), 1u) << "at " << pole.transpose();
  }
  // All teapot edges are G1, so without UVs no vertex is split: one vertex per welded point.
  EXPECT_EQ(mesh.vertex_count(), result.welded_vertices);
}

using testing::expect_identical_tessellations;

TEST(Tessellator, OutputDoesNotDependOnTheThreadCount) {
  TessellationOptions options = relative(1e-3);
  options.tangents = true;
  options.threads = 1;
  const Tessellation one = tessellate(teapot(), options);
  options.threads = 2;
  expect_identical_tessellations(one, tessellate(teapot(), options));
}

// Streaming stores (automatic from 64 MiB of output) change how the output is written, not what:
// forced on and off, on uniform grids and on split, stitched patterns, with and without UVs and
// tangents.
TEST(Tessellator, StreamingStoresWriteTheSameOutput) {
  TessellationOptions uniform = uniform_unordered(40);
  TessellationOptions fine = relative(1e-3);
  fine.tangents = true;
  TessellationOptions plain = relative(1e-2);
  plain.uv = UvMode::none;
  for (TessellationOptions* options : {&uniform, &fine, &plain}) {
    options->streaming_stores = false;
    const Tessellation ordinary = tessellate(teapot(), *options);
    options->streaming_stores = true;
    expect_identical_tessellations(tessellate(teapot(), *options), ordinary);
    options->streaming_stores.reset();
    expect_identical_tessellations(tessellate(teapot(), *options), ordinary);
  }
}

// One Tessellation reused through runs that differ in size, mode, attributes and culling (the
// arrays and the scratch keep storage from run to run) gives each run's fresh result exactly.
TEST(Tessellator, ReusedOutputGivesTheFreshResult) {
  TessellationOptions uniform = uniform_unordered(24);
  TessellationOptions fine = relative(1e-3);
  fine.tangents = true;
  fine.uv = UvMode::atlas;
  TessellationOptions culled;
  culled.camera = Camera{Vec3(8, -6, 5), Vec3(0, 0, 1.5), Vec3::UnitZ(), 40.0, 640, 480};
  culled.pixel_tolerance = 2.0;
  culled.back_face_culling = BackFaceCulling::always;  // the teapot is open: asked for
  TessellationOptions coarse = relative(1e-1);
  coarse.uv = UvMode::none;
  Tessellation reused;
  for (const TessellationOptions* options : {&uniform, &fine, &culled, &coarse, &uniform}) {
    tessellate(teapot(), *options, reused);
    expect_identical_tessellations(reused, tessellate(teapot(), *options));
  }
  // The camera run culled patches whose scratch held an earlier run's data.
  tessellate(teapot(), culled, reused);
  EXPECT_GT(reused.culled_patches, 0u);
  validate(reused.mesh);
  // A copy is the same value without the scratch; bad options leave the result as it was.
  const Tessellation copy = reused;
  expect_identical_tessellations(copy, reused);
  TessellationOptions bad;
  bad.segments = 0;
  EXPECT_THROW(tessellate(teapot(), bad, reused), InvalidInput);
  expect_identical_tessellations(copy, reused);
}

// The measured error is the largest |S - L| over ten barycentric samples of every triangle (the
// inner cells' samples evaluated as fine grids). Recomputed here from the output alone: each
// mesh triangle sampled at the same weights, S from its patch at the interpolated UVs (patch
// parameters), L from the vertex positions. On the teapot's patches without a pole (no
// triangle is dropped) the two agree to rounding.
TEST(Tessellator, MeasuredErrorIsTheLargestSampledDistanceOfTheOutput) {
  std::vector<bool> pole(teapot().patches().size(), false);
  for (const EdgeRef& e : teapot().collapsed_edges()) pole[e.patch] = true;
  std::vector<BezierPatch3> patches;
  for (std::size_t p = 0; p < teapot().patches().size(); ++p) {
    if (!pole[p]) patches.push_back(teapot().patches()[p]);
  }
  // And z = f(u) + f(v), f = 24 (u^3 / 6 - u^4 / 12) (Bernstein coefficients 0, 0, 0, 1, 2): f'' =
  // 24 u (1 - u) is largest in the middle and 0 at the ends, so the largest distance is in the
  // inner cells, away from every side.
  const std::array<double, 5> f = {0, 0, 0, 1, 2};
  std::vector<Vec3> bump;
  for (int j = 0; j <= 4; ++j) {
    for (int i = 0; i <= 4; ++i) bump.emplace_back(i / 4.0, j / 4.0, f[i] + f[j]);
  }
  TessellationOptions uniform;
  uniform.segments = 9;
  for (const PatchSet& set : {PatchSet(patches), PatchSet({BezierPatch3(4, 4, bump)})}) {
    for (const TessellationOptions& options : {relative(1e-3), relative(3e-4), uniform}) {
      const Tessellation result = tessellate(set, options);
      const RenderMesh& mesh = result.mesh;
      double reference = 0.0;
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const BezierPatch3& patch = set.patches()[result.triangle_patches[t]];
        for (const auto& w : measure_sample_weights) {
          Vec2 uv = Vec2::Zero();
          Vec3 linear = Vec3::Zero();
          for (int c = 0; c < 3; ++c) {
            uv += w[c] * mesh.uvs[mesh.indices[3 * t + c]];
            linear += w[c] * mesh.positions[mesh.indices[3 * t + c]];
          }
          reference = std::max(reference, (patch.evaluate(uv.x(), uv.y()) - linear).norm());
        }
      }
      EXPECT_GT(reference, 0.0);
      EXPECT_NEAR(result.measured_error, reference, 1e-12 * set.size());
    }
  }
}

TEST(Tessellator, TangentsAreUnitOrthogonalAndRightHanded) {
  TessellationOptions options = relative(1e-2);
  options.tangents = true;
  const Tessellation result = tessellate(teapot(), options);
  const RenderMesh& mesh = result.mesh;
  ASSERT_EQ(mesh.tangents.size(), mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_NEAR(mesh.tangents[v].head<3>().norm(), 1.0, 1e-12);
    EXPECT_NEAR(mesh.tangents[v].head<3>().dot(mesh.normals[v]), 0.0, 1e-9);
    // The teapot's patches are regular away from the poles, where the limit frame is kept
    // right-handed too: w = +1 everywhere.
    EXPECT_EQ(mesh.tangents[v].w(), 1.0);
  }
}

TEST(Tessellator, UvsArePatchParametersOrAnAtlasInTheUnitSquare) {
  for (UvMode mode : {UvMode::patch, UvMode::atlas}) {
    TessellationOptions options = relative(1e-2);
    options.uv = mode;
    const Tessellation result = tessellate(teapot(), options);
    ASSERT_EQ(result.mesh.uvs.size(), result.mesh.vertex_count());
    for (const Vec2& uv : result.mesh.uvs) {
      EXPECT_TRUE(uv.minCoeff() >= 0.0 && uv.maxCoeff() <= 1.0);
    }
  }
  // In the atlas, the patches' cells do not overlap: each triangle's uvs lie in one cell.
  TessellationOptions options = relative(1e-2);
  options.uv = UvMode::atlas;
  const Tessellation result = tessellate(teapot(), options);
  for (std::size_t t = 0; t < result.mesh.triangle_count(); ++t) {
    const std::uint32_t p = result.triangle_patches[t];
    const Vec2 cell_origin((p % 6) / 6.0, (p / 6) / 6.0);
    for (int k = 0; k < 3; ++k) {
      const Vec2 local = (result.mesh.uvs[result.mesh.indices[3 * t + k]] - cell_origin) * 6.0;
      EXPECT_TRUE(local.minCoeff() >= 0.0199 && local.maxCoeff() <= 0.9801) << "triangle " << t;
    }
  }
}

TEST(Tessellator, SplitPatchesSaveTrianglesKeepTheGuaranteeAndSpeakOfThePatches) {
  TessellationOptions options = relative(1e-3);
  options.split_patches = false;
  const Tessellation whole = tessellate(teapot(), options);
  options.split_patches = true;
  const Tessellation split = tessellate(teapot(), options);
  // 8,377 against 10,218 (the directional bound tightens whole patches less than 4 x 4 pieces).
  EXPECT_LT(static_cast<double>(split.mesh.triangle_count()), 0.9 * static_cast<double>(whole.mesh.triangle_count()));
  EXPECT_LE(split.measured_error, split.error_bound);
  EXPECT_LE(split.error_bound, split.tolerance);
  expect_render_ready(teapot(), split, split.tolerance, true);
  // UVs and triangle_patches are the patches' own: each vertex is its triangle's patch at its uv.
  const RenderMesh& mesh = split.mesh;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const BezierPatch3& patch = teapot().patches()[split.triangle_patches[t]];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      ASSERT_LT((patch.evaluate(mesh.uvs[v].x(), mesh.uvs[v].y()) - mesh.positions[v]).norm(), 1e-12)
          << "triangle " << t;
    }
  }
  // The split lines inside a patch split no vertex: vertices of one point differ in an attribute.
  std::map<std::uint32_t, std::vector<std::uint32_t>> vertices_of;
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) vertices_of[mesh.position_ids[v]].push_back(v);
  for (const auto& [id, vertices] : vertices_of) {
    for (std::size_t a = 0; a < vertices.size(); ++a) {
      for (std::size_t b = a + 1; b < vertices.size(); ++b) {
        EXPECT_FALSE(mesh.uvs[vertices[a]] == mesh.uvs[vertices[b]] &&
                     mesh.normals[vertices[a]] == mesh.normals[vertices[b]])
            << "position " << id;
      }
    }
  }
  EXPECT_THROW(split_surface_pieces(teapot(), 3), InvalidInput);
}

TEST(Tessellator, BadOptionsAreRejected) {
  const PatchSet& set = teapot();
  for (double bad : {0.0, -1e-3, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(tessellate(set, relative(bad)), InvalidInput);
    TessellationOptions options;
    options.tolerance = bad;
    EXPECT_THROW(tessellate(set, options), InvalidInput);
  }
  TessellationOptions none;
  EXPECT_THROW(tessellate(set, none), InvalidInput);
  TessellationOptions two = relative(1e-3);
  two.segments = 4;
  EXPECT_THROW(tessellate(set, two), InvalidInput);
  TessellationOptions zero;
  zero.segments = 0;
  EXPECT_THROW(tessellate(set, zero), InvalidInput);
  TessellationOptions too_many = relative(1e-6);
  too_many.max_triangles = 1'000'000;
  try {
    tessellate(set, too_many);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("triangles needed"), std::string::npos) << error.what();
  }
}

// A creased patch set: two flat squares at a right angle share an edge; the normals differ by
// 90 degrees, so the shared points are split for rendering but stay one welded point.
TEST(Tessellator, CreasesSplitVerticesButStayWelded) {
  const BezierPatch3 floor = testing::bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
  const BezierPatch3 wall = testing::bilinear(Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(0, 1, 1), Vec3(1, 1, 1));
  const PatchSet set({floor, wall});
  TessellationOptions options;
  options.segments = 3;
  options.uv = UvMode::none;
  const Tessellation result = tessellate(set, options);
  EXPECT_EQ(result.welded_vertices, 4u * 7);
  EXPECT_EQ(result.mesh.vertex_count(), 4u * 8);
  const TopologyReport report = analyze(welded_faces(result.mesh));
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_TRUE(report.manifold);
}

// PatchSet joins edges whose control points agree within its tolerance; the tessellator then
// gives both patches one side's points, which moves the other side's by the gap. The gap is part
// of the bound: the mesh is within error_bound of each patch's own surface (measured), and the
// gap reported is the exact offset (the second patch's edge row moved by delta). The patterns
// are planned for the tolerance less the gap, so a gap below half the tolerance keeps the bound
// within the tolerance; a larger one shows in it.
TEST(Tessellator, WeldGapIsPartOfTheBound) {
  TessellationOptions options;
  options.tolerance = 1e-5;
  for (const double delta : {2e-6, 2e-4}) {
    // The right patch starts where the left one ends (its u0 edge on the left's u1 edge), moved
    // by delta in z.
    const auto [left, right] = testing::height_fields_side_by_side([delta](int) { return Vec3(0, 0, delta); });
    const PatchSet set({left, right}, 1e-3);
    ASSERT_EQ(set.shared_edges().size(), 1u);
    const Tessellation result = tessellate(set, options);
    EXPECT_NEAR(result.weld_gap, delta, 1e-12);
    EXPECT_GE(result.measured_error, 0.99 * delta);
    EXPECT_LE(result.measured_error, result.error_bound);
    if (delta < 0.5 * *options.tolerance) {
      EXPECT_LE(result.error_bound, *options.tolerance);
    } else {
      EXPECT_GT(result.error_bound, *options.tolerance);
      EXPECT_LE(result.error_bound, 0.5 * *options.tolerance + result.weld_gap);
    }
  }
  // Where the edges agree exactly there is nothing to add.
  const BezierPatch3 left = testing::height_fields_side_by_side([](int) { return Vec3(0, 0, 0); })[0];
  const Tessellation exact = tessellate(PatchSet({left}), options);
  EXPECT_EQ(exact.weld_gap, 0.0);
}

// Back-face culling must not open holes. The teapot is open: seen from above, the inside of the
// body shows through the gap under the lid, and those patches face away from the eye. Ray cast
// (tests/support/ray_cast.h), the culled mesh shows every pixel the whole mesh shows; culling
// every back-facing patch (the old behaviour, now BackFaceCulling::always) loses some.
TEST(Tessellator, BackFaceCullingOpensNoHoleInAnOpenSurface) {
  TessellationOptions options;
  options.camera = Camera{Vec3(0.3, -1.2, 9.0), Vec3(0, 0, 1.5), Vec3::UnitZ(), 40.0, 400, 300};
  options.pixel_tolerance = 0.5;
  options.back_face_culling = BackFaceCulling::never;
  const Tessellation whole = tessellate(teapot(), options);
  EXPECT_EQ(whole.culled_patches, 0u);
  options.back_face_culling = BackFaceCulling::automatic;
  const Tessellation automatic = tessellate(teapot(), options);
  options.back_face_culling = BackFaceCulling::always;
  const Tessellation always = tessellate(teapot(), options);
  ASSERT_GT(always.culled_patches, 0u);
  EXPECT_EQ(automatic.culled_patches, whole.culled_patches);  // the frustum's only: the teapot is open
  const std::vector<double> seen = testing::ray_cast(whole.mesh, *options.camera);
  const std::size_t covered = static_cast<std::size_t>(std::count_if(seen.begin(), seen.end(), [](double z) { return std::isfinite(z); }));
  ASSERT_GT(covered, seen.size() / 20);
  EXPECT_EQ(testing::pixels_lost(seen, testing::ray_cast(automatic.mesh, *options.camera)), 0u);
  const std::size_t lost = testing::pixels_lost(seen, testing::ray_cast(always.mesh, *options.camera));
  EXPECT_GT(lost, covered / 200) << "the view shows back faces through the lid's gap";
  std::cout << "teapot from above: " << covered << " pixels covered, " << lost
            << " lost when every back-facing patch is culled\n";
}

// On a closed, outward-oriented surface seen from outside, back faces are hidden: they are
// culled, and the culled mesh shows every pixel at the same depth as the whole mesh.
TEST(Tessellator, BackFaceCullingOnAClosedSurfaceKeepsTheImage) {
  const PatchSet cube(testing::bulged_cube(std::vector<double>(24, 0.3)));
  TessellationOptions options;
  options.camera = Camera{Vec3(3.0, -4.0, 2.5), Vec3(0, 0, 0), Vec3::UnitZ(), 40.0, 400, 300};
  options.back_face_culling = BackFaceCulling::never;
  const Tessellation whole = tessellate(cube, options);
  options.back_face_culling = BackFaceCulling::automatic;
  const Tessellation culled = tessellate(cube, options);
  EXPECT_EQ(culled.culled_patches, 3u);  // the three faces turned away
  const std::vector<double> seen = testing::ray_cast(whole.mesh, *options.camera);
  const std::vector<double> kept = testing::ray_cast(culled.mesh, *options.camera);
  EXPECT_EQ(testing::pixels_lost(seen, kept), 0u);
  // The same surface where both show it: the meshes differ only where an edge rate followed a
  // culled neighbour, each within its bound of the surface; seen head-on, depth moves by less
  // than twice the two bounds, which only rays grazing the silhouette can exceed.
  const double depth_slack = 2.0 * (whole.error_bound + culled.error_bound);
  std::size_t covered = 0;
  std::size_t farther = 0;
  for (std::size_t k = 0; k < seen.size(); ++k) {
    if (!std::isfinite(seen[k])) continue;
    ++covered;
    if (std::abs(kept[k] - seen[k]) > depth_slack) ++farther;
  }
  EXPECT_LT(farther, covered / 500) << farther << " of " << covered << " pixels at another depth";
  // Only the frustum culls where back faces may show: from inside the box of the control points
  // (the eye may be inside the solid; here it is, and sees only back faces), and on the set
  // turned inside out below.
  const auto back_faces_culled = [&](const PatchSet& set) {
    TessellationOptions never = options;
    never.back_face_culling = BackFaceCulling::never;
    return tessellate(set, options).culled_patches - tessellate(set, never).culled_patches;
  };
  options.camera->eye = Vec3(0.2, 0.1, 0.3);
  options.camera->target = Vec3(1, 0, 0);
  EXPECT_EQ(back_faces_culled(cube), 0u);
  options.back_face_culling = BackFaceCulling::always;
  EXPECT_GT(back_faces_culled(cube), 0u);
  options.back_face_culling = BackFaceCulling::automatic;
  // Turned inside out (each face's u reversed), the set is closed but oriented inward.
  std::vector<BezierPatch3> inward;
  for (const BezierPatch3& face : cube.patches()) {
    std::vector<Vec3> points;
    for (int j = 0; j <= 3; ++j) {
      for (int i = 0; i <= 3; ++i) points.push_back(face.control_point(3 - i, j));
    }
    inward.emplace_back(3, 3, std::move(points));
  }
  options.camera = Camera{Vec3(3.0, -4.0, 2.5), Vec3(0, 0, 0), Vec3::UnitZ(), 40.0, 400, 300};
  EXPECT_EQ(tessellate(PatchSet(inward), options).culled_patches, 0u);
  EXPECT_EQ(back_faces_culled(cube), 3u);
  // Two shells, the outward cube and a smaller inside-out one beside it: the set is closed,
  // consistently oriented and of positive volume as a whole, but only the outward shell bounds a
  // solid. Its far faces are culled; the inside-out shell's are drawn, and the view is kept.
  std::vector<BezierPatch3> two = cube.patches();
  for (const BezierPatch3& face : inward) {
    std::vector<Vec3> points = face.control_points();
    for (Vec3& q : points) q = 0.5 * q + Vec3(0, 4, 0);
    two.emplace_back(3, 3, std::move(points));
  }
  const PatchSet shells(two);
  ASSERT_TRUE(report(shells).closed);
  ASSERT_TRUE(report(shells).consistently_oriented);
  ASSERT_GT(enclosed_volume(shells.patches()), 0.0);
  options.camera = Camera{Vec3(6.0, 1.0, 3.0), Vec3(0, 2, 0), Vec3::UnitZ(), 50.0, 400, 300};
  EXPECT_EQ(back_faces_culled(shells), 3u);
  TessellationOptions never = options;
  never.back_face_culling = BackFaceCulling::never;
  const Tessellation drawn = tessellate(shells, never);
  const std::vector<double> both = testing::ray_cast(drawn.mesh, *options.camera);
  const auto shown = static_cast<std::size_t>(std::count_if(both.begin(), both.end(), [](double z) { return std::isfinite(z); }));
  // Pixels that show nothing, or something farther, once culled. Where a culled face meets a kept
  // one on the silhouette the two meshes are each within the pixel tolerance (half a pixel) of
  // the surface, so a pixel centre there may fall on either side.
  const auto changed = [&](const Tessellation& culled) {
    const std::vector<double> seen = testing::ray_cast(culled.mesh, *options.camera);
    const double slack = 2.0 * (drawn.error_bound + culled.error_bound);
    std::size_t count = 0;
    for (std::size_t k = 0; k < both.size(); ++k) count += std::isfinite(both[k]) && !(seen[k] <= both[k] + slack);
    return count;
  };
  const std::size_t lost = changed(tessellate(shells, options));
  EXPECT_LE(lost, shown / 2000);
  options.back_face_culling = BackFaceCulling::always;
  const std::size_t lost_always = changed(tessellate(shells, options));
  EXPECT_GT(lost_always, shown / 50);
  std::cout << "two shells: " << shown << " pixels covered, " << lost << " changed on the silhouette, " << lost_always
            << " when every back face is culled\n";
}

// T-junctions (a long edge against two or three shorter edges, parts reversed and of higher
// degree) are welded by index: the long edge takes its parts' points end to end, so the mesh is
// one disk with one boundary loop (three components before), at coarse and fine tolerances.
TEST(Tessellator, TJunctionsAreWeldedWatertight) {
  std::vector<BezierPatch3> three = testing::t_junction_pieces(testing::wavy_bicubic(), {0.25, 0.6});
  three[2] = testing::turned_half(three[2]);
  three[3] = elevate_degree(three[3], 2, 0);
  for (const std::vector<BezierPatch3>& patches :
       {testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}), three}) {
    const PatchSet set(patches);
    ASSERT_EQ(set.t_junctions().size(), 1u);
    for (const double tolerance : {3e-2, 1e-3, 1e-4}) {
      TessellationOptions options;
      options.tolerance = tolerance;
      const Tessellation result = tessellate(set, options);
      expect_render_ready(set, result, tolerance);
      const TopologyReport report = analyze(welded_faces(result.mesh));
      EXPECT_EQ(report.components, 1) << "tolerance " << tolerance;
      EXPECT_EQ(report.boundary_loops, 1);
      EXPECT_EQ(report.euler, 1);
      EXPECT_LT(result.weld_gap, 1e-14);
    }
  }
  // A part off the long edge by 2e-10 (inside the set's tolerance of 1e-9 of its size) is still
  // joined; welding moves its points, and the move is in the bound.
  std::vector<BezierPatch3> moved = testing::t_junction_pieces(testing::wavy_bicubic(), {0.3});
  std::vector<Vec3> points = moved[2].control_points();
  for (int i = 0; i <= 3; ++i) points[static_cast<std::size_t>(i)].z() += 2e-10;
  moved[2] = BezierPatch3(3, 3, points);
  const PatchSet near(moved);
  ASSERT_EQ(near.t_junctions().size(), 1u);
  TessellationOptions fine;
  fine.tolerance = 1e-4;
  const Tessellation joined = tessellate(near, fine);
  EXPECT_GT(joined.weld_gap, 1e-10);
  EXPECT_LE(joined.weld_gap, 2e-10 * (1 + 1e-6));
  EXPECT_LE(joined.measured_error, joined.error_bound);
  EXPECT_LE(joined.error_bound, *fine.tolerance);
  EXPECT_EQ(analyze(welded_faces(joined.mesh)).components, 1);
  // A part outside the view is culled; the long edge keeps its piece, and the rest stays welded.
  const PatchSet set(testing::t_junction_pieces(testing::wavy_bicubic(), {0.3}));
  TessellationOptions view;
  view.camera = Camera{Vec3(0.8, 0.4, 1.2), Vec3(0.8, 0.4, 0.0), Vec3::UnitY(), 30.0, 400, 300};
  const Tessellation seen = tessellate(set, view);
  EXPECT_EQ(seen.culled_patches, 1u);
  ASSERT_NO_THROW(validate(seen.mesh));
  EXPECT_LE(seen.measured_error, seen.error_bound);
  const TopologyReport report = analyze(welded_faces(seen.mesh));
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_TRUE(report.manifold);
}

// Random patches and random C0-joined grids of patches, at random tolerances.
RC_GTEST_PROP(Tessellator, RandomPatchSetsAreCrackFreeWithinTolerance, ()) {
  const int degree = *rc::gen::inRange(1, 6);
  const int rows = *rc::gen::inRange(1, 3);
  const int columns = *rc::gen::inRange(1, 3);
  // One global net of (degree*columns + 1) x (degree*rows + 1) points over a wavy height field,
  // cut into patches that share their boundary rows: C0 joins.
  const int width = degree * columns + 1;
  const int height = degree * rows + 1;
  std::vector<Vec3> net;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      net.emplace_back(i + *testing::coordinate(-0.3, 0.3), j + *testing::coordinate(-0.3, 0.3),
                       *testing::coordinate(-2, 2));
    }
  }
  std::vector<BezierPatch3> patches;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      std::vector<Vec3> points;
      for (int j = 0; j <= degree; ++j) {
        for (int i = 0; i <= degree; ++i) points.push_back(net[(c * degree + i) + width * (r * degree + j)]);
      }
      patches.emplace_back(degree, degree, std::move(points));
    }
  }
  const PatchSet set(std::move(patches));
  const double r = *rc::gen::element(3e-2, 1e-2, 3e-3);
  const Tessellation result = tessellate(set, relative(r));
  RC_ASSERT(result.error_bound <= result.tolerance);
  RC_ASSERT(result.measured_error <= result.error_bound * (1 + 1e-9) + 1e-12 * set.size());
  const TopologyReport report = analyze(welded_faces(result.mesh));
  RC_ASSERT(report.manifold);
  RC_ASSERT(report.components == 1);
  RC_ASSERT(report.boundary_loops == 1);
  RC_ASSERT(report.euler == 1);
}

}  // namespace
}  // namespace patchwork
