#include "queries/curve_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Dense>

#include "core/assert.h"
#include "core/errors.h"
#include "queries/curve_overlap.h"
#include "queries/intersection_kernel.h"
#include "queries/query_arguments.h"

namespace patchwork {
namespace detail {
namespace {

using Box2 = std::array<Interval, 2>;

constexpr std::size_t max_pairs = std::size_t{1} << 21;

bool contains(const Box2& outer, const Box2& inner) {
  return outer[0].lo <= inner[0].lo && inner[0].hi <= outer[0].hi && outer[1].lo <= inner[1].lo &&
         inner[1].hi <= outer[1].hi;
}

bool contains(const Box2& box, double t, double s) {
  return box[0].lo <= t && t <= box[0].hi && box[1].lo <= s && s <= box[1].hi;
}

bool intersects(const Box2& x, const Box2& y) {
  return x[0].lo <= y[0].hi && y[0].lo <= x[0].hi && x[1].lo <= y[1].hi && y[1].lo <= x[1].hi;
}

Box2 rectangle(const CurveOverlap& o) { return {Interval{o.t0, o.t1}, Interval{std::min(o.s0, o.s1), std::max(o.s0, o.s1)}}; }

template <int Dim>
double box_gap(const Eigen::AlignedBox<double, Dim>& x, const Eigen::AlignedBox<double, Dim>& y) {
  return x.exteriorDistance(y);
}

// A pair of pieces split off the two curves.
template <int Dim>
struct Pair {
  CurvePiece<Dim> first;
  CurvePiece<Dim> second;
};

// Two pieces flat within the leaf flatness, with a contact still possible.
struct Leaf {
  Box2 box;
  double t;
  double s;
};

template <int Dim>
class Search {
 public:
  Search(const RationalBezierCurve<Dim>& A, const RationalBezierCurve<Dim>& B, double tolerance)
      : A_(A), B_(B), tolerance_(tolerance) {
    Eigen::AlignedBox<double, Dim> all;
    double scale = 0.0;
    double w_min = std::numeric_limits<double>::infinity(), w_max = 0.0;
    for (const auto* curve : {&A, &B}) {
      for (int i = 0; i <= curve->degree(); ++i) {
        const Point<Dim> p = curve->control_point(i);
        all.extend(p);
        scale = std::max(scale, p.cwiseAbs().maxCoeff());
        w_min = std::min(w_min, curve->weight(i)), w_max = std::max(w_max, curve->weight(i));
      }
    }
    size_ = all.diagonal().norm();
    eps_ = rounding_level(std::max(scale, std::numeric_limits<double>::min()), std::max(A.degree(), B.degree()));
    reach_ = tolerance_ + eps_;
    evaluation_error_ = 8.0 * (A.degree() + B.degree() + 2) * 0x1p-53 * scale * (w_max / w_min);
    match_ = tolerance_ + 16.0 * eps_;
    leaf_flatness_ = std::max(eps_, tolerance_ / 8.0);
    leaf_size_ = std::max(std::ldexp(size_, -16), tolerance_);
  }

  CurveIntersections<Dim> run() {
    std::vector<Pair<Dim>> stack;
    stack.push_back({curve_piece(A_, A_.a(), A_.b()), curve_piece(B_, B_.a(), B_.b())});
    std::size_t processed = 0;
    while (!stack.empty()) {
      Pair<Dim> pair = std::move(stack.back());
      stack.pop_back();
      if (++processed > max_pairs) {
        throw NumericalError(message("intersect_curves: more than ", max_pairs,
                                     " pairs of pieces (curves that coincide under a reparametrisation not detected as an overlap)"));
      }
      if (!settle(pair)) split(std::move(pair), stack);
    }
    return result();
  }

