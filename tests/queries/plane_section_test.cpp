// Plane sections against closed forms (circles of the sphere and the torus, the cylinder's
// ellipse), tangent and in-plane cases, and the teapot against slicing its tessellation.

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/errors.h"
#include "io/bpt.h"
#include "queries/plane_section.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/rational_shapes.h"

namespace plane_section_test {
namespace {

using namespace patchwork;
constexpr double pi = std::numbers::pi;

PatchSet set_of(const NurbsSurface& surface) {
  const NurbsBezierPatches pieces = bezier_patches(surface);
  return PatchSet(pieces.patches, pieces.joins);
}

Vec3 evaluate(const AnyBezierPatch& patch, const Vec2& uv) {
  return std::visit([&](const auto& p) -> Vec3 { return p.evaluate(uv.x(), uv.y()); }, patch);
}

// Every vertex on the plane and at its patch's point (u, v) in [0, 1]^2, to rounding.
void expect_vertices_exact(const PatchSet& set, const PlaneSection& section, const Vec3& p, const Vec3& normal) {
  const Vec3 n = normal.normalized();
  for (const SectionPolyline& line : section.polylines) {
    for (const SectionVertex& v : line.vertices) {
      EXPECT_LE(std::abs(n.dot(v.point - p)), 1e-12 * set.size());
      EXPECT_TRUE(v.uv.minCoeff() >= 0.0 && v.uv.maxCoeff() <= 1.0);
      EXPECT_LE((evaluate(set.patch(v.patch), v.uv) - v.point).norm(), 1e-14 * set.size());
    }
  }
}

// The segments of a polyline (a closed one with its last).
std::vector<std::pair<Vec3, Vec3>> segments(const SectionPolyline& line) {
  std::vector<std::pair<Vec3, Vec3>> result;
  for (std::size_t k = 0; k + 1 < line.vertices.size(); ++k) result.emplace_back(line.vertices[k].point, line.vertices[k + 1].point);
  if (line.closed && line.vertices.size() > 1) result.emplace_back(line.vertices.back().point, line.vertices.front().point);
  return result;
}

double length(const SectionPolyline& line) {
  double sum = 0.0;
  for (const auto& [a, b] : segments(line)) sum += (b - a).norm();
  return sum;
}

double distance_to_segment(const Vec3& q, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = d.squaredNorm() > 0.0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * d - q).norm();
}

// A closed polyline with vertices on the circle of `radius` about `centre` in the plane: the
// polygon holds the circle of radius - bound (each chord within the bound of its arc), so its
// length is between 2 pi (radius - bound) and 2 pi radius; each midpoint within the bound.
void expect_circle(const SectionPolyline& line, const Vec3& centre, const Vec3& n, double radius, double bound) {
  EXPECT_TRUE(line.closed);
  for (const SectionVertex& v : line.vertices) {
    EXPECT_NEAR((v.point - centre).norm(), radius, 1e-12);
    EXPECT_NEAR(n.dot(v.point - centre), 0.0, 1e-12);
  }
  for (const auto& [a, b] : segments(line)) EXPECT_LE(radius - (0.5 * (a + b) - centre).norm(), bound + 1e-12);
  EXPECT_LE(length(line), 2.0 * pi * radius + 1e-12);
  EXPECT_GE(length(line), 2.0 * pi * (radius - bound) - 1e-12);
}

TEST(PlaneSection, SphereCutAtDistanceIsItsCircle) {
  const Vec3 centre(0.3, -0.2, 0.5);
  const double r = 1.7;
  const PatchSet set = set_of(nurbs_sphere(centre, r));
  const Vec3 n = Vec3(0.3, -0.2, 0.9).normalized();
  // r - 1e-5: a loop of radius 0.0058 inside one patch.
  for (const double d : {0.0, 0.61, -1.2, 1.65, r - 1e-5}) {
    for (const double tolerance : {1e-2, 1e-6}) {
      SCOPED_TRACE(::testing::Message() << "d = " << d << ", tolerance " << tolerance);
      const Vec3 p = centre + d * n;
      const PlaneSection section = plane_section(set, p, n, tolerance);
      ASSERT_EQ(section.polylines.size(), 1U);
      EXPECT_EQ(section.uncertified_pieces, 0U);
      EXPECT_TRUE(section.tangent_points.empty());
      EXPECT_LE(section.error_bound, tolerance);
      expect_circle(section.polylines[0], p, n, std::sqrt(r * r - d * d), section.error_bound);
      expect_vertices_exact(set, section, p, n);
    }
  }
}

// The patch with u reversed (P'_ij = P_(n-i)j): its edges along u run the other way.
RationalBezierPatch reversed_u(const RationalBezierPatch& patch) {
  const int n = patch.degree_u(), m = patch.degree_v();
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      points.push_back(patch.control_point(n - i, j));
      weights.push_back(patch.weight(n - i, j));
    }
  }
  return RationalBezierPatch(n, m, points, weights);
}

