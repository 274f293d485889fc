#include "queries/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "curves/bernstein.h"
#include "queries/intersection_kernel.h"
#include "queries/query_arguments.h"

namespace patchwork {
namespace {

constexpr int max_depth = 40;

// The Bernstein coefficients of the hodograph's numerator N = H'_xyz w - H_xyz w' (C' = N / w^2)
// of the homogeneous control points H, by products (degree 2n - 2).
template <int Dim>
std::vector<Point<Dim>> hodograph_numerator(const std::vector<Point<Dim + 1>>& H) {
  const int n = static_cast<int>(H.size()) - 1;
  std::vector<Point<Dim>> N;
  if (n == 0) return N;
  std::vector<double> w(H.size()), dw(static_cast<std::size_t>(n)), coordinate(H.size()),
      d_coordinate(static_cast<std::size_t>(n));
  for (int i = 0; i <= n; ++i) w[i] = H[i][Dim];
  for (int i = 0; i < n; ++i) dw[i] = n * (H[i + 1][Dim] - H[i][Dim]);
  for (int c = 0; c < Dim; ++c) {
    for (int i = 0; i <= n; ++i) coordinate[i] = H[i][c];
    for (int i = 0; i < n; ++i) d_coordinate[i] = n * (H[i + 1][c] - H[i][c]);
    const auto first = bernstein_product(d_coordinate, w);
    const auto second = bernstein_product(coordinate, dw);
    N.resize(first.size());
    for (std::size_t k = 0; k < first.size(); ++k) N[k][c] = first[k] - second[k];
  }
  return N;
}

// The rounding level of the hodograph numerator's coefficients on any piece of the curve (file
// comment): 64 n^2 u max |H_xyz| max w.
template <int Dim>
double hodograph_noise(const RationalBezierCurve<Dim>& curve) {
  double scale = 0.0, w_max = 0.0;
  for (const auto& H : curve.homogeneous().control_points()) {
    scale = std::max(scale, H.template head<Dim>().cwiseAbs().maxCoeff());
    w_max = std::max(w_max, H[Dim]);
  }
  const int n = curve.degree();
  return 64.0 * n * n * 0x1p-53 * scale * w_max;
}

// Whether the piece's hodograph numerator lies in an open half-space cone, its coefficients within
// `noise` of zero left out (file comment).
template <int Dim>
bool monotone(const std::vector<Point<Dim>>& N, double noise) {
  const auto counts = [noise](const Point<Dim>& direction) { return direction.norm() > noise; };
  if (std::none_of(N.begin(), N.end(), counts)) return true;  // a point
  Point<Dim> v = Point<Dim>::Zero();
  for (const auto& direction : N) {
    if (counts(direction)) v += direction.normalized();
  }
  if (!(v.norm() > 0.0)) return false;
  v.normalize();
  for (const auto& direction : N) {
    if (counts(direction) && !(v.dot(direction) >= 1e-3 * direction.norm())) return false;
  }
  return true;
}

// Where on the piece (local parameter in [0, 1]) the hodograph numerator N is shortest, and |N|
// there: the best of 33 samples, refined by golden-section search between its neighbours.
template <int Dim>
std::pair<double, double> slowest(const std::vector<Point<Dim>>& N) {
  std::array<std::vector<double>, Dim> coordinates;
  for (int c = 0; c < Dim; ++c) {
    for (const auto& coefficient : N) coordinates[c].push_back(coefficient[c]);
  }
  double best_tau = 0.0, best = std::numeric_limits<double>::infinity();
  const auto speed = [&](double tau) {
    Point<Dim> value;
    for (int c = 0; c < Dim; ++c) value[c] = bernstein_evaluate(coordinates[c], tau);
    const double length = value.norm();
    if (length < best) best = length, best_tau = tau;
    return length;
  };
  constexpr int samples = 32;
  for (int k = 0; k <= samples; ++k) speed(static_cast<double>(k) / samples);
  const double centre = best_tau;
  detail::golden_section(std::max(0.0, centre - 1.0 / samples), std::min(1.0, centre + 1.0 / samples), speed);
  return {best_tau, best};
}

// Splits [t0, t1] into monotone pieces (file comment): at a zero of the hodograph inside, else in
// halves.
template <int Dim>
void monotone_pieces(const RationalBezierCurve<Dim>& curve, double t0, double t1, int depth, double noise,
                     std::vector<RationalBezierCurve<Dim>>& pieces) {
  const auto H = detail::reparametrized(curve.homogeneous().control_points(), curve.a(), curve.b(), t0, t1);
  const std::vector<Point<Dim>> N = hodograph_numerator<Dim>(H);
  double cut = 0.5 * (t0 + t1);
  if (depth >= max_depth || monotone<Dim>(N, noise) || !(t0 < cut && cut < t1)) {
    pieces.emplace_back(BezierCurve<Dim + 1>(H, t0, t1));
    return;
  }
  const auto [tau, speed] = slowest<Dim>(N);
  if (speed <= noise / 8.0 && 1.0 / 64.0 <= tau && tau <= 63.0 / 64.0) cut = t0 + tau * (t1 - t0);
  monotone_pieces(curve, t0, cut, depth + 1, noise, pieces);
  monotone_pieces(curve, cut, t1, depth + 1, noise, pieces);
}

// A curve on one line (every control point within eps of the line through the first control
// point and the farthest one from it): its position along the line p(t) = u . (C(t) - origin),
// u the unit direction, and the runs on which p is monotone.
template <int Dim>
class CurveOnLine {
 public:
  // A parameter interval [t0, t1] on which p runs monotonely from p0 to p1.
  struct Run {
    double t0;
    double t1;
    double p0;
    double p1;
    double lo() const { return std::min(p0, p1); }
    double hi() const { return std::max(p0, p1); }
  };

