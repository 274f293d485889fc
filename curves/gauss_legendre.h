#pragma once
// Gauss-Legendre quadrature rules: nodes x_k and weights w_k on [-1, 1] with
// int_{-1}^{1} f = sum_k w_k f(x_k) exactly for polynomials of degree <= 2 points - 1.
// Nodes are computed by Newton's method on the Legendre polynomial P_points (no tables).

#include <span>
#include <vector>

namespace patchwork {

class GaussLegendre {
 public:
  /// The rule with `points` nodes (1 to 64). \throws InvalidInput otherwise.
  explicit GaussLegendre(int points);

  /// Number of nodes.
  int size() const noexcept { return static_cast<int>(nodes_.size()); }
  /// Nodes on [-1, 1], ascending.
  std::span<const double> nodes() const noexcept { return nodes_; }
  /// Weights, summing to 2.
  std::span<const double> weights() const noexcept { return weights_; }

  /// Nodes mapped to [lo, hi].
  std::vector<double> nodes_on(double lo, double hi) const;
  /// Weights scaled for [lo, hi].
  std::vector<double> weights_on(double lo, double hi) const;

 private:
  std::vector<double> nodes_;
  std::vector<double> weights_;
};

}  // namespace patchwork