TEST(PlaneSection, EdgesSharedInOppositeDirectionsAreCrossedOnce) {
  // The sphere with its northern patches' u reversed: the equator's shared edges run opposite
  // ways in their two patches, and the crossing found on one is mapped to the other's parameter.
  std::vector<AnyBezierPatch> patches = bezier_patches(nurbs_sphere(Vec3::Zero(), 1.0)).patches;
  for (std::size_t k = patches.size() / 2; k < patches.size(); ++k)
    patches[k] = reversed_u(std::get<RationalBezierPatch>(patches[k]));
  const PatchSet set(patches);
  ASSERT_TRUE(std::any_of(set.shared_edges().begin(), set.shared_edges().end(), [](const SharedEdge& e) { return e.reversed; }));
  const Vec3 n = Vec3(1.0, 0.4, 0.3).normalized();
  for (const double d : {0.0, 0.35}) {
    const PlaneSection section = plane_section(set, d * n, n, 1e-5);
    ASSERT_EQ(section.polylines.size(), 1U);
    EXPECT_EQ(section.uncertified_pieces, 0U);
    expect_circle(section.polylines[0], d * n, n, std::sqrt(1.0 - d * d), section.error_bound);
    expect_vertices_exact(set, section, d * n, n);
  }
}

TEST(PlaneSection, ObliqueCylinderCutIsAnEllipse) {
  const PatchSet set = set_of(nurbs_cylinder(Vec3::Zero(), 1.0, 2.0));
  const Vec3 p(0, 0, 1), normal(0.3, 0.2, 1.0);  // z = 1 - 0.3 x - 0.2 y
  const double tolerance = 1e-4;
  const PlaneSection section = plane_section(set, p, normal, tolerance);
  ASSERT_EQ(section.polylines.size(), 1U);
  EXPECT_EQ(section.uncertified_pieces, 0U);
  EXPECT_LE(section.error_bound, tolerance);
  const SectionPolyline& line = section.polylines[0];
  EXPECT_TRUE(line.closed);
  for (const SectionVertex& v : line.vertices) EXPECT_NEAR(std::hypot(v.point.x(), v.point.y()), 1.0, 1e-12);
  expect_vertices_exact(set, section, p, normal);
  // The ellipse (cos a, sin a, 1 - 0.3 cos a - 0.2 sin a): its perimeter by the trapezoidal rule
  // (exact to rounding for a smooth periodic integrand); the polygon holds its inner parallel
  // curve at the bound, of perimeter P - 2 pi bound.
  const int samples = 2000;
  double perimeter = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double a = 2.0 * pi * k / samples;
    perimeter += std::sqrt(1.0 + std::pow(0.3 * std::sin(a) - 0.2 * std::cos(a), 2)) * 2.0 * pi / samples;
  }
  EXPECT_LE(length(line), perimeter + 1e-12);
  EXPECT_GE(length(line), perimeter - 2.0 * pi * section.error_bound - 1e-12);
}

