#pragma once
// Disjoint sets over 0..n-1 with path halving: the grouping step of components, fans and
// adjacency. unite() makes the smaller root the representative, so find() of a set is its
// smallest member and numbering sets by first appearance is deterministic.

#include <cstdint>
#include <numeric>
#include <vector>

namespace patchwork {

class UnionFind {
 public:
  /// n singleton sets {0}, ..., {n-1}.
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }

  /// The representative (smallest member) of x's set.
  std::uint32_t find(std::uint32_t x) noexcept {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  /// Merges the sets of a and b.
  void unite(std::uint32_t a, std::uint32_t b) noexcept {
    a = find(a);
    b = find(b);
    if (a < b) {
      parent_[b] = a;
    } else if (b < a) {
      parent_[a] = b;
    }
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace patchwork
