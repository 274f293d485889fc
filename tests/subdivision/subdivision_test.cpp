// Subdivision through OpenSubdiv: counts by closed forms, topology kept at every level, limit
// points against the uniform bicubic B-spline written out here, Bezier export against
// OpenSubdiv's own evaluation, sharp creases, Loop towards the sphere, exact primvars, errors,
// and the limit surface tessellated like a patch set.

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <set>

#include "core/errors.h"
#include "meshes/render_mesh.h"
#include "meshes/topology.h"
#include "subdivision/limit_surface.h"
#include "subdivision/limit_tessellator.h"
#include "subdivision/refine.h"
#include "tests/meshes/face_lists.h"
#include "tests/support/ray_cast.h"
#include "tests/meshes/mesh_generators.h"
#include "tests/surfaces/measured_error_reference.h"

namespace patchwork {
namespace {

using testing::error_message;
using testing::FaceList;
using testing::make_mesh;

// The unit cube with outward faces.
FaceVertexMesh cube() {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const FaceList faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return make_mesh(points, faces);
}

SubdivisionCage cage_of(FaceVertexMesh mesh, SubdivisionScheme scheme = SubdivisionScheme::catmull_clark) {
  SubdivisionCage cage;
  cage.mesh = std::move(mesh);
  cage.options.scheme = scheme;
  return cage;
}

// A rows x cols grid of vertices (i, j) on a torus, perturbed, glued in both directions; face
// (i, j) has corners (i, j), (i+1, j), (i+1, j+1), (i, j+1), so u runs along i and v along j.
struct TorusGrid {
  int rows;
  int cols;
  std::vector<Vec3> points;
  const Vec3& at(int i, int j) const { return points[static_cast<std::size_t>(((i % rows + rows) % rows) * cols + (j % cols + cols) % cols)]; }
  FaceVertexMesh mesh() const {
    FaceList faces;
    const auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % rows) * cols + j % cols); };
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < cols; ++j) faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
    return make_mesh(points, faces);
  }
};

TorusGrid torus_grid(int rows, int cols, testing::Random& random) {
  TorusGrid grid{rows, cols, {}};
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double a = 2 * std::numbers::pi * i / rows;
      const double b = 2 * std::numbers::pi * j / cols;
      const double r = 1.0 + random.uniform(-0.1, 0.1);
      grid.points.emplace_back((3 + r * std::cos(b)) * std::cos(a), (3 + r * std::cos(b)) * std::sin(a),
                               r * std::sin(b) + random.uniform(-0.1, 0.1));
    }
  }
  return grid;
}

// The uniform cubic B-spline basis on [0, 1].
std::array<double, 4> bspline_basis(double t) {
  const double s = 1 - t;
  return {s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6,
          t * t * t / 6};
}

Vec3 bspline_point(const TorusGrid& grid, int i, int j, double u, double v) {
  const auto bu = bspline_basis(u);
  const auto bv = bspline_basis(v);
  Vec3 point = Vec3::Zero();
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) point += bu[a] * bv[b] * grid.at(i - 1 + a, j - 1 + b);
  }
  return point;
}

// ---------------------------------------------------------------------------------------------
// counts

struct Counts {
  Count v, e, f;
};

// One level by the closed forms: the quad schemes make a vertex per face, edge and vertex and a
// quad per face corner; Loop a vertex per vertex and edge and four triangles per triangle.
Counts next_level(Counts c, Count corners, SubdivisionScheme scheme) {
  if (scheme == SubdivisionScheme::loop) return {c.v + c.e, 2 * c.e + 3 * c.f, 4 * c.f};
  return {c.v + c.e + c.f, 2 * c.e + corners, corners};
}

TEST(Subdivision, CountsFollowTheClosedForms) {
  // A mesh of triangles, quads and a pentagon (an open box with a pentagon lid split off).
  const std::vector<Vec3> points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, -1, 0}, {3, 1, 0}, {1, 3, 0.5}};
  const FaceList faces = {{0, 4, 1, 2, 3}, {1, 4, 5}, {1, 5, 2}, {2, 5, 6}, {3, 2, 6}};
  const FaceVertexMesh mixed = make_mesh(points, faces);
  for (auto scheme : {SubdivisionScheme::catmull_clark, SubdivisionScheme::bilinear}) {
    const TopologyReport base = analyze(mixed);
    Counts c{base.vertices, base.edges, base.faces};
    Count corners = static_cast<Count>(mixed.face_indices().size());
    for (int level = 1; level <= 3; ++level) {
      c = next_level(c, corners, scheme);
      corners = 4 * c.f;  // all quads from level 1 on
      const UniformRefinement refined = refine_uniform(cage_of(mixed, scheme), level);
      EXPECT_EQ(refined.topology.vertices, c.v) << scheme_name(scheme) << " level " << level;
      EXPECT_EQ(refined.topology.edges, c.e) << level;
      EXPECT_EQ(refined.topology.faces, c.f) << level;
      EXPECT_EQ(refined.topology.faces, refined_face_count(mixed, scheme, level));
    }
  }
  // A quad mesh's faces grow by 4^k; a triangle mesh under Loop likewise.
  for (int level = 0; level <= 4; ++level) {
    EXPECT_EQ(refine_uniform(cage_of(cube()), level).topology.faces, 6 * (Count{1} << (2 * level)));
    const UniformRefinement loop = refine_uniform(cage_of(testing::tetrahedron(), SubdivisionScheme::loop), level);
    Counts c{4, 6, 4};
    for (int k = 0; k < level; ++k) c = next_level(c, 0, SubdivisionScheme::loop);
    EXPECT_EQ(loop.topology.vertices, c.v);
    EXPECT_EQ(loop.topology.edges, c.e);
    EXPECT_EQ(loop.topology.faces, c.f);
  }
}

