#include "io/obj_freeform_checks.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/errors.h"

namespace patchwork {
namespace detail {

const char* basis_name(FreeformBasis basis) { return basis == FreeformBasis::bezier ? "bezier" : "bspline"; }

const char* direction_name(int direction) { return direction == 0 ? "u" : "v"; }

FreeformRecordView view_of(const FreeformCurve& curve) {
  return {"curv",
          curve.basis,
          curve.rational,
          1,
          {curve.degree, 0},
          {curve.parameters, {}},
          {curve.t0, curve.t1, 0.0, 0.0},
          curve.points,
          curve.weights};
}

FreeformRecordView view_of(const FreeformSurface& surface) {
  return {"surf",
          surface.basis,
          surface.rational,
          2,
          {surface.degree_u, surface.degree_v},
          {surface.parameters_u, surface.parameters_v},
          {surface.u0, surface.u1, surface.v0, surface.v1},
          surface.points,
          surface.weights};
}

namespace {

std::optional<FreeformProblem> direction_problem(const FreeformRecordView& record, int direction) {
  const FreeformBasis basis = record.basis;
  const int p = record.degrees[direction];
  const std::span<const double> b = record.parameters[direction];
  const std::string parm = message("parm ", direction_name(direction));
  const auto problem = [&](FreeformPart part, std::size_t index, const std::string& text) {
    return FreeformProblem{part, direction, index, text};
  };
  if (p < 1 || p > max_obj_freeform_degree) {
    return problem(FreeformPart::degree, 0, message("degree ", p, " is not in [1, ", max_obj_freeform_degree, "]"));
  }
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (!std::isfinite(b[k]))
      return problem(FreeformPart::parameter, k, message(parm, ": value ", b[k], " is not finite"));
    if (k == 0) continue;
    if (basis == FreeformBasis::bezier && !(b[k] > b[k - 1])) {
      return problem(FreeformPart::parameter, k,
                     message(parm, ": bezier breakpoints must increase strictly, found ", b[k - 1], " then ", b[k]));
    }
    if (basis == FreeformBasis::bspline && b[k] < b[k - 1]) {
      return problem(FreeformPart::parameter, k,
                     message(parm, ": bspline knots must not decrease, found ", b[k - 1], " then ", b[k]));
    }
    // Knots up to k do not decrease: b[k] equal to the knot p + 1 places back repeats p + 2 times.
    const auto reach = static_cast<std::size_t>(p) + 1;
    if (basis == FreeformBasis::bspline && k >= reach && b[k - reach] == b[k]) {
      return problem(FreeformPart::parameter, k,
                     message(parm, ": knot ", b[k], " stands more than degree + 1 = ", reach, " times"));
    }
  }
  const std::int64_t count = control_point_count(basis, p, b);
  if (count == 0) {
    return problem(FreeformPart::parameter_count, 0,
                   basis == FreeformBasis::bezier
                       ? message(parm, " gives ", b.size(), " breakpoints: a bezier direction needs at least 2")
                       : message(parm, " gives ", b.size(), " knots: a bspline direction of degree ", p,
                                 " needs at least 2 * (degree + 1) = ", 2 * (p + 1)));
  }
  // The domain [knot p, knot count] of the equivalent knots, without building them (a Bezier
  // direction's knot vector is p times longer than its breakpoints).
  const double low = basis == FreeformBasis::bezier ? b.front() : b[static_cast<std::size_t>(p)];
  const double high = basis == FreeformBasis::bezier ? b.back() : b[static_cast<std::size_t>(count)];
  if (!(low < high)) {
    return problem(FreeformPart::parameter_count, 0, message(parm, ": the domain [", low, ", ", high, "] is empty"));
  }
  // Inside the domain a knot stands at most p times (p + 1 would cut the surface in two there).
  if (basis == FreeformBasis::bspline) {
    const auto degree = static_cast<std::size_t>(p);
    for (std::size_t k = degree; k < b.size(); ++k) {
      if (b[k] > low && b[k] < high && b[k - degree] == b[k]) {
        return problem(FreeformPart::parameter, k,
                       message(parm, ": knot ", b[k], " stands more than degree = ", p,
                               " times inside the domain [", low, ", ", high, "]"));
      }
    }
  }
  const std::string range = record.directions == 1 ? "the range" : message("the ", direction_name(direction), " range");
  const double start = record.range[2 * static_cast<std::size_t>(direction)];
  const double end = record.range[2 * static_cast<std::size_t>(direction) + 1];
  if (!std::isfinite(start))
    return problem(FreeformPart::range, 0, message(range, " starts at ", start, ", not finite"));
  if (!std::isfinite(end)) return problem(FreeformPart::range, 1, message(range, " ends at ", end, ", not finite"));
  if (!(start < end)) return problem(FreeformPart::range, 1, message(range, " [", start, ", ", end, "] is empty"));
  if (start < low) {
    return problem(FreeformPart::range, 0,
                   message(range, " starts at ", start, ", before the domain [", low, ", ", high, "] of ", parm));
  }
  if (end > high) {
    return problem(FreeformPart::range, 1,
                   message(range, " ends at ", end, ", after the domain [", low, ", ", high, "] of ", parm));
  }
  return std::nullopt;
}

}  // namespace

std::optional<FreeformProblem> record_problem(const FreeformRecordView& record) {
  std::array<std::int64_t, 2> counts{1, 1};
  for (int direction = 0; direction < record.directions; ++direction) {
    if (auto problem = direction_problem(record, direction)) return problem;
    counts[static_cast<std::size_t>(direction)] =
        control_point_count(record.basis, record.degrees[direction], record.parameters[direction]);
  }
  const auto listed = static_cast<std::int64_t>(record.points.size());
  const char* rule =
      record.basis == FreeformBasis::bezier ? "points = segments * degree + 1" : "knots = points + degree + 1";
  if (record.directions == 1 && listed != counts[0]) {
    return FreeformProblem{FreeformPart::point_count, 0, 0,
                           message("parm u makes ", counts[0], " control points of degree ", record.degrees[0], " (",
                                   rule, "), curv lists ", listed)};
  }
  if (record.directions == 2 && listed != counts[0] * counts[1]) {
    return FreeformProblem{FreeformPart::point_count, 0, 0,
                           message("parm u and parm v make ", counts[0], " x ", counts[1], " = ", counts[0] * counts[1],
                                   " control points (", rule, "), surf lists ", listed)};
  }
  if (record.weights.size() != record.points.size()) {
    return FreeformProblem{FreeformPart::point_count, 0, 0,
                           message(record.points.size(), " control points but ", record.weights.size(), " weights")};
  }
  for (std::size_t k = 0; k < record.points.size(); ++k) {
    const double w = record.weights[k];
    if (!record.points[k].allFinite()) {
      return FreeformProblem{FreeformPart::point, 0, k, message("control point ", k, " is not finite")};
    }
    if (record.rational && !(std::isfinite(w) && w > 0.0)) {
      return FreeformProblem{FreeformPart::weight, 0, k,
                             message("control point ", k, " has weight ", w, ": weights are finite and > 0")};
    }
    if (!record.rational && w != 1.0) {
      return FreeformProblem{FreeformPart::weight, 0, k,
                             message("control point ", k, " has weight ", w,
                                     " but the record is not rational (cstype without rat): the weight would be lost")};
    }
  }
  return std::nullopt;
}

}  // namespace detail

