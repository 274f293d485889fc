#include "queries/curve_overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "curves/degree.h"

namespace patchwork::detail {
namespace {

// The homogeneous points in standard form w_0 = w_n = 1 (see the file comment).
template <int D>
std::vector<Point<D>> standard_form(std::vector<Point<D>> H) {
  const int n = static_cast<int>(H.size()) - 1;
  const double w0 = H.front()[D - 1];
  const double rho = n > 0 ? std::pow(H.back()[D - 1] / w0, 1.0 / n) : 1.0;
  double scale = w0;
  for (auto& h : H) {
    h /= scale;
    scale *= rho;
  }
  return H;
}

template <int D>
std::vector<Point<D>> elevated(const std::vector<Point<D>>& H, int degree) {
  const int n = static_cast<int>(H.size()) - 1;
  if (degree <= n) return H;
  return elevate_degree(BezierCurve<D>(H), degree - n).control_points();
}

// Whether the homogeneous control points describe the same piece within `match` (positions)
// and 1e-9 (standard-form weights).
template <int Dim>
bool same_piece(const std::vector<Point<Dim + 1>>& first, const std::vector<Point<Dim + 1>>& second, double match) {
  const int degree = std::max(static_cast<int>(first.size()), static_cast<int>(second.size())) - 1;
  const auto F = standard_form(elevated(first, degree));
  const auto S = standard_form(elevated(second, degree));
  for (std::size_t i = 0; i < F.size(); ++i) {
    const double wf = F[i][Dim], ws = S[i][Dim];
    if (!(std::abs(wf - ws) <= 1e-9 * std::max(wf, ws))) return false;
    if (!((F[i].template head<Dim>() / wf - S[i].template head<Dim>() / ws).norm() <= match)) return false;
  }
  return true;
}

}  // namespace

template <int Dim>
std::pair<double, double> project_onto(const RationalBezierCurve<Dim>& curve, const Point<Dim>& q, double s0, double s1) {
  constexpr int samples = 9;
  double s = s0;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k) {
    const double candidate = std::clamp(s0 + (s1 - s0) * k / (samples - 1), curve.a(), curve.b());
    const double distance = (curve.evaluate(candidate) - q).norm();
    if (distance < best) best = distance, s = candidate;
  }
  const double best_sample = s;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const auto [C, d1, d2] = point_and_derivatives(curve, s);
    const Point<Dim> r = C - q;
    const double f = d1.dot(r);
    const double df = d2.dot(r) + d1.squaredNorm();
    if (!(df > 0.0)) break;
    const double next = std::clamp(s - f / df, curve.a(), curve.b());
    const double step = std::abs(next - s);
    s = next;
    if (step <= 1e-16 * (curve.b() - curve.a())) break;
  }
  const double distance = (curve.evaluate(s) - q).norm();
  return distance <= best ? std::pair{s, distance} : std::pair{best_sample, best};
}

template <int Dim>
std::optional<std::pair<double, double>> lies_on(const CurvePiece<Dim>& piece, const RationalBezierCurve<Dim>& other,
                                                 const CurvePiece<Dim>& hint, double match) {
  const auto [y0, d0] = project_onto(other, piece.P.front(), hint.t0, hint.t1);
  if (!(d0 <= match)) return std::nullopt;
  const auto [y1, d1] = project_onto(other, piece.P.back(), hint.t0, hint.t1);
  if (!(d1 <= match)) return std::nullopt;
  if (!(std::abs(y1 - y0) > 1e-12 * (other.b() - other.a()))) return std::nullopt;
  auto H = reparametrized(other.homogeneous().control_points(), other.a(), other.b(), y0, y1);
  if (!same_piece<Dim>(piece.H, H, match)) return std::nullopt;
  return std::pair{y0, y1};
}

std::vector<CurveOverlap> merge_touching(std::vector<CurveOverlap> list, double t_margin, double s_margin) {
  std::sort(list.begin(), list.end(), [](const CurveOverlap& x, const CurveOverlap& y) { return x.t0 < y.t0; });
  std::vector<CurveOverlap> result;
  for (const CurveOverlap& o : list) {
    if (!result.empty()) {
      CurveOverlap& last = result.back();
      const bool same_direction = (last.s1 > last.s0) == (o.s1 > o.s0);
      const double lo = std::min(o.s0, o.s1), hi = std::max(o.s0, o.s1);
      const double last_lo = std::min(last.s0, last.s1), last_hi = std::max(last.s0, last.s1);
      if (same_direction && o.t0 <= last.t1 + t_margin && lo <= last_hi + s_margin && last_lo <= hi + s_margin) {
        if (o.t1 > last.t1) last.t1 = o.t1, last.s1 = o.s1;
        continue;
      }
    }
    result.push_back(o);
  }
  return result;
}

// The foot of q on curve by Newton from `guess`, kept in [lo, hi]: the branch nearest the guess
// (project_onto samples the whole range first, and may pick another branch through q).
template <int Dim>
std::pair<double, double> project_near(const RationalBezierCurve<Dim>& curve, const Point<Dim>& q, double guess, double lo,
                                       double hi) {
  double s = std::clamp(guess, lo, hi);
  for (int iteration = 0; iteration < 40; ++iteration) {
    const auto [C, d1, d2] = point_and_derivatives(curve, s);
    const Point<Dim> r = C - q;
    const double df = d2.dot(r) + d1.squaredNorm();
    if (!(df > 0.0)) break;
    const double next = std::clamp(s - d1.dot(r) / df, lo, hi);
    const double step = std::abs(next - s);
    s = next;
    if (step <= 1e-16 * (curve.b() - curve.a())) break;
  }
  return {s, (curve.evaluate(s) - q).norm()};
}

