#include "surfaces/nurbs_surface.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "curves/bspline_basis.h"
#include "curves/bspline_conversion.h"
#include "curves/bspline_curve.h"
#include "curves/knot_insertion.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

std::vector<Vec4> homogenize(const KnotVector& u, const KnotVector& v, const std::vector<Vec3>& points,
                             const std::vector<double>& weights) {
  const std::size_t count =
      static_cast<std::size_t>(u.control_point_count()) * static_cast<std::size_t>(v.control_point_count());
  if (points.size() != count) {
    throw InvalidInput(detail::message("NurbsSurface: ", points.size(), " control points, the knots carry ",
                                       u.control_point_count(), " x ", v.control_point_count()));
  }
  if (!weights.empty() && weights.size() != count) {
    throw InvalidInput(detail::message("NurbsSurface: ", weights.size(), " weights for ", count, " control points"));
  }
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!std::isfinite(weights[k]) || !(weights[k] > 0.0)) {
      throw InvalidInput(detail::message("NurbsSurface: weight ", k, " = ", weights[k], " is not positive and finite"));
    }
  }
  // Equal weights c are the B-spline of the points: stored as 1, so that knot insertion (whose
  // affine combinations of c need not give c back exactly) keeps the surface polynomial.
  const bool equal = std::all_of(weights.begin(), weights.end(), [&](double w) { return w == weights.front(); });
  std::vector<Vec4> homogeneous(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double w = equal ? 1.0 : weights[k];
    if (!points[k].allFinite())
      throw InvalidInput(detail::message("NurbsSurface: control point ", k, " is not finite"));
    homogeneous[k] << w * points[k], w;
  }
  return homogeneous;
}

void check_domain(const NurbsSurface& s, double u, double v) {
  const KnotVector& U = s.knots_u();
  const KnotVector& V = s.knots_v();
  if (!(u >= U.a() && u <= U.b()) || !(v >= V.a() && v <= V.b())) {
    throw InvalidInput(detail::message("NurbsSurface: (", u, ", ", v, ") is outside the domain [", U.a(), ", ", U.b(),
                                       "] x [", V.a(), ", ", V.b(), "]"));
  }
}

// The homogeneous surface's partial derivatives at (u, v), from the basis derivatives.
PartialDerivatives<4> homogeneous_partials(const NurbsSurface& s, double u, double v, int order) {
  const int p = s.degree_u(), q = s.degree_v();
  const int su = s.knots_u().span(u), sv = s.knots_v().span(v);
  const Eigen::MatrixXd Nu = basis_function_derivatives(s.knots_u(), u, order);
  const Eigen::MatrixXd Nv = basis_function_derivatives(s.knots_v(), v, order);
  PartialDerivatives<4> H(order);
  for (int a = 0; a <= order; ++a) {
    for (int b = 0; a + b <= order; ++b) {
      Vec4 sum = Vec4::Zero();
      for (int c = 0; c <= q; ++c) {
        Vec4 row = Vec4::Zero();
        for (int r = 0; r <= p; ++r) row += Nu(a, r) * s.at(su - p + r, sv - q + c);
        sum += Nv(b, c) * row;
      }
      H.at(a, b) = sum;
    }
  }
  return H;
}

// The homogeneous points as curves: row j along u, or column i along v.
BSplineCurve<4> row(const NurbsSurface& s, int j) {
  std::vector<Vec4> points;
  for (int i = 0; i < s.count_u(); ++i) points.push_back(s.at(i, j));
  return BSplineCurve<4>(s.knots_u(), std::move(points));
}

BSplineCurve<4> column(const NurbsSurface& s, int i) {
  std::vector<Vec4> points;
  for (int j = 0; j < s.count_v(); ++j) points.push_back(s.at(i, j));
  return BSplineCurve<4>(s.knots_v(), std::move(points));
}

