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
#include "report/queries_crosscheck_document.h"

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