 private:
  // Decides the pair if it can: true when nothing more is to be done with it.
  bool settle(Pair<Dim>& pair) {
    const CurvePiece<Dim>& p = pair.first;
    const CurvePiece<Dim>& q = pair.second;
    const Box2 box{Interval{p.t0, p.t1}, Interval{q.t0, q.t1}};
    if (box_gap(p.box, q.box) > reach_ || separation(p, q) > reach_) return true;
    const auto [alpha, beta] = segment_closest<Dim>(p.P.front(), p.P.back(), q.P.front(), q.P.back());
    for (const auto& root : unique_boxes_) {
      if (contains(root, box)) return true;
    }
    for (const CurveOverlap& o : overlaps_) {
      if (contains(rectangle(o), box)) return true;
    }
    if constexpr (Dim == 2) {
      if (certify(box)) return true;
    }
    switch (find_overlap(p, q)) {
      case Coincidence::overlap:
        return true;
      case Coincidence::local:
        // Within rounding of each other here but not as far as the curves go: a crossing at an
        // angle rounding cannot resolve (or a touching), which is a contact.
        leaves_.push_back({box, p.t0 + alpha * (p.t1 - p.t0), q.t0 + beta * (q.t1 - q.t0)});
        return true;
      case Coincidence::none:
        break;
    }
    // A leaf: both pieces flat (or split to the end), and in 2D, where Krawczyk's test decides
    // transversal crossings, also nearly parallel: a contact the test cannot decide.
    const bool p_done = (p.flatness <= leaf_flatness_ && p.box.diagonal().norm() <= leaf_size_) || tiny(p, A_);
    const bool q_done = (q.flatness <= leaf_flatness_ && q.box.diagonal().norm() <= leaf_size_) || tiny(q, B_);
    // Both pieces within rounding of one point: nothing finer can be told there. Without this, a
    // point where A' or B' vanishes (a repeated end control point, a cusp), met at an angle, is
    // never certified (the Jacobian is singular there) and never parallel, and every piece within
    // rounding of it pairs with every other down to 44 halvings: millions of pairs.
    const bool at_rounding = p.box.diagonal().norm() <= eps_ && q.box.diagonal().norm() <= eps_;
    if (at_rounding || (p_done && q_done && (Dim == 3 || tiny(p, A_) || tiny(q, B_) || nearly_parallel(p, q)))) {
      leaves_.push_back({box, p.t0 + alpha * (p.t1 - p.t0), q.t0 + beta * (q.t1 - q.t0)});
      return true;
    }
    return false;
  }

  // A lower bound on |A(t) - B(s)| over the pair: the gap between the projections of the two
  // control polygons (whose hulls hold the pieces) onto a unit axis, for axes across the chords
  // (in 2D the fat lines of both pieces; in 3D also the common normal of the chords).
  double separation(const CurvePiece<Dim>& p, const CurvePiece<Dim>& q) const {
    const Point<Dim> chord_p = p.P.back() - p.P.front(), chord_q = q.P.back() - q.P.front();
    const Point<Dim> between = q.box.center() - p.box.center();
    std::array<Point<Dim>, 3> axes;
    int count = 0;
    for (const Point<Dim>& chord : {chord_p, chord_q}) {
      const double length2 = chord.squaredNorm();
      if (length2 > 0.0) axes[count++] = between - (between.dot(chord) / length2) * chord;
    }
    if constexpr (Dim == 3) axes[count++] = chord_p.cross(chord_q);
    double gap = 0.0;
    for (int k = 0; k < count; ++k) {
      const double length = axes[k].norm();
      if (!(length > 0.0) || !std::isfinite(length)) continue;
      const Point<Dim> axis = axes[k] / length;
      double p_lo = std::numeric_limits<double>::infinity(), p_hi = -p_lo, q_lo = p_lo, q_hi = -p_lo;
      for (const auto& point : p.P) p_lo = std::min(p_lo, axis.dot(point)), p_hi = std::max(p_hi, axis.dot(point));
      for (const auto& point : q.P) q_lo = std::min(q_lo, axis.dot(point)), q_hi = std::max(q_hi, axis.dot(point));
      gap = std::max({gap, q_lo - p_hi, p_lo - q_hi});
    }
    return gap;
  }