TEST(PlaneSection, TorusCutThroughItsAxisIsTwoCircles) {
  const double R = 2.0, r = 0.5;
  const PatchSet set = set_of(nurbs_torus(Vec3::Zero(), R, r));
  // At 0.3 radians the plane crosses the patches; at 0 and pi / 2 it holds patch edges (the
  // section runs along them, the seam at angle 0 among them).
  for (const double a : {0.3, 0.0, pi / 2}) {
  SCOPED_TRACE(::testing::Message() << "angle " << a);
  const Vec3 n(std::cos(a), std::sin(a), 0.0), along(-std::sin(a), std::cos(a), 0.0);
  const PlaneSection section = plane_section(set, Vec3::Zero(), n, 1e-5);
  ASSERT_EQ(section.polylines.size(), 2U);
  EXPECT_EQ(section.uncertified_pieces, 0U);
  EXPECT_LE(section.error_bound, 1e-5);
  expect_vertices_exact(set, section, Vec3::Zero(), n);
  std::vector<double> sides;
  for (const SectionPolyline& line : section.polylines) {
    const double side = line.vertices.front().point.dot(along) > 0.0 ? 1.0 : -1.0;
    sides.push_back(side);
    for (const SectionVertex& v : line.vertices) EXPECT_LE(patchwork::testing::torus_distance(v.point, R, r), 1e-12);
    expect_circle(line, side * R * along, n, r, section.error_bound);
  }
  EXPECT_EQ(sides[0] + sides[1], 0.0);  // one circle on each side of the axis
  }
}

TEST(PlaneSection, PlaneTangentAtASaddleCrossesItself) {
  // x = R - r touches the torus at its inner equator's point (R - r, 0, 0), a saddle at a corner
  // of four patches: the section is a closed curve through it twice (a figure eight).
  const double R = 2.0, r = 0.5;
  const PatchSet set = set_of(nurbs_torus(Vec3::Zero(), R, r));
  const Vec3 saddle(R - r, 0, 0), n(1, 0, 0);
  const PlaneSection section = plane_section(set, saddle, n, 1e-4);
  EXPECT_EQ(section.uncertified_pieces, 0U);
  EXPECT_TRUE(section.tangent_points.empty());
  ASSERT_FALSE(section.polylines.empty());
  std::size_t through_saddle = 0;
  for (const SectionPolyline& line : section.polylines) {
    EXPECT_TRUE(line.closed);
    for (const SectionVertex& v : line.vertices) {
      EXPECT_LE(patchwork::testing::torus_distance(v.point, R, r), 1e-12);
      through_saddle += (v.point - saddle).norm() <= 1e-12;
    }
  }
  EXPECT_EQ(through_saddle, 2U);
  expect_vertices_exact(set, section, saddle, n);
}

