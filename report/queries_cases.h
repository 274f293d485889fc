#pragma once
// The cases and the truths of the queries cross-check (report/queries_crosscheck.cpp writes
// docs/queries-crosscheck.md): patchwork's closest points and intersections against Open
// CASCADE's on the same inputs. No Open CASCADE header here, so the tests link this library.
//
// Every truth is independent of both libraries' answers where the geometry allows it:
//
//   closest point, sphere      |q - c| - r in closed form (c, r dyadic)
//   closest point, teapot      the least of: every sample of a dense grid on every patch, and
//                              local Newton (queries/patch_evaluation.h newton_foot) from both
//                              libraries' feet and from the best sample of every patch that the
//                              grid cannot rule out (distance_truth)
//   curve x sphere             the real roots in [0, 1] of |C(t) - c|^2 - r^2, exactly (GMP
//                              rationals, Sturm sequences: the control points are doubles, so
//                              rationals); a constructed tangent contact is one answer
//   curve x teapot             the reported hits that lie on both (|F(u, v) - C(t)| small)
//                              and lead Newton to a root, merged, and hits a dense mesh shows
//                              that Newton confirms
//   2D curve x curve           the resultant in s of the two curves' equations in t, exactly,
//                              its real roots in [0, 1], each with the t where A(t) = B(s)
//                              (found in floating point, checked in [0, 1]); an identically
//                              zero resultant is an overlap (known by construction)

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "curves/bezier_curve.h"
#include "curves/rational_bezier_curve.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/patch_set.h"