  // Krawczyk's test on the widened box; true when it decides the box (no zero, or the zero).
  bool certify(const Box2& box) requires(Dim == 2) {
    const double wt = box[0].width() / 64.0, ws = box[1].width() / 64.0;
    Box2 X{Interval{box[0].lo - wt, box[0].hi + wt}, Interval{box[1].lo - ws, box[1].hi + ws}};
    const auto J = enclosure(X);
    if (!J) return false;
    Vec2 m(X[0].mid(), X[1].mid());
    Box2 image;
    auto outcome = krawczyk_at(X, m, *J, image);
    if (outcome == KrawczykOutcome::no_zero) return true;
    if (outcome != KrawczykOutcome::unique_zero) return false;
    // Newton inside X, then Krawczyk steps X <- K(X) n X to shrink the box around the zero.
    for (int iteration = 0; iteration < 50; ++iteration) {
      const auto [a, da] = point_and_derivative(A_, m[0]);
      const auto [b, db] = point_and_derivative(B_, m[1]);
      Eigen::Matrix2d jacobian;
      jacobian << da, -db;
      const Vec2 step = jacobian.fullPivLu().solve(-(a - b));
      if (!step.allFinite()) break;
      const Vec2 next(std::clamp(m[0] + step[0], X[0].lo, X[0].hi), std::clamp(m[1] + step[1], X[1].lo, X[1].hi));
      const bool done = (next - m).cwiseAbs().maxCoeff() == 0.0;
      m = next;
      if (done) break;
    }
    Box2 tight = image;
    auto J_tight = *J;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const Vec2 centre(std::clamp(m[0], tight[0].lo, tight[0].hi), std::clamp(m[1], tight[1].lo, tight[1].hi));
      if (tight[0].width() > 1e-8 * (A_.b() - A_.a()) && tight[1].width() > 1e-8 * (B_.b() - B_.a())) {
        if (const auto J_new = enclosure(tight)) J_tight = *J_new;
      }
      Box2 next;
      if (krawczyk_at(tight, centre, J_tight, next) != KrawczykOutcome::unique_zero) break;
      const double before = std::max(tight[0].width() / (A_.b() - A_.a()), tight[1].width() / (B_.b() - B_.a()));
      for (int c = 0; c < 2; ++c) tight[c] = {std::max(tight[c].lo, next[c].lo), std::min(tight[c].hi, next[c].hi)};
      const double after = std::max(tight[0].width() / (A_.b() - A_.a()), tight[1].width() / (B_.b() - B_.a()));
      if (!(after < 0.75 * before)) break;
    }
    double t = std::clamp(m[0], tight[0].lo, tight[0].hi);
    double s = std::clamp(m[1], tight[1].lo, tight[1].hi);
    for (const auto& root : unique_boxes_) {
      if (contains(root, t, s)) return true;  // found before, from a neighbouring pair
    }
    unique_boxes_.push_back(X);
    double t_bound = std::max(t - tight[0].lo, tight[0].hi - t);
    double s_bound = std::max(s - tight[1].lo, tight[1].hi - s);
    if (t < A_.a() - t_bound || t > A_.b() + t_bound || s < B_.a() - s_bound || s > B_.b() + s_bound) return true;
    const double t_in = std::clamp(t, A_.a(), A_.b()), s_in = std::clamp(s, B_.a(), B_.b());
    t_bound += std::abs(t_in - t), s_bound += std::abs(s_in - s);
    const Point<Dim> point = A_.evaluate(t_in);
    points_.push_back({t_in, s_in, point, t_bound, s_bound, (point - B_.evaluate(s_in)).norm(), false});
    return true;
  }

  // The interval Jacobian [A', -B'] of F = A - B on X, if the pieces there are valid.
  std::optional<std::array<std::array<Interval, 2>, 2>> enclosure(const Box2& X) requires(Dim == 2) {
    const auto p = curve_piece(A_, X[0].lo, X[0].hi);
    const auto q = curve_piece(B_, X[1].lo, X[1].hi);
    if (!p.valid || !q.valid) return std::nullopt;
    const auto dp = derivative_enclosure(p);
    const auto dq = derivative_enclosure(q);
    std::array<std::array<Interval, 2>, 2> J;
    for (int c = 0; c < 2; ++c) J[c] = {dp[c], Interval{-dq[c].hi, -dq[c].lo}};
    return J;
  }

  KrawczykOutcome krawczyk_at(const Box2& X, const Vec2& m, const std::array<std::array<Interval, 2>, 2>& J,
                              Box2& image) requires(Dim == 2) {
    const auto [a, da] = point_and_derivative(A_, m[0]);
    const auto [b, db] = point_and_derivative(B_, m[1]);
    Eigen::Matrix2d jacobian;
    jacobian << da, -db;
    const double scale = da.norm() * db.norm();
    if (!(std::abs(jacobian.determinant()) > 1e-14 * scale)) return KrawczykOutcome::unknown;
    return krawczyk<2>(X, m, a - b, evaluation_error_, J, jacobian.inverse(), image);
  }