  // The curve made of `pieces` on its line, if it has one (not if it is within eps of a point).
  static std::optional<CurveOnLine> make(const std::vector<RationalBezierCurve<Dim>>& pieces, double eps) {
    const Point<Dim> origin = pieces.front().control_point(0);
    Point<Dim> farthest = origin;
    for (const auto& piece : pieces) {
      for (int i = 0; i <= piece.degree(); ++i) {
        const Point<Dim> P = piece.control_point(i);
        if ((P - origin).norm() > (farthest - origin).norm()) farthest = P;
      }
    }
    if (!((farthest - origin).norm() > eps)) return std::nullopt;
    const Point<Dim> u = (farthest - origin).normalized();
    for (const auto& piece : pieces) {
      for (int i = 0; i <= piece.degree(); ++i) {
        const Point<Dim> r = piece.control_point(i) - origin;
        if (!((r - u.dot(r) * u).norm() <= eps)) return std::nullopt;
      }
    }
    return CurveOnLine(pieces, origin, u, eps);
  }

  // C(t), on the piece whose interval holds t (the first of two that share t).
  Point<Dim> point(double t) const {
    const auto piece = std::lower_bound(pieces_->begin(), pieces_->end() - 1, t,
                                        [](const RationalBezierCurve<Dim>& c, double x) { return c.b() < x; });
    return piece->evaluate(t);
  }

  double position(double t) const { return u_.dot(point(t) - origin_); }

  // The runs in order: each piece is cut at the roots of u . N (N the hodograph's numerator, so
  // p' = u . N / w^2) where p turns back, found by Bernstein subdivision; neighbouring intervals
  // on which p moves the same way (or by no more than eps) are one run.
  std::vector<Run> runs() const {
    std::vector<Run> runs;
    int direction = 0;
    for (const auto& piece : *pieces_) {
      std::vector<double> cuts{piece.a()};
      if (piece.degree() > 0) {
        std::vector<double> along;
        for (const Point<Dim>& N : hodograph_numerator<Dim>(piece.homogeneous().control_points())) {
          along.push_back(u_.dot(N));
        }
        for (const double r : bernstein_roots(along)) cuts.push_back(piece.a() + r * (piece.b() - piece.a()));
      }
      cuts.push_back(piece.b());
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double t0 = cuts[k], t1 = std::min(cuts[k + 1], piece.b());
        if (!(t1 > t0)) continue;
        const double p0 = u_.dot(piece.evaluate(t0) - origin_), p1 = u_.dot(piece.evaluate(t1) - origin_);
        const int sign = std::abs(p1 - p0) <= eps_ ? 0 : (p1 > p0 ? 1 : -1);
        if (!runs.empty() && (sign == 0 || direction == 0 || sign == direction)) {
          runs.back().t1 = t1, runs.back().p1 = p1;
          if (direction == 0) direction = sign;
        } else {
          runs.push_back({t0, t1, p0, p1});
          direction = sign;
        }
      }
    }
    return runs;
  }

  // The parameter on `run` where p = value: the run's end where p is within eps of value, else
  // by bisection.
  double parameter(const Run& run, double value) const {
    if (std::abs(value - run.p0) <= eps_) return run.t0;
    if (std::abs(value - run.p1) <= eps_) return run.t1;
    const bool increasing = run.p1 > run.p0;
    double lo = run.t0, hi = run.t1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double middle = 0.5 * (lo + hi);
      if (!(lo < middle && middle < hi)) break;
      ((position(middle) < value) == increasing ? lo : hi) = middle;
    }
    return std::abs(position(lo) - value) <= std::abs(position(hi) - value) ? lo : hi;
  }