namespace patchwork::crosscheck {

/// Answers parameters within this of a true one are that answer (t, s in [0, 1]).
constexpr double kParameterTolerance = 1e-4;
/// A distance within this (times the geometry's size) of the truth is right.
constexpr double kDistanceTolerance = 1e-9;

/// One library's answers on one family of cases, against the truth.
struct Tally {
  /// Answers that match a true one (or cases answered right).
  int right = 0;
  /// Answers that match no true one (or cases answered wrong).
  int wrong = 0;
  /// True answers that no answer matched (or cases not answered).
  int missed = 0;
  /// Answers that match a true answer another answer matched already.
  int twice = 0;
  /// The largest error of a matched answer (parameter or distance).
  double max_error = 0.0;
};

/// Adds b's counts to a's (max_error the larger).
Tally& operator+=(Tally& a, const Tally& b);

/// Matches `reports` answers to `truths` true answers: each answer to its nearest truth by
/// `distance(truth, report)` if that is within `tolerance` (the first such answer right, later
/// ones twice), else wrong; truths no answer reached are missed.
Tally match_answers(std::size_t truths, std::size_t reports,
                    const std::function<double(std::size_t, std::size_t)>& distance, double tolerance);

/// Rounds x to a multiple of 2^-bits (an exact dyadic double).
double dyadic(double x, int bits = 20);

// ---------------------------------------------------------------------------------------------
// Closest points

/// The sphere of the cross-check: centre (1/4, -1/2, 1/8), radius 3/2.
struct Sphere {
  Vec3 center = Vec3(0.25, -0.5, 0.125);
  double radius = 1.5;
};

/// The sphere as a NURBS surface (surfaces/nurbs_shapes.h nurbs_sphere).
NurbsSurface sphere_surface(const Sphere& sphere);
/// A NURBS surface's Bezier patches (rational) joined as its knots say.
PatchSet nurbs_patch_set(const NurbsSurface& surface);

/// Query points of one kind.
struct PointFamily {
  std::string name;
  std::vector<Vec3> points;
};

/// Points in a box twice the sphere's, near it, at and near its centre, on it; `count` each.
std::vector<PointFamily> sphere_point_families(const Sphere& sphere, int count, std::uint64_t seed);
/// Points in a box twice the teapot's, near its surface, on its axis x = y = 0, on it.
std::vector<PointFamily> teapot_point_families(const PatchSet& teapot, int count, std::uint64_t seed);

/// The distance from q to the sphere, | |q - c| - r |.
double sphere_distance(const Sphere& sphere, const Vec3& q);

/// An n x n grid of points on every patch, u and v at k / (n - 1), point (i, j) of patch p at
/// p n^2 + i + n j, and per patch a reach: every point of the patch is within it of a sample.
struct SampledPatches {
  int n = 0;
  std::vector<Vec3> points;
  std::vector<double> reach;
};
/// Samples every patch of `set` (reach from the hodographs' control points: n max|P_(i+1)j - P_ij|
/// times half a grid step, in u and in v). \pre n >= 2.
SampledPatches sample_patches(const PatchSet& set, int n);

/// A point on a patch.
struct Foot {
  std::uint32_t patch;
  double u;
  double v;
};

/// The teapot's truth for q (file comment).
struct DistanceTruth {
  /// The least distance found (an upper bound of the exact one, attained by a surface point).
  double distance;
  /// The grid's lower bound: the nearest sample less its patch's reach.
  double lower_bound;
};
/// The least distance from q to the set among: every sample, Newton from every given foot, and
/// Newton from the nearest sample of every patch whose nearest sample less its reach is below the
/// best so far.
DistanceTruth distance_truth(const PatchSet& set, const SampledPatches& samples, const Vec3& q,
                             std::span<const Foot> feet);

/// The verdict on one closest-point answer: `distance` the reported distance (none: missed),
/// `gap` |F(u, v) - point| between the reported parameters' point and the reported point.
/// Wrong when distance > truth + tolerance or gap > tolerance.
enum class Verdict { right, wrong, missed };
Verdict judge_distance(std::optional<double> distance, double gap, double truth, double tolerance);

// ---------------------------------------------------------------------------------------------
// Curves against surfaces

/// A space curve on [0, 1] and, where the case was built tangent, the parameter of the contact.
struct CurveCase {
  BezierCurve3 curve;
  std::optional<double> contact_t;
};

/// Curves of one kind against one surface.
struct CurveFamily {
  std::string name;
  std::vector<CurveCase> cases;
};

/// Random lines and cubics through a box around the sphere, and lines tangent to it (at the
/// poles and seams of its patches, where the tangent lines are exactly dyadic, and at random
/// points); `count` each. The random curves' control points are dyadic.
std::vector<CurveFamily> sphere_curve_families(const Sphere& sphere, int count, std::uint64_t seed);
/// Random lines and cubics through the teapot's box, lines through the midpoints of its shared
/// edges, and lines tangent to it at random points where it is convex (K > 0) along a principal
/// direction.
std::vector<CurveFamily> teapot_curve_families(const PatchSet& teapot, int count, std::uint64_t seed);

/// The distinct roots in [0, 1] of |C(t) - c|^2 - r^2, exactly, each at the middle of an interval of
/// width 2^-60 that holds it.
std::vector<double> sphere_hit_parameters(const BezierCurve3& curve, const Sphere& sphere);

/// The truth for a curve against the sphere: the exact roots, where the case has a contact that
/// and the roots farther than kParameterTolerance from it.
std::vector<double> sphere_hit_truth(const CurveCase& c, const Sphere& sphere);

/// A hit some library reported.
struct ReportedHit {
  std::uint32_t patch;
  double t;
  double u;
  double v;
};

/// The truth for a curve against the teapot (file comment).
struct HitTruth {
  /// The curve parameters of the true hits, increasing.
  std::vector<double> t;
  /// Crossings of the sampled mesh near no true hit that Newton did not confirm.
  int unresolved = 0;
};
/// The reports within 1e-7 of the size of both curve and patch from which Newton on
/// F(u, v) = C(t) reaches a root (to 1e-12 of the size) within kParameterTolerance in t, merged
/// where within kParameterTolerance / 100; the contact where the case has one; and the crossings
/// of the grid of `samples` (as triangles) with the curve's polyline (32 pieces) that Newton
/// confirms.
HitTruth teapot_hit_truth(const PatchSet& set, const SampledPatches& samples, const CurveCase& c,
                          std::span<const ReportedHit> reports);

// ---------------------------------------------------------------------------------------------
// Planar curves

/// Two planar curves on [0, 1] (polynomial when every weight is 1), and where they overlap by
/// construction, first's parameter interval of the overlap.
struct CurvePair {
  RationalBezierCurve2 first;
  RationalBezierCurve2 second;
  bool rational = false;
  std::optional<Vec2> overlap;
};

/// Pairs of one kind.
struct PairFamily {
  std::string name;
  std::vector<CurvePair> pairs;
};

/// Random cubic pairs (polynomial and rational), tangencies (multiplicity 2), inflection
/// contacts (multiplicity 3), near-parallel crossings, overlaps and meetings at end points; every
/// control point and weight dyadic. `count` random pairs of each kind.
std::vector<PairFamily> curve_pair_families(int count, std::uint64_t seed);

/// The planar truth of a pair.
struct PairTruth {
  /// (t, s) of every true intersection point.
  std::vector<Vec2> points;
  /// Its multiplicity as a root of the resultant.
  std::vector<int> multiplicity;
  /// The resultant vanishes identically (the curves share a component).
  bool overlap = false;
  /// Real roots of the resultant in [0, 1] whose t was within 1e-9 of 0 or 1 and could not be
  /// decided exactly (left out of points).
  int undecided = 0;
};
/// The resultant (file comment) and its roots in [0, 1] matched with t.
PairTruth pair_truth(const CurvePair& pair);

}  // namespace patchwork::crosscheck
