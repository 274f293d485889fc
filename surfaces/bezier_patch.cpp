#include "surfaces/bezier_patch.h"

#include <algorithm>
#include <array>

#include "core/errors.h"
#include "curves/degree.h"
#include "curves/subdivision.h"

namespace patchwork {
namespace {

void check_parameters(const char* function, double u, double v) {
  if (!std::isfinite(u) || !std::isfinite(v)) {
    throw InvalidInput(detail::message(function, ": parameters (", u, ", ", v, ") are not finite"));
  }
}

// Row j (the points P_0j .. P_nj) and column i (P_i0 .. P_im) of the net.
template <int Dim>
std::vector<Point<Dim>> row(const BezierPatch<Dim>& patch, int j) {
  const auto first = patch.control_points().begin() + static_cast<std::ptrdiff_t>((patch.degree_u() + 1) * j);
  return {first, first + patch.degree_u() + 1};
}

template <int Dim>
std::vector<Point<Dim>> column(const BezierPatch<Dim>& patch, int i) {
  std::vector<Point<Dim>> points(static_cast<std::size_t>(patch.degree_v()) + 1);
  for (int j = 0; j <= patch.degree_v(); ++j) points[static_cast<std::size_t>(j)] = patch.control_point(i, j);
  return points;
}

// de Casteljau in place on points[0..n] at s; returns the point.
template <int Dim>
Point<Dim> de_casteljau(Point<Dim>* points, int n, double s) {
  const double r = 1.0 - s;
  for (int k = 1; k <= n; ++k) {
    for (int i = 0; i + k <= n; ++i) points[i] = r * points[i] + s * points[i + 1];
  }
  return points[0];
}

// A patch built from rows: net[j] is row j.
template <int Dim>
BezierPatch<Dim> from_rows(const std::vector<std::vector<Point<Dim>>>& rows) {
  const int n = static_cast<int>(rows.front().size()) - 1;
  const int m = static_cast<int>(rows.size()) - 1;
  std::vector<Point<Dim>> points;
  points.reserve(static_cast<std::size_t>((n + 1) * (m + 1)));
  for (const auto& r : rows) points.insert(points.end(), r.begin(), r.end());
  return BezierPatch<Dim>(n, m, std::move(points));
}

// A patch built from columns: net[i] is column i.
template <int Dim>
BezierPatch<Dim> from_columns(const std::vector<std::vector<Point<Dim>>>& columns) {
  const int n = static_cast<int>(columns.size()) - 1;
  const int m = static_cast<int>(columns.front().size()) - 1;
  std::vector<Point<Dim>> points(static_cast<std::size_t>((n + 1) * (m + 1)));
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) points[static_cast<std::size_t>(i + (n + 1) * j)] = columns[i][j];
  }
  return BezierPatch<Dim>(n, m, std::move(points));
}

// Applies `op` (control points -> control points) to every row, or to every column.
template <int Dim, class Op>
BezierPatch<Dim> map_rows(const BezierPatch<Dim>& patch, Op op) {
  std::vector<std::vector<Point<Dim>>> rows;
  for (int j = 0; j <= patch.degree_v(); ++j) rows.push_back(op(row(patch, j)));
  return from_rows(rows);
}

template <int Dim, class Op>
BezierPatch<Dim> map_columns(const BezierPatch<Dim>& patch, Op op) {
  std::vector<std::vector<Point<Dim>>> columns;
  for (int i = 0; i <= patch.degree_u(); ++i) columns.push_back(op(column(patch, i)));
  return from_columns(columns);
}

// k forward differences times n!/(n-k)!: the control points of the k-th hodograph.
template <int Dim>
std::vector<Point<Dim>> hodograph_points(std::vector<Point<Dim>> points, int k) {
  const int n = static_cast<int>(points.size()) - 1;
  if (k > n) return {Point<Dim>::Zero()};
  for (int step = 0; step < k; ++step) {
    const int degree = n - step;
    for (int i = 0; i < degree; ++i) points[i] = degree * (points[i + 1] - points[i]);
    points.pop_back();
  }
  return points;
}

}  // namespace