  // Records an overlap if one piece lies on the other curve and the two curves coincide from
  // there on to where one of them ends, on both sides. `local` when the piece lies on the other
  // curve but the two part further out (whole_overlap): curves within rounding of each other
  // near a crossing at a tiny angle.
  enum class Coincidence { none, overlap, local };
  Coincidence find_overlap(const CurvePiece<Dim>& p, const CurvePiece<Dim>& q) {
    if (!long_enough(p, A_) && !long_enough(q, B_)) return Coincidence::none;
    Eigen::AlignedBox<double, Dim> q_box = q.box, p_box = p.box;
    const Point<Dim> margin = Point<Dim>::Constant(match_);
    q_box.min() -= margin, q_box.max() += margin, p_box.min() -= margin, p_box.max() += margin;
    std::optional<CurveOverlap> found;
    if (long_enough(p, A_) && q_box.contains(p.P.front()) && q_box.contains(p.P.back())) {
      if (const auto on = lies_on(p, B_, q, match_)) found = CurveOverlap{p.t0, p.t1, on->first, on->second};
    }
    if (!found && long_enough(q, B_) && p_box.contains(q.P.front()) && p_box.contains(q.P.back())) {
      if (const auto on = lies_on(q, A_, p, match_)) {
        found = on->first < on->second ? CurveOverlap{on->first, on->second, q.t0, q.t1}
                                       : CurveOverlap{on->second, on->first, q.t1, q.t0};
      }
    }
    if (!found) return Coincidence::none;
    const std::optional<CurveOverlap> whole = whole_overlap(*found, A_, B_, match_);
    if (!whole) return Coincidence::local;
    overlaps_.push_back(*whole);
    return Coincidence::overlap;
  }

  bool long_enough(const CurvePiece<Dim>& piece, const RationalBezierCurve<Dim>& curve) const {
    const double length = (piece.P.back() - piece.P.front()).norm();
    if (!(length >= 64.0 * tolerance_)) return false;
    return (piece.t0 == curve.a() && piece.t1 == curve.b()) || length >= size_ / 1024.0;
  }

  // Pieces split 44 times are not split further.
  static bool tiny(const CurvePiece<Dim>& piece, const RationalBezierCurve<Dim>& curve) {
    return piece.t1 - piece.t0 <= std::ldexp(curve.b() - curve.a(), -44);
  }

  // The chords make an angle whose sine is at most 1e-4 (or one is a point).
  static bool nearly_parallel(const CurvePiece<Dim>& p, const CurvePiece<Dim>& q) {
    const Point<Dim> a = p.P.back() - p.P.front(), b = q.P.back() - q.P.front();
    double cross = 0.0;
    if constexpr (Dim == 2) {
      cross = std::abs(a.x() * b.y() - a.y() * b.x());
    } else {
      cross = a.cross(b).norm();
    }
    return !(cross > 1e-4 * a.norm() * b.norm());
  }

  // Splits the larger piece (by box diagonal) that is not tiny.
  void split(Pair<Dim> pair, std::vector<Pair<Dim>>& stack) {
    const bool first_tiny = tiny(pair.first, A_), second_tiny = tiny(pair.second, B_);
    const bool split_first = !first_tiny && (second_tiny || pair.first.box.diagonal().norm() >= pair.second.box.diagonal().norm());
    const CurvePiece<Dim>& piece = split_first ? pair.first : pair.second;
    const RationalBezierCurve<Dim>& curve = split_first ? A_ : B_;
    const double middle = 0.5 * (piece.t0 + piece.t1);
    PATCHWORK_ASSERT(piece.t0 < middle && middle < piece.t1, "a piece that is not tiny can be halved");
    for (const auto& [t0, t1] : {std::pair{piece.t0, middle}, std::pair{middle, piece.t1}}) {
      auto half = curve_piece(curve, t0, t1);
      stack.push_back(split_first ? Pair<Dim>{std::move(half), pair.second} : Pair<Dim>{pair.first, std::move(half)});
    }
  }

