#include "surfaces/bernstein_product.h"

#include <algorithm>

#include "core/assert.h"
#include "curves/bernstein.h"

namespace patchwork::detail {

ScalarPatch multiply(const ScalarPatch& a, const ScalarPatch& b) {
  ScalarPatch product{a.n + b.n, a.m + b.m, {}};
  product.c.assign(static_cast<std::size_t>((product.n + 1) * (product.m + 1)), 0.0);
  for (int j1 = 0; j1 <= a.m; ++j1) {
    for (int i1 = 0; i1 <= a.n; ++i1) {
      const double wa = binomial(a.n, i1) * binomial(a.m, j1) * a.at(i1, j1);
      for (int j2 = 0; j2 <= b.m; ++j2) {
        for (int i2 = 0; i2 <= b.n; ++i2) {
          product.c[static_cast<std::size_t>(i1 + i2 + (product.n + 1) * (j1 + j2))] +=
              wa * binomial(b.n, i2) * binomial(b.m, j2) * b.at(i2, j2);
        }
      }
    }
  }
  for (int l = 0; l <= product.m; ++l) {
    for (int k = 0; k <= product.n; ++k) {
      product.c[static_cast<std::size_t>(k + (product.n + 1) * l)] /= binomial(product.n, k) * binomial(product.m, l);
    }
  }
  return product;
}

ScalarPatch elevated(const ScalarPatch& p, int n, int m) {
  PATCHWORK_ASSERT(n >= p.n && m >= p.m, "elevation raises degrees");
  ScalarPatch q = p;
  while (q.n < n) {
    ScalarPatch r{q.n + 1, q.m, {}};
    for (int j = 0; j <= q.m; ++j) {
      for (int i = 0; i <= r.n; ++i) {
        const double t = static_cast<double>(i) / r.n;
        r.c.push_back((i > 0 ? t * q.at(i - 1, j) : 0.0) + (i < r.n ? (1 - t) * q.at(i, j) : 0.0));
      }
    }
    q = std::move(r);
  }
  while (q.m < m) {
    ScalarPatch r{q.n, q.m + 1, {}};
    for (int j = 0; j <= r.m; ++j) {
      const double t = static_cast<double>(j) / r.m;
      for (int i = 0; i <= q.n; ++i) r.c.push_back((j > 0 ? t * q.at(i, j - 1) : 0.0) + (j < r.m ? (1 - t) * q.at(i, j) : 0.0));
    }
    q = std::move(r);
  }
  return q;
}

void add(ScalarPatch& sum, const ScalarPatch& term, double sign) {
  if (sum.c.empty()) sum = ScalarPatch{term.n, term.m, std::vector<double>(term.c.size(), 0.0)};
  const int n = std::max(sum.n, term.n);
  const int m = std::max(sum.m, term.m);
  if (sum.n != n || sum.m != m) sum = elevated(sum, n, m);
  const ScalarPatch raised = term.n == n && term.m == m ? term : elevated(term, n, m);
  for (std::size_t k = 0; k < raised.c.size(); ++k) sum.c[k] += sign * raised.c[k];
}

ScalarPatch derivative(const ScalarPatch& p, bool along_u) {
  const int degree = along_u ? p.n : p.m;
  if (degree == 0) {
    return {p.n, p.m, std::vector<double>(p.c.size(), 0.0)};
  }
  ScalarPatch d{along_u ? p.n - 1 : p.n, along_u ? p.m : p.m - 1, {}};
  for (int j = 0; j <= d.m; ++j) {
    for (int i = 0; i <= d.n; ++i) {
      d.c.push_back(degree * (along_u ? p.at(i + 1, j) - p.at(i, j) : p.at(i, j + 1) - p.at(i, j)));
    }
  }
  return d;
}

}  // namespace patchwork::detail