NurbsSurface from_homogeneous(KnotVector u, KnotVector v, const std::vector<Vec4>& homogeneous) {
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (const Vec4& h : homogeneous) {
    points.push_back(h.head<3>() / h[3]);
    weights.push_back(h[3]);
  }
  return NurbsSurface(std::move(u), std::move(v), points, weights);
}

// The joins between neighbouring patches of an extraction (NurbsBezierPatches::joins).
std::vector<KnownJoin> neighbour_joins(const NurbsBezierPatches& pieces) {
  std::vector<KnownJoin> joins;
  for (int t = 0; t < pieces.spans_v; ++t) {
    for (int s = 0; s < pieces.spans_u; ++s) {
      const auto k = static_cast<std::uint32_t>(s + pieces.spans_u * t);
      if (s + 1 < pieces.spans_u) {
        joins.push_back(
            {{k, PatchEdge::u1}, {k + 1, PatchEdge::u0}, false, pieces.continuity_u[static_cast<std::size_t>(s)]});
      }
      if (t + 1 < pieces.spans_v) {
        joins.push_back({{k, PatchEdge::v1},
                         {k + static_cast<std::uint32_t>(pieces.spans_u), PatchEdge::v0},
                         false,
                         pieces.continuity_v[static_cast<std::size_t>(t)]});
      }
    }
  }
  return joins;
}

}  // namespace

NurbsSurface::NurbsSurface(KnotVector u, KnotVector v, const std::vector<Vec3>& points,
                           const std::vector<double>& weights)
    : u_(std::move(u)), v_(std::move(v)), homogeneous_(homogenize(u_, v_, points, weights)) {
  rational_ = std::any_of(homogeneous_.begin(), homogeneous_.end(),
                          [&](const Vec4& h) { return h[3] != homogeneous_.front()[3]; });
}

Vec3 NurbsSurface::control_point(int i, int j) const {
  const Vec4& h = at(i, j);
  return h.head<3>() / h[3];
}

Vec3 NurbsSurface::evaluate(double u, double v) const {
  check_domain(*this, u, v);
  const Vec4 h = homogeneous_partials(*this, u, v, 0).at(0, 0);
  return h.head<3>() / h[3];
}

PartialDerivatives<3> partial_derivatives(const NurbsSurface& surface, double u, double v, int order) {
  if (order < 0) throw InvalidInput(detail::message("partial_derivatives: order ", order, " < 0"));
  check_domain(surface, u, v);
  return detail::projected_partial_derivatives(homogeneous_partials(surface, u, v, order));
}

namespace detail {

DegeneracyThresholds degeneracy_thresholds(const NurbsSurface& surface, int i0, int i1, int j0, int j1) {
  Eigen::AlignedBox3d box(surface.control_point(i0, j0));
  double w_min = surface.weight(i0, j0);
  double w_max = w_min;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      box.extend(surface.control_point(i, j));
      w_min = std::min(w_min, surface.weight(i, j));
      w_max = std::max(w_max, surface.weight(i, j));
    }
  }
  return degeneracy_thresholds(surface.degree_u(), surface.degree_v(), box, true, w_max / w_min);
}

}  // namespace detail

Vec3 unit_normal(const NurbsSurface& surface, double u, double v) {
  check_domain(surface, u, v);
  const int p = surface.degree_u(), q = surface.degree_v();
  const KnotVector& U = surface.knots_u();
  const KnotVector& V = surface.knots_v();
  const int su = U.span(u), sv = V.span(v);
  // In the parameters (s, t) in [0,1]^2 of the span's Bezier piece: derivatives scale by the
  // span lengths (chain rule), and the limit direction looks towards the piece's centre.
  const double du = U[su + 1] - U[su], dv = V[sv + 1] - V[sv];
  // Vanishing is judged against the span's control points and weights, the net of the piece's
  // derivatives.
  const detail::DegeneracyThresholds thresholds = detail::degeneracy_thresholds(surface, su - p, su, sv - q, sv);
  const auto in_piece = [&](int order) {
    PartialDerivatives<3> F = partial_derivatives(surface, u, v, order);
    for (int a = 0; a <= order; ++a) {
      for (int b = 0; a + b <= order; ++b) F.at(a, b) *= std::pow(du, a) * std::pow(dv, b);
    }
    return F;
  };
  const PartialDerivatives<3> first = in_piece(1);
  if (!detail::first_normal_vanishes(first.at(1, 0), first.at(0, 1), thresholds)) {
    return first.at(1, 0).cross(first.at(0, 1)).normalized();
  }
  return detail::limit_unit_normal(in_piece(std::min(p + q, 12) + 1), (u - U[su]) / du, (v - V[sv]) / dv, thresholds,
                                   p, q);
}