TEST(PlaneSection, PlaneTangentAtASaddleInsideAPatchCrossesItself) {
  // The tangent plane at a point of the torus's inner half (negative curvature), inside a patch:
  // the section crosses itself there, in a cell whose crossings are joined to one of them.
  const double R = 2.0, r = 0.5, theta = 0.3, phi = 0.75 * pi + 0.2;
  const PatchSet set = set_of(nurbs_torus(Vec3::Zero(), R, r));
  const Vec3 n(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
  const Vec3 saddle = Vec3(R * std::cos(theta), R * std::sin(theta), 0.0) + r * n;
  // (Much below 1e-5 f is rounding noise on cells small enough: see docs/queries.md.)
  for (const double tolerance : {1e-3, 1e-5}) {
    const PlaneSection section = plane_section(set, saddle, n, tolerance);
    EXPECT_EQ(section.uncertified_pieces, 0U);
    EXPECT_LE(section.error_bound, tolerance);
    double nearest = std::numeric_limits<double>::infinity();
    for (const SectionPolyline& line : section.polylines) {
      EXPECT_TRUE(line.closed);
      for (const SectionVertex& v : line.vertices) {
        EXPECT_LE(patchwork::testing::torus_distance(v.point, R, r), 1e-12);
        nearest = std::min(nearest, (v.point - saddle).norm());
      }
    }
    EXPECT_LE(nearest, section.error_bound);
    expect_vertices_exact(set, section, saddle, n);
    // The four arms meet at one vertex, which the polylines pass twice.
    std::vector<std::array<double, 3>> points;
    for (const SectionPolyline& line : section.polylines)
      for (const SectionVertex& v : line.vertices) points.push_back({v.point.x(), v.point.y(), v.point.z()});
    std::sort(points.begin(), points.end());
    EXPECT_NE(std::adjacent_find(points.begin(), points.end()), points.end());
  }
}

TEST(PlaneSection, PlaneThroughAPoleCrossesIt) {
  const PatchSet set = set_of(nurbs_sphere(Vec3::Zero(), 1.0));
  const Vec3 pole(0, 0, 1), n = Vec3(1, 0.3, 1).normalized();
  const PlaneSection section = plane_section(set, pole, n, 1e-4);
  ASSERT_EQ(section.polylines.size(), 1U);
  EXPECT_TRUE(section.tangent_points.empty());
  EXPECT_EQ(section.uncertified_pieces, 0U);
  expect_circle(section.polylines[0], n.dot(pole) * n, n, std::sqrt(1.0 - std::pow(n.dot(pole), 2)), section.error_bound);
  const auto& vertices = section.polylines[0].vertices;
  EXPECT_TRUE(std::any_of(vertices.begin(), vertices.end(), [&](const SectionVertex& v) { return (v.point - pole).norm() <= 1e-12; }));
}

TEST(PlaneSection, TangentPlaneGivesAFlaggedPoint) {
  const PatchSet set = set_of(nurbs_sphere(Vec3::Zero(), 1.0));
  const Vec3 inner = Vec3(0.48, 0.6, 0.64);  // a unit vector inside a patch
  // At the pole (a collapsed edge), at a corner of four patches (1, 0, 0), inside a patch.
  for (const Vec3& touch : {Vec3(0, 0, 1), Vec3(1, 0, 0), inner}) {
    SCOPED_TRACE(::testing::Message() << touch.transpose());
    const PlaneSection section = plane_section(set, touch, touch, 1e-3);
    EXPECT_TRUE(section.polylines.empty());
    EXPECT_EQ(section.uncertified_pieces, 0U);
    ASSERT_EQ(section.tangent_points.size(), 1U);
    EXPECT_LE((section.tangent_points[0].point - touch).norm(), section.error_bound + 1e-12);
    EXPECT_LE(section.error_bound, 1e-3);
    // The plane moved just off the sphere cuts nothing.
    const PlaneSection off = plane_section(set, 1.001 * touch, touch, 1e-3);
    EXPECT_TRUE(off.polylines.empty() && off.tangent_points.empty());
  }
}

TEST(PlaneSection, TangencyAlongACurveInsideAPatchIsNotCertified) {
  // The plane touches the cylinder along the ruling at 45 degrees, inside a patch: f <= 0 with a
  // double zero along a line, which the cells cannot resolve into arcs or isolated points. The
  // search stops at its budget and says so instead of claiming a certified answer.
  const PatchSet set = set_of(nurbs_cylinder(Vec3::Zero(), 1.0, 2.0));
  const Vec3 touch(std::sqrt(0.5), std::sqrt(0.5), 0.0);
  const PlaneSection section = plane_section(set, touch, touch, 1e-2);
  EXPECT_GT(section.uncertified_pieces, 0U);
  EXPECT_TRUE(section.polylines.empty());
  // Along the seam (a shared edge) the same tangency is a side in the plane: a certified segment.
  const PlaneSection seam = plane_section(set, Vec3(1, 0, 0), Vec3(1, 0, 0), 1e-2);
  EXPECT_EQ(seam.uncertified_pieces, 0U);
  ASSERT_EQ(seam.polylines.size(), 1U);
  EXPECT_FALSE(seam.polylines[0].closed);
  for (const SectionVertex& v : seam.polylines[0].vertices) EXPECT_LE((v.point - Vec3(1, 0, v.point.z())).norm(), 1e-15);
  EXPECT_NEAR(length(seam.polylines[0]), 2.0, 1e-15);
}

TEST(PlaneSection, PatchInThePlaneIsReportedWhole) {
  // The wedge's bottom cap (patch 1, rational, z = 0) and flat side (patch 3, y = 0).
  const PatchSet set(patchwork::testing::wedge(2.0, 1.0, Vec3::Zero()));
  const PlaneSection bottom = plane_section(set, Vec3(5, 5, 0), Vec3(0, 0, 3), 1e-3);
  EXPECT_EQ(bottom.patches_in_plane, std::vector<std::uint32_t>{1});
  EXPECT_TRUE(bottom.polylines.empty());
  EXPECT_TRUE(bottom.tangent_points.empty());
  const PlaneSection side = plane_section(set, Vec3::Zero(), Vec3(0, -1, 0), 1e-3);
  EXPECT_EQ(side.patches_in_plane, std::vector<std::uint32_t>{3});
  EXPECT_TRUE(side.polylines.empty());
  // A plane across the wedge cuts it in one closed loop (two segments in the caps, arcs elsewhere).
  const PlaneSection across = plane_section(set, Vec3(0, 0, 0.5), Vec3(1, 1, 0.2), 1e-4);
  EXPECT_TRUE(across.patches_in_plane.empty());
  ASSERT_EQ(across.polylines.size(), 1U);
  EXPECT_TRUE(across.polylines[0].closed);
  expect_vertices_exact(set, across, Vec3(0, 0, 0.5), Vec3(1, 1, 0.2));
}

// The loops of a triangle mesh cut by the plane through p with unit normal n, and their total
// length: each triangle with corners on both sides gives a segment between points on its edges,
// the point of an edge computed once per pair of welded positions so segments join exactly.
struct MeshSlice {
  std::size_t loops = 0;
  std::size_t open = 0;
  double length = 0.0;
};

MeshSlice slice_mesh(const RenderMesh& mesh, const Vec3& p, const Vec3& n) {
  const auto height = [&](const Vec3& x) { return n.dot(x - p); };
  const auto side = [&](std::uint32_t v) { return height(mesh.positions[v]) >= 0.0; };  // on the plane: above
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edge_segments;
  std::vector<std::array<std::pair<std::uint32_t, std::uint32_t>, 2>> ends;
  std::vector<std::array<Vec3, 2>> points;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> keys;
    std::vector<Vec3> cut;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.indices[3 * t + k], b = mesh.indices[3 * t + (k + 1) % 3];
      if (side(a) == side(b)) continue;
      const std::uint32_t ia = mesh.position_ids[a], ib = mesh.position_ids[b];
      const Vec3& pa = ia < ib ? mesh.positions[a] : mesh.positions[b];
      const Vec3& pb = ia < ib ? mesh.positions[b] : mesh.positions[a];
      const double s = height(pa) / (height(pa) - height(pb));
      keys.emplace_back(std::min(ia, ib), std::max(ia, ib));
      cut.push_back(pa + s * (pb - pa));
    }
    if (keys.size() != 2) continue;
    const std::size_t segment = ends.size();
    ends.push_back({keys[0], keys[1]});
    points.push_back({cut[0], cut[1]});
    for (const auto& key : keys) edge_segments[key].push_back(segment);
  }
  MeshSlice result;
  std::vector<bool> seen(ends.size(), false);
  for (std::size_t start = 0; start < ends.size(); ++start) {
    if (seen[start]) continue;
    // Walk both ways from the segment; a loop returns to it.
    bool closed = true;
    std::vector<std::size_t> todo{start};
    seen[start] = true;
    while (!todo.empty()) {
      const std::size_t s = todo.back();
      todo.pop_back();
      result.length += (points[s][1] - points[s][0]).norm();
      for (const auto& key : ends[s]) {
        const std::vector<std::size_t>& at = edge_segments[key];
        if (at.size() < 2) closed = false;
        for (const std::size_t other : at)
          if (!seen[other]) {
            seen[other] = true;
            todo.push_back(other);
          }
      }
    }
    (closed ? result.loops : result.open) += 1;
  }
  return result;
}