template <int Dim>
BezierPatch<Dim>::BezierPatch(int n, int m, std::vector<Point> control_points)
    : n_(n), m_(m), points_(std::move(control_points)) {
  if (n < 0 || m < 0) throw InvalidInput(detail::message("BezierPatch: degrees (", n, ", ", m, ") are negative"));
  const std::size_t expected = static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(m + 1);
  if (points_.size() != expected) {
    throw InvalidInput(detail::message("BezierPatch: degrees (", n, ", ", m, ") need ", expected, " control points, got ",
                                       points_.size()));
  }
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if (!points_[k].allFinite()) {
      throw InvalidInput(detail::message("BezierPatch: control point ", k, " (i = ", k % (n + 1), ", j = ", k / (n + 1),
                                         ") is not finite"));
    }
  }
}

template <int Dim>
typename BezierPatch<Dim>::Point BezierPatch<Dim>::evaluate(double u, double v) const {
  check_parameters("BezierPatch::evaluate", u, v);
  if (n_ <= 15 && m_ <= 15) {
    std::array<Point, 16> line;
    std::array<Point, 16> across;
    for (int j = 0; j <= m_; ++j) {
      std::copy_n(points_.begin() + (n_ + 1) * j, n_ + 1, line.begin());
      across[j] = de_casteljau<Dim>(line.data(), n_, u);
    }
    return de_casteljau<Dim>(across.data(), m_, v);
  }
  std::vector<Point> line(static_cast<std::size_t>(n_) + 1);
  std::vector<Point> across(static_cast<std::size_t>(m_) + 1);
  for (int j = 0; j <= m_; ++j) {
    std::copy_n(points_.begin() + (n_ + 1) * j, n_ + 1, line.begin());
    across[j] = de_casteljau<Dim>(line.data(), n_, u);
  }
  return de_casteljau<Dim>(across.data(), m_, v);
}

template <int Dim>
Point<Dim> derivative(const BezierPatch<Dim>& patch, double u, double v, int ku, int kv) {
  check_parameters("derivative", u, v);
  if (ku < 0 || kv < 0) throw InvalidInput(detail::message("derivative: orders (", ku, ", ", kv, ") are negative"));
  if (ku > patch.degree_u() || kv > patch.degree_v()) return Point<Dim>::Zero();
  if (ku == 0 && kv == 0) return patch.evaluate(u, v);
  BezierPatch<Dim> differenced = patch;
  if (ku > 0) differenced = map_rows(differenced, [ku](std::vector<Point<Dim>> r) { return hodograph_points(std::move(r), ku); });
  if (kv > 0) differenced = map_columns(differenced, [kv](std::vector<Point<Dim>> c) { return hodograph_points(std::move(c), kv); });
  return differenced.evaluate(u, v);
}

