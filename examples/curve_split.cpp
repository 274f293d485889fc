// examples/curve_split.cpp: evaluate a cubic Bezier curve, split it, and check the pieces.
#include <iostream>

#include "check.h"
#include "curves/bezier_curve.h"
#include "curves/continuity.h"
#include "curves/subdivision.h"

int main() {
  using examples::check;
  using patchwork::Vec2;
  // P_0 .. P_3 on the default interval [0, 1]; dyadic coordinates keep C(1/2) exact.
  const patchwork::BezierCurve2 curve({Vec2(0, 0), Vec2(1, 2), Vec2(3, 2), Vec2(4, 0)});

  // C(1/2) = (P_0 + 3 P_1 + 3 P_2 + P_3) / 8 and C'(0) = 3 (P_1 - P_0).
  const Vec2 middle = curve(0.5);
  const Vec2 start_velocity = patchwork::derivative(curve, 0.0, 1);
  std::cout << "degree " << curve.degree() << ", C(0.5) = (" << middle.transpose() << "), C'(0) = ("
            << start_velocity.transpose() << ")\n";
  check(middle == Vec2(2, 1.5), "C(0.5) = (2, 1.5)");
  check(start_velocity == Vec2(3, 6), "C'(0) = 3 (P_1 - P_0) = (3, 6)");

  // Split at t = 0.3: both pieces keep the global parameter t, so they evaluate to the curve's
  // points on their own intervals, and they join with C^3 (the degree) at the split point.
  const auto [left, right] = patchwork::split(curve, 0.3);
  const double tolerance = 1e-14 * 4.0;  // rounding, relative to the control polygon's size 4
  std::cout << "left on [" << left.a() << ", " << left.b() << "], right on [" << right.a() << ", " << right.b()
            << "], split point (" << left.control_points().back().transpose() << ")\n";
  check((left.control_points().back() - curve(0.3)).norm() <= tolerance, "left ends at C(0.3)");
  check(left.control_points().back() == right.control_points().front(), "right starts where left ends");
  bool same_points = true;
  for (const double t : {0.0, 0.1, 0.2, 0.3}) same_points &= (left(t) - curve(t)).norm() <= tolerance;
  for (const double t : {0.3, 0.5, 0.8, 1.0}) same_points &= (right(t) - curve(t)).norm() <= tolerance;
  check(same_points, "each piece evaluates to the curve's points at the same t");
  const patchwork::Continuity join = patchwork::continuity(left, right, 3);
  std::cout << "join: C^" << join.ck << (join.g1 ? ", G^1" : "") << ", gap " << join.gap << '\n';
  check(join.ck == 3 && join.g1, "the pieces join with C^3");
  return examples::exit_code();
}