// An open polyline ends only where the set has an open edge: both its end vertices lie on an
// open edge of their patch.
void expect_open_ends_on_open_edges(const PatchSet& set, const PlaneSection& section) {
  for (const SectionPolyline& line : section.polylines) {
    if (line.closed) continue;
    for (const SectionVertex* end : {&line.vertices.front(), &line.vertices.back()}) {
      const bool on_open_edge = std::any_of(set.open_edges().begin(), set.open_edges().end(), [&](const EdgeRef& e) {
        if (e.patch != end->patch) return false;
        switch (e.edge) {
          case PatchEdge::v0: return end->uv.y() == 0.0;
          case PatchEdge::u1: return end->uv.x() == 1.0;
          case PatchEdge::v1: return end->uv.y() == 1.0;
          case PatchEdge::u0: return end->uv.x() == 0.0;
        }
        return false;
      });
      EXPECT_TRUE(on_open_edge) << "patch " << end->patch << " at " << end->uv.transpose();
    }
  }
}

TEST(PlaneSection, TeapotSlicesAgreeWithItsTessellation) {
  const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  TessellationOptions options;
  options.tolerance = 1e-4;
  options.measure = false;
  const Tessellation mesh = tessellate(set, options);
  for (const double height : {0.31, 0.77, 1.43, 1.91, 2.6}) {
    SCOPED_TRACE(::testing::Message() << "z = " << height);
    const PlaneSection section = plane_section(set, Vec3(0, 0, height), Vec3(0, 0, 1), 1e-4);
    EXPECT_EQ(section.uncertified_pieces, 0U);
    EXPECT_LE(section.error_bound, 1e-4);
    expect_vertices_exact(set, section, Vec3(0, 0, height), Vec3(0, 0, 1));
    const MeshSlice slice = slice_mesh(mesh.mesh, Vec3(0, 0, height), Vec3(0, 0, 1));
    std::size_t closed = 0;
    double total = 0.0;  // the lengths agree to 1e-3 (measured: 3e-5 to 1e-4)
    for (const SectionPolyline& line : section.polylines) {
      closed += line.closed;
      total += length(line);
    }
    // Same loops, and the same open chains (z = 0.77 crosses the spout's open end inside the body).
    EXPECT_EQ(closed, slice.loops);
    EXPECT_EQ(section.polylines.size() - closed, slice.open);
    EXPECT_NEAR(total, slice.length, 1e-3 * slice.length);
    expect_open_ends_on_open_edges(set, section);
  }
}

