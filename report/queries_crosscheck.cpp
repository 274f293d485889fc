// The Open CASCADE cross-check of patchwork's modeling queries (issue 19): the same cases through
// patchwork and through OCCT in one run, each answer judged against an independent truth
// (report/queries_cases.h), written as a Markdown table (docs/queries-crosscheck.md,
// scripts/crosscheck-queries).
//
//   patchwork_queries_crosscheck --out FILE [--count N] [--commit TEXT] [--verbose]
//
// OCCT's side: GeomAPI_ProjectPointOnSurf (one per patch, Init'ed once with the patch's surface
// and bounds, Perform per point, the least LowerDistance over the patches), GeomAPI_IntCS (per
// patch; hits of different patches at one curve point merged, as a B-rep user would), and
// Geom2dAPI_InterCurveCurve (tolerance 1e-6, its default). Surfaces and curves are built before
// the clocks start; only the queries are timed.

#include <Geom2dAPI_InterCurveCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <GeomAPI_IntCS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BezierCurve.hxx>
#include <IntRes2d_IntersectionPoint.hxx>
#include <IntRes2d_IntersectionSegment.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/bpt.h"
#include "queries/closest_point.h"
#include "queries/curve_intersection.h"
#include "queries/curve_surface_intersection.h"
#include "queries/patch_bvh.h"
#include "queries/patch_evaluation.h"
#include "report/format.h"
#include "report/occt_geometry.h"
#include "report/occt_peer.h"
#include "report/queries_cases.h"

namespace patchwork::crosscheck {
namespace {

using Clock = std::chrono::steady_clock;

// --verbose: every case where a library is not right, with the truth and both answers, on stderr.
bool verbose = false;

std::string list(const std::vector<double>& x) {
  std::ostringstream out;
  out.precision(17);
  for (const double v : x) out << v << " ";
  return out.str();
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double median(std::vector<double> x) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  const std::size_t h = x.size() / 2;
  return x.size() % 2 == 1 ? x[h] : 0.5 * (x[h - 1] + x[h]);
}

double slowest(const std::vector<double>& x) { return x.empty() ? 0.0 : *std::max_element(x.begin(), x.end()); }

double total(const std::vector<double>& x) {
  double s = 0;
  for (const double v : x) s += v;
  return s;
}

// One row of the table: a query kind on a family, both libraries.
struct Row {
  std::string query;
  std::string family;
  int cases = 0;
  int truths = 0;  // true answers (for closest points: cases)
  Tally patchwork;
  Tally occt;
  std::vector<double> patchwork_seconds;
  std::vector<double> occt_seconds;
  // OCCT on every patch, without the box culling (where there is more than one surface).
  std::vector<double> occt_unculled_seconds;
  // Cases where the culled and unculled OCCT answers differ (they may not: the boxes hold the patches).
  int culling_changed = 0;
  std::string notes;
};

// The note on OCCT without culling: its median time and patchwork's speed ratio against it.
std::string unculled_note(const Row& row) {
  if (row.occt_unculled_seconds.empty()) return "";
  double ours = 0, theirs = 0;
  for (const double x : row.patchwork_seconds) ours += x;
  for (const double x : row.occt_unculled_seconds) theirs += x;
  std::string note = "OCCT on every patch without box culling: median " +
                     performance::text("%.3g", median(row.occt_unculled_seconds) * 1e6) + " us, speed ratio " +
                     performance::text("%.2f", theirs / ours) + ". ";
  if (row.culling_changed > 0) note += std::to_string(row.culling_changed) + " answers changed by culling! ";
  return note;
}

// A row with no answers yet.
Row new_row(std::string query, std::string family, std::size_t cases) {
  Row row;
  row.query = std::move(query), row.family = std::move(family), row.cases = static_cast<int>(cases);
  return row;
}

gp_Pnt occt_point(const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); }
Vec3 vec(const gp_Pnt& p) { return Vec3(p.X(), p.Y(), p.Z()); }

void add_verdict(Tally& tally, Verdict verdict, double error) {
  if (verdict == Verdict::right) ++tally.right, tally.max_error = std::max(tally.max_error, error);
  if (verdict == Verdict::wrong) ++tally.wrong;
  if (verdict == Verdict::missed) ++tally.missed;
}

// ---------------------------------------------------------------------------------------------
// Closest points

// OCCT's projection of q onto every surface, the least distance kept.
struct OcctFoot {
  std::optional<double> distance;
  std::uint32_t surface = 0;
  double u = 0, v = 0;
  Vec3 point = Vec3::Zero();
  int failures = 0;
};

// The boxes of the control points of every surface (one box of all when the surfaces are not the
// set's patches): each holds its surface (convex hull), so a caller may skip a surface by its box.
std::vector<Eigen::AlignedBox3d> control_boxes(const PatchSet& set, std::size_t surfaces) {
  std::vector<Eigen::AlignedBox3d> boxes(surfaces == set.count() ? surfaces : 1);
  for (std::size_t p = 0; p < set.count(); ++p) {
    for (const Vec3& P : set.control_nets()[p].control_points()) boxes[boxes.size() == 1 ? 0 : p].extend(P);
  }
  return boxes;
}

// The surfaces in increasing distance of their boxes from q.
std::vector<std::pair<double, std::size_t>> by_box_distance(const std::vector<Eigen::AlignedBox3d>& boxes,
                                                            const Vec3& q) {
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < boxes.size(); ++k) order.emplace_back(boxes[k].exteriorDistance(q), k);
  std::sort(order.begin(), order.end());
  return order;
}

