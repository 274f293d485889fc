#include "queries/curve_surface_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Dense>

#include "core/assert.h"
#include "core/errors.h"
#include "queries/curve_intersection.h"
#include "queries/intersection_kernel.h"

namespace patchwork {
namespace {

using detail::CurvePiece;
using detail::Interval;
using Box3 = std::array<Interval, 3>;

constexpr std::size_t max_triples = std::size_t{1} << 21;
constexpr double domain_slack = 1e-13;

// The piece of a rational patch over [u0, u1] x [v0, v1]: homogeneous net, projected points, box,
// unit normal of its plane and the slab half-width about it.
struct PatchPiece {
  double u0, u1, v0, v1;
  std::vector<Vec4> H;
  std::vector<Vec3> P;
  Eigen::AlignedBox3d box;
  Vec3 normal;
  double flatness;
  bool valid;
};

PatchPiece patch_piece(const RationalBezierPatch& patch, double u0, double u1, double v0, double v1) {
  const int n = patch.degree_u(), m = patch.degree_v();
  PatchPiece piece{u0, u1, v0, v1,
                   detail::reparametrized_net(patch.homogeneous().control_points(), n, m, u0, u1, v0, v1),
                   {}, {}, Vec3::Zero(), 0.0, true};
  for (const Vec4& h : piece.H) {
    if (!(h[3] > 0.0)) piece.valid = false;
    piece.P.push_back(h.head<3>() / h[3]);
    piece.box.extend(piece.P.back());
  }
  auto at = [&](int i, int j) -> const Vec3& { return piece.P[static_cast<std::size_t>(i + (n + 1) * j)]; };
  const Vec3 along_u = at(n, 0) - at(0, 0) + at(n, m) - at(0, m);
  const Vec3 along_v = at(0, m) - at(0, 0) + at(n, m) - at(n, 0);
  const Vec3 normal = along_u.cross(along_v);
  if (normal.norm() > 0.0 && std::isfinite(normal.norm())) {
    piece.normal = normal.normalized();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& p : piece.P) lo = std::min(lo, piece.normal.dot(p)), hi = std::max(hi, piece.normal.dot(p));
    piece.flatness = hi - lo;
  } else {
    piece.flatness = piece.box.diagonal().norm();
  }
  return piece;
}

// Per coordinate, intervals containing F_u and F_v on the piece: F_u = (H_u,xyz - w_u F) / w.
std::array<std::array<Interval, 3>, 2> patch_derivative_enclosure(const PatchPiece& piece, int n, int m) {
  auto hull = [](const std::vector<Vec4>& points, int c) {
    Interval result{points[0][c], points[0][c]};
    for (const Vec4& p : points) result.lo = std::min(result.lo, p[c]), result.hi = std::max(result.hi, p[c]);
    return result;
  };
  std::array<std::array<Interval, 3>, 2> result;
  Interval w = hull(piece.H, 3);
  std::array<Interval, 3> F;
  for (int c = 0; c < 3; ++c) {
    F[c] = {piece.box.min()[c], piece.box.max()[c]};
  }
  for (int direction = 0; direction < 2; ++direction) {
    const int degree = direction == 0 ? n : m;
    const double width = direction == 0 ? piece.u1 - piece.u0 : piece.v1 - piece.v0;
    std::vector<Vec4> hodograph;
    if (degree == 0) {
      hodograph.push_back(Vec4::Zero());
    } else {
      for (int j = 0; j <= m - (direction == 1 ? 1 : 0); ++j) {
        for (int i = 0; i <= n - (direction == 0 ? 1 : 0); ++i) {
          const Vec4& here = piece.H[static_cast<std::size_t>(i + (n + 1) * j)];
          const Vec4& next = direction == 0 ? piece.H[static_cast<std::size_t>(i + 1 + (n + 1) * j)]
                                            : piece.H[static_cast<std::size_t>(i + (n + 1) * (j + 1))];
          hodograph.push_back((degree / width) * (next - here));
        }
      }
    }
    const Interval dw = hull(hodograph, 3);
    for (int c = 0; c < 3; ++c) result[direction][c] = detail::divide_positive(hull(hodograph, c) - dw * F[c], w);
  }
  return result;
}

struct Triple {
  CurvePiece<3> curve;
  PatchPiece patch;
};

struct SurfaceLeaf {
  Box3 box;
};

bool contains(const Box3& box, const Vec3& x) {
  for (int c = 0; c < 3; ++c) {
    if (!(box[c].lo <= x[c] && x[c] <= box[c].hi)) return false;
  }
  return true;
}

bool contains(const Box3& outer, const Box3& inner) {
  for (int c = 0; c < 3; ++c) {
    if (!(outer[c].lo <= inner[c].lo && inner[c].hi <= outer[c].hi)) return false;
  }
  return true;
}

class SurfaceSearch {
 public:
  SurfaceSearch(const RationalBezierCurve3& curve, const RationalBezierPatch& patch, std::uint32_t index)
      : C_(curve), F_(patch), index_(index), n_(patch.degree_u()), m_(patch.degree_v()) {
    double scale = 0.0, w_min = std::numeric_limits<double>::infinity(), w_max = 0.0;
    for (int i = 0; i <= curve.degree(); ++i) {
      scale = std::max(scale, curve.control_point(i).cwiseAbs().maxCoeff());
      w_min = std::min(w_min, curve.weight(i)), w_max = std::max(w_max, curve.weight(i));
    }
    for (const Vec4& h : patch.homogeneous().control_points()) {
      scale = std::max(scale, (h.head<3>() / h[3]).cwiseAbs().maxCoeff());
      w_min = std::min(w_min, h[3]), w_max = std::max(w_max, h[3]);
    }
    const int degree = std::max({curve.degree(), n_ + m_});
    eps_ = detail::rounding_level(std::max(scale, std::numeric_limits<double>::min()), degree);
    evaluation_error_ = 8.0 * (curve.degree() + n_ + m_ + 3) * 0x1p-53 * scale * (w_max / w_min);
  }

