#include "queries/intersection_kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>

#include "core/assert.h"

namespace patchwork::detail {
namespace {

Interval widened(Interval x) {
  const double e = 4.0 * unit_roundoff * (std::abs(x.lo) + std::abs(x.hi)) + std::numeric_limits<double>::denorm_min();
  return {x.lo - e, x.hi + e};
}

// The hull of the values of coordinate c of the points.
template <int D>
Interval coordinate_hull(const std::vector<Point<D>>& points, int c) {
  Interval result{points[0][c], points[0][c]};
  for (const auto& p : points) {
    result.lo = std::min(result.lo, p[c]);
    result.hi = std::max(result.hi, p[c]);
  }
  return result;
}

// The hodograph n (H_{i+1} - H_i) / width of homogeneous points (a single zero point for n = 0).
template <int D>
std::vector<Point<D>> hodograph(const std::vector<Point<D>>& H, double width) {
  const int n = static_cast<int>(H.size()) - 1;
  if (n == 0) return {Point<D>::Zero()};
  std::vector<Point<D>> result(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) result[i] = (n / width) * (H[i + 1] - H[i]);
  return result;
}

}  // namespace

Interval operator+(Interval x, Interval y) { return widened({x.lo + y.lo, x.hi + y.hi}); }
Interval operator-(Interval x, Interval y) { return widened({x.lo - y.hi, x.hi - y.lo}); }
Interval operator*(Interval x, Interval y) {
  const double a = x.lo * y.lo, b = x.lo * y.hi, c = x.hi * y.lo, d = x.hi * y.hi;
  return widened({std::min({a, b, c, d}), std::max({a, b, c, d})});
}
Interval divide_positive(Interval x, Interval y) {
  PATCHWORK_ASSERT(y.lo > 0.0, "divide_positive: the divisor must be positive");
  const double a = x.lo / y.lo, b = x.lo / y.hi, c = x.hi / y.lo, d = x.hi / y.hi;
  return widened({std::min({a, b, c, d}), std::max({a, b, c, d})});
}

double rounding_level(double scale, int n) { return 64.0 * (n + 1) * unit_roundoff * scale; }

template <int D>
std::vector<Point<D>> reparametrized(const std::vector<Point<D>>& P, double a, double b, double t0, double t1) {
  const int n = static_cast<int>(P.size()) - 1;
  const double s0 = (t0 - a) / (b - a);
  const double s1 = (t1 - a) / (b - a);
  std::vector<Point<D>> result(P.size());
  std::vector<Point<D>> work(P.size());
  for (int i = 0; i <= n; ++i) {
    work = P;
    // Blossom h(s0^(n-i), s1^i): n - i de Casteljau levels at s0, then i at s1.
    for (int level = 1; level <= n; ++level) {
      const double s = level <= n - i ? s0 : s1;
      for (int k = 0; k + level <= n; ++k) work[k] = (1.0 - s) * work[k] + s * work[k + 1];
    }
    result[i] = work[0];
  }
  return result;
}

std::vector<Vec4> reparametrized_net(const std::vector<Vec4>& net, int n, int m, double u0, double u1, double v0,
                                     double v1) {
  std::vector<Vec4> result(net.size());
  std::vector<Vec4> line;
  for (int j = 0; j <= m; ++j) {
    line.assign(net.begin() + j * (n + 1), net.begin() + (j + 1) * (n + 1));
    const auto row = reparametrized(line, 0.0, 1.0, u0, u1);
    std::copy(row.begin(), row.end(), result.begin() + j * (n + 1));
  }
  for (int i = 0; i <= n; ++i) {
    line.clear();
    for (int j = 0; j <= m; ++j) line.push_back(result[i + (n + 1) * j]);
    const auto column = reparametrized(line, 0.0, 1.0, v0, v1);
    for (int j = 0; j <= m; ++j) result[i + (n + 1) * j] = column[j];
  }
  return result;
}

template <int Dim>
double segment_distance(const Point<Dim>& q, const Point<Dim>& p0, const Point<Dim>& p1) {
  const Point<Dim> d = p1 - p0;
  const double length2 = d.squaredNorm();
  const double alpha = length2 > 0.0 ? std::clamp((q - p0).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (q - (p0 + alpha * d)).norm();
}

template <int Dim>
std::pair<double, double> segment_closest(const Point<Dim>& p0, const Point<Dim>& p1, const Point<Dim>& q0,
                                          const Point<Dim>& q1) {
  // Minimise |p0 + alpha d1 - q0 - beta d2|^2 over [0,1]^2: the interior stationary point if it
  // is inside, else the best of the four edges (each a clamped projection).
  const Point<Dim> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
  auto value = [&](double alpha, double beta) { return (r + alpha * d1 - beta * d2).squaredNorm(); };
  double best_alpha = 0.0, best_beta = 0.0, best = std::numeric_limits<double>::infinity();
  auto consider = [&](double alpha, double beta) {
    const double v = value(alpha, beta);
    if (v < best) best = v, best_alpha = alpha, best_beta = beta;
  };
  const double denominator = a * e - b * b;
  if (denominator > 1e-300) {
    const double alpha = (b * f - c * e) / denominator, beta = (a * f - b * c) / denominator;
    if (alpha >= 0.0 && alpha <= 1.0 && beta >= 0.0 && beta <= 1.0) consider(alpha, beta);
  }
  for (double beta : {0.0, 1.0}) consider(a > 0.0 ? std::clamp((beta * b - c) / a, 0.0, 1.0) : 0.0, beta);
  for (double alpha : {0.0, 1.0}) consider(alpha, e > 0.0 ? std::clamp((alpha * b + f) / e, 0.0, 1.0) : 0.0);
  return {best_alpha, best_beta};
}

template <int Dim>
CurvePiece<Dim> curve_piece(const RationalBezierCurve<Dim>& curve, double t0, double t1) {
  const auto& homogeneous = curve.homogeneous();
  CurvePiece<Dim> piece{t0, t1, reparametrized(homogeneous.control_points(), curve.a(), curve.b(), t0, t1), {}, {}, 0.0, true};
  piece.P.reserve(piece.H.size());
  for (const auto& h : piece.H) {
    if (!(h[Dim] > 0.0)) piece.valid = false;
    piece.P.push_back(h.template head<Dim>() / h[Dim]);
  }
  for (const auto& p : piece.P) piece.box.extend(p);
  for (const auto& p : piece.P) piece.flatness = std::max(piece.flatness, segment_distance<Dim>(p, piece.P.front(), piece.P.back()));
  return piece;
}

template <int Dim>
std::array<Interval, Dim> derivative_enclosure(const CurvePiece<Dim>& piece) {
  const auto dH = hodograph(piece.H, piece.t1 - piece.t0);
  const Interval w = coordinate_hull(piece.H, Dim);
  const Interval dw = coordinate_hull(dH, Dim);
  std::array<Interval, Dim> result;
  for (int c = 0; c < Dim; ++c) {
    result[c] = divide_positive(coordinate_hull(dH, c) - dw * coordinate_hull(piece.P, c), w);
  }
  return result;
}

template <int Dim>
std::array<Point<Dim>, 3> point_and_derivatives(const RationalBezierCurve<Dim>& curve, double t) {
  return {curve.evaluate(t), derivative(curve, t, 1), derivative(curve, t, 2)};
}

template <int Dim>
std::pair<Point<Dim>, Point<Dim>> point_and_derivative(const RationalBezierCurve<Dim>& curve, double t) {
  return {curve.evaluate(t), derivative(curve, t, 1)};
}

template <int N>
KrawczykOutcome krawczyk(const std::array<Interval, N>& X, const Eigen::Matrix<double, N, 1>& m,
                         const Eigen::Matrix<double, N, 1>& g, double g_error,
                         const std::array<std::array<Interval, N>, N>& J, const Eigen::Matrix<double, N, N>& Y,
                         std::array<Interval, N>& image) {
  if (!Y.allFinite()) return KrawczykOutcome::unknown;
  bool inside = true;
  for (int i = 0; i < N; ++i) {
    // m_i - (Y G(m))_i
    Interval value = point_interval(m[i]);
    for (int k = 0; k < N; ++k) value = value - point_interval(Y(i, k)) * Interval{g[k] - g_error, g[k] + g_error};
    // + sum_j (I - Y J)_ij (X_j - m_j)
    for (int j = 0; j < N; ++j) {
      Interval entry = point_interval(i == j ? 1.0 : 0.0);
      for (int k = 0; k < N; ++k) entry = entry - point_interval(Y(i, k)) * J[k][j];
      value = value + entry * (X[j] - point_interval(m[j]));
    }
    image[i] = value;
    if (!(value.lo <= value.hi)) return KrawczykOutcome::unknown;  // NaN
    if (value.hi < X[i].lo || value.lo > X[i].hi) return KrawczykOutcome::no_zero;
    if (!(value.lo > X[i].lo && value.hi < X[i].hi)) inside = false;
  }
  return inside ? KrawczykOutcome::unique_zero : KrawczykOutcome::unknown;
}

template <int N>
std::vector<std::vector<std::size_t>> touching_groups(const std::vector<std::array<Interval, N>>& boxes, double margin) {
  std::vector<std::size_t> parent(boxes.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<std::size_t> order(boxes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return boxes[x][0].lo < boxes[y][0].lo; });
  for (std::size_t a = 0; a < order.size(); ++a) {
    const auto& box = boxes[order[a]];
    for (std::size_t b = a + 1; b < order.size() && boxes[order[b]][0].lo <= box[0].hi + 2 * margin; ++b) {
      const auto& other = boxes[order[b]];
      bool touch = true;
      for (int c = 1; c < N; ++c) touch = touch && other[c].lo <= box[c].hi + 2 * margin && box[c].lo <= other[c].hi + 2 * margin;
      if (touch) parent[root(order[a])] = root(order[b]);
    }
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::size_t> group_of(boxes.size(), boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::size_t r = root(i);
    if (group_of[r] == boxes.size()) {
      group_of[r] = groups.size();
      groups.emplace_back();
    }
    groups[group_of[r]].push_back(i);
  }
  return groups;
}

#define PATCHWORK_INSTANTIATE(D)                                                                                \
  template CurvePiece<D> curve_piece(const RationalBezierCurve<D>&, double, double);                            \
  template std::array<Interval, D> derivative_enclosure<D>(const CurvePiece<D>&);                                  \
  template std::pair<Point<D>, Point<D>> point_and_derivative(const RationalBezierCurve<D>&, double);           \
  template std::array<Point<D>, 3> point_and_derivatives(const RationalBezierCurve<D>&, double);                \
  template double segment_distance<D>(const Point<D>&, const Point<D>&, const Point<D>&);                       \
  template std::pair<double, double> segment_closest<D>(const Point<D>&, const Point<D>&, const Point<D>&,      \
                                                        const Point<D>&);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

template std::vector<Point<3>> reparametrized(const std::vector<Point<3>>&, double, double, double, double);
template std::vector<Point<4>> reparametrized(const std::vector<Point<4>>&, double, double, double, double);
template KrawczykOutcome krawczyk<2>(const std::array<Interval, 2>&, const Eigen::Matrix<double, 2, 1>&,
                                     const Eigen::Matrix<double, 2, 1>&, double,
                                     const std::array<std::array<Interval, 2>, 2>&, const Eigen::Matrix<double, 2, 2>&,
                                     std::array<Interval, 2>&);
template KrawczykOutcome krawczyk<3>(const std::array<Interval, 3>&, const Eigen::Matrix<double, 3, 1>&,
                                     const Eigen::Matrix<double, 3, 1>&, double,
                                     const std::array<std::array<Interval, 3>, 3>&, const Eigen::Matrix<double, 3, 3>&,
                                     std::array<Interval, 3>&);
template std::vector<std::vector<std::size_t>> touching_groups<2>(const std::vector<std::array<Interval, 2>>&, double);
template std::vector<std::vector<std::size_t>> touching_groups<3>(const std::vector<std::array<Interval, 3>>&, double);

}  // namespace patchwork::detail
