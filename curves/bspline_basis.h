#pragma once
// B-spline basis functions by the Cox-de Boor recursion (The NURBS Book, eq. 2.5, A2.2, A2.3):
//
//   N_{i,0}(u) = 1 if u_i <= u < u_{i+1}, else 0
//   N_{i,q}(u) = (u - u_i)/(u_{i+q} - u_i) N_{i,q-1}(u) + (u_{i+q+1} - u)/(u_{i+q+1} - u_{i+1}) N_{i+1,q-1}(u)
//
// with 0/0 = 0. On span s (u_s <= u < u_{s+1}) only N_{s-p,p} .. N_{s,p} can be non-zero; they
// are non-negative and sum to 1 (partition of unity). Both functions return those p + 1 values,
// index r standing for N_{s-p+r,p}; the span follows KnotVector::span (u = b: last span).

#include <Eigen/Core>
#include <vector>

#include "curves/knot_vector.h"

namespace patchwork {

/// N_{s-p,p}(u) .. N_{s,p}(u) on the span s = knots.span(u) (A2.2).
/// \throws InvalidInput if u is not finite or outside [a, b].
std::vector<double> basis_functions(const KnotVector& knots, double u);

/// Row k (0..order) holds d^k/du^k of N_{s-p,p} .. N_{s,p} at u on s = knots.span(u) (A2.3);
/// rows above p are zero. \throws InvalidInput if order < 0 or u is not in [a, b].
Eigen::MatrixXd basis_function_derivatives(const KnotVector& knots, double u, int order);

namespace detail {

/// basis_functions on a given span s (u_s <= u <= u_{s+1}, u_s < u_{s+1}); no checks.
std::vector<double> basis_functions_on_span(const KnotVector& knots, int s, double u);

}  // namespace detail
}  // namespace patchwork
