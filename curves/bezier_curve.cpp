#include "curves/bezier_curve.h"

#include <array>
#include <cmath>

#include "core/errors.h"
#include "curves/curve_checks.h"
#include "curves/dimensions.h"
#include "curves/limit_tangent.h"

namespace patchwork {
namespace {

// Scratch space for de Casteljau: on the stack up to degree 15, on the heap beyond.
template <int Dim>
class Scratch {
 public:
  using Point = patchwork::Point<Dim>;
  explicit Scratch(const std::vector<Point>& points) {
    if (points.size() <= small_.size()) {
      std::copy(points.begin(), points.end(), small_.begin());
      data_ = small_.data();
    } else {
      large_ = points;
      data_ = large_.data();
    }
  }
  Point* data() noexcept { return data_; }

 private:
  std::array<Point, 16> small_;
  std::vector<Point> large_;
  Point* data_;
};

// de Casteljau steps on work[0..n], leaving work[0..n-steps] as the level-`steps` points.
template <int Dim>
void de_casteljau_steps(Point<Dim>* work, int n, int steps, double s) {
  const double r = 1.0 - s;
  for (int k = 1; k <= steps; ++k) {
    for (int i = 0; i + k <= n; ++i) work[i] = r * work[i] + s * work[i + 1];
  }
}

}  // namespace

template <int Dim>
BezierCurve<Dim>::BezierCurve(std::vector<Point> control_points, double a, double b)
    : points_(std::move(control_points)), a_(a), b_(b) {
  detail::check_control_points("BezierCurve", points_);
  detail::check_interval("BezierCurve", a_, b_);
}

template <int Dim>
typename BezierCurve<Dim>::Point BezierCurve<Dim>::evaluate(double t) const {
  detail::check_parameter("BezierCurve::evaluate", t);
  const double s = local_parameter(t);
  const int n = degree();
  if (n == 3) {  // the common cubic, unrolled
    const double r = 1.0 - s;
    const Point p01 = r * points_[0] + s * points_[1];
    const Point p12 = r * points_[1] + s * points_[2];
    const Point p23 = r * points_[2] + s * points_[3];
    const Point p012 = r * p01 + s * p12;
    const Point p123 = r * p12 + s * p23;
    return r * p012 + s * p123;
  }
  Scratch<Dim> work(points_);
  de_casteljau_steps<Dim>(work.data(), n, n, s);
  return work.data()[0];
}

template <int Dim>
BezierCurve<Dim> with_interval(const BezierCurve<Dim>& curve, double a, double b) {
  return BezierCurve<Dim>(curve.control_points(), a, b);
}

template <int Dim>
BezierCurve<Dim> derivative_curve(const BezierCurve<Dim>& curve) {
  const int n = curve.degree();
  const auto& P = curve.control_points();
  if (n == 0) return BezierCurve<Dim>({Point<Dim>::Zero()}, curve.a(), curve.b());
  const double factor = n / (curve.b() - curve.a());
  std::vector<Point<Dim>> Q(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) Q[i] = factor * (P[i + 1] - P[i]);
  return BezierCurve<Dim>(std::move(Q), curve.a(), curve.b());
}

template <int Dim>
std::vector<Point<Dim>> derivatives(const BezierCurve<Dim>& curve, double t, int k) {
  detail::check_parameter("derivatives", t);
  if (k < 0) throw InvalidInput(detail::message("derivatives: order ", k, " is negative"));
  const int n = curve.degree();
  const double h = curve.b() - curve.a();
  const double s = curve.local_parameter(t);
  std::vector<Point<Dim>> result(static_cast<std::size_t>(k) + 1, Point<Dim>::Zero());
  const int top = std::min(k, n);
  // de Casteljau down to level n - top leaves top+1 points whose polygon is the curve's
  // degree-`top` blossom at s: its j-th forward difference times n!/(n-j)! is C^(j) in s.
  Scratch<Dim> scratch(curve.control_points());
  Point<Dim>* work = scratch.data();
  de_casteljau_steps<Dim>(work, n, n - top, s);
  for (int j = 0; j <= top; ++j) {
    // work[0..top-j] now holds the (j)-th differences; finish de Casteljau on them.
    std::vector<Point<Dim>> level(work, work + (top - j + 1));
    de_casteljau_steps<Dim>(level.data(), top - j, top - j, s);
    result[static_cast<std::size_t>(j)] = falling_factorial(n, j) / std::pow(h, j) * level[0];
    for (int i = 0; i + j < top; ++i) work[i] = work[i + 1] - work[i];
  }
  return result;
}

template <int Dim>
Point<Dim> derivative(const BezierCurve<Dim>& curve, double t, int k) {
  if (k == 0) return curve.evaluate(t);
  if (k > curve.degree()) {  // zero, without tabulating the k + 1 orders of derivatives()
    detail::check_parameter("derivative", t);
    return Point<Dim>::Zero();
  }
  return derivatives(curve, t, k).back();
}

template <int Dim>
Point<Dim> tangent(const BezierCurve<Dim>& curve, double t) {
  const int n = curve.degree();
  double magnitude = 0.0;
  for (const auto& p : curve.control_points()) magnitude = std::max(magnitude, p.norm());
  return detail::limit_tangent<Dim>(derivatives(curve, t, std::max(n, 1)), n, curve.b() - curve.a(),
                                    magnitude, t >= curve.b(), t);
}

template <int Dim>
double curvature(const BezierCurve<Dim>& curve, double t) {
  const std::vector<Point<Dim>> d = derivatives(curve, t, 2);
  const Point<Dim>& d1 = d[1];
  const Point<Dim>& d2 = d[2];
  const double speed2 = d1.squaredNorm();
  if (speed2 == 0.0) throw NumericalError(detail::message("curvature: C'(t) = 0 at t = ", t));
  double cross2;
  if constexpr (Dim == 2) {
    const double c = d1[0] * d2[1] - d1[1] * d2[0];
    cross2 = c * c;
  } else if constexpr (Dim == 3) {
    cross2 = d1.cross(d2).squaredNorm();
  } else {
    // |d1|^2 |d2|^2 - (d1.d2)^2: the squared area of the parallelogram, in any dimension.
    cross2 = std::max(0.0, speed2 * d2.squaredNorm() - d1.dot(d2) * d1.dot(d2));
  }
  return std::sqrt(cross2) / (speed2 * std::sqrt(speed2));
}

template <int Dim>
std::vector<Point<Dim>> evaluate(const BezierCurve<Dim>& curve, const BernsteinTable& table) {
  if (table.degree() != curve.degree()) {
    throw InvalidInput(detail::message("evaluate: table of degree ", table.degree(), " for a curve of degree ", curve.degree()));
  }
  const auto& P = curve.control_points();
  const std::size_t width = P.size();
  std::vector<Point<Dim>> result(table.size());
  for (std::size_t row = 0; row < table.size(); ++row) {
    const std::span<const double> w = table.weights(row);
    Point<Dim> sum = w[0] * P[0];
    for (std::size_t i = 1; i < width; ++i) sum += w[i] * P[i];
    result[row] = sum;
  }
  return result;
}

template <int Dim>
std::vector<Point<Dim>> evaluate_many(const BezierCurve<Dim>& curve, std::span<const double> ts) {
  std::vector<double> local(ts.size());
  for (std::size_t i = 0; i < ts.size(); ++i) {
    detail::check_parameter("evaluate_many", ts[i]);
    local[i] = curve.local_parameter(ts[i]);
  }
  return evaluate(curve, BernsteinTable(curve.degree(), local));
}

#define PATCHWORK_INSTANTIATE(D)                                                                   \
  template class BezierCurve<D>;                                                                   \
  template BezierCurve<D> with_interval(const BezierCurve<D>&, double, double);                    \
  template BezierCurve<D> derivative_curve(const BezierCurve<D>&);                                 \
  template std::vector<Point<D>> derivatives(const BezierCurve<D>&, double, int);                  \
  template Point<D> derivative(const BezierCurve<D>&, double, int);                                \
  template Point<D> tangent(const BezierCurve<D>&, double);                                        \
  template double curvature(const BezierCurve<D>&, double);                                        \
  template std::vector<Point<D>> evaluate(const BezierCurve<D>&, const BernsteinTable&);           \
  template std::vector<Point<D>> evaluate_many(const BezierCurve<D>&, std::span<const double>);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