RC_GTEST_PROP(Subdivision, TopologyIsKeptAtEveryLevel, ()) {
  testing::Random random(*rc::gen::arbitrary<std::uint64_t>());
  testing::KnownSurface surface = testing::orientable_surface(random, 2);
  if (random.coin()) {
    // Components of two kinds (the per-component counts follow each one's own closed form).
    const testing::KnownSurface other = testing::orientable_surface(random, 1);
    if ((other.mesh.face_sizes()[0] == 3) == (surface.mesh.face_sizes()[0] == 3)) {
      surface = testing::disjoint_union(surface, other);
    }
  }
  const bool triangles = surface.mesh.face_sizes()[0] == 3;
  const auto scheme = triangles && random.coin() ? SubdivisionScheme::loop
                                                 : (random.coin() ? SubdivisionScheme::catmull_clark
                                                                  : SubdivisionScheme::bilinear);
  const int levels = random.coin() ? 2 : 1;
  const UniformRefinement refined = refine_uniform(cage_of(surface.mesh, scheme), levels);
  const TopologyReport& report = refined.topology;
  RC_ASSERT(report.euler == surface.euler);
  RC_ASSERT(report.boundary_loops == surface.boundary_loops);
  RC_ASSERT(report.components == surface.components);
  RC_ASSERT(report.orientable);
  RC_ASSERT(report.manifold);
  RC_ASSERT(report.genus == surface.genus);
  RC_ASSERT(report.faces == refined_face_count(surface.mesh, scheme, levels));
  // The report (from the cage's by the closed forms) is the refined mesh's, element for element.
  RC_ASSERT(to_json(report) == to_json(analyze(refined.cage.mesh)));
}

// Non-orientable cages (Moebius band, Klein bottle, projective plane, hemi-cube) refine
// uniformly: OpenSubdiv takes an edge walked the same way by its two faces as a non-manifold
// seam. The surface keeps its chi and boundary and stays non-orientable; its limit surface is
// refused.
RC_GTEST_PROP(Subdivision, NonOrientableCagesRefineUniformly, ()) {
  testing::Random random(*rc::gen::arbitrary<std::uint64_t>());
  const testing::KnownSurface surface = testing::non_orientable_surface(random);
  const bool triangles = surface.mesh.face_sizes()[0] == 3;
  const auto scheme = triangles && random.coin()
                          ? SubdivisionScheme::loop
                          : (random.coin() ? SubdivisionScheme::catmull_clark : SubdivisionScheme::bilinear);
  const int levels = 1 + static_cast<int>(random.below(3));
  const UniformRefinement refined = refine_uniform(cage_of(surface.mesh, scheme), levels);
  const TopologyReport& report = refined.topology;
  RC_ASSERT(report.euler == surface.euler);
  RC_ASSERT(report.boundary_loops == surface.boundary_loops);
  RC_ASSERT(report.components == surface.components);
  RC_ASSERT(!report.orientable);
  RC_ASSERT(report.manifold);
  RC_ASSERT(!report.genus.has_value());
  RC_ASSERT(report.faces == refined_face_count(surface.mesh, scheme, levels));
  RC_ASSERT(to_json(report) == to_json(analyze(refined.cage.mesh)));
  RC_ASSERT(refined.cage.mesh.positions().allFinite());
  const std::string message = error_message<TopologyError>([&] { LimitSurface limit(cage_of(surface.mesh, scheme)); });
  RC_ASSERT(message.find("LimitSurface: the cage is not orientable") != std::string::npos);
  RC_ASSERT(!error_message<TopologyError>([&] { limit_at_vertices(cage_of(surface.mesh, scheme)); }).empty());
}

// The bilinear scheme's new points are exact: the old vertices, the edges' midpoints and the
// faces' centroids (of its corners), as a multiset, whatever the winding.
std::vector<Vec3> bilinear_points(const FaceVertexMesh& mesh) {
  std::vector<Vec3> points = testing::points_of(mesh);
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    Vec3 centroid = Vec3::Zero();
    for (std::size_t k = 0; k < face.size(); ++k) {
      centroid += mesh.position(face[k]);
      const std::uint32_t a = face[k], b = face[(k + 1) % face.size()];
      if (edges.insert({std::min(a, b), std::max(a, b)}).second) {
        points.push_back((mesh.position(a) + mesh.position(b)) / 2);
      }
    }
    points.push_back(centroid / static_cast<double>(face.size()));
  }
  return points;
}

// The distance from p to the nearest of `points` (brute force).
double nearest_distance(const Vec3& p, const std::vector<Vec3>& points) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Vec3& q : points) nearest = std::min(nearest, (p - q).norm());
  return nearest;
}

// The largest distance from a point of `a` to the nearest of `b`, and back.
double hausdorff_of_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  const auto one_way = [](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
    double worst = 0;
    for (const Vec3& p : from) worst = std::max(worst, nearest_distance(p, to));
    return worst;
  };
  return std::max(one_way(a, b), one_way(b, a));
}

