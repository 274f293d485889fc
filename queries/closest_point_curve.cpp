// Closest points of curves: branch and bound over halved pieces (queries/closest_point.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "queries/closest_point.h"
#include "queries/net_piece.h"
#include "queries/query_arguments.h"

namespace patchwork {
namespace {

constexpr double unbounded = std::numeric_limits<double>::infinity();

// One Bezier segment of the curve in homogeneous form (w = 1 when polynomial), for halving, and
// its exact evaluation for Newton.
template <int Dim>
struct Segment {
  std::vector<Point<Dim + 1>> points;
  double a, b;
  // C, C', C'' at t (the curve's own parameter).
  std::array<Point<Dim>, 3> (*derivatives)(const void* curve, double t);
  const void* curve;
};

template <int Dim>
std::array<Point<Dim>, 3> bezier_derivatives(const void* curve, double t) {
  const auto d = derivatives(*static_cast<const BezierCurve<Dim>*>(curve), t, 2);
  return {d[0], d[1], d[2]};
}

template <int Dim>
std::array<Point<Dim>, 3> rational_derivatives(const void* curve, double t) {
  const auto& c = *static_cast<const RationalBezierCurve<Dim>*>(curve);
  return {c.evaluate(t), derivative(c, t, 1), derivative(c, t, 2)};
}

template <int Dim>
Segment<Dim> segment_of(const BezierCurve<Dim>& curve) {
  Segment<Dim> s{{}, curve.a(), curve.b(), &bezier_derivatives<Dim>, &curve};
  for (const auto& p : curve.control_points()) {
    Point<Dim + 1> h;
    h << p, 1.0;
    s.points.push_back(h);
  }
  return s;
}

template <int Dim>
Segment<Dim> segment_of(const RationalBezierCurve<Dim>& curve) {
  return {curve.homogeneous().control_points(), curve.a(), curve.b(), &rational_derivatives<Dim>, &curve};
}

template <int Dim>
struct CurvePiece {
  double lower;
  int segment;
  double t0, t1;
  int depth;
  std::vector<Point<Dim + 1>> points;
  bool operator>(const CurvePiece& other) const { return lower > other.lower; }
};

template <int Dim>
Point<Dim> dehomogenised(const Point<Dim + 1>& h) {
  return h.template head<Dim>() / h[Dim];
}

template <int Dim>
double margin_of(const std::vector<Point<Dim + 1>>& points, int depth) {
  double size = 0.0;
  for (const auto& h : points) size = std::max(size, dehomogenised<Dim>(h).cwiseAbs().maxCoeff());
  return 8.0 * (depth + 4) * (static_cast<double>(points.size()) + 1) * unit_roundoff * size;
}

// The distance from q to a cylinder about the chord P_0 P_n that holds every control point (the
// convex hull, hence the piece): a second-order lower bound (see the header).
template <int Dim>
double lower_bound(const std::vector<Point<Dim + 1>>& points, int depth, const Point<Dim>& q) {
  const Point<Dim> p0 = dehomogenised<Dim>(points.front());
  const Point<Dim> axis_vector = dehomogenised<Dim>(points.back()) - p0;
  const double length = axis_vector.norm();
  double distance = 0.0;
  if (!(length > 0.0)) {
    Eigen::AlignedBox<double, Dim> box;
    for (const auto& h : points) box.extend(dehomogenised<Dim>(h));
    distance = std::sqrt(box.squaredExteriorDistance(q));
  } else {
    const Point<Dim> axis = axis_vector / length;
    double low = unbounded, high = -unbounded, radius = 0.0;
    for (const auto& h : points) {
      const Point<Dim> d = dehomogenised<Dim>(h) - p0;
      const double along = d.dot(axis);
      low = std::min(low, along);
      high = std::max(high, along);
      radius = std::max(radius, (d - along * axis).norm());
    }
    const Point<Dim> dq = q - p0;
    const double along_q = dq.dot(axis);
    const double radial = std::max(0.0, (dq - along_q * axis).norm() - radius);
    const double axial = std::max({0.0, low - along_q, along_q - high});
    distance = std::sqrt(radial * radial + axial * axial);
  }
  return std::max(0.0, distance - margin_of<Dim>(points, depth));
}

template <int Dim>
std::pair<std::vector<Point<Dim + 1>>, std::vector<Point<Dim + 1>>> halved(const std::vector<Point<Dim + 1>>& points) {
  std::vector<Point<Dim + 1>> work = points, left(points.size()), right(points.size());
  const std::size_t count = points.size();
  for (std::size_t r = 0; r < count; ++r) {
    left[r] = work[0];
    right[count - 1 - r] = work[count - 1 - r];
    for (std::size_t i = 0; i + 1 < count - r; ++i) work[i] = 0.5 * (work[i] + work[i + 1]);
  }
  return {std::move(left), std::move(right)};
}

struct Foot {
  int segment;
  double t;
  double distance;
};

// Newton on g(t) = C'(t).(C(t) - q) from t, clamped to [a, b]; the local minimum it reaches.
template <int Dim>
Foot newton_foot(const Segment<Dim>& segment, int index, double t, const Point<Dim>& q) {
  double best_t = t;
  double best = (segment.derivatives(segment.curve, t)[0] - q).norm();
  for (int iteration = 0; iteration < 32; ++iteration) {
    const auto d = segment.derivatives(segment.curve, t);
    const Point<Dim> r = d[0] - q;
    const double g = d[1].dot(r);
    double gp = d[2].dot(r) + d[1].squaredNorm();
    double step = 0.0;
    if (gp > 0.0) {
      step = -g / gp;
    } else {
      // Not convex here: a gradient step of the size of the parameter range's hundredth.
      step = g > 0 ? -(segment.b - segment.a) / 100 : (segment.b - segment.a) / 100;
    }
    const double next = std::clamp(t + step, segment.a, segment.b);
    const Point<Dim> point = segment.derivatives(segment.curve, next)[0];
    const double distance = (point - q).norm();
    // Equal up to rounding counts as no worse: at a minimum the distance is flat, and the
    // converged, orthogonal foot is the one to keep.
    if (distance <= best + 8 * unit_roundoff * (best + q.cwiseAbs().maxCoeff() + point.cwiseAbs().maxCoeff())) {
      best = distance;
      best_t = next;
    }
    if (std::abs(next - t) <= 4 * unit_roundoff * std::max({std::abs(t), std::abs(segment.a), std::abs(segment.b)})) break;
    t = next;
  }
  return {index, best_t, best};
}

template <int Dim>
CurveClosestPoint<Dim> search(const std::vector<Segment<Dim>>& segments, const Point<Dim>& q,
                              const ClosestPointOptions& options) {
  require_finite(q, "closest_point", "point");
  Eigen::AlignedBox<double, Dim> box;
  for (const auto& s : segments)
    for (const auto& h : s.points) box.extend(dehomogenised<Dim>(h));
  box.extend(q);
  const double size = std::max(box.diagonal().norm(), std::numeric_limits<double>::min());
  const double gap = options.relative_gap * size;
  const double separation = options.relative_separation * size;
  const double newton_threshold = 1e-6 * size;

  std::vector<Foot> feet;
  Foot best{0, segments[0].a, unbounded};
  auto offer = [&](const Foot& foot, bool is_local_minimum) {
    if (is_local_minimum) feet.push_back(foot);
    if (foot.distance < best.distance) best = foot;
  };

  std::priority_queue<CurvePiece<Dim>, std::vector<CurvePiece<Dim>>, std::greater<>> heap;
  for (int s = 0; s < static_cast<int>(segments.size()); ++s) {
    const auto& seg = segments[static_cast<std::size_t>(s)];
    offer({s, seg.a, (dehomogenised<Dim>(seg.points.front()) - q).norm()}, false);
    offer({s, seg.b, (dehomogenised<Dim>(seg.points.back()) - q).norm()}, false);
    heap.push({lower_bound<Dim>(seg.points, 0, q), s, seg.a, seg.b, 0, seg.points});
  }
  double pruned_lower = unbounded;
  double lower = unbounded;
  std::int64_t examined = 0;
  while (!heap.empty()) {
    CurvePiece<Dim> piece = heap.top();
    if (piece.lower >= best.distance - gap) {
      lower = piece.lower;
      break;
    }
    heap.pop();
    if (++examined > options.max_pieces) {
      lower = piece.lower;
      break;
    }
    const auto& seg = segments[static_cast<std::size_t>(piece.segment)];
    if (best.distance - piece.lower > newton_threshold || piece.depth == 0)
      offer(newton_foot(seg, piece.segment, 0.5 * (piece.t0 + piece.t1), q), true);
    auto [left, right] = halved<Dim>(piece.points);
    const double mid = 0.5 * (piece.t0 + piece.t1);
    offer({piece.segment, mid, (dehomogenised<Dim>(left.back()) - q).norm()}, false);
    CurvePiece<Dim> children[2] = {{0, piece.segment, piece.t0, mid, piece.depth + 1, std::move(left)},
                                   {0, piece.segment, mid, piece.t1, piece.depth + 1, std::move(right)}};
    for (auto& child : children) {
      if (!(child.t0 < child.t1)) continue;  // the parameter cannot be halved further
      child.lower = lower_bound<Dim>(child.points, child.depth, q);
      if (child.lower >= best.distance - gap)
        pruned_lower = std::min(pruned_lower, child.lower);
      else
        heap.push(std::move(child));
    }
  }
  // A foot found as a piece's end point is polished by Newton (equal distance up to rounding, but
  // orthogonal); its distance is then taken from the exact curve.
  {
    const Foot polished = newton_foot(segments[static_cast<std::size_t>(best.segment)], best.segment, best.t, q);
    if (polished.distance <= best.distance + 8 * unit_roundoff * (best.distance + size)) best = polished;
  }
  const auto& seg = segments[static_cast<std::size_t>(best.segment)];
  const Point<Dim> foot = seg.derivatives(seg.curve, best.t)[0];
  CurveClosestPoint<Dim> result;
  result.distance = (foot - q).norm();
  result.point = foot;
  result.t = best.t;
  result.lower_bound = std::clamp(std::min({lower, pruned_lower, best.distance}), 0.0, result.distance);
  result.pieces = examined;
  for (const Foot& f : feet) {
    const auto& s = segments[static_cast<std::size_t>(f.segment)];
    if (f.distance <= best.distance + 4 * gap &&
        (s.derivatives(s.curve, f.t)[0] - foot).norm() > separation)
      result.attained_more_than_once = true;
  }
  return result;
}

}  // namespace

template <int Dim>
CurveClosestPoint<Dim> closest_point(const BezierCurve<Dim>& curve, const Point<Dim>& q, const ClosestPointOptions& options) {
  return search<Dim>({segment_of(curve)}, q, options);
}

template <int Dim>
CurveClosestPoint<Dim> closest_point(const RationalBezierCurve<Dim>& curve, const Point<Dim>& q,
                                     const ClosestPointOptions& options) {
  return search<Dim>({segment_of(curve)}, q, options);
}

template <int Dim>
CurveClosestPoint<Dim> closest_point(const BSplineCurve<Dim>& curve, const Point<Dim>& q, const ClosestPointOptions& options) {
  const std::vector<BezierCurve<Dim>> pieces = bezier_pieces(curve);
  std::vector<Segment<Dim>> segments;
  for (const auto& piece : pieces) segments.push_back(segment_of(piece));
  return search<Dim>(segments, q, options);
}

template <int Dim>
CurveClosestPoint<Dim> closest_point(const NurbsCurve<Dim>& curve, const Point<Dim>& q, const ClosestPointOptions& options) {
  const std::vector<RationalBezierCurve<Dim>> pieces = bezier_pieces(curve);
  std::vector<Segment<Dim>> segments;
  for (const auto& piece : pieces) segments.push_back(segment_of(piece));
  return search<Dim>(segments, q, options);
}

#define PATCHWORK_INSTANTIATE(Dim)                                                                                     \
  template CurveClosestPoint<Dim> closest_point(const BezierCurve<Dim>&, const Point<Dim>&, const ClosestPointOptions&);  \
  template CurveClosestPoint<Dim> closest_point(const RationalBezierCurve<Dim>&, const Point<Dim>&,                   \
                                                const ClosestPointOptions&);                                            \
  template CurveClosestPoint<Dim> closest_point(const BSplineCurve<Dim>&, const Point<Dim>&, const ClosestPointOptions&); \
  template CurveClosestPoint<Dim> closest_point(const NurbsCurve<Dim>&, const Point<Dim>&, const ClosestPointOptions&);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