TEST(PlaneSection, HandleSectionEndsOnItsOpenEdgeBesideTheBody) {
  // The teapot's handle (patches 12 to 15) touches its body at (-2, 0, 0.9) without sharing an
  // edge there, its open edge v1 leaving the point tangent to the body's edge. This plane (from
  // TeapotRandomPlanesAreCertified) passes 8e-6 from the point: the handle's section ends on that
  // open edge some 1e-10 from a crossing of the body's section, closer than the set's tolerance.
  // The two are different points of different curves: the body's loop stays closed and the
  // handle's arc ends on its open edge, as in the tessellation's slice.
  const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  const Vec3 touch(-2, 0, 0.9), p(-1.299, -0.81, 1.0256), normal(-0.654, -0.715, -0.961);
  ASSERT_EQ(set.touching_points().size(), 1U);
  ASSERT_LE((set.touching_points()[0].point - touch).norm(), set.tolerance());
  ASSERT_LE(std::abs(normal.normalized().dot(touch - p)), 1e-5);
  const double tolerance = 1e-4;
  const PlaneSection section = plane_section(set, p, normal, tolerance);
  EXPECT_EQ(section.uncertified_pieces, 0U);
  EXPECT_LE(section.error_bound, tolerance);
  expect_vertices_exact(set, section, p, normal);
  expect_open_ends_on_open_edges(set, section);
  ASSERT_EQ(section.polylines.size(), 2U);
  const bool first_closed = section.polylines[0].closed;
  ASSERT_NE(first_closed, section.polylines[1].closed);
  const SectionPolyline& loop = section.polylines[first_closed ? 0 : 1];
  const SectionPolyline& arc = section.polylines[first_closed ? 1 : 0];
  const auto on_handle = [](const SectionVertex& v) { return v.patch >= 12 && v.patch <= 15; };
  EXPECT_TRUE(std::none_of(loop.vertices.begin(), loop.vertices.end(), on_handle));
  EXPECT_TRUE(std::all_of(arc.vertices.begin(), arc.vertices.end(), on_handle));
  // One end of the arc is within the set's tolerance of the loop (the case that joined them).
  double nearest = std::numeric_limits<double>::infinity();
  for (const SectionVertex* end : {&arc.vertices.front(), &arc.vertices.back()}) {
    EXPECT_EQ(end->patch, 15U);
    EXPECT_EQ(end->uv.y(), 1.0);
    for (const SectionVertex& v : loop.vertices) nearest = std::min(nearest, (v.point - end->point).norm());
  }
  EXPECT_LE(nearest, set.tolerance());
  TessellationOptions options;
  options.tolerance = 1e-4;
  options.measure = false;
  const MeshSlice slice = slice_mesh(tessellate(set, options).mesh, p, normal.normalized());
  EXPECT_EQ(slice.loops, 1U);
  EXPECT_EQ(slice.open, 1U);
  EXPECT_NEAR(length(loop) + length(arc), slice.length, 1e-3 * slice.length);
}