TEST(Subdivision, BilinearRefinementOfNonOrientableCagesIsExact) {
  for (const testing::KnownSurface& surface : {testing::mobius_band(3, 8), testing::klein_bottle(4, 6)}) {
    SubdivisionCage cage = cage_of(surface.mesh, SubdivisionScheme::bilinear);
    for (int level = 1; level <= 2; ++level) {
      const UniformRefinement next = refine_uniform(cage, 1);
      const std::vector<Vec3> expected = bilinear_points(cage.mesh);
      ASSERT_EQ(next.cage.mesh.vertex_count(), expected.size()) << surface.name << " level " << level;
      EXPECT_LE(hausdorff_of_points(testing::points_of(next.cage.mesh), expected), 1e-15) << surface.name;
      cage = next.cage;
    }
    const UniformRefinement two = refine_uniform(cage_of(surface.mesh, SubdivisionScheme::bilinear), 2);
    EXPECT_EQ(two.topology.faces, 16 * static_cast<Count>(surface.mesh.face_count())) << surface.name;
    EXPECT_EQ(two.topology.euler, surface.euler) << surface.name;
    EXPECT_EQ(two.topology.boundary_loops, surface.boundary_loops) << surface.name;
    EXPECT_FALSE(two.topology.orientable) << surface.name;
    EXPECT_LE(hausdorff_of_points(testing::points_of(two.cage.mesh), testing::points_of(cage.mesh)), 1e-15);
  }
}

// Catmull-Clark on a non-orientable cage is, away from its seam, Catmull-Clark on the orientable
// cage cut open along the seam (a strip for the Moebius band, a cylinder for the Klein bottle):
// each new point depends on the cage within two columns of it at level 2. On the seam,
// OpenSubdiv's non-manifold edges are infinitely sharp: their edge points are their midpoints.
TEST(Subdivision, CatmullClarkOnNonOrientableCagesAwayFromTheSeamIsTheCutOpenCages) {
  constexpr int cols = 16;
  struct Case {
    testing::KnownSurface surface;
    FaceVertexMesh cut_open;
    // Whether a point is at least 5 columns from the seam (column 0 = column cols).
    std::function<bool(const Vec3&)> far_from_seam;
  };
  const auto moebius = [](int i, int j) { return testing::mobius_point(3, cols, i, j); };
  const auto klein = [](int i, int j) { return Vec3(j, i, 0.25 * i * j); };
  const auto angle_column = [](const Vec3& p) {
    const double phi = std::atan2(p.y(), p.x());
    return (phi < 0 ? phi + 2 * std::numbers::pi : phi) * cols / (2 * std::numbers::pi);
  };
  const std::vector<Case> cases = {
      {testing::mobius_band(3, cols),
       testing::glued_grid(3, cols, testing::Gluing::none, testing::Gluing::none, moebius),
       [&](const Vec3& p) { return angle_column(p) >= 5 && angle_column(p) <= cols - 5; }},
      {testing::klein_bottle(4, cols),
       testing::glued_grid(4, cols, testing::Gluing::none, testing::Gluing::straight, klein),
       [](const Vec3& p) { return p.x() >= 5 && p.x() <= cols - 5; }},
  };
  for (const Case& c : cases) {
    ASSERT_TRUE(analyze(c.cut_open).orientable) << c.surface.name;
    const UniformRefinement seamed = refine_uniform(cage_of(c.surface.mesh), 2);
    const UniformRefinement cut = refine_uniform(cage_of(c.cut_open), 2);
    EXPECT_EQ(seamed.topology.faces, 16 * static_cast<Count>(c.surface.mesh.face_count()));
    EXPECT_EQ(seamed.topology.euler, c.surface.euler);
    EXPECT_FALSE(seamed.topology.orientable);
    std::vector<Vec3> far;
    for (const Vec3& p : testing::points_of(cut.cage.mesh)) {
      if (c.far_from_seam(p)) far.push_back(p);
    }
    // About 6 of 16 columns of the level-2 points.
    ASSERT_GE(far.size(), cut.cage.mesh.vertex_count() / 4) << c.surface.name;
    const std::vector<Vec3> all = testing::points_of(seamed.cage.mesh);
    for (const Vec3& p : far)
      EXPECT_LE(nearest_distance(p, all), 1e-12) << c.surface.name << ": (" << p.transpose() << ")";
  }
  // The seam: every edge both faces walk the same way has its midpoint as its level-1 edge point.
  const FaceVertexMesh band = testing::mobius_band(3, cols).mesh;
  const std::vector<Vec3> level1 = testing::points_of(refine_uniform(cage_of(band), 1).cage.mesh);
  int seam_edges = 0;
  for (std::size_t f = 0; f < band.face_count(); ++f) {
    for (std::size_t g = f + 1; g < band.face_count(); ++g) {
      const auto a = band.face(f), b = band.face(g);
      for (std::size_t k = 0; k < 4; ++k) {
        for (std::size_t l = 0; l < 4; ++l) {
          if (a[k] == b[l] && a[(k + 1) % 4] == b[(l + 1) % 4]) {
            ++seam_edges;
            const Vec3 midpoint = (band.position(a[k]) + band.position(a[(k + 1) % 4])) / 2;
            EXPECT_LE(nearest_distance(midpoint, level1), 1e-15);
          }
        }
      }
    }
  }
  EXPECT_EQ(seam_edges, 3);
}