// With `boxes`, the surfaces are projected onto nearest box first, and those whose box is no
// nearer than the best distance so far are skipped (what a caller with many faces would do);
// without, every surface is.
OcctFoot occt_closest(std::vector<GeomAPI_ProjectPointOnSurf>& projectors, const Vec3& q,
                      const std::vector<Eigen::AlignedBox3d>* boxes) {
  OcctFoot best;
  const gp_Pnt P = occt_point(q);
  std::vector<std::pair<double, std::size_t>> order;
  if (boxes) {
    order = by_box_distance(*boxes, q);
  } else {
    for (std::size_t k = 0; k < projectors.size(); ++k) order.emplace_back(0.0, k);
  }
  for (const auto& [box_distance, k] : order) {
    if (best.distance && box_distance >= *best.distance) break;
    try {
      projectors[k].Perform(P);
      if (!projectors[k].IsDone() || projectors[k].NbPoints() == 0) continue;
      const double d = projectors[k].LowerDistance();
      if (!best.distance || d < *best.distance) {
        best.distance = d;
        best.surface = static_cast<std::uint32_t>(k);
        projectors[k].LowerDistanceParameters(best.u, best.v);
        best.point = vec(projectors[k].NearestPoint());
      }
    } catch (const Standard_Failure&) {
      ++best.failures;
    }
  }
  return best;
}

// The closest-point rows of one surface. `truth(q, patchwork foot, occt foot)` gives the true
// distance.
template <class Truth>
std::vector<Row> closest_point_rows(const std::string& surface_name, const PatchSet& set,
                                    const std::vector<Handle(Geom_Surface)>& surfaces,
                                    const std::vector<PointFamily>& families, const Truth& truth) {
  const PatchBvh bvh(set);
  std::vector<GeomAPI_ProjectPointOnSurf> projectors(surfaces.size());
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    double u0, u1, v0, v1;
    surfaces[k]->Bounds(u0, u1, v0, v1);
    projectors[k].Init(surfaces[k], u0, u1, v0, v1);
  }
  const std::vector<Eigen::AlignedBox3d> boxes = control_boxes(set, surfaces.size());
  const double tolerance = kDistanceTolerance * set.size();
  std::vector<Row> rows;
  for (const PointFamily& family : families) {
    Row row = new_row("closest point", surface_name + ": " + family.name, family.points.size());
    row.truths = row.cases;
    int below_truth = 0, occt_failures = 0, attained_twice = 0, uncertified = 0;
    for (const Vec3& q : family.points) {
      auto start = Clock::now();
      const SurfaceClosestPoint ours = closest_point(bvh, q);
      row.patchwork_seconds.push_back(seconds_since(start));
      start = Clock::now();
      const OcctFoot theirs = occt_closest(projectors, q, &boxes);
      row.occt_seconds.push_back(seconds_since(start));
      occt_failures += theirs.failures;
      if (surfaces.size() > 1) {
        start = Clock::now();
        const OcctFoot unculled = occt_closest(projectors, q, nullptr);
        row.occt_unculled_seconds.push_back(seconds_since(start));
        row.culling_changed += unculled.distance != theirs.distance ? 1 : 0;
      }

      const double d =
          truth(q, Foot{ours.patch, ours.u, ours.v},
                theirs.distance ? std::optional<Foot>(Foot{theirs.surface, theirs.u, theirs.v}) : std::nullopt);
      const double our_gap = (detail::patch_point(set, ours.patch, ours.u, ours.v) - ours.point).norm();
      Verdict verdict = judge_distance(ours.distance, our_gap, d, tolerance);
      // The certificate must hold too.
      if (verdict == Verdict::right && ours.lower_bound > d + tolerance) verdict = Verdict::wrong;
      if (ours.distance - ours.lower_bound > 2 * tolerance) ++uncertified;
      attained_twice += ours.attained_more_than_once ? 1 : 0;
      add_verdict(row.patchwork, verdict, std::abs(ours.distance - d));
      below_truth += ours.distance < d - tolerance ? 1 : 0;

      double their_gap = 0;
      if (theirs.distance) {
        their_gap = (vec(surfaces[theirs.surface]->Value(theirs.u, theirs.v)) - theirs.point).norm();
        below_truth += *theirs.distance < d - tolerance ? 1 : 0;
      }
      add_verdict(row.occt, judge_distance(theirs.distance, their_gap, d, tolerance),
                  theirs.distance ? std::abs(*theirs.distance - d) : 0.0);
    }
    std::ostringstream notes;
    if (attained_twice > 0) notes << "patchwork flags " << attained_twice << " as attained more than once. ";
    if (uncertified > 0)
      notes << "patchwork's interval wider than 2 tolerances on " << uncertified << " (piece budget). ";
    if (occt_failures > 0)
      notes << "OCCT raised " << occt_failures << " exceptions (counted as no answer on that patch). ";
    if (below_truth > 0) notes << below_truth << " answers below the truth (truth not the minimum!). ";
    notes << unculled_note(row);
    row.notes = notes.str();
    rows.push_back(std::move(row));
  }
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Curves against surfaces

