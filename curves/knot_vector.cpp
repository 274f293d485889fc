#include "curves/knot_vector.h"

#include <algorithm>
#include <cmath>

#include "core/assert.h"
#include "core/errors.h"
#include "curves/curve_checks.h"

namespace patchwork {

KnotVector::KnotVector(int degree, std::vector<double> knots) : p_(degree), knots_(std::move(knots)) {
  if (p_ < 0) throw InvalidInput(detail::message("KnotVector: degree ", p_, " is negative"));
  const int count = size();
  if (count < 2 * (p_ + 1)) {
    throw InvalidInput(detail::message("KnotVector: ", count, " knots for degree ", p_, ", need at least ",
                                       2 * (p_ + 1), " (p + 1 control points)"));
  }
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(knots_[static_cast<std::size_t>(i)])) {
      throw InvalidInput(
          detail::message("KnotVector: knot ", i, " = ", knots_[static_cast<std::size_t>(i)], " is not finite"));
    }
    if (i > 0 && knots_[static_cast<std::size_t>(i)] < knots_[static_cast<std::size_t>(i) - 1]) {
      throw InvalidInput(detail::message("KnotVector: knot ", i, " = ", knots_[static_cast<std::size_t>(i)],
                                         " is below knot ", i - 1, " = ", knots_[static_cast<std::size_t>(i) - 1]));
    }
  }
  if (!(a() < b())) {
    throw InvalidInput(detail::message("KnotVector: the valid range [u_p, u_{n+1}] = [", a(), ", ", b(), "] is empty"));
  }
  for (int i = 0; i < count;) {
    const double u = knots_[static_cast<std::size_t>(i)];
    int j = i;
    while (j < count && knots_[static_cast<std::size_t>(j)] == u) ++j;
    const int m = j - i;
    // Inside (a, b) a knot of multiplicity p + 1 would cut the curve in two (C^-1).
    const int allowed = (a() < u && u < b()) ? p_ : p_ + 1;
    if (m > allowed) {
      throw InvalidInput(detail::message("KnotVector: knot ", u, " has multiplicity ", m, " > ", allowed,
                                         " for degree ", p_, (allowed == p_ ? " inside the valid range" : "")));
    }
    i = j;
  }
}

int KnotVector::span(double u) const {
  detail::check_parameter("KnotVector::span", u);
  if (u < a() || u > b()) {
    throw InvalidInput(
        detail::message("KnotVector::span: u = ", u, " is outside the valid range [", a(), ", ", b(), "]"));
  }
  const int n = control_point_count() - 1;
  const auto first = knots_.begin() + p_;
  const auto last = knots_.begin() + n + 1;  // u_{n+1} = b
  int span;
  if (u == b()) {
    // The last non-empty span: the last knot below b.
    span = static_cast<int>(std::lower_bound(first, last, u) - knots_.begin()) - 1;
  } else {
    span = static_cast<int>(std::upper_bound(first, last, u) - knots_.begin()) - 1;
  }
  PATCHWORK_ASSERT(span >= p_ && span <= n, "span index outside [p, n]");
  PATCHWORK_ASSERT(knots_[static_cast<std::size_t>(span)] <= u && u <= knots_[static_cast<std::size_t>(span) + 1] &&
                       knots_[static_cast<std::size_t>(span)] < knots_[static_cast<std::size_t>(span) + 1],
                   "u outside its non-empty span");
  return span;
}

int KnotVector::multiplicity(double u) const {
  const auto [first, last] = std::equal_range(knots_.begin(), knots_.end(), u);
  return static_cast<int>(last - first);
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> values;
  for (int i = p_; i <= control_point_count(); ++i) {
    const double u = knots_[static_cast<std::size_t>(i)];
    if (values.empty() || values.back() != u) values.push_back(u);
  }
  return values;
}

std::vector<int> KnotVector::breakpoint_continuity() const {
  const std::vector<double> values = breakpoints();
  std::vector<int> orders;
  for (std::size_t i = 1; i + 1 < values.size(); ++i) orders.push_back(p_ - multiplicity(values[i]));
  return orders;
}

bool KnotVector::is_clamped() const { return knots_[0] == a() && knots_.back() == b(); }

namespace {

void check_uniform_arguments(const char* function, int degree, int control_points, double a, double b) {
  if (degree < 0) throw InvalidInput(detail::message(function, ": degree ", degree, " is negative"));
  if (control_points < degree + 1) {
    throw InvalidInput(detail::message(function, ": ", control_points, " control points for degree ", degree,
                                       ", need at least ", degree + 1));
  }
  detail::check_interval(function, a, b);
}

// a + (b - a) j / spans, with the ends exact (j = 0 gives a, j = spans gives b).
double uniform_knot(double a, double b, int j, int spans) {
  if (j == 0) return a;
  if (j == spans) return b;
  return a + (b - a) * (static_cast<double>(j) / spans);
}

}  // namespace

KnotVector clamped_uniform_knots(int degree, int control_points, double a, double b) {
  check_uniform_arguments("clamped_uniform_knots", degree, control_points, a, b);
  const int spans = control_points - degree;
  std::vector<double> knots(static_cast<std::size_t>(control_points + degree + 1));
  for (int i = 0; i < static_cast<int>(knots.size()); ++i) {
    knots[static_cast<std::size_t>(i)] = uniform_knot(a, b, std::clamp(i - degree, 0, spans), spans);
  }
  return KnotVector(degree, std::move(knots));
}

KnotVector uniform_knots(int degree, int control_points, double a, double b) {
  check_uniform_arguments("uniform_knots", degree, control_points, a, b);
  const int spans = control_points - degree;
  std::vector<double> knots(static_cast<std::size_t>(control_points + degree + 1));
  for (int i = 0; i < static_cast<int>(knots.size()); ++i) {
    knots[static_cast<std::size_t>(i)] = uniform_knot(a, b, i - degree, spans);
  }
  return KnotVector(degree, std::move(knots));
}

KnotVector periodic_knots(int degree, int polygon_points, double a, double b) {
  if (polygon_points < 2) {
    throw InvalidInput(
        detail::message("periodic_knots: a closed polygon of ", polygon_points, " points, need at least 2"));
  }
  return uniform_knots(degree, polygon_points + degree, a, b);
}

}  // namespace patchwork
