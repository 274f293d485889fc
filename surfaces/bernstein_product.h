#pragma once
// Scalar tensor-product Bernstein polynomials and their exact-basis products: what the
// back-patch test (view_culling.cpp) and the rational bounds (rational_bounds.cpp) need to bound
// polynomial expressions in a patch's coordinates through their coefficients (convex hull).
//
//   p(u, v) = sum_ij c_ij B_i^n(u) B_j^m(v),   c_ij at i + (n + 1) j.
//
// Product (Bernstein basis): with c'_ij = C(n1,i) C(m1,j) a_ij (likewise for b), the product's
// scaled coefficients are the convolution of a' and b', divided by C(n1+n2,k) C(m1+m2,l).
// Derivative: d/du has degree n - 1 and coefficients n (c_{i+1,j} - c_ij) (seed Satz 21).

#include <vector>

namespace patchwork::detail {

/// A scalar Bernstein polynomial of degrees (n, m) >= 0.
struct ScalarPatch {
  int n;
  int m;
  std::vector<double> c;
  double at(int i, int j) const { return c[static_cast<std::size_t>(i + (n + 1) * j)]; }
};

/// a * b, of degrees (a.n + b.n, a.m + b.m).
ScalarPatch multiply(const ScalarPatch& a, const ScalarPatch& b);

/// sum += sign * term (sum empty: it becomes sign * term); the lower degree is elevated to the
/// higher first.
void add(ScalarPatch& sum, const ScalarPatch& term, double sign);

/// The same polynomial at degrees (n, m) >= its own (degree elevation, per direction
/// c'_i = (i / (k+1)) c_{i-1} + (1 - i / (k+1)) c_i).
ScalarPatch elevated(const ScalarPatch& p, int n, int m);

/// d/du (along_u) or d/dv; the derivative of a degree-0 direction is the zero polynomial of
/// degree 0 there.
ScalarPatch derivative(const ScalarPatch& p, bool along_u);

}  // namespace patchwork::detail