Handle(Geom_BezierCurve) occt_curve(const BezierCurve3& curve) {
  TColgp_Array1OfPnt poles(1, curve.degree() + 1);
  for (int i = 0; i <= curve.degree(); ++i)
    poles.SetValue(i + 1, occt_point(curve.control_points()[static_cast<std::size_t>(i)]));
  return new Geom_BezierCurve(poles);
}

// OCCT's hits of a curve on every surface; hits of different surfaces within 1e-7 in t are one.
struct OcctHits {
  std::vector<ReportedHit> hits;
  int segments = 0;
  int failures = 0;
  int merged = 0;
};

// With `boxes` and the curve's control box, surfaces whose box misses the curve's are skipped
// (neither holds the other's points there: convex hulls); without, every surface is intersected.
OcctHits occt_intersect(const Handle(Geom_Curve) & curve, const std::vector<Handle(Geom_Surface)>& surfaces,
                        const std::vector<Eigen::AlignedBox3d>* boxes, const Eigen::AlignedBox3d& curve_box) {
  OcctHits result;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    if (boxes && !(*boxes)[k].intersects(curve_box)) continue;
    try {
      GeomAPI_IntCS intersector(curve, surfaces[k]);
      if (!intersector.IsDone()) {
        ++result.failures;
        continue;
      }
      result.segments += intersector.NbSegments();
      for (int i = 1; i <= intersector.NbPoints(); ++i) {
        double u, v, w;
        intersector.Parameters(i, u, v, w);
        bool merged = false;
        for (const ReportedHit& h : result.hits) merged = merged || (h.patch != k && std::abs(h.t - w) <= 1e-7);
        if (merged) {
          ++result.merged;
        } else {
          result.hits.push_back({static_cast<std::uint32_t>(k), w, u, v});
        }
      }
    } catch (const Standard_Failure&) {
      ++result.failures;
    }
  }
  return result;
}