template <int Dim>
PartialDerivatives<Dim> partial_derivatives(const BezierPatch<Dim>& patch, double u, double v, int order) {
  if (order < 0) throw InvalidInput(detail::message("partial_derivatives: order ", order, " is negative"));
  check_parameters("partial_derivatives", u, v);
  PartialDerivatives<Dim> table(order);
  // The rows are differenced once per order in u and reused for every order in v, in place in
  // two flat nets of stride n + 1 (the same arithmetic as hodograph_points and evaluate, without
  // a patch per entry: limit normals at poles call this on every sample there).
  const int n = patch.degree_u();
  const int m = patch.degree_v();
  const int stride = n + 1;
  // Up to bicubic the nets live on the stack (limit normals, G1 tests and tangents call this per
  // sample, where four allocations cost more than the arithmetic); the arithmetic is the same.
  constexpr std::size_t small = 16;
  const std::size_t count = patch.control_points().size();
  const std::size_t width = static_cast<std::size_t>(std::max(n, m)) + 1;
  const bool fits = count <= small && width <= 4;
  std::array<Point<Dim>, small> in_u_small, in_uv_small;
  std::array<Point<Dim>, 4> line_small, across_small;
  std::vector<Point<Dim>> in_u_heap, in_uv_heap, line_heap, across_heap;
  if (!fits) {
    in_u_heap.resize(count);
    in_uv_heap.resize(count);
    line_heap.resize(width);
    across_heap.resize(static_cast<std::size_t>(m) + 1);
  }
  Point<Dim>* const in_u = fits ? in_u_small.data() : in_u_heap.data();
  Point<Dim>* const in_uv = fits ? in_uv_small.data() : in_uv_heap.data();
  Point<Dim>* const line = fits ? line_small.data() : line_heap.data();
  Point<Dim>* const across = fits ? across_small.data() : across_heap.data();
  std::copy(patch.control_points().begin(), patch.control_points().end(), in_u);
  for (int a = 0; a <= order; ++a) {
    const int du = n - a;
    if (du >= 0) std::copy(in_u, in_u + count, in_uv);
    for (int b = 0; a + b <= order; ++b) {
      const int dv = m - b;
      if (du < 0 || dv < 0) {
        table.at(a, b) = Point<Dim>::Zero();
        continue;
      }
      for (int j = 0; j <= dv; ++j) {
        std::copy_n(in_uv + stride * j, du + 1, line);
        across[j] = de_casteljau<Dim>(line, du, u);
      }
      table.at(a, b) = de_casteljau<Dim>(across, dv, v);
      if (a + b < order) {
        for (int i = 0; i <= du; ++i) {
          for (int j = 0; j < dv; ++j) in_uv[i + stride * j] = dv * (in_uv[i + stride * (j + 1)] - in_uv[i + stride * j]);
        }
      }
    }
    if (a < order && du > 0) {
      for (int j = 0; j <= m; ++j) {
        for (int i = 0; i < du; ++i) in_u[i + stride * j] = du * (in_u[i + 1 + stride * j] - in_u[i + stride * j]);
      }
    }
  }
  return table;
}

template <int Dim>
std::pair<BezierPatch<Dim>, BezierPatch<Dim>> split_u(const BezierPatch<Dim>& patch, double u) {
  if (!(u > 0.0 && u < 1.0)) throw InvalidInput(detail::message("split_u: u = ", u, " is not inside (0, 1)"));
  std::vector<std::vector<Point<Dim>>> left;
  std::vector<std::vector<Point<Dim>>> right;
  for (int j = 0; j <= patch.degree_v(); ++j) {
    auto [l, r] = split(BezierCurve<Dim>(row(patch, j)), u);
    left.push_back(l.control_points());
    right.push_back(r.control_points());
  }
  return {from_rows(left), from_rows(right)};
}

template <int Dim>
std::pair<BezierPatch<Dim>, BezierPatch<Dim>> split_v(const BezierPatch<Dim>& patch, double v) {
  if (!(v > 0.0 && v < 1.0)) throw InvalidInput(detail::message("split_v: v = ", v, " is not inside (0, 1)"));
  std::vector<std::vector<Point<Dim>>> lower;
  std::vector<std::vector<Point<Dim>>> upper;
  for (int i = 0; i <= patch.degree_u(); ++i) {
    auto [l, r] = split(BezierCurve<Dim>(column(patch, i)), v);
    lower.push_back(l.control_points());
    upper.push_back(r.control_points());
  }
  return {from_columns(lower), from_columns(upper)};
}

template <int Dim>
BezierPatch<Dim> subpatch(const BezierPatch<Dim>& patch, double u0, double u1, double v0, double v1) {
  if (!(0.0 <= u0 && u0 < u1 && u1 <= 1.0 && 0.0 <= v0 && v0 < v1 && v1 <= 1.0)) {
    throw InvalidInput(detail::message("subpatch: [", u0, ", ", u1, "] x [", v0, ", ", v1, "] is not a part of [0,1]^2"));
  }
  const auto piece = [](const std::vector<Point<Dim>>& points, double t0, double t1) {
    return subcurve(BezierCurve<Dim>(points), t0, t1).control_points();
  };
  BezierPatch<Dim> result = map_rows(patch, [&](const std::vector<Point<Dim>>& r) { return piece(r, u0, u1); });
  return map_columns(result, [&](const std::vector<Point<Dim>>& c) { return piece(c, v0, v1); });
}

