// Rational patches in a PatchSet and through the tessellator: adjacency with weights, the
// guarantee against the exact quadrics (distance to the implicit form), closed meshes, exact
// normals at the poles.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/errors.h"
#include "meshes/topology.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/patch_grid.h"
#include "surfaces/patch_set.h"
#include "surfaces/rational_bounds.h"
#include "surfaces/surface_normal.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/rational_shapes.h"

namespace patchwork {
namespace {

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

class RationalTessellation : public ::testing::TestWithParam<double> {};

TEST_P(RationalTessellation, SphereIsClosedAndWithinTheTolerance) {
  const double tolerance = GetParam();
  const PatchSet set(testing::as_any(testing::unit_sphere_octants()));
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
  const PatchSet set(testing::as_any(testing::torus_patches(R, r)));
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
  const PatchSet set(testing::as_any(testing::unit_sphere_octants()));
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

// Strongly uneven weights (a middle weight 8 pulls the surface towards its control point, and
// F_uu is far from the net's): the pieces carry the rational quotient-rule bounds, and the
// measured error stays within the bound.
TEST(RationalTessellation, UnevenWeightsKeepTheGuarantee) {
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= 2; ++i) {
      points.emplace_back(i, j, (i == 1 && j == 1) ? 2.0 : 0.25 * i * j);
      weights.push_back((i == 1 ? 8.0 : 1.0) * (j == 1 ? 0.5 : 1.0));
    }
  }
  const RationalBezierPatch patch(2, 2, points, weights);
  const PatchSet set(std::vector<AnyBezierPatch>{patch});
  const SurfacePieces pieces = surface_pieces(set);
  const SecondDerivativeBounds expected = second_derivative_bounds(patch, 4);
  ASSERT_EQ(pieces.bounds.size(), 1u);
  EXPECT_EQ(pieces.bounds[0].uu, expected.uu);
  EXPECT_EQ(pieces.bounds[0].uv, expected.uv);
  EXPECT_EQ(pieces.bounds[0].vv, expected.vv);
  for (const double tolerance : {1e-2, 1e-3}) {
    TessellationOptions options;
    options.tolerance = tolerance;
    const Tessellation result = tessellate(set, options);
    EXPECT_LE(result.error_bound, tolerance);
    EXPECT_LE(result.measured_error, result.error_bound);
  }
}

// Split pieces (k = 2, 4) of rational patches: joined across the split lines and the octants'
// edges, closed, within the bound.
TEST(RationalTessellation, SplitPiecesOfTheSphereStayClosed) {
  const PatchSet set(testing::as_any(testing::unit_sphere_octants()));
  for (const int k : {2, 4}) {
    TessellationOptions options;
    options.tolerance = 1e-3;
    const Tessellation result = tessellate(split_surface_pieces(set, k), options);
    EXPECT_LE(result.measured_error, result.error_bound) << k;
    double worst = 0.0;
    for (const Vec3& p : result.mesh.positions) worst = std::max(worst, std::abs(p.norm() - 1.0));
    EXPECT_LT(worst, 1e-15) << k;
    const TopologyReport topology = analyze(welded_faces(result.mesh));
    EXPECT_TRUE(topology.closed) << k;
    EXPECT_EQ(topology.euler, 2) << k;
  }
}

// A closed shell of rational and polynomial patches, 1000 units wide and far from the origin:
// the camera mode finds it a solid (the rational patches' volume by quadrature to a tolerance
// relative to the set) and culls the polynomial sides that face away; rational ones are kept.
TEST(RationalTessellation, MixedSolidFarFromTheOriginIsCulledByItsPolynomialSides) {
  const Vec3 offset(5000, -3000, 2000);
  const PatchSet set(testing::wedge(1000.0, 400.0, offset));
  const PatchSetReport r = report(set);
  EXPECT_EQ(r.rational_patches, 3u);
  ASSERT_TRUE(r.closed);
  ASSERT_TRUE(r.consistently_oriented);
  TessellationOptions options;
  options.camera = Camera{offset + Vec3(3000, 3000, 1500), offset + Vec3(300, 300, 200), Vec3::UnitZ(), 45.0, 800, 600};
  options.pixel_tolerance = 0.5;
  const Tessellation seen = tessellate(set, options);
  // The sides x = 0 and y = 0 face away from an eye at x, y > 0.
  EXPECT_EQ(seen.culled_patches, 2u);
  EXPECT_LE(seen.measured_error, seen.error_bound);
  TessellationOptions everything = options;
  everything.back_face_culling = BackFaceCulling::never;
  EXPECT_EQ(tessellate(set, everything).culled_patches, 0u);
}

// The rational grid evaluation against the pointwise functions, the poles included.
TEST(RationalTessellation, GridEvaluationMatchesPointwiseEvaluation) {
  const RationalBezierPatch octant = sphere_octant(Vec3(1, 2, 3), 2.0);
  const std::vector<double> us = {0.0, 0.25, 0.5, 1.0}, vs = {0.0, 0.3, 0.9, 1.0};
  const std::size_t count = us.size() * vs.size();
  std::vector<Vec3> points(count), normals(count);
  std::vector<Vec4> tangents(count);
  evaluate_grid(octant, PatchGridWeights(2, 2, us, vs), {points, normals, tangents});
  for (std::size_t b = 0; b < vs.size(); ++b) {
    for (std::size_t a = 0; a < us.size(); ++a) {
      const std::size_t k = a + us.size() * b;
      EXPECT_LT((points[k] - octant.evaluate(us[a], vs[b])).norm(), 1e-14);
      const Vec3 normal = unit_normal(octant, us[a], vs[b]);
      EXPECT_LT((normals[k] - normal).norm(), 1e-12) << us[a] << " " << vs[b];
      // On the sphere the normal is the radial direction, at the pole (v = 1) too.
      EXPECT_LT((normals[k] - (points[k] - Vec3(1, 2, 3)).normalized()).norm(), 1e-12);
      const Vec4 tangent = unit_tangent(octant, us[a], vs[b], normal);
      EXPECT_LT((tangents[k] - tangent).norm(), 1e-9) << us[a] << " " << vs[b];
      EXPECT_LT(std::abs(tangents[k].head<3>().dot(normals[k])), 1e-12);
    }
  }
}

// The NURBS shapes (surfaces/nurbs_shapes.h) through extraction and the tessellator: closed
// where they should be, every vertex, edge midpoint and centroid within the bound of the
// implicit surface, exact normals (the sphere's and cone's collapsed rows included).
TEST(NurbsTessellation, ShapesAreWatertightAndWithinTheTolerance) {
  struct Shape {
    const char* name;
    NurbsSurface surface;
    std::function<double(const Vec3&)> distance;
    std::function<Vec3(const Vec3&)> normal;
    int euler;
    int boundary_loops;
  };
  const double R = 2.0, r = 0.5, h = 1.5;
  const double slant = std::atan2(1.0, h);  // the cone of radius 1 and height h
  const std::vector<Shape> shapes = {
      {"sphere", nurbs_sphere(Vec3::Zero(), 1.0), [](const Vec3& p) { return std::abs(p.norm() - 1.0); },
       [](const Vec3& p) { return p.normalized(); }, 2, 0},
      {"torus", nurbs_torus(Vec3::Zero(), R, r), [&](const Vec3& p) { return testing::torus_distance(p, R, r); },
       [&](const Vec3& p) { return testing::torus_normal(p, R); }, 0, 0},
      {"cylinder", nurbs_cylinder(Vec3::Zero(), 1.0, h),
       [](const Vec3& p) { return std::abs(std::hypot(p.x(), p.y()) - 1.0); },
       [](const Vec3& p) { return Vec3(p.x(), p.y(), 0).normalized(); }, 0, 2},
      {"cone", nurbs_cone(Vec3::Zero(), 1.0, h),
       [&](const Vec3& p) { return std::abs((std::hypot(p.x(), p.y()) - (1.0 - p.z() / h)) * std::cos(slant)); },
       [&](const Vec3& p) {
         const double rho = std::hypot(p.x(), p.y());
         // The apex has no one normal (each quarter's limit normal differs); it is skipped.
         return rho < 1e-12 ? Vec3(Vec3::Zero()) : Vec3(Vec3(h * p.x() / rho, h * p.y() / rho, 1.0).normalized());
       },
       1, 1},
  };
  for (const Shape& shape : shapes) {
    SCOPED_TRACE(shape.name);
    const PatchSet set(bezier_patches(shape.surface).patches);
    TessellationOptions options;
    options.tolerance = 1e-3;
    const Tessellation result = tessellate(set, options);
    EXPECT_LE(result.error_bound, 1e-3);
    EXPECT_LE(result.measured_error, result.error_bound);
    double worst = 0.0, worst_angle = 0.0;
    const RenderMesh& mesh = result.mesh;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const Vec3 n = shape.normal(mesh.positions[v]);
      if (n == Vec3::Zero()) continue;
      worst_angle = std::max(worst_angle, std::atan2(n.cross(mesh.normals[v]).norm(), n.dot(mesh.normals[v])));
    }
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const Vec3& a = mesh.positions[mesh.indices[3 * t]];
      const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
      const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
      for (const Vec3& p : {a, Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2), Vec3((a + b + c) / 3)}) {
        worst = std::max(worst, shape.distance(p));
      }
    }
    EXPECT_LE(worst, result.error_bound);
    EXPECT_LT(worst_angle, 1e-7);
    const TopologyReport topology = analyze(welded_faces(mesh));
    EXPECT_TRUE(topology.manifold);
    EXPECT_EQ(topology.components, 1);
    EXPECT_EQ(topology.euler, shape.euler);
    EXPECT_EQ(topology.boundary_loops, shape.boundary_loops);
  }
}

}  // namespace
}  // namespace patchwork