// The curve-surface rows of one surface; `truth(case, all reports)` gives the true t values.
template <class Truth>
std::vector<Row> curve_surface_rows(const std::string& surface_name, const PatchSet& set,
                                    const std::vector<Handle(Geom_Surface)>& surfaces,
                                    const std::vector<CurveFamily>& families, const Truth& truth) {
  const std::vector<Eigen::AlignedBox3d> boxes = control_boxes(set, surfaces.size());
  std::vector<Row> rows;
  for (const CurveFamily& family : families) {
    Row row = new_row("curve x surface", surface_name + ": " + family.name, family.cases.size());
    std::vector<Handle(Geom_Curve)> curves;
    for (const CurveCase& c : family.cases) curves.push_back(occt_curve(c.curve));
    int segments = 0, failures = 0, merged = 0, flagged = 0, unresolved = 0, errors = 0;
    for (std::size_t k = 0; k < family.cases.size(); ++k) {
      const CurveCase& c = family.cases[k];
      auto start = Clock::now();
      std::vector<ReportedHit> ours;
      try {
        const CurveSurfaceHits hits = intersect_curve_surface(c.curve, set);
        row.patchwork_seconds.push_back(seconds_since(start));
        for (const CurveSurfaceHit& h : hits.hits) {
          ours.push_back({h.patch, h.t, h.u, h.v});
          flagged += h.tangential ? 1 : 0;
        }
      } catch (const std::exception&) {
        row.patchwork_seconds.push_back(seconds_since(start));
        ++errors;
      }
      Eigen::AlignedBox3d curve_box;
      for (const Vec3& P : c.curve.control_points()) curve_box.extend(P);
      // Widened by rounding: a hit on a box's face must not be culled.
      const Vec3 margin = Vec3::Constant(1e-12 * set.size());
      curve_box = Eigen::AlignedBox3d(curve_box.min() - margin, curve_box.max() + margin);
      start = Clock::now();
      const OcctHits theirs = occt_intersect(curves[k], surfaces, &boxes, curve_box);
      row.occt_seconds.push_back(seconds_since(start));
      if (surfaces.size() > 1) {
        start = Clock::now();
        const OcctHits unculled = occt_intersect(curves[k], surfaces, nullptr, curve_box);
        row.occt_unculled_seconds.push_back(seconds_since(start));
        row.culling_changed += unculled.hits.size() != theirs.hits.size() ? 1 : 0;
      }
      segments += theirs.segments, failures += theirs.failures, merged += theirs.merged;

      std::vector<ReportedHit> all = ours;
      all.insert(all.end(), theirs.hits.begin(), theirs.hits.end());
      int case_unresolved = 0;
      const std::vector<double> t = truth(c, all, case_unresolved);
      unresolved += case_unresolved;
      row.truths += static_cast<int>(t.size());
      const auto judge = [&](const std::vector<ReportedHit>& hits) {
        return match_answers(
            t.size(), hits.size(), [&](std::size_t i, std::size_t j) { return std::abs(t[i] - hits[j].t); },
            kParameterTolerance);
      };
      const Tally a = judge(ours), b = judge(theirs.hits);
      row.patchwork += a;
      row.occt += b;
      if (verbose && (a.wrong + a.missed + a.twice + b.wrong + b.missed + b.twice) > 0) {
        std::vector<double> ta, tb;
        for (const ReportedHit& h : ours) ta.push_back(h.t);
        for (const ReportedHit& h : theirs.hits) tb.push_back(h.t);
        std::cerr << row.family << " case " << k << ": truth " << list(t) << "| patchwork " << list(ta) << "| OCCT "
                  << list(tb) << "\n";
      }
    }
    std::ostringstream notes;
    if (flagged > 0) notes << "patchwork flags " << flagged << " hits tangential. ";
    if (errors > 0) notes << "patchwork threw on " << errors << " cases. ";
    if (segments > 0) notes << "OCCT reports " << segments << " segments (not counted). ";
    if (failures > 0) notes << "OCCT failed (IsDone false or exception) " << failures << " times. ";
    if (merged > 0) notes << merged << " OCCT hits merged across patches. ";
    if (unresolved > 0) notes << unresolved << " mesh crossings Newton did not confirm. ";
    notes << unculled_note(row);
    row.notes = notes.str();
    rows.push_back(std::move(row));
  }
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Planar curves

Handle(Geom2d_BezierCurve) occt_curve(const RationalBezierCurve2& curve, bool rational) {
  TColgp_Array1OfPnt2d poles(1, curve.degree() + 1);
  TColStd_Array1OfReal weights(1, curve.degree() + 1);
  for (int i = 0; i <= curve.degree(); ++i) {
    const Vec2 p = curve.control_point(i);
    poles.SetValue(i + 1, gp_Pnt2d(p.x(), p.y()));
    weights.SetValue(i + 1, curve.weight(i));
  }
  return rational ? new Geom2d_BezierCurve(poles, weights) : new Geom2d_BezierCurve(poles);
}

BezierCurve2 polynomial_curve(const RationalBezierCurve2& curve) {
  std::vector<Vec2> P;
  for (int i = 0; i <= curve.degree(); ++i) P.push_back(curve.control_point(i));
  return BezierCurve2(P);
}

// An answer: a point (t, s), or intervals of t and s (an overlap, or OCCT's segment: where the
// curves are within its tolerance) with (t, s) at one end.
struct PlanarAnswer {
  Vec2 ts;
  std::optional<Vec2> t_range;
  std::optional<Vec2> s_range;
};

// The ordered interval of two values.
Vec2 ordered(double a, double b) { return Vec2(std::min(a, b), std::max(a, b)); }

// How far x lies outside the answer's range (or from its point where it has none).
double outside(double x, double point, const std::optional<Vec2>& range) {
  if (!range) return std::abs(x - point);
  return std::max({0.0, range->x() - x, x - range->y()});
}

std::vector<PlanarAnswer> ours_planar(const CurvePair& pair, int& flagged) {
  const CurveIntersections<2> result =
      pair.rational ? intersect_curves(pair.first, pair.second)
                    : intersect_curves(polynomial_curve(pair.first), polynomial_curve(pair.second));
  std::vector<PlanarAnswer> answers;
  for (const auto& x : result.points) answers.push_back({Vec2(x.t, x.s), {}, {}}), flagged += x.tangential ? 1 : 0;
  for (const auto& o : result.overlaps) answers.push_back({Vec2(o.t0, o.s0), ordered(o.t0, o.t1), ordered(o.s0, o.s1)});
  return answers;
}

std::vector<PlanarAnswer> occt_planar(const Geom2dAPI_InterCurveCurve& intersection) {
  std::vector<PlanarAnswer> answers;
  const Geom2dInt_GInter& result = intersection.Intersector();
  for (int i = 1; i <= result.NbPoints(); ++i) {
    answers.push_back({Vec2(result.Point(i).ParamOnFirst(), result.Point(i).ParamOnSecond()), {}, {}});
  }
  for (int i = 1; i <= result.NbSegments(); ++i) {
    const IntRes2d_IntersectionSegment& segment = result.Segment(i);
    const double t0 = segment.HasFirstPoint() ? segment.FirstPoint().ParamOnFirst() : 0.0;
    const double t1 = segment.HasLastPoint() ? segment.LastPoint().ParamOnFirst() : 1.0;
    const double s0 = segment.HasFirstPoint() ? segment.FirstPoint().ParamOnSecond() : 0.0;
    const double s1 = segment.HasLastPoint() ? segment.LastPoint().ParamOnSecond() : 1.0;
    answers.push_back({Vec2(t0, s0), ordered(t0, t1), ordered(s0, s1)});
  }
  return answers;
}

// Judges the answers of one pair: points against the truth's points (an interval answer matches
// a true point inside it), or against the overlap: one interval matching it is right, points or a
// wrong interval wrong, nothing missed.
Tally judge_planar(const CurvePair& pair, const PairTruth& truth, const std::vector<PlanarAnswer>& answers) {
  if (truth.overlap) {
    Tally tally;
    const Vec2 range = pair.overlap.value_or(Vec2(0, 1));
    int matching = 0;
    for (const PlanarAnswer& a : answers) {
      const bool match = a.t_range && std::abs((*a.t_range)[0] - range[0]) <= kParameterTolerance &&
                         std::abs((*a.t_range)[1] - range[1]) <= kParameterTolerance;
      matching += match ? 1 : 0;
      if (match) tally.max_error = std::max(tally.max_error, ((*a.t_range) - range).cwiseAbs().maxCoeff());
    }
    // One matching interval is the answer; more are the answer twice; points or other intervals
    // are wrong (the points lie on both curves, but the answer is the interval).
    tally.right = matching > 0 ? 1 : 0;
    tally.twice = std::max(0, matching - 1);
    tally.wrong = static_cast<int>(answers.size()) - matching;
    tally.missed = matching == 0 ? 1 : 0;
    return tally;
  }
  return match_answers(
      truth.points.size(), answers.size(),
      [&](std::size_t i, std::size_t j) {
        const PlanarAnswer& a = answers[j];
        return std::max(outside(truth.points[i].x(), a.ts.x(), a.t_range),
                        outside(truth.points[i].y(), a.ts.y(), a.s_range));
      },
      kParameterTolerance);
}

std::vector<Row> planar_rows(const std::vector<PairFamily>& families) {
  std::vector<Row> rows;
  for (const PairFamily& family : families) {
    Row row = new_row("2D curve x curve", family.name, family.pairs.size());
    int flagged = 0, undecided = 0, segments = 0, failures = 0, errors = 0;
    double longest = 0, overlap_end_error = 0;
    int our_intervals = 0;
    std::vector<std::pair<Handle(Geom2d_Curve), Handle(Geom2d_Curve)>> curves;
    for (const CurvePair& pair : family.pairs) {
      curves.emplace_back(occt_curve(pair.first, pair.rational), occt_curve(pair.second, pair.rational));
    }
    for (std::size_t k = 0; k < family.pairs.size(); ++k) {
      const CurvePair& pair = family.pairs[k];
      const PairTruth truth = pair_truth(pair);
      undecided += truth.undecided;
      row.truths += truth.overlap ? 1 : static_cast<int>(truth.points.size());

      auto start = Clock::now();
      std::vector<PlanarAnswer> ours;
      try {
        ours = ours_planar(pair, flagged);
      } catch (const std::exception&) {
        ++errors;
      }
      row.patchwork_seconds.push_back(seconds_since(start));
      if (verbose && row.patchwork_seconds.back() > 0.01) {
        std::cerr << family.name << " pair " << k << ": patchwork took " << row.patchwork_seconds.back() << " s\n";
      }
      start = Clock::now();
      std::vector<PlanarAnswer> theirs;
      try {
        const Geom2dAPI_InterCurveCurve intersection(curves[k].first, curves[k].second);
        theirs = occt_planar(intersection);
        segments += intersection.NbSegments();
        for (const PlanarAnswer& a : theirs) {
          if (a.t_range) longest = std::max(longest, a.t_range->y() - a.t_range->x());
        }
      } catch (const Standard_Failure&) {
        ++failures;
      }
      row.occt_seconds.push_back(seconds_since(start));
      const Tally a = judge_planar(pair, truth, ours), b = judge_planar(pair, truth, theirs);
      if (!truth.overlap) {
        for (const PlanarAnswer& x : ours) our_intervals += x.t_range ? 1 : 0;
      }
      if (truth.overlap && pair.overlap) {
        for (const PlanarAnswer& x : theirs) {
          if (x.t_range)
            overlap_end_error = std::max(overlap_end_error, (*x.t_range - *pair.overlap).cwiseAbs().maxCoeff());
        }
      }
      row.patchwork += a;
      row.occt += b;
      if (verbose && (a.wrong + a.missed + a.twice + b.wrong + b.missed + b.twice) > 0) {
        std::ostringstream line;
        line.precision(17);
        line << family.name << " pair " << k << ": truth" << (truth.overlap ? " overlap" : "");
        for (const Vec2& x : truth.points) line << " (" << x.x() << ", " << x.y() << ")";
        for (const auto* answers : {&ours, &theirs}) {
          line << (answers == &ours ? " | patchwork" : " | OCCT");
          for (const PlanarAnswer& x : *answers) {
            line << " (" << x.ts.x() << ", " << x.ts.y() << ")";
            if (x.t_range) line << "[t " << x.t_range->x() << " .. " << x.t_range->y() << "]";
          }
        }
        std::cerr << line.str() << "\n";
      }
    }
    std::ostringstream notes;
    if (flagged > 0) notes << "patchwork flags " << flagged << " points tangential. ";
    if (errors > 0) notes << "patchwork threw on " << errors << " pairs. ";
    if (our_intervals > 0) notes << "patchwork reports " << our_intervals << " overlaps where the truth is a point. ";
    if (segments > 0)
      notes << "OCCT reports " << segments << " segments (the longest " << performance::text("%.2g", longest)
            << " in t). ";
    if (failures > 0) notes << "OCCT raised " << failures << " exceptions. ";
    if (overlap_end_error > 0) {
      notes << "OCCT's segments end up to " << performance::text("%.2g", overlap_end_error)
            << " in t from the overlap's ends. ";
    }
    if (undecided > 0) notes << undecided << " resultant roots at an end left undecided (not in the truth). ";
    row.notes = notes.str();
    rows.push_back(std::move(row));
  }
  return rows;
}

// ---------------------------------------------------------------------------------------------
// The document

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

std::string tally_cell(const Tally& t, bool twice) {
  std::string cell = std::to_string(t.right) + " / " + std::to_string(t.wrong) + " / " + std::to_string(t.missed);
  if (twice) cell += " / " + std::to_string(t.twice);
  return cell;
}

std::string microseconds(double seconds) { return performance::text("%.3g", seconds * 1e6); }

// The sizes tolerances are relative to: the diagonals of the control points' boxes.
struct Sizes {
  double teapot;
  double sphere;
};

// How every number of the table is made: the truths, the matching, the timing.
std::string definitions(const Sizes& sizes) {
  std::ostringstream out;
  out << "## How the table is made\n\n"
      << "Everything comes from `report/queries_cases.h` (the cases and truths, no Open CASCADE, tested by\n"
      << "`tests/report/queries_cases_test.cpp`) and `report/queries_crosscheck.cpp` (both libraries, the table).\n"
      << "The size below is the diagonal of the box of the control points: teapot "
      << performance::text("%.4g", sizes.teapot) << ", sphere " << performance::text("%.4g", sizes.sphere) << ".\n\n"
      << "**Closest point.** patchwork: `closest_point(bvh, q)`, the `PatchBvh` built once. OCCT: one\n"
      << "`GeomAPI_ProjectPointOnSurf` per patch (the teapot's 32 `Geom_BezierSurface`s; the sphere as one\n"
      << "`Geom_BSplineSurface`, the same NURBS surface), `Init`ed once with the surface and its bounds\n"
      << "outside the timing, then `Perform(q)` patch by patch, nearest control-point box first, skipping\n"
      << "patches whose box is no nearer than the best distance so far (the box holds the patch, so this\n"
      << "loses nothing), and the least `LowerDistance` kept. The notes give OCCT's time without that\n"
      << "culling (every patch projected), measured in the same run.\n\n"
      << "- Truth, sphere: `||q - c| - r|` in closed form, c = (1/4, -1/2, 1/8), r = 3/2 (the NURBS sphere's\n"
      << "  weights are rounded doubles: it is that sphere to about 1e-16).\n"
      << "- Truth, teapot: the least of (a) every sample of a 48 x 48 grid on every patch, (b) local Newton\n"
      << "  (`newton_foot`, queries/patch_evaluation.h) from both libraries' feet, (c) the same Newton from the\n"
      << "  nearest sample of every patch whose nearest sample, less the patch's reach (n max |P_(i+1)j - P_ij|\n"
      << "  plus the same along v, times half a grid step: no point of the patch is farther than that from a\n"
      << "  sample), is below the best so far. (a) and (c) use neither library's answer. The truth is a\n"
      << "  distance some surface point attains; it misses the exact minimum only if that lies in a basin\n"
      << "  that neither library, nor Newton from the nearest sample of its patch, reaches.\n"
      << "- Right: the reported distance is within 1e-9 x size of the truth (so not above it by more; no\n"
      << "  answer was below it by more), the point at the reported parameters (OCCT: `S(U, V)` by OCCT;\n"
      << "  patchwork: `F(u, v)`) is within 1e-9 x size of the reported point (OCCT's issue #345), and for\n"
      << "  patchwork the certified lower bound is at most the truth (+ 1e-9 x size). Wrong: an answer that\n"
      << "  fails one of these. Missed: no answer (OCCT: no extremum on any patch).\n\n"
      << "**Curve x surface.** patchwork: `intersect_curve_surface(curve, set)` (the sphere: its 8 rational\n"
      << "patches). OCCT: `GeomAPI_IntCS(Geom_BezierCurve, surface)` on every patch whose control-point box\n"
      << "meets the curve's (the notes give the time without that culling); hits of different patches\n"
      << "within 1e-7 in t are merged by this program (a hit on a shared edge, found by both patches: a\n"
      << "B-rep caller would merge them too); hits of one surface are not merged. Curves run over t in [0, 1].\n\n"
      << "- Truth, sphere: the real roots in [0, 1] of `|C(t) - c|^2 - r^2`, exactly (Sturm sequences in GMP\n"
      << "  rationals; the control points are doubles, so rationals), each isolated to 2^-60. Tangent lines:\n"
      << "  one contact at t = 1/2 plus the exact roots farther than 1e-4 from it. The first 12 touch at the\n"
      << "  poles and at the patch corners on the equator and are exactly tangent (dyadic numbers); the\n"
      << "  others are tangent to rounding (the exact line misses or cuts by about 1e-16, roots within\n"
      << "  about 1e-8 of 1/2), counted as one contact.\n"
      << "- Truth, teapot: no closed form. The answers of either library that lie within 1e-7 x size of both\n"
      << "  curve and patch and from which Newton on F(u, v) = C(t) reaches a root (residual 1e-12 x size)\n"
      << "  within 1e-4 in t; the contact of a tangent line (built at a convex point, K > 0.01, along a\n"
      << "  principal direction); and a dense check: the curve's polyline (1 piece for lines, 32 for cubics)\n"
      << "  against the triangles of the 48 x 48 grid of every patch, Newton from every crossing, a root\n"
      << "  found this way joins the truth (a hit both missed). Crossings no Newton confirms far from every\n"
      << "  true hit are counted in the notes. A hit that both libraries and the mesh miss is not in the truth.\n"
      << "- Matching: every answer goes to the nearest true t within 1e-4; the first is right, further ones\n"
      << "  are reported twice, answers with no true t that near are wrong; true hits no answer reached are\n"
      << "  missed.\n\n"
      << "**2D curve x curve.** patchwork: `intersect_curves` (Bezier or rational Bezier). OCCT:\n"
      << "`Geom2dAPI_InterCurveCurve` on two `Geom2d_BezierCurve`s with its default tolerance 1e-6, points and\n"
      << "segments from its `Intersector()`. Control points are multiples of 1/64 and weights 1/2 to 2 in\n"
      << "steps of 1/4, so the inputs are exact rationals.\n\n"
      << "- Truth: the resultant R(s) = Res_t(X_A(t) w_B(s) - X_B(s) w_A(t), Y_A(t) w_B(s) - Y_B(s) w_A(t)) in\n"
      << "  GMP rationals (Sylvester determinants at 2 n_A n_B + 1 integers s, interpolated exactly), its\n"
      << "  distinct real roots in [0, 1] isolated by Sturm sequences to 2^-60, the multiplicity of each from\n"
      << "  repeated gcds. For each root s the partner t is found in floating point (the least |A(t) - B(s)|\n"
      << "  over [-1/4, 5/4], sampling then Gauss-Newton); the root is a true point if that distance is below\n"
      << "  4e-9 and t lies in [0, 1] (a t within 1e-9 of 0 or 1 is decided exactly: A(end) = B(s) in\n"
      << "  rationals). So the count in s is exact; the t of each point and its being inside [0, 1] are\n"
      << "  decided in floating point away from the ends. R = 0 identically: the curves overlap (the\n"
      << "  overlap's interval is known from the construction).\n"
      << "- Cases: random cubic pairs in [0, 1]^2 (polynomial, and rational); tangent: a cubic and a\n"
      << "  parabola touching a line, a cubic touching its mirror image (multiplicity 2); inflection: a cubic\n"
      << "  against its inflection tangent, and y = (2t - 1)^3 against y = c (2s - 1)^3 (multiplicity 3);\n"
      << "  near-parallel: lines at angles 2^-10 to 2^-34, and a cubic against itself lifted by\n"
      << "  e (3t - 3/2) (crossing at an angle of about 3e); overlapping: a cubic (x increasing, so without a\n"
      << "  loop) against its middle half, forward or reversed, or two pieces sharing [3/8, 5/8] of it; end\n"
      << "  points: end to end, and an end on the other's middle. The hard cases are turned by 90 degrees and\n"
      << "  moved (exactly).\n"
      << "- Matching: a point answer goes to the nearest true point within 1e-4 in t and in s; an interval\n"
      << "  answer (patchwork's overlap, OCCT's segment: where the curves are within its tolerance) matches a\n"
      << "  true point inside it. Against an overlap, an interval whose ends are within 1e-4 of the\n"
      << "  overlap's is right, further such intervals are reported twice, points and other intervals are\n"
      << "  wrong, and without such an interval the overlap is missed.\n\n"
      << "**Time.** `steady_clock` around each call (a point, a curve against the whole surface, a pair);\n"
      << "patchwork and OCCT alternate case by case in one process, one thread, Release (-O3). The machine is\n"
      << "shared with other builds: times and ratios move by some 20% between runs. The speed ratio is\n"
      << "OCCT's total time over patchwork's for the family (patchwork's queries per second over OCCT's); a\n"
      << "family with one slow case (see the slowest column) has its ratio set by that case.\n\n"
      << "**Limits.** The teapot's truths are not proofs: for closest points a minimum in a basin that no\n"
      << "start reaches would be missed by the truth too; for curves a hit that both libraries and the\n"
      << "48 x 48 mesh miss (two hits closer than the mesh resolves, a tangent contact the mesh does not\n"
      << "cross) is not in the truth, so there \"right\" means agreement with verified hits. In the plane the\n"
      << "count of roots in s is exact, but each root's t comes from floating point (roots whose t lies\n"
      << "within 1e-9 of 0 or 1 are decided exactly or reported as undecided in the notes). The matching\n"
      << "tolerance of 1e-4 in the parameters is generous (tangent contacts are known to about 1e-8,\n"
      << "inflection contacts to about 1e-5); the error column shows how close the right answers came.\n"
      << "OCCT answers within its tolerance (1e-6 for planar curves): its points along near-parallel lines\n"
      << "lie within that tolerance of both curves but are not crossings, so they count as wrong, while its\n"
      << "segments count as right when they contain the true point. Random tangent lines to the sphere are\n"
      << "tangent only to rounding and count as one contact by definition.\n";
  return out.str();
}

std::string document(const std::vector<Row>& rows, const std::string& commit, int count, double run_seconds,
                     const Sizes& sizes) {
  std::ostringstream out;
  out << "# Modeling queries: patchwork against Open CASCADE\n\n"
      << "Written by `scripts/crosscheck-queries` (report/queries_crosscheck.cpp) in one run: the same cases\n"
      << "through patchwork's queries and through Open CASCADE " << performance::occt_version()
      << ", each answer judged against an independent truth\n(definitions below the table). Machine: " << machine()
      << "; one thread, Release build; commit " << commit << "; " << count
      << " random cases per random family; the run took " << performance::text("%.0f", run_seconds) << " s.\n\n"
      << "Columns: right / wrong / missed (and / reported twice for intersections) per library; the time is the\n"
      << "median of one query (one point, one curve against the whole surface, one pair), measured side by side; the\n"
      << "ratio is patchwork's queries per second over OCCT's, from the total times of the family. The error is the\n"
      << "largest of a right answer (distance for closest points, parameter for intersections).\n\n"
      << "| query | family | cases | true answers | patchwork | OCCT | patchwork us | OCCT us | speed ratio | slowest "
         "ms patchwork / OCCT | max error patchwork / OCCT |\n"
      << "|---|---|---:|---:|---|---|---:|---:|---:|---|---|\n";
  for (const Row& row : rows) {
    const bool twice = row.query != "closest point";
    const double ours = total(row.patchwork_seconds), theirs = total(row.occt_seconds);
    out << "| " << row.query << " | " << row.family << " | " << row.cases << " | " << row.truths << " | "
        << tally_cell(row.patchwork, twice) << " | " << tally_cell(row.occt, twice) << " | "
        << microseconds(median(row.patchwork_seconds)) << " | " << microseconds(median(row.occt_seconds)) << " | "
        << performance::text("%.2f", ours > 0 ? theirs / ours : 0.0) << " | "
        << performance::text("%.3g", slowest(row.patchwork_seconds) * 1e3) << " / "
        << performance::text("%.3g", slowest(row.occt_seconds) * 1e3) << " | "
        << performance::text("%.1e", row.patchwork.max_error) << " / " << performance::text("%.1e", row.occt.max_error)
        << " |\n";
  }
  out << "\nNotes per row (rows without notes left out):\n\n";
  for (const Row& row : rows) {
    if (!row.notes.empty()) out << "- " << row.query << ", " << row.family << ": " << row.notes << "\n";
  }
  out << "\n" << definitions(sizes);
  return out.str();
}

struct Arguments {
  std::string out;
  std::string commit = "unknown";
  int count = 200;
};

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--out" && k + 1 < argc) {
      a.out = argv[++k];
    } else if (arg == "--commit" && k + 1 < argc) {
      a.commit = argv[++k];
    } else if (arg == "--verbose") {
      verbose = true;
    } else if (arg == "--count" && k + 1 < argc) {
      a.count = std::stoi(argv[++k]);
    } else {
      throw InvalidInput("patchwork_queries_crosscheck: unknown argument '" + arg +
                         "' (usage: --out FILE [--count N] [--commit TEXT] [--verbose])");
    }
  }
  if (a.out.empty()) throw InvalidInput("patchwork_queries_crosscheck: --out FILE is required");
  return a;
}