  double eps() const { return eps_; }

  std::vector<CurveSurfaceHit> run() {
    std::vector<Triple> stack;
    stack.push_back({detail::curve_piece(C_, C_.a(), C_.b()), patch_piece(F_, 0.0, 1.0, 0.0, 1.0)});
    std::size_t processed = 0;
    while (!stack.empty()) {
      Triple triple = std::move(stack.back());
      stack.pop_back();
      if (++processed > max_triples) {
        throw NumericalError(detail::message("intersect_curve_surface: more than ", max_triples, " triples of pieces"));
      }
      if (!settle(triple)) split(std::move(triple), stack);
    }
    std::vector<Box3> boxes;
    for (const SurfaceLeaf& leaf : leaves_) boxes.push_back(leaf.box);
    for (const auto& group : detail::touching_groups<3>(boxes, 0.0)) report_contact(group);
    return std::move(hits_);
  }

 private:
  static Box3 box_of(const Triple& x) {
    return {Interval{x.curve.t0, x.curve.t1}, Interval{x.patch.u0, x.patch.u1}, Interval{x.patch.v0, x.patch.v1}};
  }

  bool tiny_curve(const CurvePiece<3>& c) const { return c.t1 - c.t0 <= std::ldexp(C_.b() - C_.a(), -44); }
  static bool tiny_patch(const PatchPiece& p) { return p.u1 - p.u0 <= 0x1p-44 && p.v1 - p.v0 <= 0x1p-44; }