// ---------------------------------------------------------------------------------------------
// the limit surface

TEST(LimitSurface, RegularGridIsTheUniformBicubicBSpline) {
  testing::Random random(7);
  const TorusGrid grid = torus_grid(6, 7, random);
  const SubdivisionCage cage = cage_of(grid.mesh());
  const LimitSurface surface(cage);
  double worst = 0.0;
  for (int i = 0; i < grid.rows; ++i) {
    for (int j = 0; j < grid.cols; ++j) {
      const std::size_t f = static_cast<std::size_t>(i * grid.cols + j);
      for (int k = 0; k < 5; ++k) {
        const double u = random.uniform(0, 1);
        const double v = random.uniform(0, 1);
        worst = std::max(worst, (surface.evaluate(f, u, v).position - bspline_point(grid, i, j, u, v)).norm());
      }
    }
  }
  EXPECT_LT(worst, 1e-12);
  // Limit points at the vertices: the tensor mask (1 4 1)/6 x (1 4 1)/6.
  const VertexLimits limits = limit_at_vertices(cage);
  for (int i = 0; i < grid.rows; ++i) {
    for (int j = 0; j < grid.cols; ++j) {
      const Vec3 expected = bspline_point(grid, i, j, 0.0, 0.0);
      EXPECT_LT((limits.positions[static_cast<std::size_t>(i * grid.cols + j)] - expected).norm(), 1e-12);
      // The normal is du x dv there, as at the face's corner.
      const LimitPoint corner = surface.evaluate(static_cast<std::size_t>(i * grid.cols + j), 0, 0);
      EXPECT_GT(limits.normals[static_cast<std::size_t>(i * grid.cols + j)].dot(corner.normal), 1 - 1e-9);
    }
  }
}

// The derivatives OpenSubdiv returns are those of the position (central differences).
TEST(LimitSurface, DerivativesMatchDifferences) {
  SubdivisionCage cage = cage_of(cube());
  const LimitSurface surface(cage);
  const double h = 1e-6;
  for (std::size_t f = 0; f < 6; ++f) {
    const LimitPoint p = surface.evaluate(f, 0.3, 0.6);
    const Vec3 du = (surface.position(f, 0.3 + h, 0.6) - surface.position(f, 0.3 - h, 0.6)) / (2 * h);
    const Vec3 dv = (surface.position(f, 0.3, 0.6 + h) - surface.position(f, 0.3, 0.6 - h)) / (2 * h);
    EXPECT_LT((p.du - du).norm(), 1e-7);
    EXPECT_LT((p.dv - dv).norm(), 1e-7);
    // Outward on the cube.
    EXPECT_GT(p.normal.dot(p.position - Vec3(0.5, 0.5, 0.5)), 0.0);
  }
}

