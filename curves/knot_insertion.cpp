#include "curves/knot_insertion.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "curves/curve_checks.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

template <int Dim>
double largest_norm(const std::vector<Point<Dim>>& points) {
  double largest = 0.0;
  for (const auto& p : points) largest = std::max(largest, p.norm());
  return largest;
}

// u inserted `times` times where it has multiplicity s, k the last knot index with u_k <= u (A5.1).
template <int Dim>
BSplineCurve<Dim> boehm(const BSplineCurve<Dim>& curve, double u, int times) {
  const KnotVector& U = curve.knot_vector();
  const auto& P = curve.control_points();
  const int p = curve.degree();
  const int n = U.control_point_count() - 1;
  const int k = static_cast<int>(std::upper_bound(U.knots().begin(), U.knots().end(), u) - U.knots().begin()) - 1;
  const int s = U.multiplicity(u);
  PATCHWORK_ASSERT(s + times <= p && k >= p && k - s <= n, "insertion outside the checked range");

  std::vector<double> knots(U.knots());
  knots.insert(knots.begin() + k + 1, at(times), u);
  std::vector<Point<Dim>> Q(P.size() + at(times));
  for (int i = 0; i <= k - p; ++i) Q[at(i)] = P[at(i)];
  for (int i = k - s; i <= n; ++i) Q[at(i + times)] = P[at(i)];
  std::vector<Point<Dim>> R(P.begin() + (k - p), P.begin() + (k - s + 1));
  int L = k - p;
  for (int j = 1; j <= times; ++j) {
    L = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (u - U[L + i]) / (U[i + k + 1] - U[L + i]);
      R[at(i)] = alpha * R[at(i) + 1] + (1.0 - alpha) * R[at(i)];
    }
    Q[at(L)] = R[0];
    Q[at(k + times - j - s)] = R[at(p - j - s)];
  }
  for (int i = L + 1; i < k - s; ++i) Q[at(i)] = R[at(i - L)];
  return BSplineCurve<Dim>(KnotVector(p, std::move(knots)), std::move(Q));
}

template <int Dim>
void check_insertion(const char* function, const BSplineCurve<Dim>& curve, double u, int times) {
  detail::check_parameter(function, u);
  if (u < curve.a() || u > curve.b()) {
    throw InvalidInput(
        detail::message(function, ": u = ", u, " is outside the valid range [", curve.a(), ", ", curve.b(), "]"));
  }
  if (times < 0) throw InvalidInput(detail::message(function, ": times = ", times, " is negative"));
  const int s = curve.knot_vector().multiplicity(u);
  if (s + times > curve.degree()) {
    throw InvalidInput(detail::message(function, ": knot ", u, " of multiplicity ", s, " inserted ", times,
                                       " times would exceed the degree ", curve.degree()));
  }
}

// One removal of the interior knot u (last index r, multiplicity s): the k = p - s + 1 relations
// P_{first+e} = alpha_e Q[e+1] + (1 - alpha_e) Q[e], e = 0..k-1, with Q[0] = P_{first-1} and
// Q[k] = P_{last+1} known, solved for Q[1..k-1] from the left up to the middle and from the right
// down to it (A5.8 with one removal); the middle relation is the one left over.
template <int Dim>
BSplineCurve<Dim> remove_once(const BSplineCurve<Dim>& curve, double u) {
  const KnotVector& U = curve.knot_vector();
  const auto& P = curve.control_points();
  const int p = curve.degree();
  const int r = static_cast<int>(std::upper_bound(U.knots().begin(), U.knots().end(), u) - U.knots().begin()) - 1;
  const int s = U.multiplicity(u);
  const int first = r - p;
  const int last = r - s;
  const int k = last - first + 1;
  PATCHWORK_ASSERT(first >= 1 && last + 1 < static_cast<int>(P.size()), "removal of a knot outside (a, b)");
  // 0 < alpha_e < 1: u_{first+e} < u (indices before u's first copy) and u_{first+e+p+1} > u.
  const auto alpha = [&](int e) { return (u - U[first + e]) / (U[first + e + p + 1] - U[first + e]); };
  std::vector<Point<Dim>> Q(at(k) + 1);
  Q[0] = P[at(first - 1)];
  Q[at(k)] = P[at(last + 1)];
  const int middle = (k - 1) / 2;
  for (int e = 0; e < middle; ++e) Q[at(e) + 1] = (P[at(first + e)] - (1.0 - alpha(e)) * Q[at(e)]) / alpha(e);
  for (int e = k - 1; e > middle; --e) Q[at(e)] = (P[at(first + e)] - alpha(e) * Q[at(e) + 1]) / (1.0 - alpha(e));

  std::vector<Point<Dim>> points(P.begin(), P.begin() + first);
  points.insert(points.end(), Q.begin() + 1, Q.end() - 1);
  points.insert(points.end(), P.begin() + last + 1, P.end());
  std::vector<double> knots(U.knots());
  knots.erase(knots.begin() + r);
  return BSplineCurve<Dim>(KnotVector(p, std::move(knots)), std::move(points));
}

// d = max_i |P_i - R_i| with R the candidate re-inserted `times` times at u on the original's
// knots, plus the rounding of computing R (a few ulps of the largest point per insertion).
template <int Dim>
double homogeneous_distance(const BSplineCurve<Dim>& original, const BSplineCurve<Dim>& candidate, double u,
                            int times) {
  const BSplineCurve<Dim> reconstructed = boehm(candidate, u, times);
  PATCHWORK_ASSERT(reconstructed.knot_vector() == original.knot_vector(), "re-insertion gives other knots");
  double d = 0.0;
  for (std::size_t i = 0; i < original.control_points().size(); ++i) {
    d = std::max(d, (original.control_points()[i] - reconstructed.control_points()[i]).norm());
  }
  const double scale =
      std::max(largest_norm<Dim>(original.control_points()), largest_norm<Dim>(candidate.control_points()));
  return d + 4.0 * (times + 1) * Dim * std::numeric_limits<double>::epsilon() * scale;
}