  // The gap between the projections of the two control nets onto unit axes (file comment).
  double separation(const CurvePiece<3>& c, const PatchPiece& p) const {
    const Vec3 chord = c.P.back() - c.P.front();
    const Vec3 between = p.box.center() - c.box.center();
    std::array<Vec3, 3> axes{p.normal, chord.squaredNorm() > 0.0 ? Vec3(between - (between.dot(chord) / chord.squaredNorm()) * chord) : Vec3::Zero(),
                             chord.cross(p.normal)};
    double gap = c.box.exteriorDistance(p.box);
    for (const Vec3& candidate : axes) {
      const double length = candidate.norm();
      if (!(length > 0.0) || !std::isfinite(length)) continue;
      const Vec3 axis = candidate / length;
      double c_lo = std::numeric_limits<double>::infinity(), c_hi = -c_lo, p_lo = c_lo, p_hi = -c_lo;
      for (const Vec3& x : c.P) c_lo = std::min(c_lo, axis.dot(x)), c_hi = std::max(c_hi, axis.dot(x));
      for (const Vec3& x : p.P) p_lo = std::min(p_lo, axis.dot(x)), p_hi = std::max(p_hi, axis.dot(x));
      gap = std::max({gap, p_lo - c_hi, c_lo - p_hi});
    }
    return gap;
  }

  bool settle(const Triple& x) {
    if (separation(x.curve, x.patch) > eps_) return true;
    const Box3 box = box_of(x);
    for (const Box3& root : unique_boxes_) {
      if (contains(root, box)) return true;
    }
    if (certify(box)) return true;
    const bool curve_done = x.curve.flatness <= eps_ || tiny_curve(x.curve);
    const bool patch_done = x.patch.flatness <= eps_ || tiny_patch(x.patch);
    const Vec3 chord = x.curve.P.back() - x.curve.P.front();
    const bool parallel = !(std::abs(chord.dot(x.patch.normal)) > 1e-4 * chord.norm());
    if (curve_done && patch_done && (parallel || tiny_curve(x.curve) || tiny_patch(x.patch))) {
      leaves_.push_back({box});
      return true;
    }
    return false;
  }

  void split(Triple x, std::vector<Triple>& stack) const {
    const double curve_size = tiny_curve(x.curve) ? -1.0 : x.curve.box.diagonal().norm();
    const double patch_size = tiny_patch(x.patch) ? -1.0 : x.patch.box.diagonal().norm();
    PATCHWORK_ASSERT(curve_size >= 0.0 || patch_size >= 0.0, "a triple that is not a leaf can be split");
    if (curve_size >= patch_size) {
      const double middle = 0.5 * (x.curve.t0 + x.curve.t1);
      for (const auto& [t0, t1] : {std::pair{x.curve.t0, middle}, std::pair{middle, x.curve.t1}}) {
        stack.push_back({detail::curve_piece(C_, t0, t1), x.patch});
      }
      return;
    }
    const PatchPiece& p = x.patch;
    auto at = [&](int i, int j) -> const Vec3& { return p.P[static_cast<std::size_t>(i + (n_ + 1) * j)]; };
    const double u_length = (at(n_, 0) - at(0, 0)).norm() + (at(n_, m_) - at(0, m_)).norm();
    const double v_length = (at(0, m_) - at(0, 0)).norm() + (at(n_, m_) - at(n_, 0)).norm();
    const bool u_splittable = p.u1 - p.u0 > 0x1p-44, v_splittable = p.v1 - p.v0 > 0x1p-44;
    if (u_splittable && (!v_splittable || u_length >= v_length)) {
      const double middle = 0.5 * (p.u0 + p.u1);
      stack.push_back({x.curve, patch_piece(F_, p.u0, middle, p.v0, p.v1)});
      stack.push_back({x.curve, patch_piece(F_, middle, p.u1, p.v0, p.v1)});
    } else {
      const double middle = 0.5 * (p.v0 + p.v1);
      stack.push_back({x.curve, patch_piece(F_, p.u0, p.u1, p.v0, middle)});
      stack.push_back({x.curve, patch_piece(F_, p.u0, p.u1, middle, p.v1)});
    }
  }

  // G(x) = F(u, v) - C(t) and its Jacobian [-C', F_u, F_v] at x = (t, u, v).
  std::pair<Vec3, Eigen::Matrix3d> system(const Vec3& x) const {
    const auto [point, d] = detail::point_and_derivative(C_, x[0]);
    const PartialDerivatives<3> D = partial_derivatives(F_, x[1], x[2], 1);
    Eigen::Matrix3d J;
    J << -d, D.at(1, 0), D.at(0, 1);
    return {D.at(0, 0) - point, J};
  }