int run(const Arguments& arguments) {
  const auto start = Clock::now();
  const int count = arguments.count;
  const PatchSet teapot(read_bpt(std::string(PATCHWORK_SOURCE_DIR) + "/data/teapot.bpt"));
  const Sphere sphere;
  const NurbsSurface sphere_nurbs = sphere_surface(sphere);
  const PatchSet sphere_set = nurbs_patch_set(sphere_nurbs);
  std::vector<Handle(Geom_Surface)> teapot_surfaces;
  for (const BezierPatch3& patch : teapot.patches())
    teapot_surfaces.push_back(performance::detail::occt_bezier_surface(patch));
  const std::vector<Handle(Geom_Surface)> sphere_surfaces{performance::detail::occt_bspline_surface(sphere_nurbs)};
  const SampledPatches samples = sample_patches(teapot, 48);

  std::vector<Row> rows;
  const auto add = [&](std::vector<Row> more) {
    for (Row& row : more) {
      std::cerr << row.query << ", " << row.family << ": done\n";
      rows.push_back(std::move(row));
    }
  };
  add(closest_point_rows("teapot", teapot, teapot_surfaces, teapot_point_families(teapot, count, 19001),
                         [&](const Vec3& q, const Foot& ours, const std::optional<Foot>& theirs) {
                           std::vector<Foot> feet{ours};
                           if (theirs) feet.push_back(*theirs);
                           return distance_truth(teapot, samples, q, feet).distance;
                         }));
  add(closest_point_rows(
      "sphere", sphere_set, sphere_surfaces, sphere_point_families(sphere, count, 19002),
      [&](const Vec3& q, const Foot&, const std::optional<Foot>&) { return sphere_distance(sphere, q); }));
  add(curve_surface_rows("teapot", teapot, teapot_surfaces, teapot_curve_families(teapot, count, 19003),
                         [&](const CurveCase& c, const std::vector<ReportedHit>& reports, int& unresolved) {
                           const HitTruth truth = teapot_hit_truth(teapot, samples, c, reports);
                           unresolved = truth.unresolved;
                           return truth.t;
                         }));
  add(curve_surface_rows(
      "sphere", sphere_set, sphere_surfaces, sphere_curve_families(sphere, count, 19004),
      [&](const CurveCase& c, const std::vector<ReportedHit>&, int&) { return sphere_hit_truth(c, sphere); }));
  add(planar_rows(curve_pair_families(count, 19005)));

  write_file_atomically(arguments.out, document(rows, arguments.commit, count, seconds_since(start),
                                                Sizes{teapot.size(), sphere_set.size()}));
  return 0;
}

}  // namespace
}  // namespace patchwork::crosscheck

int main(int argc, char** argv) {
  try {
    return patchwork::crosscheck::run(patchwork::crosscheck::parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