  // Where the curves touch, [A', -B'] has rank 1 and Gauss-Newton may stall: minimise
  // d(t) = min over s of |A(t) - B(s)| instead, by golden-section search on t within the contact's
  // box, each d(t) by Newton on s.
  void refine_along_first(const Box2& hull, double& t, double& s, double& best) const {
    auto foot = [&](double at, double from) {
      const Point<Dim> a = A_.evaluate(at);
      double distance = (B_.evaluate(from) - a).norm();
      for (int iteration = 0; iteration < 20; ++iteration) {
        const auto [b, db, ddb] = point_and_derivatives(B_, from);
        const double slope = db.dot(b - a), curvature = ddb.dot(b - a) + db.squaredNorm();
        if (!(curvature > 0.0)) break;
        const double next = std::clamp(from - slope / curvature, hull[1].lo, hull[1].hi);
        const double d = (B_.evaluate(next) - a).norm();
        if (!(d < distance)) break;
        distance = d, from = next;
      }
      return std::pair{distance, from};
    };
    golden_section(hull[0].lo, hull[0].hi, [&](double at) {
      const auto [d, from] = foot(at, s);
      if (d < best) best = d, t = at, s = from;
      return d;
    });
  }

  // The contact of a group of leaves: its closest point by Gauss-Newton inside the group's box.
  void report_contact(const std::vector<std::size_t>& group) {
    Box2 hull = leaves_[group[0]].box;
    double t = leaves_[group[0]].t, s = leaves_[group[0]].s;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t index : group) {
      const Leaf& leaf = leaves_[index];
      for (int c = 0; c < 2; ++c) hull[c] = {std::min(hull[c].lo, leaf.box[c].lo), std::max(hull[c].hi, leaf.box[c].hi)};
      const double distance = (A_.evaluate(leaf.t) - B_.evaluate(leaf.s)).norm();
      if (distance < best) best = distance, t = leaf.t, s = leaf.s;
    }
    double damping = 1e-12;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const auto [a, da] = point_and_derivative(A_, t);
      const auto [b, db] = point_and_derivative(B_, s);
      Eigen::Matrix<double, Dim, 2> jacobian;
      jacobian << da, -db;
      const Eigen::Matrix2d normal = jacobian.transpose() * jacobian;
      const Vec2 step = (normal + damping * normal.trace() * Eigen::Matrix2d::Identity()).ldlt().solve(-jacobian.transpose() * (a - b));
      if (!step.allFinite()) break;
      const double t_next = std::clamp(t + step[0], hull[0].lo, hull[0].hi);
      const double s_next = std::clamp(s + step[1], hull[1].lo, hull[1].hi);
      const double distance = (A_.evaluate(t_next) - B_.evaluate(s_next)).norm();
      if (distance < best) {
        const bool moved = t_next != t || s_next != s;
        best = distance, t = t_next, s = s_next, damping = std::max(1e-12, damping / 10.0);
        if (!moved) break;
      } else {
        damping *= 10.0;
        if (damping > 1e6) break;
      }
    }
    if (!(best <= reach_)) refine_along_first(hull, t, s, best);
    if (!(best <= reach_)) return;
    for (const auto& root : unique_boxes_) {
      if (contains(root, t, s)) return;
    }
    for (const CurveOverlap& o : overlaps_) {
      if (intersects(rectangle(o), hull)) return;
    }
    const auto [a, da] = point_and_derivative(A_, t);
    const auto [b, db] = point_and_derivative(B_, s);
    bool tangential = true;
    if constexpr (Dim == 3) {
      const double sine = da.cross(db).norm() / (da.norm() * db.norm());
      tangential = !(sine > std::sqrt(tolerance_ / size_));
    }
    points_.push_back({t, s, a, std::max(t - hull[0].lo, hull[0].hi - t), std::max(s - hull[1].lo, hull[1].hi - s),
                       (a - b).norm(), tangential});
  }

  CurveIntersections<Dim> result() {
    overlaps_ = merged_overlaps(std::move(overlaps_), A_, B_, match_);
    std::vector<Box2> boxes;
    boxes.reserve(leaves_.size());
    for (const Leaf& leaf : leaves_) boxes.push_back(leaf.box);
    for (const auto& group : touching_groups<2>(boxes, 0.0)) report_contact(group);
    std::erase_if(points_, [&](const CurveIntersection<Dim>& x) {
      return std::any_of(overlaps_.begin(), overlaps_.end(), [&](const CurveOverlap& o) { return contains(rectangle(o), x.t, x.s); });
    });
    std::sort(points_.begin(), points_.end(), [](const auto& x, const auto& y) { return x.t < y.t || (x.t == y.t && x.s < y.s); });
    return {std::move(points_), std::move(overlaps_), eps_};
  }

