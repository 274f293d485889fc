#pragma once
// Internal: the homogeneous form shared by the rational curve types (RationalBezierCurve,
// NurbsCurve). A rational curve C = H / w is stored as the polynomial curve of homogeneous points
// (w_i P_i, w_i); its derivatives follow from H = w C by Leibniz's rule:
//
//   C^(k) = (H^(k)_xyz - sum_{j=1}^{k} C(k,j) w^(j) C^(k-j)) / w.

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/errors.h"
#include "core/types.h"
#include "curves/bernstein.h"
#include "curves/curve_checks.h"

namespace patchwork::detail {

/// The points (w_i P_i, w_i). \throws InvalidInput if the points are empty or not finite, the
/// sizes differ, or a weight is not positive and finite.
template <int Dim>
std::vector<Point<Dim + 1>> homogeneous_points(const char* function, const std::vector<Point<Dim>>& points,
                                               const std::vector<double>& weights) {
  check_control_points(function, points);
  if (weights.size() != points.size()) {
    throw InvalidInput(message(function, ": ", points.size(), " control points but ", weights.size(), " weights"));
  }
  std::vector<Point<Dim + 1>> H(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(weights[i]) || !(weights[i] > 0.0)) {
      throw InvalidInput(message(function, ": weight ", i, " = ", weights[i], " is not positive and finite"));
    }
    H[i] << weights[i] * points[i], weights[i];
  }
  return H;
}

/// Throws unless every homogeneous point has a positive weight (last coordinate).
template <int Dim>
void check_homogeneous_weights(const char* function, const std::vector<Point<Dim + 1>>& H) {
  for (std::size_t i = 0; i < H.size(); ++i) {
    if (!(H[i][Dim] > 0.0)) throw InvalidInput(message(function, ": weight ", i, " = ", H[i][Dim], " is not positive"));
  }
}

/// The point P = h_xyz / w of a homogeneous point h = (w P, w).
template <int Dim>
Point<Dim> projected(const Point<Dim + 1>& h) {
  return h.template head<Dim>() / h[Dim];
}

/// C, C', ..., C^(k) from the homogeneous derivatives H, H', ..., H^(k) (Leibniz's rule).
template <int Dim>
std::vector<Point<Dim>> quotient_derivatives(const std::vector<Point<Dim + 1>>& H) {
  const double w = H[0][Dim];
  std::vector<Point<Dim>> C(H.size());
  for (std::size_t order = 0; order < H.size(); ++order) {
    Point<Dim> numerator = H[order].template head<Dim>();
    for (std::size_t j = 1; j <= order; ++j) {
      numerator -= binomial(static_cast<int>(order), static_cast<int>(j)) * H[j][Dim] * C[order - j];
    }
    C[order] = numerator / w;
  }
  return C;
}

}  // namespace patchwork::detail