 private:
  CurveOnLine(const std::vector<RationalBezierCurve<Dim>>& pieces, const Point<Dim>& origin, const Point<Dim>& u,
              double eps)
      : pieces_(&pieces), origin_(origin), u_(u), eps_(eps) {}

  const std::vector<RationalBezierCurve<Dim>>* pieces_;
  Point<Dim> origin_;
  Point<Dim> u_;
  double eps_;
};

// What every answer is filtered by: the curve's parameter interval [a, b], whether it closes, and
// the width of the narrowest piece the splitting may leave, (b - a) / 2^40.
struct Ends {
  double a;
  double b;
  bool closed;
  double shortest;
};

// Adds an answer of a pair of pieces, unless it is their shared end or the curve's closing.
template <int Dim>
void add_point(std::vector<CurveIntersection<Dim>>& points, const CurveIntersection<Dim>& x, const Ends& ends) {
  const double slack = 4.0 * ends.shortest;
  if (x.s - x.t <= x.t_bound + x.s_bound + slack) return;  // the pieces' shared end
  if (ends.closed && x.t - ends.a <= x.t_bound + slack && ends.b - x.s <= x.s_bound + slack) return;  // the closing
  detail::add_or_merge(points, x, ends.shortest, ends.shortest);
}

// The self-intersections of any curve (file comment): every pair of monotone pieces whose
// control boxes come within tolerance + eps is intersected (the pairs farther apart are those
// intersect_rational drops at its first test).
template <int Dim>
CurveIntersections<Dim> self_intersections_of_monotone_pieces(const std::vector<RationalBezierCurve<Dim>>& curve_pieces,
                                                              double tolerance, const Ends& ends) {
  std::vector<RationalBezierCurve<Dim>> pieces;
  for (const auto& curve : curve_pieces) {
    monotone_pieces(curve, curve.a(), curve.b(), 0, hodograph_noise(curve), pieces);
  }
  std::vector<Eigen::AlignedBox<double, Dim>> boxes(pieces.size());
  std::vector<double> scales(pieces.size(), std::numeric_limits<double>::min());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (int k = 0; k <= pieces[i].degree(); ++k) {
      boxes[i].extend(pieces[i].control_point(k));
      scales[i] = std::max(scales[i], pieces[i].control_point(k).cwiseAbs().maxCoeff());
    }
  }
  CurveIntersections<Dim> result;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const double eps =
          detail::rounding_level(std::max(scales[i], scales[j]), std::max(pieces[i].degree(), pieces[j].degree()));
      result.eps = std::max(result.eps, eps);
      if (boxes[i].exteriorDistance(boxes[j]) > tolerance + eps) continue;
      CurveIntersections<Dim> pair = detail::intersect_rational(pieces[i], pieces[j], tolerance);
      result.eps = std::max(result.eps, pair.eps);
      for (const CurveIntersection<Dim>& x : pair.points) add_point(result.points, x, ends);
      result.overlaps.insert(result.overlaps.end(), pair.overlaps.begin(), pair.overlaps.end());
    }
  }
  // Overlaps of neighbouring pieces that continue one another.
  std::sort(result.overlaps.begin(), result.overlaps.end(),
            [](const CurveOverlap& x, const CurveOverlap& y) { return x.t0 < y.t0; });
  std::vector<CurveOverlap> merged;
  for (const CurveOverlap& o : result.overlaps) {
    if (!merged.empty() && o.t0 <= merged.back().t1 + ends.shortest &&
        std::abs(o.s0 - merged.back().s1) <= ends.shortest) {
      merged.back().t1 = o.t1, merged.back().s1 = o.s1;
    } else {
      merged.push_back(o);
    }
  }
  result.overlaps = std::move(merged);
  return result;
}