  const RationalBezierCurve<Dim>& A_;
  const RationalBezierCurve<Dim>& B_;
  double tolerance_;
  double size_ = 0.0;
  double eps_ = 0.0;
  double reach_ = 0.0;
  double evaluation_error_ = 0.0;
  double match_ = 0.0;
  double leaf_flatness_ = 0.0;
  double leaf_size_ = 0.0;
  std::vector<CurveIntersection<Dim>> points_;
  std::vector<Box2> unique_boxes_;
  std::vector<CurveOverlap> overlaps_;
  std::vector<Leaf> leaves_;
};

}  // namespace

template <int Dim>
void add_or_merge(std::vector<CurveIntersection<Dim>>& points, const CurveIntersection<Dim>& x, double t_slack,
                  double s_slack) {
  for (CurveIntersection<Dim>& y : points) {
    if (!(std::abs(x.t - y.t) <= x.t_bound + y.t_bound + t_slack && std::abs(x.s - y.s) <= x.s_bound + y.s_bound + s_slack)) continue;
    const double t_lo = std::min(x.t - x.t_bound, y.t - y.t_bound), t_hi = std::max(x.t + x.t_bound, y.t + y.t_bound);
    const double s_lo = std::min(x.s - x.s_bound, y.s - y.s_bound), s_hi = std::max(x.s + x.s_bound, y.s + y.s_bound);
    // In 2D a point that is not tangential is certified; in 3D the closer point is the contact's.
    const bool take_x = Dim == 2 && x.tangential != y.tangential ? !x.tangential : x.distance < y.distance;
    if (take_x) y = x;
    y.t_bound = std::max(y.t - t_lo, t_hi - y.t);
    y.s_bound = std::max(y.s - s_lo, s_hi - y.s);
    return;
  }
  points.push_back(x);
}

template void add_or_merge(std::vector<CurveIntersection<2>>&, const CurveIntersection<2>&, double, double);
template void add_or_merge(std::vector<CurveIntersection<3>>&, const CurveIntersection<3>&, double, double);

template <int Dim>
CurveIntersections<Dim> intersect_rational(const RationalBezierCurve<Dim>& first, const RationalBezierCurve<Dim>& second,
                                           double tolerance) {
  return Search<Dim>(first, second, tolerance).run();
}

template CurveIntersections<2> intersect_rational(const RationalBezierCurve<2>&, const RationalBezierCurve<2>&, double);
template CurveIntersections<3> intersect_rational(const RationalBezierCurve<3>&, const RationalBezierCurve<3>&, double);

}  // namespace detail

template <int Dim>
RationalBezierCurve<Dim> as_rational(const BezierCurve<Dim>& curve) {
  return RationalBezierCurve<Dim>(curve.control_points(), std::vector<double>(curve.control_points().size(), 1.0), curve.a(),
                                  curve.b());
}

template RationalBezierCurve<2> as_rational(const BezierCurve<2>&);
template RationalBezierCurve<3> as_rational(const BezierCurve<3>&);

CurveIntersections<2> intersect_curves(const BezierCurve2& first, const BezierCurve2& second) {
  return detail::intersect_rational(as_rational(first), as_rational(second), 0.0);
}

CurveIntersections<2> intersect_curves(const RationalBezierCurve2& first, const RationalBezierCurve2& second) {
  return detail::intersect_rational(first, second, 0.0);
}

CurveIntersections<3> intersect_curves(const BezierCurve3& first, const BezierCurve3& second, double tolerance) {
  require_positive(tolerance, "intersect_curves", "tolerance");
  return detail::intersect_rational(as_rational(first), as_rational(second), tolerance);
}

CurveIntersections<3> intersect_curves(const RationalBezierCurve3& first, const RationalBezierCurve3& second,
                                       double tolerance) {
  require_positive(tolerance, "intersect_curves", "tolerance");
  return detail::intersect_rational(first, second, tolerance);
}

}  // namespace patchwork
