// The cases and truths of the queries cross-check (report/queries_cases.h) against closed forms,
// patchwork's certified intervals and exact root counts: the table in docs/queries-crosscheck.md
// is only as good as these.

#include "report/queries_cases.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/bpt.h"
#include "queries/closest_point.h"
#include "queries/patch_bvh.h"
#include "tests/queries/exact_root_count.h"

namespace queries_cases_test {
namespace {

using namespace patchwork;
using namespace patchwork::crosscheck;

const PatchSet& teapot() {
  static const PatchSet set(read_bpt(std::string(PATCHWORK_DATA_DIR) + "/teapot.bpt"));
  return set;
}

const PairFamily& family(const std::vector<PairFamily>& families, const std::string& name) {
  for (const PairFamily& f : families) {
    if (f.name == name) return f;
  }
  throw std::runtime_error("no family " + name);
}

TEST(QueriesCrosscheckCases, SphereClosedFormLiesInPatchworksCertifiedInterval) {
  const Sphere sphere;
  const PatchSet set = nurbs_patch_set(sphere_surface(sphere));
  const PatchBvh bvh(set);
  const double slack = 1e-12 * set.size();
  for (const PointFamily& f : sphere_point_families(sphere, 6, 7)) {
    for (const Vec3& q : f.points) {
      const double truth = sphere_distance(sphere, q);
      const SurfaceClosestPoint x = closest_point(bvh, q);
      EXPECT_LE(x.lower_bound, truth + slack) << f.name;
      EXPECT_GE(x.distance, truth - slack) << f.name;
      if (f.name != "centre and near it") {
        EXPECT_NEAR(x.distance, truth, slack) << f.name;  // elsewhere tight
      }
    }
  }
}

TEST(QueriesCrosscheckCases, TeapotTruthLiesInPatchworksCertifiedInterval) {
  const PatchBvh bvh(teapot());
  const SampledPatches samples = sample_patches(teapot(), 24);
  const double slack = 1e-12 * teapot().size();
  for (const PointFamily& f : teapot_point_families(teapot(), 5, 11)) {
    for (const Vec3& q : f.points) {
      // No foot given: the grid and Newton from it alone.
      const DistanceTruth truth = distance_truth(teapot(), samples, q, {});
      const SurfaceClosestPoint x = closest_point(bvh, q);
      EXPECT_LE(x.lower_bound, truth.distance + slack) << f.name;
      EXPECT_NEAR(x.distance, truth.distance, 1e-9 * teapot().size()) << f.name;
      EXPECT_LE(truth.lower_bound, truth.distance);
      if (f.name == "on the surface") {
        EXPECT_LE(truth.distance, slack);
      }
    }
  }
}

TEST(QueriesCrosscheckCases, SphereHitsAreTheQuadraticsRoots) {
  const Sphere sphere;
  int roots = 0;
  for (const CurveFamily& f : sphere_curve_families(sphere, 30, 5)) {
    if (f.name != "lines, random") continue;
    for (const CurveCase& c : f.cases) {
      // |a + t d - c|^2 = r^2: t = (-b -+ sqrt(b^2 - |d|^2 (|a - c|^2 - r^2))) / |d|^2, b = d.(a - c).
      const Vec3 a = c.curve.control_points()[0], d = c.curve.control_points()[1] - a, m = a - sphere.center;
      const double b = d.dot(m), dd = d.squaredNorm(),
                   disc = b * b - dd * (m.squaredNorm() - sphere.radius * sphere.radius);
      std::vector<double> expected;
      if (disc > 0) {
        for (const double t : {(-b - std::sqrt(disc)) / dd, (-b + std::sqrt(disc)) / dd}) {
          if (t >= 0 && t <= 1) expected.push_back(t);
        }
      }
      const std::vector<double> exact = sphere_hit_parameters(c.curve, sphere);
      ASSERT_EQ(exact.size(), expected.size());
      for (std::size_t k = 0; k < exact.size(); ++k) EXPECT_NEAR(exact[k], expected[k], 1e-12);
      roots += static_cast<int>(exact.size());
    }
  }
  EXPECT_GT(roots, 20);  // the lines do cross the sphere
}

TEST(QueriesCrosscheckCases, TangentLinesToTheSphereAreOneContact) {
  const Sphere sphere;
  for (const CurveFamily& f : sphere_curve_families(sphere, 16, 5)) {
    if (f.name != "tangent lines") continue;
    for (const CurveCase& c : f.cases) {
      ASSERT_TRUE(c.contact_t);
      EXPECT_NEAR(sphere_distance(sphere, c.curve.evaluate(*c.contact_t)), 0.0, 1e-15);
      EXPECT_EQ(sphere_hit_truth(c, sphere), std::vector<double>{0.5});
    }
  }
}

TEST(QueriesCrosscheckCases, MeshCheckFindsAHitNoLibraryReported) {
  // A line through the midpoint of a shared edge, no reports: the dense check and Newton find it
  // (on the grid the cross-check uses: a coarser one misses hits 5e-3 apart, case 0).
  const SampledPatches samples = sample_patches(teapot(), 48);
  for (const CurveFamily& f : teapot_curve_families(teapot(), 4, 3)) {
    if (f.name != "lines through shared edges") continue;
    for (const CurveCase& c : f.cases) {
      const HitTruth truth = teapot_hit_truth(teapot(), samples, c, {});
      bool midpoint = false;
      for (const double t : truth.t) midpoint = midpoint || std::abs(t - 0.5) < 1e-9;
      EXPECT_TRUE(midpoint) << ::testing::PrintToString(truth.t) << " unresolved " << truth.unresolved;
    }
  }
}

TEST(QueriesCrosscheckCases, HardPlanarCasesHaveTheirExactRootCounts) {
  const std::vector<PairFamily> families = curve_pair_families(10, 9);
  for (const CurvePair& pair : family(families, "tangent (multiplicity 2)").pairs) {
    const PairTruth truth = pair_truth(pair);
    ASSERT_EQ(truth.points.size(), 1u);
    EXPECT_EQ(truth.multiplicity[0], 2);
    EXPECT_NEAR(truth.points[0].x(), 0.5, 1e-12);
  }
  for (const CurvePair& pair : family(families, "inflection contact (multiplicity 3)").pairs) {
    const PairTruth truth = pair_truth(pair);
    ASSERT_EQ(truth.points.size(), 1u);
    EXPECT_EQ(truth.multiplicity[0], 3);
    EXPECT_NEAR(truth.points[0].x(), 0.5, 1e-12);
    EXPECT_NEAR(truth.points[0].y(), 0.5, 1e-12);
  }
  for (const CurvePair& pair : family(families, "near-parallel crossings").pairs) {
    const PairTruth truth = pair_truth(pair);
    ASSERT_EQ(truth.points.size(), 1u);
    EXPECT_EQ(truth.multiplicity[0], 1);
    const double at = pair.first.degree() == 1 ? 2.0 / 3.0 : 0.5;
    EXPECT_NEAR(truth.points[0].x(), at, 1e-12);
    EXPECT_NEAR(truth.points[0].y(), at, 1e-12);
  }
  for (const CurvePair& pair : family(families, "overlapping").pairs) {
    EXPECT_TRUE(pair_truth(pair).overlap);
    EXPECT_TRUE(pair.overlap);
  }
  for (const CurvePair& pair : family(families, "meeting at end points").pairs) {
    const PairTruth truth = pair_truth(pair);
    EXPECT_EQ(truth.undecided, 0);
    int at_start_of_second = 0;
    for (const Vec2& x : truth.points) at_start_of_second += x.y() == 0.0 ? 1 : 0;
    EXPECT_EQ(at_start_of_second, 1);  // second(0) lies on first exactly once
  }
}

TEST(QueriesCrosscheckCases, RandomPlanarTruthsAreCrossings) {
  // Every true point is a point of both curves.
  for (const PairFamily& f : curve_pair_families(12, 21)) {
    if (f.name.find("random") == std::string::npos) continue;
    for (const CurvePair& pair : f.pairs) {
      const PairTruth truth = pair_truth(pair);
      EXPECT_FALSE(truth.overlap);
      for (const Vec2& x : truth.points)
        EXPECT_LE((pair.first.evaluate(x.x()) - pair.second.evaluate(x.y())).norm(), 1e-12);
    }
  }
}

TEST(QueriesCrosscheckCases, RootIsolationKeepsARootNextToARootAtTheEnd) {
  // f = s (s - 3/5): the root 0 at the interval's end, and 3/5 isolated apart from it.
  const exact::Polynomial f{mpq_class(0), mpq_class(-3, 5), mpq_class(1)};
  mpq_class width(1);
  width /= mpz_class(1) << 40;
  const std::vector<exact::RootInterval> roots = exact::isolated_roots(f, 0, 1, width);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_EQ(roots[0].lo, 0);
  EXPECT_EQ(roots[0].hi, 0);
  EXPECT_LE(roots[1].lo, mpq_class(3, 5));
  EXPECT_GE(roots[1].hi, mpq_class(3, 5));
  EXPECT_LE(roots[1].hi - roots[1].lo, width);
}

TEST(QueriesCrosscheckCases, MatchingCountsRightWrongMissedAndTwice) {
  const std::vector<double> truth{0.1, 0.5, 0.9};
  const std::vector<double> reports{0.1, 0.10000001, 0.5, 0.7};
  const Tally tally = match_answers(
      truth.size(), reports.size(), [&](std::size_t i, std::size_t j) { return std::abs(truth[i] - reports[j]); },
      kParameterTolerance);
  EXPECT_EQ(tally.right, 2);
  EXPECT_EQ(tally.twice, 1);
  EXPECT_EQ(tally.wrong, 1);
  EXPECT_EQ(tally.missed, 1);
}

}  // namespace
}  // namespace queries_cases_test