// Random planes through the teapot's box: certified, on the plane, open only at open edges.
RC_GTEST_PROP(PlaneSection, TeapotRandomPlanesAreCertified, ()) {
  static const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  const auto coordinate = [] { return *rc::gen::inRange(-1000, 1001) / 1000.0; };
  const Vec3 p(3.0 * coordinate(), 2.0 * coordinate(), 1.6 + 1.6 * coordinate());
  const Vec3 normal(coordinate(), coordinate(), coordinate());
  RC_PRE(normal.norm() > 0.1);
  const double tolerance = 1e-4;
  const PlaneSection section = plane_section(set, p, normal, tolerance);
  RC_ASSERT(section.uncertified_pieces == 0U);
  RC_ASSERT(section.error_bound <= tolerance);
  for (const SectionPolyline& line : section.polylines) {
    RC_ASSERT(line.vertices.size() >= 2U);
    for (const SectionVertex& v : line.vertices) RC_ASSERT(std::abs(normal.normalized().dot(v.point - p)) <= 1e-12 * set.size());
  }
  expect_open_ends_on_open_edges(set, section);
}

// A plane through a point of the torus, not tangent there, has a section through that point.
RC_GTEST_PROP(PlaneSection, PlaneThroughASurfacePointPassesNearIt, ()) {
  const double R = 2.0, r = 0.5;
  static const PatchSet set = set_of(nurbs_torus(Vec3::Zero(), R, r));
  const auto unit = [](int k) { return k / 1000.0; };
  const auto patch = static_cast<std::uint32_t>(*rc::gen::inRange<int>(0, static_cast<int>(set.count())));
  const Vec2 uv(unit(*rc::gen::inRange(0, 1001)), unit(*rc::gen::inRange(0, 1001)));
  const Vec3 p = evaluate(set.patch(patch), uv);
  const Vec3 normal(unit(*rc::gen::inRange(-1000, 1001)), unit(*rc::gen::inRange(-1000, 1001)),
                    unit(*rc::gen::inRange(-1000, 1001)));
  RC_PRE(normal.norm() > 0.1);
  // Not within 10 degrees of tangent (where the section may shrink to the point or cross itself).
  RC_PRE(std::abs(normal.normalized().dot(patchwork::testing::torus_normal(p, R))) < std::cos(10.0 * pi / 180.0));
  const double tolerance = 1e-4;
  const PlaneSection section = plane_section(set, p, normal, tolerance);
  RC_ASSERT(section.uncertified_pieces == 0U);
  RC_ASSERT(section.error_bound <= tolerance);
  double nearest = std::numeric_limits<double>::infinity();
  for (const SectionPolyline& line : section.polylines) {
    RC_ASSERT(line.closed);
    for (const auto& [a, b] : segments(line)) nearest = std::min(nearest, distance_to_segment(p, a, b));
    for (const SectionVertex& v : line.vertices) {
      RC_ASSERT(std::abs(normal.normalized().dot(v.point - p)) <= 1e-12);
      RC_ASSERT(patchwork::testing::torus_distance(v.point, R, r) <= 1e-12);
    }
  }
  RC_ASSERT(nearest <= section.error_bound + 1e-12);
}

TEST(PlaneSection, BadArgumentsNameTheArgument) {
  const PatchSet set = set_of(nurbs_sphere(Vec3::Zero(), 1.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [&](const Vec3& p, const Vec3& n, double tolerance) -> std::string {
    try {
      plane_section(set, p, n, tolerance);
    } catch (const InvalidInput& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_EQ(message(Vec3(nan, 0, 0), Vec3(0, 0, 1), 1e-3), "plane_section: argument 'point' is not finite (nan, 0, 0)");
  EXPECT_EQ(message(Vec3::Zero(), Vec3::Zero(), 1e-3), "plane_section: argument 'normal' is the zero vector");
  EXPECT_EQ(message(Vec3::Zero(), Vec3(0, 0, 1), 0.0), "plane_section: argument 'tolerance' must be finite and positive, not 0");
  EXPECT_EQ(message(Vec3::Zero(), Vec3(0, 0, 1e-300), 1e-3), "");  // a tiny normal is a normal
}

}  // namespace
}  // namespace plane_section_test
