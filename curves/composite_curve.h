#pragma once
// A piecewise Bezier curve: segments on contiguous intervals
//
//   [t_0, t_1] [t_1, t_2] ... [t_{N-1}, t_N],   segment i has a() = t_i, b() = t_{i+1}
//
// evaluated anywhere in [t_0, t_N]. At a breakpoint t_i (0 < i < N) the segment starting there
// is used; continuity() tells how the segments join (Def 58).

#include <span>
#include <vector>

#include "curves/bezier_curve.h"
#include "curves/continuity.h"

namespace patchwork {

template <int Dim>
class CompositeCurve {
 public:
  using Point = patchwork::Point<Dim>;

  /// \throws InvalidInput if there is no segment or segment i+1 does not start where segment i
  ///         ends (a() == previous b(), exactly).
  explicit CompositeCurve(std::vector<BezierCurve<Dim>> segments);

  /// The segments, in parameter order.
  const std::vector<BezierCurve<Dim>>& segments() const noexcept { return segments_; }
  /// Start of the whole parameter range.
  double a() const noexcept { return segments_.front().a(); }
  /// End of the whole parameter range.
  double b() const noexcept { return segments_.back().b(); }
  /// Index of the segment that evaluates t. \throws InvalidInput if t is outside [a, b].
  std::size_t segment_index(double t) const;

  /// C(t). \throws InvalidInput if t is outside [a, b] or not finite.
  Point evaluate(double t) const;
  Point operator()(double t) const { return evaluate(t); }
  /// d^k C / dt^k at t (one-sided at breakpoints: from the segment starting there).
  Point derivative(double t, int k) const;

  /// The join at each of the N-1 breakpoints, in order.
  std::vector<Continuity> continuity(int max_order, double relative_tolerance = 1e-10) const;

 private:
  std::vector<BezierCurve<Dim>> segments_;
};

}  // namespace patchwork