std::int64_t control_point_count(FreeformBasis basis, int degree, std::span<const double> parameters) {
  const auto m = static_cast<std::int64_t>(parameters.size());
  if (degree < 1) return 0;
  if (basis == FreeformBasis::bezier) return m >= 2 ? (m - 1) * degree + 1 : 0;
  return m >= 2 * (std::int64_t{degree} + 1) ? m - degree - 1 : 0;
}

std::vector<double> bspline_knots(FreeformBasis basis, int degree, std::span<const double> parameters) {
  if (basis == FreeformBasis::bspline) return {parameters.begin(), parameters.end()};
  std::vector<double> knots;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const bool end = k == 0 || k + 1 == parameters.size();
    knots.insert(knots.end(), static_cast<std::size_t>(end ? degree + 1 : degree), parameters[k]);
  }
  return knots;
}

std::pair<std::int64_t, std::int64_t> control_point_counts(const FreeformSurface& surface) {
  return {control_point_count(surface.basis, surface.degree_u, surface.parameters_u),
          control_point_count(surface.basis, surface.degree_v, surface.parameters_v)};
}

void validate(const FreeformCurve& curve) {
  if (const auto problem = detail::record_problem(detail::view_of(curve)))
    throw InvalidInput("FreeformCurve: " + problem->message);
}

void validate(const FreeformSurface& surface) {
  if (const auto problem = detail::record_problem(detail::view_of(surface)))
    throw InvalidInput("FreeformSurface: " + problem->message);
}

}  // namespace patchwork
