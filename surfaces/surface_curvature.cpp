#include "surfaces/surface_curvature.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/errors.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

// The curves through a pole sampled for the fit (file comment).
constexpr int pole_samples = 9;

SurfaceCurvature undefined_curvature() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SurfaceCurvature c;
  c.defined = false;
  c.gaussian = c.mean = c.k1 = c.k2 = c.pole_residual = nan;
  c.d1 = c.d2 = c.normal = Vec3::Constant(nan);
  return c;
}

// The curvature from the shape operator S written in the orthonormal frame (e1, e2, n).
SurfaceCurvature from_shape_operator(const Eigen::Matrix2d& S, const Vec3& e1, const Vec3& e2, const Vec3& n,
                                     double size) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
  solver.computeDirect(0.5 * (S + S.transpose()));
  SurfaceCurvature c;
  c.defined = true;
  c.normal = n;
  c.k2 = solver.eigenvalues()[0];  // ascending
  c.k1 = solver.eigenvalues()[1];
  c.gaussian = c.k1 * c.k2;
  c.mean = 0.5 * (c.k1 + c.k2);
  c.umbilic = c.k1 - c.k2 <= 1e-8 * (std::abs(c.k1) + std::abs(c.k2) + 1.0 / size);
  if (c.umbilic) {
    c.d1 = e1;
  } else {
    const Eigen::Vector2d a = solver.eigenvectors().col(1);
    c.d1 = (a[0] * e1 + a[1] * e2).normalized();
  }
  c.d2 = n.cross(c.d1);
  return c;
}

template <class Points>
double box_size(const Points& points) {
  Eigen::AlignedBox3d box(points.front());
  for (const Vec3& p : points) box.extend(p);
  return box.diagonal().norm();
}

// A boundary edge whose control points coincide, through the point asked for: the curves leave
// it along v (a v-edge, s = u runs along it) or along u.
struct Pole {
  bool curves_along_v;
  double fixed;  // the edge's v (or u)
  double lo;     // the range of s along the edge
  double hi;
};

// Equal to rounding: 1e-12 of the net's size, or the derivatives' rounding far from the origin
// (a split or knot insertion leaves a pole's points some ulps apart there).
bool collapsed(const std::vector<Vec3>& row, double size, const detail::DegeneracyThresholds& thresholds) {
  const double tolerance = std::max(1e-12 * size, thresholds.noise);
  return std::all_of(row.begin(), row.end(), [&](const Vec3& p) { return (p - row.front()).norm() <= tolerance; });
}

// The pole fit of the file comment; `derivatives(u, v)` gives the partial derivatives of order 2.
template <class Derivatives>
SurfaceCurvature pole_curvature(const Derivatives& derivatives, const Vec3& n, const Pole& pole, double size,
                                int degree) {
  Eigen::Matrix<double, pole_samples, 3> A;
  Eigen::Matrix<double, pole_samples, 1> kn;
  Vec3 e1 = Vec3::Zero();
  Vec3 e2 = Vec3::Zero();
  for (int k = 0; k < pole_samples; ++k) {
    const double s = pole.lo + (pole.hi - pole.lo) * k / (pole_samples - 1);
    const PartialDerivatives<3> F = pole.curves_along_v ? derivatives(s, pole.fixed) : derivatives(pole.fixed, s);
    const Vec3 c1 = pole.curves_along_v ? F.at(0, 1) : F.at(1, 0);
    const Vec3 c2 = pole.curves_along_v ? F.at(0, 2) : F.at(2, 0);
    if (!(c1.norm() > 1e-12 * std::max(degree, 1) * size)) return undefined_curvature();  // c' = 0: not regular
    const Vec3 T = c1.normalized();
    if (std::abs(T.dot(n)) > 1e-8) return undefined_curvature();  // the tangents form a cone
    if (k == 0) {
      e1 = (T - T.dot(n) * n).normalized();
      e2 = n.cross(e1);
    }
    const double x = T.dot(e1);
    const double y = T.dot(e2);
    A.row(k) << x * x, 2.0 * x * y, y * y;
    kn[k] = c2.dot(n) / c1.squaredNorm();
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, pole_samples, 3>> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& sigma = svd.singularValues();
  if (!(sigma[2] > 1e-6 * sigma[0])) return undefined_curvature();  // the directions do not span the plane
  const Eigen::Vector3d abc = svd.solve(kn);
  Eigen::Matrix2d S;
  S << abc[0], abc[1], abc[1], abc[2];
  SurfaceCurvature c = from_shape_operator(S, e1, e2, n, size);
  c.at_pole = true;
  c.pole_residual = (A * abc - kn).cwiseAbs().maxCoeff();
  return c;
}

// The curvature at (u, v) of a surface given by its derivatives, its unit (limit) normal and its
// poles: regular where F_u x F_v does not vanish, else the pole fit, else undefined.
template <class Derivatives, class UnitNormal>
SurfaceCurvature curvature_of(const Derivatives& derivatives, const UnitNormal& unit_normal,
                              const std::optional<Pole>& pole, double u, double v, double size,
                              const detail::DegeneracyThresholds& thresholds, int n, int m) {
  const PartialDerivatives<3> F = derivatives(u, v);
  if (!detail::first_normal_vanishes(F.at(1, 0), F.at(0, 1), thresholds)) {
    return detail::regular_curvature(F, size);
  }
  if (!pole) return undefined_curvature();
  Vec3 normal;
  try {
    normal = unit_normal(u, v);
  } catch (const NumericalError&) {
    return undefined_curvature();
  }
  return pole_curvature(derivatives, normal, *pole, size, pole->curves_along_v ? m : n);
}

// The pole through (u, v) of a patch on [0,1]^2 whose edge rows are given by `row(edge)`.
template <class Row>
std::optional<Pole> patch_pole(const Row& row, double u, double v, double size,
                               const detail::DegeneracyThresholds& t) {
  if ((v == 0.0 && collapsed(row(PatchEdge::v0), size, t)) || (v == 1.0 && collapsed(row(PatchEdge::v1), size, t))) {
    return Pole{true, v, 0.0, 1.0};
  }
  if ((u == 0.0 && collapsed(row(PatchEdge::u0), size, t)) || (u == 1.0 && collapsed(row(PatchEdge::u1), size, t))) {
    return Pole{false, u, 0.0, 1.0};
  }
  return std::nullopt;
}

std::vector<Vec3> projected(const std::vector<Vec4>& H) {
  std::vector<Vec3> points(H.size());
  for (std::size_t k = 0; k < H.size(); ++k) points[k] = H[k].head<3>() / H[k][3];
  return points;
}

}  // namespace