NurbsSurface insert_knot_u(const NurbsSurface& surface, double u, int times) {
  std::vector<BSplineCurve<4>> rows;
  for (int j = 0; j < surface.count_v(); ++j) rows.push_back(insert_knot(row(surface, j), u, times));
  const int count_u = rows.front().knot_vector().control_point_count();
  std::vector<Vec4> homogeneous;
  for (int j = 0; j < surface.count_v(); ++j) {
    for (int i = 0; i < count_u; ++i)
      homogeneous.push_back(rows[static_cast<std::size_t>(j)].control_points()[static_cast<std::size_t>(i)]);
  }
  return from_homogeneous(rows.front().knot_vector(), surface.knots_v(), homogeneous);
}

NurbsSurface insert_knot_v(const NurbsSurface& surface, double v, int times) {
  std::vector<BSplineCurve<4>> columns;
  for (int i = 0; i < surface.count_u(); ++i) columns.push_back(insert_knot(column(surface, i), v, times));
  const int count_v = columns.front().knot_vector().control_point_count();
  std::vector<Vec4> homogeneous;
  for (int j = 0; j < count_v; ++j) {
    for (int i = 0; i < surface.count_u(); ++i)
      homogeneous.push_back(columns[static_cast<std::size_t>(i)].control_points()[static_cast<std::size_t>(j)]);
  }
  return from_homogeneous(surface.knots_u(), columns.front().knot_vector(), homogeneous);
}

NurbsBezierPatches bezier_patches(const NurbsSurface& surface) {
  const int p = surface.degree_u(), q = surface.degree_v();
  NurbsBezierPatches result;
  result.breaks_u = surface.knots_u().breakpoints();
  result.breaks_v = surface.knots_v().breakpoints();
  result.continuity_u = surface.knots_u().breakpoint_continuity();
  result.continuity_v = surface.knots_v().breakpoint_continuity();
  // Every row cut into its u-pieces: pieces[j][s] has p + 1 homogeneous points.
  std::vector<std::vector<BezierCurve<4>>> row_pieces;
  for (int j = 0; j < surface.count_v(); ++j) row_pieces.push_back(bezier_pieces(row(surface, j)));
  result.spans_u = static_cast<int>(row_pieces.front().size());
  // Then each column of those pieces' points cut into its v-pieces.
  std::vector<std::vector<std::vector<BezierCurve<4>>>> column_pieces(static_cast<std::size_t>(result.spans_u));
  for (int s = 0; s < result.spans_u; ++s) {
    for (int r = 0; r <= p; ++r) {
      std::vector<Vec4> points;
      for (int j = 0; j < surface.count_v(); ++j) {
        points.push_back(row_pieces[static_cast<std::size_t>(j)][static_cast<std::size_t>(s)]
                             .control_points()[static_cast<std::size_t>(r)]);
      }
      column_pieces[static_cast<std::size_t>(s)].push_back(
          bezier_pieces(BSplineCurve<4>(surface.knots_v(), std::move(points))));
    }
  }
  result.spans_v = static_cast<int>(column_pieces.front().front().size());
  for (int t = 0; t < result.spans_v; ++t) {
    for (int s = 0; s < result.spans_u; ++s) {
      std::vector<Vec4> net;  // (p + 1) x (q + 1), u fastest
      for (int c = 0; c <= q; ++c) {
        for (int r = 0; r <= p; ++r) {
          net.push_back(
              column_pieces[static_cast<std::size_t>(s)][static_cast<std::size_t>(r)][static_cast<std::size_t>(t)]
                  .control_points()[static_cast<std::size_t>(c)]);
        }
      }
      const RationalBezierPatch patch{BezierPatch4(p, q, std::move(net))};
      if (surface.rational()) {
        result.patches.emplace_back(patch);
      } else {
        result.patches.emplace_back(patch.control_net());  // every weight is the same: polynomial
      }
    }
  }
  result.joins = neighbour_joins(result);
  return result;
}

