#include "tools/curve_demo.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <vector>

#include "curves/arc_length.h"
#include "curves/bezier_curve.h"
#include "curves/compensated.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork::tools {
namespace {

// (t - 3/4)^n in Bernstein form: t - 3/4 = t/4 - 3(1-t)/4, so b_i = (-3)^(n-i) / 4^n, exactly
// representable while 3^n < 2^53 (n <= 33). The exact value at a double t is (t - 3/4)^n, with
// t - 3/4 exact for t in [3/8, 3/2].
BezierCurve1 shifted_power(int n) {
  std::vector<Point<1>> b(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    b[static_cast<std::size_t>(i)][0] = std::ldexp(std::pow(-3.0, n - i), -2 * n);
  }
  return BezierCurve1(std::move(b));
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void run_curve_demo(std::ostream& out, int degree, long evaluations) {
  out << "patchwork curve demo: what curves/ does, measured (patch sets are tessellated by patchwork "
         "tessellate)\n\n";

  out << "1. Accuracy near a root of multiplicity " << degree << ": p(t) = (t - 3/4)^" << degree
      << " in Bernstein form\n";
  out << "   t          condition   plain rel.err   compensated rel.err   compensated bound\n";
  const BezierCurve1 p = shifted_power(degree);
  for (double t : {0.4, 0.6, 0.7, 0.72, 0.74}) {
    // The reference in long double: t - 3/4 is exact, and powl errs by a few ulps of long double.
    const long double exact = std::pow(static_cast<long double>(t) - 0.75L, degree);
    const double plain = p.evaluate(t)[0];
    const CompensatedPoint<1> compensated = evaluate_compensated(p, t);
    // p~(t) = sum |b_i| B_i(t) = (3/4 - t/2)^n: the condition number is p~ / |p|.
    const double condition = std::pow(0.75 - 0.5 * t, degree) / std::abs(static_cast<double>(exact));
    const auto relative = [exact](double value) {
      return static_cast<double>(std::abs((static_cast<long double>(value) - exact) / exact));
    };
    out << "   " << std::left << std::setw(10) << t << " " << std::setw(10) << std::setprecision(2)
        << std::scientific << condition << "  " << std::setw(14) << relative(plain) << "  " << std::setw(20)
        << relative(compensated.value[0]) << "  " << compensated.error_bound[0] / std::abs(static_cast<double>(exact))
        << std::defaultfloat << std::setprecision(6) << std::right << "\n";
  }

  out << "\n2. Arc length of an exact rational unit circle (4 quadratic arcs), tolerance 1e-13\n";
  double length = 0.0;
  double estimate = 0.0;
  for (const auto& arc : circle_arc(Vec2(0.0, 0.0), 1.0, 0.0, 2.0 * std::numbers::pi)) {
    const ArcLength piece = arc_length(arc, 1e-13 / 4.0);
    length += piece.length;
    estimate += piece.error_estimate;
  }
  out << "   length " << std::setprecision(17) << length << ", 2 pi = " << 2.0 * std::numbers::pi
      << ", error " << std::setprecision(3) << std::abs(length - 2.0 * std::numbers::pi) << " (estimate " << estimate
      << ")\n";

  out << "\n3. Speed: " << evaluations << " evaluations of a cubic in 3D\n";
  const BezierCurve3 cubic({Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(3, -1, 1), Vec3(4, 1, 2)});
  Vec3 checksum = Vec3::Zero();
  auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < evaluations; ++k) checksum += cubic.evaluate(static_cast<double>(k) / evaluations);
  const double plain_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  for (long k = 0; k < evaluations; ++k) checksum += evaluate_compensated(cubic, static_cast<double>(k) / evaluations).value;
  const double compensated_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const BernsteinTable table = BernsteinTable::uniform(3, static_cast<std::size_t>(evaluations));
  const double table_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  for (const Vec3& point : evaluate(cubic, table)) checksum += point;
  const double batch_seconds = seconds_since(start);
  const auto rate = [evaluations](double seconds) { return static_cast<double>(evaluations) / seconds / 1e6; };
  out << std::setprecision(4) << "   de Casteljau           " << rate(plain_seconds) << " M points/s\n"
      << "   compensated            " << rate(compensated_seconds) << " M points/s\n"
      << "   batch (table reused)   " << rate(batch_seconds) << " M points/s (building the table: "
      << rate(table_seconds) << " M rows/s)\n"
      << "   (checksum " << checksum.sum() << ")\n";
}

}  // namespace patchwork::tools