namespace detail {

SurfaceCurvature regular_curvature(const PartialDerivatives<3>& F, double size) {
  const Vec3& Fu = F.at(1, 0);
  const Vec3& Fv = F.at(0, 1);
  const Vec3 n = Fu.cross(Fv).normalized();
  const Vec3 e1 = Fu.normalized();
  const Vec3 e2 = n.cross(e1);
  // [F_u F_v] = [e1 e2] R, and II in the frame is R^(-T) II R^(-1).
  Eigen::Matrix2d R;
  R << Fu.norm(), e1.dot(Fv), 0.0, e2.dot(Fv);
  Eigen::Matrix2d II;
  II << F.at(2, 0).dot(n), F.at(1, 1).dot(n), F.at(1, 1).dot(n), F.at(0, 2).dot(n);
  const Eigen::Matrix2d Rinv = R.inverse();
  return from_shape_operator(Rinv.transpose() * II * Rinv, e1, e2, n, size);
}

}  // namespace detail

SurfaceCurvature curvature(const BezierPatch3& patch, double u, double v) {
  const double size = box_size(patch.control_points());
  const auto row = [&](PatchEdge edge) { return row_from_edge(patch, edge, 0); };
  const detail::DegeneracyThresholds thresholds = detail::degeneracy_thresholds(patch);
  return curvature_of([&](double s, double t) { return partial_derivatives(patch, s, t, 2); },
                      [&](double s, double t) { return unit_normal(patch, s, t); },
                      patch_pole(row, u, v, size, thresholds), u, v, size, thresholds, patch.degree_u(),
                      patch.degree_v());
}

SurfaceCurvature curvature(const RationalBezierPatch& patch, double u, double v) {
  const double size = box_size(projected(patch.homogeneous().control_points()));
  const auto row = [&](PatchEdge edge) { return projected(row_from_edge(patch.homogeneous(), edge, 0)); };
  const detail::DegeneracyThresholds thresholds = detail::degeneracy_thresholds(patch);
  return curvature_of([&](double s, double t) { return partial_derivatives(patch, s, t, 2); },
                      [&](double s, double t) { return unit_normal(patch, s, t); },
                      patch_pole(row, u, v, size, thresholds), u, v, size, thresholds, patch.degree_u(),
                      patch.degree_v());
}

SurfaceCurvature curvature(const NurbsSurface& surface, double u, double v) {
  const double size = box_size(projected(surface.homogeneous()));
  // Clamped ends: the boundary rows of control points are the edges.
  const auto row_v = [&](int j) {
    std::vector<Vec3> row;
    for (int i = 0; i < surface.count_u(); ++i) row.push_back(surface.control_point(i, j));
    return row;
  };
  const auto row_u = [&](int i) {
    std::vector<Vec3> row;
    for (int j = 0; j < surface.count_v(); ++j) row.push_back(surface.control_point(i, j));
    return row;
  };
  const KnotVector& U = surface.knots_u();
  const KnotVector& V = surface.knots_v();
  // The whole net's points and weights (a span's piece lies in its hull).
  const detail::DegeneracyThresholds t =
      detail::degeneracy_thresholds(surface, 0, surface.count_u() - 1, 0, surface.count_v() - 1);
  std::optional<Pole> pole;
  if (V.is_clamped() && ((v == V.a() && collapsed(row_v(0), size, t)) ||
                         (v == V.b() && collapsed(row_v(surface.count_v() - 1), size, t)))) {
    pole = Pole{true, v, U.a(), U.b()};
  } else if (U.is_clamped() && ((u == U.a() && collapsed(row_u(0), size, t)) ||
                                (u == U.b() && collapsed(row_u(surface.count_u() - 1), size, t)))) {
    pole = Pole{false, u, V.a(), V.b()};
  }
  return curvature_of([&](double s, double t) { return partial_derivatives(surface, s, t, 2); },
                      [&](double s, double t) { return unit_normal(surface, s, t); }, pole, u, v, size, t,
                      surface.degree_u(), surface.degree_v());
}

}  // namespace patchwork