  std::optional<std::array<std::array<Interval, 3>, 3>> enclosure(const Box3& X) const {
    const auto c = detail::curve_piece(C_, X[0].lo, X[0].hi);
    const PatchPiece p = patch_piece(F_, X[1].lo, X[1].hi, X[2].lo, X[2].hi);
    if (!c.valid || !p.valid) return std::nullopt;
    const auto dc = detail::derivative_enclosure(c);
    const auto dp = patch_derivative_enclosure(p, n_, m_);
    std::array<std::array<Interval, 3>, 3> J;
    for (int row = 0; row < 3; ++row) J[row] = {Interval{-dc[row].hi, -dc[row].lo}, dp[0][row], dp[1][row]};
    return J;
  }

  detail::KrawczykOutcome krawczyk_at(const Box3& X, const Vec3& m, const std::array<std::array<Interval, 3>, 3>& J, Box3& image) const {
    const auto [g, jacobian] = system(m);
    const double scale = jacobian.col(0).norm() * jacobian.col(1).norm() * jacobian.col(2).norm();
    if (!(std::abs(jacobian.determinant()) > 1e-14 * scale)) return detail::KrawczykOutcome::unknown;
    return detail::krawczyk<3>(X, m, g, evaluation_error_, J, jacobian.inverse(), image);
  }

  bool certify(const Box3& box) {
    Box3 X;
    for (int c = 0; c < 3; ++c) X[c] = {box[c].lo - box[c].width() / 64.0, box[c].hi + box[c].width() / 64.0};
    const auto J = enclosure(X);
    if (!J) return false;
    Vec3 m(X[0].mid(), X[1].mid(), X[2].mid());
    Box3 image;
    const auto outcome = krawczyk_at(X, m, *J, image);
    if (outcome == detail::KrawczykOutcome::no_zero) return true;
    if (outcome != detail::KrawczykOutcome::unique_zero) return false;
    for (int iteration = 0; iteration < 50; ++iteration) {
      const auto [g, jacobian] = system(m);
      const Vec3 step = jacobian.fullPivLu().solve(-g);
      if (!step.allFinite()) break;
      Vec3 next = m + step;
      for (int c = 0; c < 3; ++c) next[c] = std::clamp(next[c], X[c].lo, X[c].hi);
      const bool done = next == m;
      m = next;
      if (done) break;
    }
    Box3 tight = image;
    auto J_tight = *J;
    for (int iteration = 0; iteration < 60; ++iteration) {
      Vec3 centre;
      for (int c = 0; c < 3; ++c) centre[c] = std::clamp(m[c], tight[c].lo, tight[c].hi);
      if (tight[0].width() > 1e-8 * (C_.b() - C_.a()) && tight[1].width() > 1e-8 && tight[2].width() > 1e-8) {
        if (const auto J_new = enclosure(tight)) J_tight = *J_new;
      }
      Box3 next;
      if (krawczyk_at(tight, centre, J_tight, next) != detail::KrawczykOutcome::unique_zero) break;
      auto width = [&](const Box3& b) { return std::max({b[0].width() / (C_.b() - C_.a()), b[1].width(), b[2].width()}); };
      const double before = width(tight);
      for (int c = 0; c < 3; ++c) tight[c] = {std::max(tight[c].lo, next[c].lo), std::min(tight[c].hi, next[c].hi)};
      if (!(width(tight) < 0.75 * before)) break;
    }
    Vec3 x;
    for (int c = 0; c < 3; ++c) x[c] = std::clamp(m[c], tight[c].lo, tight[c].hi);
    for (const Box3& root : unique_boxes_) {
      if (contains(root, x)) return true;  // found before, from a neighbouring triple
    }
    unique_boxes_.push_back(X);
    Vec3 bound;
    for (int c = 0; c < 3; ++c) bound[c] = std::max(x[c] - tight[c].lo, tight[c].hi - x[c]);
    const std::array<Interval, 3> domain{Interval{C_.a(), C_.b()}, Interval{0.0, 1.0}, Interval{0.0, 1.0}};
    for (int c = 0; c < 3; ++c) {
      const double slack = bound[c] + domain_slack * domain[c].width();
      if (x[c] < domain[c].lo - slack || x[c] > domain[c].hi + slack) return true;
      const double inside = std::clamp(x[c], domain[c].lo, domain[c].hi);
      bound[c] += std::abs(inside - x[c]);
      x[c] = inside;
    }
    const Vec3 point = C_.evaluate(x[0]);
    hits_.push_back({x[0], index_, x[1], x[2], point, bound[0], bound[1], bound[2], (F_.evaluate(x[1], x[2]) - point).norm(), false});
    return true;
  }