// Bezier patches from B-splines (phantom rows at boundaries, end caps at extraordinary
// vertices) evaluate where OpenSubdiv evaluates, on a mesh with every kind of patch.
TEST(LimitSurface, BezierPatchesEvaluateLikeThePatchTable) {
  // An open box (5 faces: boundary, corners, extraordinary vertices of valence 3) with a crease
  // and a semi-sharp corner, and a pentagon and triangle elsewhere.
  FaceVertexMesh box = cube();
  FaceList faces = testing::faces_of(box);
  faces.erase(faces.begin() + 1);  // the top is open
  SubdivisionCage cage = cage_of(make_mesh(testing::points_of(box), faces));
  cage.creases.push_back({0, 1, 2.5});
  cage.corners.push_back({2, 1.0});
  const LimitSurface surface(cage, 3);
  const std::vector<BezierPatch3> patches = surface.bezier_patches();
  const std::vector<std::uint32_t> faces_of_patches = surface.patch_faces();
  ASSERT_EQ(patches.size(), surface.patch_count());
  // Each patch covers a dyadic square of its face; find it from the corners' evaluation.
  testing::Random random(3);
  double worst = 0.0;
  std::size_t checked = 0;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const std::size_t f = faces_of_patches[p];
    // Sample the face, keep the points whose patch is p: the Bezier point at the local
    // parameters must equal the face's point. The local square is found by search over depths.
    for (int depth = 0; depth <= 3; ++depth) {
      const int n = 1 << depth;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          const double u = (a + 0.5) / n;
          const double v = (b + 0.5) / n;
          if ((patches[p].evaluate(0.5, 0.5) - surface.position(f, u, v)).norm() > 1e-9) continue;
          for (int k = 0; k < 4; ++k) {
            const double s = random.uniform(0, 1);
            const double t = random.uniform(0, 1);
            worst = std::max(worst, (patches[p].evaluate(s, t) - surface.position(f, (a + s) / n, (b + t) / n)).norm());
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_GE(checked, patches.size());
  EXPECT_LT(worst, 1e-12);
}

// Where every patch is regular, the Bezier patches join as the B-splines do: C^2, and closed.
TEST(LimitSurface, RegularPatchesJoinC2AsAPatchSet) {
  testing::Random random(11);
  const TorusGrid grid = torus_grid(5, 6, random);
  const LimitSurface surface(cage_of(grid.mesh()));
  const PatchSetReport r = report(to_patch_set(surface));
  EXPECT_EQ(r.patches, 30u);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_EQ(r.shared_edges, 60u);
  EXPECT_EQ(r.min_ck, 2);
}

// Feature-adaptive refinement: a face whose four corners are regular stays one patch; each of the
// cube's faces has four valence-3 corners, so every level keeps 3 regular children of each of the
// 4 irregular ones (12 patches) and the last level adds the 4 end caps: 12 (L - 1) + 4 per face,
// none at depth 0 or 1.
TEST(LimitSurface, AdaptiveRefinementIsolatesOnlyTheExtraordinaryVertices) {
  for (int level = 2; level <= 5; ++level) {
    const LimitSurface surface(cage_of(cube()), level);
    std::vector<std::size_t> expected(static_cast<std::size_t>(level) + 1, 6 * 12);
    expected[0] = expected[1] = 0;
    expected.back() += 6 * 4;
    EXPECT_EQ(surface.patches_per_depth(), expected) << "level " << level;
    EXPECT_EQ(surface.patch_count(), static_cast<std::size_t>(6 * (12 * (level - 1) + 4)));
  }
  testing::Random random(2);
  const LimitSurface regular(cage_of(torus_grid(4, 5, random).mesh()), 6);
  EXPECT_EQ(regular.patches_per_depth(), std::vector<std::size_t>{20});
  // An infinitely sharp crease is a boundary of regular patches, not a feature to isolate.
  SubdivisionCage creased = cage_of(torus_grid(4, 5, random).mesh());
  creased.creases.push_back({0, 1, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(LimitSurface(creased, 6).patches_per_depth().size(), 7u);  // its ends are irregular
}

// End caps approximate the limit near extraordinary vertices: deeper isolation moves the surface
// less and less (about 2.4x per level at the cube's valence-3 corners); a regular torus has no
// end cap and does not move at all.
// The adaptive patches of the cube meet at T-junctions (a regular patch of depth d beside two
// of depth d + 1): as a PatchSet every such edge is found tiled by its neighbours', so the set is
// closed and consistently oriented, and its tessellation is one welded sphere (chi = 2).
TEST(LimitSurface, AdaptivePatchesJoinAtTJunctionsIntoAClosedPatchSet) {
  const PatchSet set = to_patch_set(LimitSurface(cage_of(cube()), 3));
  const PatchSetReport r = report(set);
  // Per face 12 (L - 1) + 4 = 28 patches at L = 3. In each corner quarter of a face, the
  // irregular depth-2 patch is split into four of depth 3, and its two regular depth-2
  // neighbours each meet two of them along one edge: 2 T-junctions a corner, 6 x 4 x 2 = 48.
  EXPECT_EQ(r.patches, 168u);
  EXPECT_EQ(r.t_junctions, 48u);
  EXPECT_TRUE(r.closed) << r.open_edges << " open edges";
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_EQ(r.touching_points, 0u);
  TessellationOptions options;
  options.relative_tolerance = 1e-3;
  const Tessellation result = tessellate(set, options);
  const TopologyReport topology = analyze(welded_faces(result.mesh));
  EXPECT_EQ(topology.components, 1);
  EXPECT_EQ(topology.boundary_loops, 0);
  EXPECT_EQ(topology.euler, 2);
  EXPECT_TRUE(topology.manifold);
  EXPECT_LE(result.measured_error, result.error_bound);
  EXPECT_LE(result.error_bound, result.tolerance);
  std::cout << r.patches << " patches, " << r.t_junctions << " T-junctions, " << result.mesh.triangle_count()
            << " triangles, weld gap " << result.weld_gap << "\n";
  // A closed, outward surface whose silhouette runs through patch interiors: from outside,
  // automatic back-face culling leaves out the far patches and changes only pixels on the
  // silhouette, where the culled and the kept meshes are each within half a pixel of the surface.
  TessellationOptions view;
  view.camera = Camera{Vec3(3.0, -2.5, 2.0), Vec3(0, 0, 0), Vec3::UnitZ(), 35.0, 320, 240};
  view.back_face_culling = BackFaceCulling::never;
  const Tessellation whole = tessellate(set, view);
  view.back_face_culling = BackFaceCulling::automatic;
  const Tessellation culled = tessellate(set, view);
  EXPECT_GT(culled.culled_patches, whole.culled_patches + 20);
  const std::vector<double> all = testing::ray_cast(whole.mesh, *view.camera);
  const std::vector<double> kept = testing::ray_cast(culled.mesh, *view.camera);
  const double slack = 2.0 * (whole.error_bound + culled.error_bound);
  std::size_t shown = 0;
  std::size_t changed = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (!std::isfinite(all[k])) continue;
    ++shown;
    changed += !(kept[k] <= all[k] + slack);
  }
  EXPECT_LE(changed, shown / 2000) << changed << " of " << shown << " pixels changed";
  std::cout << culled.culled_patches - whole.culled_patches << " patches back-face culled, " << changed << " of "
            << shown << " pixels changed\n";
}

TEST(LimitSurface, EndCapsConvergeWithTheIsolationLevel) {
  const SubdivisionCage cage = cage_of(cube());
  double previous = 1.0;
  for (int level = 2; level <= 5; ++level) {
    const double deviation = isolation_deviation(LimitSurface(cage, level));
    EXPECT_GT(deviation, 0.0);
    EXPECT_LT(deviation, previous / 2) << "level " << level;
    previous = deviation;
  }
  testing::Random random(5);
  EXPECT_LT(isolation_deviation(LimitSurface(cage_of(torus_grid(4, 5, random).mesh()), 2)), 1e-14);
}

TEST(LimitSurface, InfinitelySharpCreasesKeepTheCubesEdgesStraight) {
  SubdivisionCage cage = cage_of(cube());
  const TopologyReport base = analyze(cage.mesh);
  for (std::uint32_t a = 0; a < 8; ++a) {
    for (std::uint32_t b = a + 1; b < 8; ++b) {
      // Cube edges join vertices that differ in one coordinate.
      const Vec3 d = cage.mesh.position(a) - cage.mesh.position(b);
      if (std::abs(d.norm() - 1.0) < 1e-12) cage.creases.push_back({a, b, std::numeric_limits<double>::infinity()});
    }
  }
  ASSERT_EQ(cage.creases.size(), static_cast<std::size_t>(base.edges));
  // Refined vertices on a cube edge stay on it; the limit of each face is flat.
  const UniformRefinement refined = refine_uniform(cage, 3);
  for (std::size_t v = 0; v < refined.cage.mesh.vertex_count(); ++v) {
    const Vec3 p = refined.cage.mesh.position(v);
    int on_faces = 0;
    for (int k = 0; k < 3; ++k) on_faces += (p[k] == 0.0 || p[k] == 1.0) ? 1 : 0;
    EXPECT_GE(on_faces, 1) << "vertex " << v << " left the cube: " << p.transpose();
  }
  const LimitSurface surface(cage);
  for (std::size_t f = 0; f < 6; ++f) {
    for (double t : {0.0, 0.25, 0.5, 0.9}) {
      // Along the face's edge v = 0, two coordinates stay at 0 or 1 (a cube edge).
      const Vec3 p = surface.position(f, t, 0.0);
      int fixed = 0;
      for (int k = 0; k < 3; ++k) fixed += (std::abs(p[k]) < 1e-12 || std::abs(p[k] - 1.0) < 1e-12) ? 1 : 0;
      EXPECT_GE(fixed, 2) << "face " << f << " t " << t << ": " << p.transpose();
    }
  }
  // Semi-sharp creases lose one unit per level.
  SubdivisionCage semi = cage_of(cube());
  semi.creases.push_back({0, 1, 2.0});
  const UniformRefinement one = refine_uniform(semi, 1);
  ASSERT_EQ(one.cage.creases.size(), 2u);  // the two halves of the edge
  for (const Crease& crease : one.cage.creases) EXPECT_DOUBLE_EQ(crease.sharpness, 1.0);
  EXPECT_TRUE(refine_uniform(semi, 2).cage.creases.empty());
}

// The twelve-vertex icosahedron, unit circumradius.
FaceVertexMesh icosahedron() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : points) p.normalize();
  const FaceList faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                          {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                          {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  return make_mesh(points, faces);
}

// The Loop limit of an icosahedron is not a sphere (its radius varies by about 1%), so the radius
// spread of the level-k vertices does not shrink to zero: it converges to the limit's. What
// converges is the mesh to its limit: level-k vertices approach their limit points by about 4x
// per level.
TEST(Subdivision, LoopOnAnIcosahedronConvergesToItsNearlySphericalLimit) {
  const auto spread_of = [](const std::vector<Vec3>& points) {
    double lo = 1e9;
    double hi = 0.0;
    for (const Vec3& p : points) {
      lo = std::min(lo, p.norm());
      hi = std::max(hi, p.norm());
    }
    return (hi - lo) / hi;
  };
  double previous_distance = 1.0;
  for (int level = 1; level <= 5; ++level) {
    const UniformRefinement refined = refine_uniform(cage_of(icosahedron(), SubdivisionScheme::loop), level);
    EXPECT_EQ(refined.topology.euler, 2);
    const VertexLimits limits = limit_at_vertices(refined.cage);
    double distance = 0.0;
    std::vector<Vec3> points;
    for (std::size_t v = 0; v < refined.cage.mesh.vertex_count(); ++v) {
      points.push_back(refined.cage.mesh.position(v));
      distance = std::max(distance, (points.back() - limits.positions[v]).norm());
    }
    EXPECT_LT(distance, previous_distance / 3) << "level " << level;
    previous_distance = distance;
    EXPECT_LT(spread_of(limits.positions), 0.02);
    EXPECT_LT(spread_of(points), 0.02);
  }
}

TEST(Subdivision, LinearFaceVaryingValuesStayExact) {
  // A 4 x 4 grid with UVs (i/4, j/4), one value per vertex (no seams): linear interpolation of
  // a linear function on dyadic values is exact, so every refined UV is the exact bilinear one.
  const int n = 4;
  std::vector<Vec3> points;
  FaceList faces;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) points.emplace_back(i, j, 0.1 * ((i * j) % 3));
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const auto id = [&](int a, int b) { return static_cast<std::uint32_t>(b * (n + 1) + a); };
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  for (auto scheme : {SubdivisionScheme::catmull_clark, SubdivisionScheme::bilinear}) {
    SubdivisionCage cage = cage_of(make_mesh(points, faces), scheme);
    FaceVaryingData uv;
    uv.values.resize(static_cast<Eigen::Index>(points.size()), 2);
    for (std::size_t v = 0; v < points.size(); ++v) {
      uv.values.row(static_cast<Eigen::Index>(v)) << points[v].x() / n, points[v].y() / n;
    }
    uv.indices = cage.mesh.face_indices();
    cage.face_varying = uv;
    cage.options.face_varying = FaceVaryingInterpolation::all;
    // Colours as vertex data: here the positions themselves, so they refine like the positions.
    cage.vertex_data = cage.mesh.positions();
    const UniformRefinement refined = refine_uniform(cage, 3);
    const FaceVaryingData& out = *refined.cage.face_varying;
    ASSERT_EQ(out.indices.size(), refined.cage.mesh.face_indices().size());
    if (scheme == SubdivisionScheme::bilinear) {
      // Bilinear positions are the bilinear interpolation too: the UV is the position / n.
      for (std::size_t c = 0; c < out.indices.size(); ++c) {
        const Vec3 p = refined.cage.mesh.position(refined.cage.mesh.face_indices()[c]);
        EXPECT_EQ(out.values(out.indices[c], 0), p.x() / n);
        EXPECT_EQ(out.values(out.indices[c], 1), p.y() / n);
      }
    }
    // The cage's corners keep their UVs exactly, and every UV lies on the 1/32 lattice.
    for (Eigen::Index r = 0; r < out.values.rows(); ++r) {
      for (int k = 0; k < 2; ++k) {
        const double scaled = out.values(r, k) * 32.0;
        EXPECT_EQ(scaled, std::round(scaled));
      }
    }
    EXPECT_EQ(refined.cage.vertex_data, refined.cage.mesh.positions().cast<double>());
  }
}

TEST(Subdivision, HolesLeaveBoundary) {
  SubdivisionCage cage = cage_of(cube());
  cage.holes = {1};
  const UniformRefinement refined = refine_uniform(cage, 2);
  EXPECT_EQ(refined.cage.holes.size(), 16u);
  EXPECT_EQ(refined.topology.boundary_loops, 1);
  EXPECT_EQ(refined.topology.euler, 1);
  const LimitSurface surface(cage);
  EXPECT_FALSE(surface.has_surface(1));
  EXPECT_THROW(surface.evaluate(1, 0.5, 0.5), InvalidInput);
}

TEST(Subdivision, BadInputIsRefusedWithTheElement) {
  EXPECT_NE(error_message<TopologyError>([] { refine_uniform(cage_of(testing::book()), 1); }).find("non-manifold"),
            std::string::npos);
  EXPECT_NE(error_message<TopologyError>([] { refine_uniform(cage_of(cube(), SubdivisionScheme::loop), 1); })
                .find("face 0 has 4 corners"),
            std::string::npos);
  // Two triangles on one vertex triple: Loop would join them by edges with the same ends.
  const FaceVertexMesh pillow = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, FaceList{{0, 1, 2}, {1, 0, 2}});
  EXPECT_NE(error_message<TopologyError>([&] { refine_uniform(cage_of(pillow, SubdivisionScheme::loop), 2); })
                .find("faces 0 and 1 are both the triangle (0, 1, 2)"),
            std::string::npos);
  // Catmull-Clark splits it into quads through face points: a closed sphere at every level.
  const UniformRefinement pillow_quads = refine_uniform(cage_of(pillow), 2);
  EXPECT_EQ(to_json(pillow_quads.topology), to_json(analyze(pillow_quads.cage.mesh)));
  EXPECT_EQ(pillow_quads.topology.euler, 2);
  FaceList faces = testing::faces_of(cube());
  std::reverse(faces[2].begin(), faces[2].end());
  const FaceVertexMesh flipped = make_mesh(testing::points_of(cube()), faces);
  EXPECT_NE(error_message<TopologyError>([&] {
              refine_uniform(cage_of(flipped), 1);
            }).find("in the same direction (orient_cage() the cage first)"),
            std::string::npos);
  SubdivisionCage cage = cage_of(cube());
  cage.creases.push_back({0, 6, 1.0});
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("not an edge"), std::string::npos);
  cage.creases = {{0, 1, -1.0}};
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("crease 0"), std::string::npos);
  cage.creases = {{0, 1, std::nan("")}};
  EXPECT_THROW(refine_uniform(cage, 1), InvalidInput);
  cage.creases.clear();
  cage.corners = {{8, 1.0}};
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("corner 0"), std::string::npos);
  cage.corners.clear();
  cage.holes = {6};
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("hole 0"), std::string::npos);
  cage.holes.clear();
  EXPECT_THROW(refine_uniform(cage, 11), InvalidInput);
  EXPECT_THROW(refine_uniform(cage, -1), InvalidInput);
  // 96 faces at 10 levels would be 96 * 4^10 > 10^8 faces: refused before any work.
  const SubdivisionCage big = refine_uniform(cage, 2).cage;
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(big, 10); }).find("more than"), std::string::npos);
  EXPECT_THROW(LimitSurface(cage, 0), InvalidInput);
  EXPECT_THROW(LimitSurface(cage, 11), InvalidInput);
  cage.vertex_data = Eigen::MatrixXd::Zero(7, 2);
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("7 rows"), std::string::npos);
  cage.vertex_data.resize(0, 0);
  FaceVaryingData uv;
  uv.values = Eigen::MatrixXd::Zero(3, 2);
  uv.indices.assign(24, 3);
  cage.face_varying = uv;
  EXPECT_NE(error_message<InvalidInput>([&] { refine_uniform(cage, 1); }).find("face-varying index 0"),
            std::string::npos);
  EXPECT_THROW(parse_scheme("doo-sabin"), InvalidInput);
  const LimitSurface surface(cage_of(cube()));
  EXPECT_THROW(surface.evaluate(6, 0.5, 0.5), InvalidInput);
  EXPECT_THROW(surface.evaluate(0, 1.5, 0.5), InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// tessellation of the limit surface

void expect_closed_sphere(const Tessellation& t) {
  validate(t.mesh);
  const TopologyReport report = analyze(welded_faces(t.mesh));
  EXPECT_TRUE(report.manifold);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.euler, 2);
  EXPECT_EQ(report.components, 1);
}

