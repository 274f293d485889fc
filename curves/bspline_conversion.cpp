#include "curves/bspline_conversion.h"

#include <algorithm>
#include <limits>

#include "core/assert.h"
#include "core/errors.h"
#include "curves/continuity.h"
#include "curves/degree.h"
#include "curves/dimensions.h"
#include "curves/knot_insertion.h"

namespace patchwork {
namespace {

// The non-empty spans s in [p, n], in order.
std::vector<int> spans(const KnotVector& knots) {
  std::vector<int> result;
  for (int s = knots.degree(); s < knots.control_point_count(); ++s) {
    if (knots[s] < knots[s + 1]) result.push_back(s);
  }
  return result;
}

// The B-spline of Bezier pieces of one degree p >= 1 on contiguous intervals, with the
// multiplicity multiplicities[i] in [1, p] at the joint of pieces i and i+1: the C^0 form, then
// each knot removed p - multiplicity times, unconditionally (the caller knows the joins). Where
// two pieces' end points differ by rounding, the C^0 form keeps the first piece's end.
template <int Dim>
BSplineCurve<Dim> join_pieces(const std::vector<BezierCurve<Dim>>& pieces, const std::vector<int>& multiplicities) {
  PATCHWORK_ASSERT(!pieces.empty() && multiplicities.size() + 1 == pieces.size(), "one multiplicity per joint");
  const int p = pieces.front().degree();
  PATCHWORK_ASSERT(p >= 1, "joined pieces need degree >= 1");
  std::vector<double> knots(static_cast<std::size_t>(p) + 1, pieces.front().a());
  std::vector<Point<Dim>> points(pieces.front().control_points());
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    PATCHWORK_ASSERT(pieces[i].degree() == p && pieces[i].a() == pieces[i - 1].b(), "pieces of one degree, contiguous");
    knots.insert(knots.end(), static_cast<std::size_t>(p), pieces[i].a());
    points.insert(points.end(), pieces[i].control_points().begin() + 1, pieces[i].control_points().end());
  }
  knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, pieces.back().b());
  BSplineCurve<Dim> curve(KnotVector(p, std::move(knots)), std::move(points));
  for (std::size_t i = 0; i < multiplicities.size(); ++i) {
    const int removals = p - multiplicities[i];
    PATCHWORK_ASSERT(removals >= 0 && removals < p, "multiplicity in [1, p]");
    if (removals == 0) continue;
    auto removal = remove_knot(curve, pieces[i].b(), removals, std::numeric_limits<double>::infinity());
    PATCHWORK_ASSERT(removal.removed == removals, "an unconditional removal stopped");
    curve = std::move(removal.curve);
  }
  return curve;
}

}  // namespace

template <int Dim>
BezierCurve<Dim> bezier_piece(const BSplineCurve<Dim>& curve, int span) {
  const KnotVector& knots = curve.knot_vector();
  const int p = curve.degree();
  if (span < p || span >= knots.control_point_count() || !(knots[span] < knots[span + 1])) {
    throw InvalidInput(detail::message("bezier_piece: ", span, " is not a non-empty span in [", p, ", ",
                                       knots.control_point_count() - 1, "]"));
  }
  const double a = knots[span];
  const double b = knots[span + 1];
  std::vector<Point<Dim>> points(static_cast<std::size_t>(p) + 1);
  std::vector<double> arguments(static_cast<std::size_t>(p));
  for (int j = 0; j <= p; ++j) {
    std::fill(arguments.begin(), arguments.end(), a);
    std::fill(arguments.end() - j, arguments.end(), b);
    points[static_cast<std::size_t>(j)] = blossom(curve, span, arguments);
  }
  return BezierCurve<Dim>(std::move(points), a, b);
}

template <int Dim>
RationalBezierCurve<Dim> bezier_piece(const NurbsCurve<Dim>& curve, int span) {
  return RationalBezierCurve<Dim>(bezier_piece(curve.homogeneous(), span));
}

template <int Dim>
std::vector<BezierCurve<Dim>> bezier_pieces(const BSplineCurve<Dim>& curve) {
  std::vector<BezierCurve<Dim>> pieces;
  for (int s : spans(curve.knot_vector())) pieces.push_back(bezier_piece(curve, s));
  return pieces;
}

template <int Dim>
std::vector<RationalBezierCurve<Dim>> bezier_pieces(const NurbsCurve<Dim>& curve) {
  std::vector<RationalBezierCurve<Dim>> pieces;
  for (int s : spans(curve.knot_vector())) pieces.push_back(bezier_piece(curve, s));
  return pieces;
}

template <int Dim>
CompositeCurve<Dim> to_composite(const BSplineCurve<Dim>& curve) {
  return CompositeCurve<Dim>(bezier_pieces(curve));
}