void check_removal(const char* function, const KnotVector& knots, double u, int times, double tolerance) {
  detail::check_parameter(function, u);
  const int s = knots.multiplicity(u);
  if (!(knots.a() < u && u < knots.b()) || s == 0) {
    throw InvalidInput(detail::message(function, ": u = ", u, " is not a knot inside the valid range (", knots.a(),
                                       ", ", knots.b(), ")"));
  }
  if (times < 1 || times > s) {
    throw InvalidInput(
        detail::message(function, ": times = ", times, " is not in [1, ", s, "] (the multiplicity of ", u, ")"));
  }
  if (std::isnan(tolerance) || tolerance < 0.0) {
    throw InvalidInput(detail::message(function, ": tolerance ", tolerance, " is negative or NaN"));
  }
}

// Removes u up to `times` times from the polynomial curve `curve`; bound(candidate, t) is the
// guaranteed change of the t-fold removal, or nothing where the candidate is not a valid curve.
template <int Dim>
KnotRemoval<BSplineCurve<Dim>> remove_within(
    const BSplineCurve<Dim>& curve, double u, int times, double tolerance,
    const std::function<std::optional<double>(const BSplineCurve<Dim>&, int)>& bound) {
  // The bound is not monotone in t (each t-fold removal is re-inserted on its own), so every
  // removal up to `times` is tried and the last one within the tolerance kept.
  KnotRemoval<BSplineCurve<Dim>> result{curve, 0, 0.0};
  BSplineCurve<Dim> candidate = curve;
  for (int t = 1; t <= times; ++t) {
    candidate = remove_once(candidate, u);
    const std::optional<double> change = bound(candidate, t);
    if (change && *change <= tolerance) result = {candidate, t, *change};
  }
  return result;
}

}  // namespace

template <int Dim>
BSplineCurve<Dim> insert_knot(const BSplineCurve<Dim>& curve, double u, int times) {
  check_insertion("insert_knot", curve, u, times);
  if (times == 0) return curve;
  return boehm(curve, u, times);
}

template <int Dim>
NurbsCurve<Dim> insert_knot(const NurbsCurve<Dim>& curve, double u, int times) {
  return NurbsCurve<Dim>(insert_knot(curve.homogeneous(), u, times));
}

template <int Dim>
BSplineCurve<Dim> refine_knots(const BSplineCurve<Dim>& curve, std::span<const double> knots) {
  std::vector<double> sorted(knots.begin(), knots.end());
  for (double u : sorted) detail::check_parameter("refine_knots", u);
  std::sort(sorted.begin(), sorted.end());
  BSplineCurve<Dim> refined = curve;
  for (double u : sorted) {
    check_insertion("refine_knots", refined, u, 1);
    refined = boehm(refined, u, 1);
  }
  return refined;
}

template <int Dim>
NurbsCurve<Dim> refine_knots(const NurbsCurve<Dim>& curve, std::span<const double> knots) {
  return NurbsCurve<Dim>(refine_knots(curve.homogeneous(), knots));
}

template <int Dim>
KnotRemoval<BSplineCurve<Dim>> remove_knot(const BSplineCurve<Dim>& curve, double u, int times, double tolerance) {
  check_removal("remove_knot", curve.knot_vector(), u, times, tolerance);
  return remove_within<Dim>(curve, u, times, tolerance, [&](const BSplineCurve<Dim>& candidate, int t) {
    return std::optional<double>(homogeneous_distance(curve, candidate, u, t));
  });
}

template <int Dim>
KnotRemoval<NurbsCurve<Dim>> remove_knot(const NurbsCurve<Dim>& curve, double u, int times, double tolerance) {
  check_removal("remove_knot", curve.knot_vector(), u, times, tolerance);
  double largest_point = 0.0;
  for (int i = 0; i < curve.control_point_count(); ++i)
    largest_point = std::max(largest_point, curve.control_point(i).norm());
  const auto& H = curve.homogeneous();
  auto removal = remove_within<Dim + 1>(H, u, times, tolerance, [&](const BSplineCurve<Dim + 1>& candidate, int t) {
    double smallest_weight = std::numeric_limits<double>::infinity();
    for (const auto& h : candidate.control_points()) smallest_weight = std::min(smallest_weight, h[Dim]);
    if (!(smallest_weight > 0.0)) return std::optional<double>();  // not a NURBS curve: refused
    return std::optional<double>(homogeneous_distance(H, candidate, u, t) * (1.0 + largest_point) / smallest_weight);
  });
  return {NurbsCurve<Dim>(std::move(removal.curve)), removal.removed, removal.bound};
}

#define PATCHWORK_INSTANTIATE(D)                                                          \
  template BSplineCurve<D> insert_knot(const BSplineCurve<D>&, double, int);              \
  template BSplineCurve<D> refine_knots(const BSplineCurve<D>&, std::span<const double>); \
  template KnotRemoval<BSplineCurve<D>> remove_knot(const BSplineCurve<D>&, double, int, double);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

#define PATCHWORK_INSTANTIATE(D)                                                      \
  template NurbsCurve<D> insert_knot(const NurbsCurve<D>&, double, int);              \
  template NurbsCurve<D> refine_knots(const NurbsCurve<D>&, std::span<const double>); \
  template KnotRemoval<NurbsCurve<D>> remove_knot(const NurbsCurve<D>&, double, int, double);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