TEST(LimitTessellation, CatmullClarkMeetsTheToleranceWeldedAndClosed) {
  // A cube with a pentagon-free mix: refined once first internally when there are non-quads.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const FaceList faces = {{0, 3, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const LimitSurface surface(cage_of(make_mesh(points, faces)));
  EXPECT_EQ(surface.face_count(), 4u * 5 + 3 * 2);
  TessellationOptions options;
  options.relative_tolerance = 1e-3;
  options.tangents = true;
  const Tessellation t = tessellate_limit(surface, options);
  expect_closed_sphere(t);
  EXPECT_LE(t.error_bound, t.tolerance);
  EXPECT_LE(t.measured_error, t.error_bound);
  EXPECT_GT(t.measured_error, 0.0);
  // Normals point out of the (convex) surface.
  const Vec3 centre(0.5, 0.5, 0.5);
  for (std::size_t v = 0; v < t.mesh.vertex_count(); ++v) {
    EXPECT_GT(t.mesh.normals[v].dot(t.mesh.positions[v] - centre), 0.0);
  }
  // Finer tolerance, more triangles, smaller error (4e-4 under the sanitizers: 1e-4 took 15 s there).
#ifdef PATCHWORK_ENABLE_ASSERTS
  options.relative_tolerance = 4e-4;
#else
  options.relative_tolerance = 1e-4;
#endif
  const Tessellation finer = tessellate_limit(surface, options);
  EXPECT_GT(finer.mesh.triangle_count(), t.mesh.triangle_count());
  EXPECT_LE(finer.measured_error, finer.tolerance);
}