  // Where the curve touches the surface, G's Jacobian has rank 2 and Gauss-Newton stalls: minimise
  // d(t) = min over (u, v) of |F(u, v) - C(t)| instead, by golden-section search on t within the
  // contact's box, each d(t) by Gauss-Newton on (u, v) (regular: F_u x F_v != 0 off poles).
  void refine_along_curve(const Box3& hull, Vec3& x, double& best) const {
    auto foot = [&](double t, Eigen::Vector2d uv) {
      const Vec3 c = C_.evaluate(t);
      double distance = (F_.evaluate(uv[0], uv[1]) - c).norm();
      for (int iteration = 0; iteration < 20; ++iteration) {
        const PartialDerivatives<3> D = partial_derivatives(F_, uv[0], uv[1], 1);
        Eigen::Matrix<double, 3, 2> J;
        J << D.at(1, 0), D.at(0, 1);
        const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(-J.transpose() * (D.at(0, 0) - c));
        if (!step.allFinite()) break;
        const Eigen::Vector2d next(std::clamp(uv[0] + step[0], hull[1].lo, hull[1].hi), std::clamp(uv[1] + step[1], hull[2].lo, hull[2].hi));
        const double d = (F_.evaluate(next[0], next[1]) - c).norm();
        if (!(d < distance)) break;
        distance = d, uv = next;
      }
      return std::pair{distance, uv};
    };
    detail::golden_section(hull[0].lo, hull[0].hi, [&](double t) {
      const auto [d, uv] = foot(t, Eigen::Vector2d(x[1], x[2]));
      if (d < best) best = d, x = Vec3(t, uv[0], uv[1]);
      return d;
    });
  }

  // The contact of a group of leaves: its closest point by Gauss-Newton inside the group's box.
  void report_contact(const std::vector<std::size_t>& group) {
    Box3 hull = leaves_[group[0]].box;
    Vec3 x(hull[0].mid(), hull[1].mid(), hull[2].mid());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t index : group) {
      const Box3& box = leaves_[index].box;
      for (int c = 0; c < 3; ++c) hull[c] = {std::min(hull[c].lo, box[c].lo), std::max(hull[c].hi, box[c].hi)};
      const Vec3 centre(box[0].mid(), box[1].mid(), box[2].mid());
      const double distance = system(centre).first.norm();
      if (distance < best) best = distance, x = centre;
    }
    double damping = 1e-12;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const auto [g, J] = system(x);
      const Eigen::Matrix3d normal = J.transpose() * J;
      const Vec3 step = (normal + damping * normal.trace() * Eigen::Matrix3d::Identity()).ldlt().solve(-J.transpose() * g);
      if (!step.allFinite()) break;
      Vec3 next = x + step;
      for (int c = 0; c < 3; ++c) next[c] = std::clamp(next[c], hull[c].lo, hull[c].hi);
      const double distance = system(next).first.norm();
      if (distance < best) {
        const bool moved = next != x;
        best = distance, x = next, damping = std::max(1e-12, damping / 10.0);
        if (!moved) break;
      } else if ((damping *= 10.0) > 1e6) {
        break;
      }
    }
    if (!(best <= eps_)) refine_along_curve(hull, x, best);
    if (!(best <= eps_)) return;
    for (const Box3& root : unique_boxes_) {
      if (contains(root, x)) return;
    }
    Vec3 bound;
    for (int c = 0; c < 3; ++c) bound[c] = std::max(x[c] - hull[c].lo, hull[c].hi - x[c]);
    hits_.push_back({x[0], index_, x[1], x[2], C_.evaluate(x[0]), bound[0], bound[1], bound[2], best, true});
  }

  const RationalBezierCurve3& C_;
  const RationalBezierPatch& F_;
  std::uint32_t index_;
  int n_;
  int m_;
  double eps_ = 0.0;
  double evaluation_error_ = 0.0;
  std::vector<CurveSurfaceHit> hits_;
  std::vector<Box3> unique_boxes_;
  std::vector<SurfaceLeaf> leaves_;
};

