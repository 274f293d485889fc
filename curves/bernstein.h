#pragma once
// Bernstein polynomials (seed Def 56, Satz 20) and scalar polynomials in Bernstein form.
//
//   B_i^n(t) = C(n,i) (1-t)^(n-i) t^i,  i = 0..n,  and B_i^n = 0 for i < 0 or i > n.
//
// Values are computed by the recursion of Satz 20, B_i^n = (1-t) B_i^(n-1) + t B_(i-1)^(n-1),
// so no factorial is ever formed and high degrees (n = 100 and beyond) stay finite and accurate.
// A scalar polynomial in Bernstein form of degree n is a span of its n+1 coefficients c_0..c_n:
// p(t) = sum_i c_i B_i^n(t).

#include <cstddef>
#include <span>
#include <vector>

namespace patchwork {

/// Binomial coefficient C(n, k) as a double (exact while it is below 2^53); 0 outside 0 <= k <= n.
double binomial(int n, int k);

/// The falling factorial n (n-1) ... (n-k+1) (1 for k = 0): the factor of a k-th derivative.
double falling_factorial(int n, int k);

/// B_i^n(t); 0 for i outside [0, n]. \throws InvalidInput if n < 0 or t is not finite.
double bernstein(int n, int i, double t);

/// All n+1 values B_0^n(t) .. B_n^n(t) into `out` (size n+1), by Satz 20. \throws InvalidInput.
void bernstein_all(int n, double t, std::span<double> out);

/// All n+1 values B_0^n(t) .. B_n^n(t). \throws InvalidInput if n < 0 or t is not finite.
std::vector<double> bernstein_all(int n, double t);

/// The k-th derivatives d^k/dt^k B_i^n(t), i = 0..n (zero for k > n). \throws InvalidInput if k < 0.
std::vector<double> bernstein_all_derivatives(int n, double t, int k);
/// The same into `out` (n + 1 entries, no allocation). \throws InvalidInput if k < 0 or out is too small.
void bernstein_all_derivatives(int n, double t, int k, std::span<double> out);

/// d^k/dt^k B_i^n(t). \throws InvalidInput if n < 0, k < 0 or t is not finite.
double bernstein_derivative(int n, int i, double t, int k);

/// Bernstein values of one degree at many parameters, one row of n+1 weights per parameter:
/// computed once, reused to evaluate any number of curves (or patch rows) of that degree.
class BernsteinTable {
 public:
  /// Tabulates B_0^n .. B_n^n at each parameter. \throws InvalidInput on n < 0 or a non-finite t.
  BernsteinTable(int degree, std::span<const double> parameters);

  /// Tabulates degree n at `count` uniform parameters k/(count-1), k = 0..count-1 (count >= 2).
  static BernsteinTable uniform(int degree, std::size_t count);

  /// The degree n.
  int degree() const noexcept { return degree_; }
  /// Number of parameters (rows).
  std::size_t size() const noexcept { return parameters_.size(); }
  /// The parameters, in the order given.
  std::span<const double> parameters() const noexcept { return parameters_; }
  /// The n+1 weights of row `row`.
  std::span<const double> weights(std::size_t row) const noexcept {
    return {weights_.data() + row * static_cast<std::size_t>(degree_ + 1),
            static_cast<std::size_t>(degree_ + 1)};
  }

 private:
  int degree_;
  std::vector<double> parameters_;
  std::vector<double> weights_;  // row-major, size() x (degree_ + 1)
};

/// p(t) for p in Bernstein form, by de Casteljau. \throws InvalidInput if `coefficients` is empty.
double bernstein_evaluate(std::span<const double> coefficients, double t);

/// Coefficients of p' (degree n-1; for n = 0 the single coefficient 0).
std::vector<double> bernstein_derivative_coefficients(std::span<const double> coefficients);

/// Coefficients of the product f*g (degree m+n) in Bernstein form.
std::vector<double> bernstein_product(std::span<const double> f, std::span<const double> g);

/// Real roots of p in [0, 1], ascending. Isolates by subdivision (a Bernstein coefficient
/// sequence with one sign change has exactly one root) then refines with safeguarded Newton to
/// full precision. Roots closer than 1e-10 are returned once (the first). A multiple root, or a
/// cluster of roots that rounding cannot separate (p numerically zero between them:
/// |p| <= 4 (n+1) u max|c_i| there), is returned once, at the middle of that cluster; how far
/// that lies from the exact root grows with the multiplicity m, like (rounding level)^(1/m).
/// The zero polynomial has no isolated roots and returns none.
std::vector<double> bernstein_roots(std::span<const double> coefficients);

}  // namespace patchwork