template <int Dim>
BezierPatch<Dim> elevate_degree(const BezierPatch<Dim>& patch, int times_u, int times_v) {
  if (times_u < 0 || times_v < 0) {
    throw InvalidInput(detail::message("elevate_degree: times (", times_u, ", ", times_v, ") are negative"));
  }
  // Elevating by 0 is the identity (each row or column copied as it is): skipped, since patch
  // sets compare every shared edge at the higher of its two degrees, mostly equal.
  BezierPatch<Dim> result = times_u == 0 ? patch : map_rows(patch, [times_u](const std::vector<Point<Dim>>& r) {
    return elevate_degree(BezierCurve<Dim>(r), times_u).control_points();
  });
  if (times_v == 0) return result;
  return map_columns(result, [times_v](const std::vector<Point<Dim>>& c) {
    return elevate_degree(BezierCurve<Dim>(c), times_v).control_points();
  });
}

template <int Dim>
BezierCurve<Dim> iso_curve_u(const BezierPatch<Dim>& patch, double u) {
  check_parameters("iso_curve_u", u, 0.0);
  std::vector<Point<Dim>> points(static_cast<std::size_t>(patch.degree_v()) + 1);
  for (int j = 0; j <= patch.degree_v(); ++j) points[j] = BezierCurve<Dim>(row(patch, j)).evaluate(u);
  return BezierCurve<Dim>(std::move(points));
}

template <int Dim>
BezierCurve<Dim> iso_curve_v(const BezierPatch<Dim>& patch, double v) {
  check_parameters("iso_curve_v", 0.0, v);
  std::vector<Point<Dim>> points(static_cast<std::size_t>(patch.degree_u()) + 1);
  for (int i = 0; i <= patch.degree_u(); ++i) points[i] = BezierCurve<Dim>(column(patch, i)).evaluate(v);
  return BezierCurve<Dim>(std::move(points));
}

template <int Dim>
std::vector<Point<Dim>> row_from_edge(const BezierPatch<Dim>& patch, PatchEdge edge, int k) {
  switch (edge) {
    case PatchEdge::v0: return row(patch, k);
    case PatchEdge::v1: return row(patch, patch.degree_v() - k);
    case PatchEdge::u0: return column(patch, k);
    case PatchEdge::u1: return column(patch, patch.degree_u() - k);
  }
  throw InvalidInput("row_from_edge: not an edge");
}

template <int Dim>
BezierCurve<Dim> boundary_curve(const BezierPatch<Dim>& patch, PatchEdge edge) {
  return BezierCurve<Dim>(row_from_edge(patch, edge, 0));
}

#define PATCHWORK_INSTANTIATE(D)                                                                          \
  template class BezierPatch<D>;                                                                          \
  template Point<D> derivative(const BezierPatch<D>&, double, double, int, int);                          \
  template PartialDerivatives<D> partial_derivatives(const BezierPatch<D>&, double, double, int);         \
  template std::pair<BezierPatch<D>, BezierPatch<D>> split_u(const BezierPatch<D>&, double);              \
  template std::pair<BezierPatch<D>, BezierPatch<D>> split_v(const BezierPatch<D>&, double);              \
  template BezierPatch<D> subpatch(const BezierPatch<D>&, double, double, double, double);                \
  template BezierPatch<D> elevate_degree(const BezierPatch<D>&, int, int);                                \
  template BezierCurve<D> iso_curve_u(const BezierPatch<D>&, double);                                     \
  template BezierCurve<D> iso_curve_v(const BezierPatch<D>&, double);                                     \
  template BezierCurve<D> boundary_curve(const BezierPatch<D>&, PatchEdge);                               \
  template std::vector<Point<D>> row_from_edge(const BezierPatch<D>&, PatchEdge, int);
PATCHWORK_INSTANTIATE(3)
PATCHWORK_INSTANTIATE(4)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