void sort_by_t(std::vector<CurveSurfaceHit>& hits) {
  std::sort(hits.begin(), hits.end(), [](const CurveSurfaceHit& x, const CurveSurfaceHit& y) { return x.t < y.t; });
}

CurveSurfaceHits on_patch(const RationalBezierCurve3& curve, const RationalBezierPatch& patch) {
  SurfaceSearch search(curve, patch, 0);
  CurveSurfaceHits result{search.run(), search.eps()};
  sort_by_t(result.hits);
  return result;
}

}  // namespace

namespace detail {

CurveSurfaceHits intersect_pieces_with_set(const std::vector<RationalBezierCurve3>& pieces, const PatchSet& set) {
  CurveSurfaceHits result;
  std::vector<CurveSurfaceHit> all;
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    const RationalBezierPatch patch = set.rational_patch(p);
    for (const RationalBezierCurve3& piece : pieces) {
      SurfaceSearch search(piece, patch, p);
      result.eps = std::max(result.eps, search.eps());
      const auto hits = search.run();
      all.insert(all.end(), hits.begin(), hits.end());
    }
  }
  // One hit per point of the curve: hits whose t intervals meet are the same (the lowest patch).
  std::stable_sort(all.begin(), all.end(), [](const CurveSurfaceHit& x, const CurveSurfaceHit& y) { return x.patch < y.patch; });
  const double slack = domain_slack * (pieces.back().b() - pieces.front().a());
  for (const CurveSurfaceHit& hit : all) {
    const auto kept = std::find_if(result.hits.begin(), result.hits.end(), [&](const CurveSurfaceHit& y) {
      return std::abs(y.t - hit.t) <= y.t_bound + hit.t_bound + slack;
    });
    if (kept == result.hits.end()) {
      result.hits.push_back(hit);
      continue;
    }
    // One point of the curve: keep the certified (else the closer) hit, its t bound covering both.
    const double t_lo = std::min(kept->t - kept->t_bound, hit.t - hit.t_bound);
    const double t_hi = std::max(kept->t + kept->t_bound, hit.t + hit.t_bound);
    if (kept->tangential != hit.tangential ? !hit.tangential : hit.distance < kept->distance) *kept = hit;
    kept->t_bound = std::max(kept->t - t_lo, t_hi - kept->t);
  }
  sort_by_t(result.hits);
  return result;
}

}  // namespace detail

namespace {

CurveSurfaceHits on_set(const RationalBezierCurve3& curve, const PatchSet& set) {
  return detail::intersect_pieces_with_set(std::vector<RationalBezierCurve3>{curve}, set);
}

}  // namespace

CurveSurfaceHits intersect_curve_surface(const BezierCurve3& curve, const BezierPatch3& patch) {
  return on_patch(as_rational(curve), as_rational(patch));
}

CurveSurfaceHits intersect_curve_surface(const RationalBezierCurve3& curve, const RationalBezierPatch& patch) {
  return on_patch(curve, patch);
}

CurveSurfaceHits intersect_curve_surface(const BezierCurve3& curve, const PatchSet& set) { return on_set(as_rational(curve), set); }

CurveSurfaceHits intersect_curve_surface(const RationalBezierCurve3& curve, const PatchSet& set) { return on_set(curve, set); }

}  // namespace patchwork