TEST(LimitTessellation, LoopAndBilinearInSegmentsMode) {
  TessellationOptions options;
  options.segments = 4;
  const Tessellation loop = tessellate_limit(LimitSurface(cage_of(icosahedron(), SubdivisionScheme::loop)), options);
  expect_closed_sphere(loop);
  // A triangle as a quad with a collapsed side: 2 N^2 triangles, N of them degenerate and dropped.
  EXPECT_EQ(loop.mesh.triangle_count(), 20u * (2 * 16 - 4));
  EXPECT_TRUE(std::isinf(loop.error_bound));
  EXPECT_GT(loop.measured_error, 0.0);
  TessellationOptions tolerance;
  tolerance.tolerance = 1e-3;
  EXPECT_THROW(tessellate_limit(LimitSurface(cage_of(icosahedron(), SubdivisionScheme::loop)), tolerance),
               InvalidInput);
  // The bilinear limit of a cube is the cube: exact at any rate.
  const Tessellation box = tessellate_limit(LimitSurface(cage_of(cube(), SubdivisionScheme::bilinear)), options);
  expect_closed_sphere(box);
  EXPECT_EQ(box.error_bound, 0.0);
  EXPECT_LT(box.measured_error, 1e-15);
}

// The measured error of limit pieces against the reference (tests/surfaces/
// measured_error_reference.h: every sample of every triangle, point by point with the limit
// surface's position): Catmull-Clark at a tolerance and in segments, Loop in segments (its
// triangles' collapsed sides drop triangles, which are sampled too). Each piece agrees to rounding.
TEST(LimitTessellation, MeasuredErrorMatchesThePointwiseReference) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const FaceList faces = {{0, 3, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const LimitSurface catmull_clark(cage_of(make_mesh(points, faces)));
  const LimitSurface loop(cage_of(icosahedron(), SubdivisionScheme::loop));
  TessellationOptions tolerance;
  tolerance.relative_tolerance = 1e-3;
  TessellationOptions segments;
  segments.segments = 5;
  for (const auto& [surface, options] :
       {std::pair{&catmull_clark, tolerance}, std::pair{&catmull_clark, segments}, std::pair{&loop, segments}}) {
    const LimitPieces pieces = limit_pieces(*surface);
    const testing::MeasuredErrorComparison c =
        testing::compare_measured_error(pieces.pieces, options, pieces.pieces.evaluate);
    const double rounding = 1e-13 * c.scale;
    double reference = 0.0;
    for (std::size_t p = 0; p < c.meter.size(); ++p) {
      EXPECT_NEAR(c.meter[p], c.reference[p], rounding) << "piece " << p;
      reference = std::max(reference, c.reference[p]);
    }
    EXPECT_GT(reference, 0.0);
    EXPECT_NEAR(c.measured_error, reference, rounding);
  }
}

}  // namespace
}  // namespace patchwork