// The foot of an end of `first` on `second`, on the side [lo, hi] the overlap continues to:
// first from where the overlap's correspondence, carried on linearly, puts it; else sampled.
template <int Dim>
std::pair<double, double> continued_foot(const RationalBezierCurve<Dim>& second, const Point<Dim>& q, double guess,
                                         double lo, double hi, double match) {
  const auto near = project_near(second, q, guess, lo, hi);
  return near.second <= match ? near : project_onto(second, q, lo, hi);
}

template <int Dim>
CurveOverlap continued_overlap(CurveOverlap o, const RationalBezierCurve<Dim>& first,
                               const RationalBezierCurve<Dim>& second, double match) {
  const double direction = o.s1 > o.s0 ? 1.0 : -1.0;
  // ds / dt along the overlap found, to carry the correspondence on to the curve's ends.
  const double slope = o.t1 > o.t0 ? (o.s1 - o.s0) / (o.t1 - o.t0) : direction;
  // Each end is looked for on the side the overlap continues to, nearest the correspondence (a
  // search over the whole other curve can land on another branch of it through the same point,
  // a loop's, and lose the overlap).
  if (o.t0 > first.a()) {
    const double guess = o.s0 + slope * (first.a() - o.t0);
    const auto [s, d] = direction > 0 ? continued_foot(second, first.evaluate(first.a()), guess, second.a(), o.s0, match)
                                      : continued_foot(second, first.evaluate(first.a()), guess, o.s0, second.b(), match);
    const double end = direction > 0 ? second.a() : second.b();
    if (d <= match && (s - o.s0) * direction <= 0.0) {
      o.t0 = first.a(), o.s0 = s;
    } else if (const auto [t, e] = project_onto(first, second.evaluate(end), first.a(), o.t0); e <= match && t <= o.t0) {
      o.t0 = t, o.s0 = end;
    }
  }
  if (o.t1 < first.b()) {
    const double guess = o.s1 + slope * (first.b() - o.t1);
    const auto [s, d] = direction > 0 ? continued_foot(second, first.evaluate(first.b()), guess, o.s1, second.b(), match)
                                      : continued_foot(second, first.evaluate(first.b()), guess, second.a(), o.s1, match);
    const double end = direction > 0 ? second.b() : second.a();
    if (d <= match && (s - o.s1) * direction >= 0.0) {
      o.t1 = first.b(), o.s1 = s;
    } else if (const auto [t, e] = project_onto(first, second.evaluate(end), o.t1, first.b()); e <= match && t >= o.t1) {
      o.t1 = t, o.s1 = end;
    }
  }
  return o;
}

template <int Dim>
std::optional<CurveOverlap> whole_overlap(const CurveOverlap& found, const RationalBezierCurve<Dim>& first,
                                          const RationalBezierCurve<Dim>& second, double match) {
  const CurveOverlap o = continued_overlap(found, first, second, match);
  // Each end of a coincidence is an end of one of the curves (see the header).
  const bool starts = o.t0 == first.a() || o.s0 == second.a() || o.s0 == second.b();
  const bool ends = o.t1 == first.b() || o.s1 == second.a() || o.s1 == second.b();
  if (!starts || !ends) return std::nullopt;
  const CurvePiece<Dim> piece = curve_piece(first, o.t0, o.t1);
  const CurvePiece<Dim> hint = curve_piece(second, std::min(o.s0, o.s1), std::max(o.s0, o.s1));
  const auto on = lies_on(piece, second, hint, match);
  if (!on) return std::nullopt;
  return CurveOverlap{o.t0, o.t1, on->first, on->second};
}

template <int Dim>
std::vector<CurveOverlap> merged_overlaps(std::vector<CurveOverlap> overlaps, const RationalBezierCurve<Dim>& first,
                                          const RationalBezierCurve<Dim>& second, double match) {
  const double t_margin = 1e-12 * (first.b() - first.a());
  const double s_margin = 1e-12 * (second.b() - second.a());
  overlaps = merge_touching(std::move(overlaps), t_margin, s_margin);
  for (CurveOverlap& o : overlaps) o = continued_overlap(o, first, second, match);
  return merge_touching(std::move(overlaps), t_margin, s_margin);
}

#define PATCHWORK_INSTANTIATE(D)                                                                                     \
  template std::pair<double, double> project_onto(const RationalBezierCurve<D>&, const Point<D>&, double, double);   \
  template std::optional<std::pair<double, double>> lies_on(const CurvePiece<D>&, const RationalBezierCurve<D>&,     \
                                                            const CurvePiece<D>&, double);                           \
  template std::vector<CurveOverlap> merged_overlaps(std::vector<CurveOverlap>, const RationalBezierCurve<D>&,       \
                                                     const RationalBezierCurve<D>&, double);                         \
  template std::optional<CurveOverlap> whole_overlap(const CurveOverlap&, const RationalBezierCurve<D>&,             \
                                                     const RationalBezierCurve<D>&, double);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork::detail