// The self-intersections of a curve on a line, from its runs (file comment): two runs meet where
// their ranges of p do, an overlap when that is longer than max(eps, 64 tolerance), else a contact
// if the ranges come within tolerance + eps.
template <int Dim>
CurveIntersections<Dim> self_intersections_on_line(const CurveOnLine<Dim>& line, double tolerance, double eps,
                                                   const Ends& ends) {
  using Run = typename CurveOnLine<Dim>::Run;
  CurveIntersections<Dim> result;
  result.eps = eps;
  const double reach = tolerance + eps;
  const std::vector<Run> runs = line.runs();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    for (std::size_t j = i + 1; j < runs.size(); ++j) {
      const Run& first = runs[i];
      const Run& second = runs[j];
      const double lo = std::max(first.lo(), second.lo()), hi = std::min(first.hi(), second.hi());
      if (hi - lo > std::max(eps, 64.0 * tolerance)) {
        const double t_lo = line.parameter(first, lo), t_hi = line.parameter(first, hi);
        const double s_lo = line.parameter(second, lo), s_hi = line.parameter(second, hi);
        result.overlaps.push_back(t_lo < t_hi ? CurveOverlap{t_lo, t_hi, s_lo, s_hi}
                                              : CurveOverlap{t_hi, t_lo, s_hi, s_lo});
        continue;
      }
      if (!(hi - lo >= -reach)) continue;
      // A contact: at the values closest to the other range, with bounds over the values within
      // reach of it.
      const double middle = 0.5 * (lo + hi);
      const auto around = [&](const Run& run, const Run& other, double& bound) {
        const double at = line.parameter(run, std::clamp(middle, run.lo(), run.hi()));
        const double from = line.parameter(run, std::max(run.lo(), other.lo() - reach));
        const double to = line.parameter(run, std::min(run.hi(), other.hi() + reach));
        bound = std::max(std::abs(at - from), std::abs(at - to));
        return at;
      };
      CurveIntersection<Dim> x;
      x.t = around(first, second, x.t_bound);
      x.s = around(second, first, x.s_bound);
      x.point = line.point(x.t);
      x.distance = (x.point - line.point(x.s)).norm();
      x.tangential = true;
      if (x.distance <= reach) add_point(result.points, x, ends);
    }
  }
  // A contact at a corner of an overlap's parameter rectangle is the overlap's end.
  std::erase_if(result.points, [&](const CurveIntersection<Dim>& x) {
    return std::any_of(result.overlaps.begin(), result.overlaps.end(), [&](const CurveOverlap& o) {
      return o.t0 - x.t_bound <= x.t && x.t <= o.t1 + x.t_bound && std::min(o.s0, o.s1) - x.s_bound <= x.s &&
             x.s <= std::max(o.s0, o.s1) + x.s_bound;
    });
  });
  return result;
}

}  // namespace

namespace detail {

template <int Dim>
CurveIntersections<Dim> self_intersections_of_pieces(const std::vector<RationalBezierCurve<Dim>>& curve_pieces,
                                                     double tolerance) {
  const RationalBezierCurve<Dim>& first = curve_pieces.front();
  const RationalBezierCurve<Dim>& last = curve_pieces.back();
  Ends ends{first.a(), last.b(), false, std::numeric_limits<double>::infinity()};
  double scale = 0.0;
  int degree = 0;
  for (const auto& curve : curve_pieces) {
    for (int i = 0; i <= curve.degree(); ++i) scale = std::max(scale, curve.control_point(i).cwiseAbs().maxCoeff());
    degree = std::max(degree, curve.degree());
    ends.shortest = std::min(ends.shortest, std::ldexp(curve.b() - curve.a(), -max_depth));
  }
  // A closed curve's start and end meet where it closes, which is no crossing.
  ends.closed = (first.evaluate(ends.a) - last.evaluate(ends.b)).norm() <= tolerance + rounding_level(scale, 1);
  const double eps = rounding_level(std::max(scale, std::numeric_limits<double>::min()), degree);
  CurveIntersections<Dim> result;
  if (const auto line = CurveOnLine<Dim>::make(curve_pieces, eps)) {
    result = self_intersections_on_line(*line, tolerance, eps, ends);
  } else {
    result = self_intersections_of_monotone_pieces(curve_pieces, tolerance, ends);
  }
  std::sort(result.points.begin(), result.points.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  std::sort(result.overlaps.begin(), result.overlaps.end(),
            [](const CurveOverlap& x, const CurveOverlap& y) { return x.t0 < y.t0; });
  return result;
}

template CurveIntersections<2> self_intersections_of_pieces(const std::vector<RationalBezierCurve<2>>&, double);
template CurveIntersections<3> self_intersections_of_pieces(const std::vector<RationalBezierCurve<3>>&, double);

}  // namespace detail

namespace {

template <int Dim>
CurveIntersections<Dim> self_intersections_of(const RationalBezierCurve<Dim>& curve, double tolerance) {
  return detail::self_intersections_of_pieces(std::vector<RationalBezierCurve<Dim>>{curve}, tolerance);
}

}  // namespace

CurveIntersections<2> self_intersections(const BezierCurve2& curve) { return self_intersections_of(as_rational(curve), 0.0); }

CurveIntersections<2> self_intersections(const RationalBezierCurve2& curve) { return self_intersections_of(curve, 0.0); }

CurveIntersections<3> self_intersections(const BezierCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return self_intersections_of(as_rational(curve), tolerance);
}

CurveIntersections<3> self_intersections(const RationalBezierCurve3& curve, double tolerance) {
  require_positive(tolerance, "self_intersections", "tolerance");
  return self_intersections_of(curve, tolerance);
}

}  // namespace patchwork