NurbsBezierPatches bezier_patches(const NurbsSurface& surface, double u0, double u1, double v0, double v1) {
  const KnotVector& U = surface.knots_u();
  const KnotVector& V = surface.knots_v();
  if (!(U.a() <= u0 && u0 < u1 && u1 <= U.b()) || !(V.a() <= v0 && v0 < v1 && v1 <= V.b())) {
    throw InvalidInput(detail::message("bezier_patches: the range [", u0, ", ", u1, "] x [", v0, ", ", v1,
                                       "] is not inside the domain [", U.a(), ", ", U.b(), "] x [", V.a(), ", ", V.b(),
                                       "]"));
  }
  NurbsSurface cut = surface;
  // An interior end becomes a breakpoint of multiplicity p: the pieces then end there.
  const auto cut_u = [&](double u) {
    const int room = cut.degree_u() - cut.knots_u().multiplicity(u);
    if (u > U.a() && u < U.b() && room > 0) cut = insert_knot_u(cut, u, room);
  };
  const auto cut_v = [&](double v) {
    const int room = cut.degree_v() - cut.knots_v().multiplicity(v);
    if (v > V.a() && v < V.b() && room > 0) cut = insert_knot_v(cut, v, room);
  };
  cut_u(u0);
  cut_u(u1);
  cut_v(v0);
  cut_v(v1);
  const NurbsBezierPatches whole = bezier_patches(cut);
  // The spans inside the range, and the breakpoints and continuities between them.
  const auto inside = [](const std::vector<double>& breaks, double from, double to) {
    std::vector<int> spans;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      if (breaks[k] >= from && breaks[k + 1] <= to) spans.push_back(static_cast<int>(k));
    }
    return spans;
  };
  const std::vector<int> su = inside(whole.breaks_u, u0, u1), sv = inside(whole.breaks_v, v0, v1);
  NurbsBezierPatches result;
  result.spans_u = static_cast<int>(su.size());
  result.spans_v = static_cast<int>(sv.size());
  for (int s : su) result.breaks_u.push_back(whole.breaks_u[static_cast<std::size_t>(s)]);
  result.breaks_u.push_back(whole.breaks_u[static_cast<std::size_t>(su.back()) + 1]);
  for (int t : sv) result.breaks_v.push_back(whole.breaks_v[static_cast<std::size_t>(t)]);
  result.breaks_v.push_back(whole.breaks_v[static_cast<std::size_t>(sv.back()) + 1]);
  for (std::size_t k = 0; k + 1 < su.size(); ++k)
    result.continuity_u.push_back(whole.continuity_u[static_cast<std::size_t>(su[k])]);
  for (std::size_t k = 0; k + 1 < sv.size(); ++k)
    result.continuity_v.push_back(whole.continuity_v[static_cast<std::size_t>(sv[k])]);
  for (int t : sv) {
    for (int s : su) result.patches.push_back(whole.patches[static_cast<std::size_t>(s + whole.spans_u * t)]);
  }
  result.joins = neighbour_joins(result);
  return result;
}

}  // namespace patchwork