template <int Dim>
BSplineCurve<Dim> to_bspline(const CompositeCurve<Dim>& curve, double relative_tolerance) {
  int p = 1;
  for (const auto& segment : curve.segments()) p = std::max(p, segment.degree());
  std::vector<BezierCurve<Dim>> pieces;
  for (const auto& segment : curve.segments()) pieces.push_back(elevate_degree(segment, p - segment.degree()));
  std::vector<int> multiplicities;
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const Continuity join = continuity(pieces[i - 1], pieces[i], p - 1, relative_tolerance);
    if (join.ck < 0) {
      throw InvalidInput(detail::message("to_bspline: segments ", i - 1, " and ", i, " do not meet (gap ", join.gap,
                                         ") at t = ", pieces[i].a()));
    }
    multiplicities.push_back(p - join.ck);
  }
  return join_pieces(pieces, multiplicities);
}

template <int Dim>
BSplineCurve<Dim> elevate_degree(const BSplineCurve<Dim>& curve, int times) {
  if (times < 0) throw InvalidInput(detail::message("elevate_degree: times = ", times, " is negative"));
  if (times == 0) return curve;
  const KnotVector& knots = curve.knot_vector();
  std::vector<BezierCurve<Dim>> pieces = bezier_pieces(curve);
  for (auto& piece : pieces) piece = elevate_degree(piece, times);
  std::vector<int> multiplicities;
  const std::vector<double> breakpoints = knots.breakpoints();
  for (std::size_t i = 1; i + 1 < breakpoints.size(); ++i)
    multiplicities.push_back(knots.multiplicity(breakpoints[i]) + times);
  return join_pieces(pieces, multiplicities);
}

template <int Dim>
NurbsCurve<Dim> elevate_degree(const NurbsCurve<Dim>& curve, int times) {
  return NurbsCurve<Dim>(elevate_degree(curve.homogeneous(), times));
}

template <int Dim>
NurbsCurve<Dim> join_rational_pieces(const std::vector<RationalBezierCurve<Dim>>& pieces) {
  if (pieces.empty()) throw InvalidInput("join_rational_pieces: no pieces");
  const int p = pieces.front().homogeneous().degree();
  if (p < 1) throw InvalidInput("join_rational_pieces: pieces of degree 0");
  const double n = static_cast<double>(pieces.size());
  std::vector<BezierCurve<Dim + 1>> homogeneous;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const BezierCurve<Dim + 1>& h = pieces[i].homogeneous();
    if (h.degree() != p) throw InvalidInput(detail::message("join_rational_pieces: piece ", i, " has degree ", h.degree(), ", not ", p));
    // Scaled so that its first weight is the previous piece's last (the same point, the same
    // homogeneous point: the C^0 join of the homogeneous curve).
    std::vector<Point<Dim + 1>> points = h.control_points();
    if (i > 0) {
      const Point<Dim + 1>& previous = homogeneous.back().control_points().back();
      const double scale = previous[Dim] / points.front()[Dim];
      for (auto& q : points) q *= scale;
      const Point<Dim> end = previous.template head<Dim>() / previous[Dim];
      const Point<Dim> start = points.front().template head<Dim>() / points.front()[Dim];
      if ((end - start).norm() > 1e-12 * std::max({1.0, end.norm(), start.norm()})) {
        throw InvalidInput(detail::message("join_rational_pieces: piece ", i, " does not start where piece ", i - 1, " ends"));
      }
    }
    homogeneous.emplace_back(std::move(points), static_cast<double>(i) / n, i + 1 == pieces.size() ? 1.0 : (i + 1) / n);
  }
  return NurbsCurve<Dim>(join_pieces(homogeneous, std::vector<int>(pieces.size() - 1, p)));
}

#define PATCHWORK_INSTANTIATE(D)                                              \
  template BezierCurve<D> bezier_piece(const BSplineCurve<D>&, int);          \
  template std::vector<BezierCurve<D>> bezier_pieces(const BSplineCurve<D>&); \
  template CompositeCurve<D> to_composite(const BSplineCurve<D>&);            \
  template BSplineCurve<D> to_bspline(const CompositeCurve<D>&, double);      \
  template BSplineCurve<D> elevate_degree(const BSplineCurve<D>&, int);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

#define PATCHWORK_INSTANTIATE(D)                                                    \
  template RationalBezierCurve<D> bezier_piece(const NurbsCurve<D>&, int);          \
  template std::vector<RationalBezierCurve<D>> bezier_pieces(const NurbsCurve<D>&); \
  template NurbsCurve<D> elevate_degree(const NurbsCurve<D>&, int);                 \
  template NurbsCurve<D> join_rational_pieces(const std::vector<RationalBezierCurve<D>>&);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
