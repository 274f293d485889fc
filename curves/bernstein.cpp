#include "curves/bernstein.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/assert.h"
#include "core/errors.h"

namespace patchwork {
namespace {

void check_degree(const char* function, int n) {
  if (n < 0) throw InvalidInput(detail::message(function, ": degree ", n, " is negative"));
}

void check_parameter(const char* function, double t) {
  if (!std::isfinite(t)) throw InvalidInput(detail::message(function, ": parameter t = ", t, " is not finite"));
}

// Satz 20 in place: after step k, out[0..k] holds B_0^k .. B_k^k.
void bernstein_recursion(int n, double t, double* out) {
  const double r = 1.0 - t;
  out[0] = 1.0;
  for (int k = 1; k <= n; ++k) {
    double previous = 0.0;  // B_{i-1}^{k-1}
    for (int i = 0; i < k; ++i) {
      const double current = out[i];
      out[i] = r * current + t * previous;
      previous = current;
    }
    out[k] = t * previous;
  }
}

// de Casteljau on scalar coefficients, in a scratch copy.
double de_casteljau(std::span<const double> c, double t) {
  const std::size_t n = c.size() - 1;
  const double r = 1.0 - t;
  double small[32];
  std::vector<double> large;
  double* work = small;
  if (c.size() > 32) {
    large.assign(c.begin(), c.end());
    work = large.data();
  } else {
    std::copy(c.begin(), c.end(), small);
  }
  for (std::size_t k = 1; k <= n; ++k) {
    for (std::size_t i = 0; i + k <= n; ++i) work[i] = r * work[i] + t * work[i + 1];
  }
  return work[0];
}

// Left and right halves of c on [0, s] and [s, 1].
void split_coefficients(std::span<const double> c, double s, std::vector<double>& left,
                        std::vector<double>& right) {
  const std::size_t n = c.size() - 1;
  std::vector<double> work(c.begin(), c.end());
  left.resize(n + 1);
  right.resize(n + 1);
  const double r = 1.0 - s;
  left[0] = work[0];
  right[n] = work[n];
  for (std::size_t k = 1; k <= n; ++k) {
    for (std::size_t i = 0; i + k <= n; ++i) work[i] = r * work[i] + s * work[i + 1];
    left[k] = work[0];
    right[n - k] = work[n - k];
  }
}

// Coefficients of c restricted to [x1, x2], 0 <= x1 < x2 <= 1: split at x2, then at x1 / x2.
std::vector<double> coefficients_between(std::span<const double> c, double x1, double x2) {
  std::vector<double> up_to_x2;
  std::vector<double> unused;
  split_coefficients(c, x2, up_to_x2, unused);
  std::vector<double> between;
  split_coefficients(up_to_x2, x1 / x2, unused, between);
  return between;
}

int sign_changes(const std::vector<double>& c) {
  int changes = 0;
  int last = 0;
  for (double value : c) {
    const int sign = (value > 0.0) - (value < 0.0);
    if (sign == 0) continue;
    if (last != 0 && sign != last) ++changes;
    last = sign;
  }
  return changes;
}

// The single root of p in [lo, hi], whose coefficients there (`local`) have one sign change and
// nonzero ends: Newton steps kept inside a shrinking bracket, bisection where Newton leaves it.
// The bracket's end signs are those of local.front() = p(lo) and local.back() = p(hi), the ones
// that showed the sign change: evaluating p at an end anew can give the other sign where p is at
// the rounding level there (a root at a subdivision point), and would then lose the bracket.
double refine_root(std::span<const double> p, std::span<const double> dp, const std::vector<double>& local,
                   double lo, double hi) {
  const bool negative_at_lo = local.front() < 0.0;
  double x = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = de_casteljau(p, x);
    if (f == 0.0) return x;
    if ((f < 0.0) == negative_at_lo) {
      lo = x;
    } else {
      hi = x;
    }
    const double df = dp.empty() ? 0.0 : de_casteljau(dp, x);
    double next = (df != 0.0) ? x - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == x || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(x))) return next;
    x = next;
  }
  return x;
}

bool numerically_zero(const std::vector<double>& local, double noise) {
  return std::all_of(local.begin(), local.end(), [noise](double c) { return std::abs(c) <= noise; });
}

// Recursive isolation. `noise` is the rounding level of p's values (4 n u max|c_i|): a piece
// whose coefficients are all below it is numerically zero (the neighbourhood of a multiple
// root) and is reported once, at its midpoint, instead of being subdivided without end.
void isolate_roots(std::span<const double> p, std::span<const double> dp,
                   const std::vector<double>& local, double lo, double hi, int depth,
                   double noise, std::vector<double>& roots) {
  const int changes = sign_changes(local);
  const bool ends_nonzero = local.front() != 0.0 && local.back() != 0.0;
  if (changes == 0) {
    // No sign change: a root can only be where a coefficient sequence touches zero at an end,
    // or, inside a piece reached by subdividing a sign change, where p is numerically zero (an
    // even-order multiple root, whose computed coefficients may all share one sign).
    if (local.front() == 0.0) roots.push_back(lo);
    if (local.back() == 0.0) roots.push_back(hi);
    if (ends_nonzero && numerically_zero(local, noise)) roots.push_back(0.5 * (lo + hi));
    return;
  }
  if (changes == 1 && ends_nonzero) {
    roots.push_back(refine_root(p, dp, local, lo, hi));
    return;
  }
  if (numerically_zero(local, noise) || depth >= 60 || hi - lo < 1e-11) {
    roots.push_back(0.5 * (lo + hi));  // a cluster or multiple root
    return;
  }
  std::vector<double> left;
  std::vector<double> right;
  split_coefficients(local, 0.5, left, right);
  const double mid = 0.5 * (lo + hi);
  isolate_roots(p, dp, left, lo, mid, depth + 1, noise, roots);
  isolate_roots(p, dp, right, mid, hi, depth + 1, noise, roots);
}

}  // namespace

double falling_factorial(int n, int k) {
  double result = 1.0;
  for (int j = 0; j < k; ++j) result *= n - j;
  return result;
}

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  k = std::min(k, n - k);
  double result = 1.0;
  // Each partial result is the integer C(n-k+i, i), so every step is exact while below 2^53.
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

double bernstein(int n, int i, double t) {
  check_degree("bernstein", n);
  check_parameter("bernstein", t);
  if (i < 0 || i > n) return 0.0;
  return bernstein_all(n, t)[static_cast<std::size_t>(i)];
}

void bernstein_all(int n, double t, std::span<double> out) {
  check_degree("bernstein_all", n);
  check_parameter("bernstein_all", t);
  if (out.size() != static_cast<std::size_t>(n) + 1) {
    throw InvalidInput(detail::message("bernstein_all: output has ", out.size(), " entries, degree ", n, " needs ", n + 1));
  }
  bernstein_recursion(n, t, out.data());
}

std::vector<double> bernstein_all(int n, double t) {
  check_degree("bernstein_all", n);
  std::vector<double> out(static_cast<std::size_t>(n) + 1);
  bernstein_all(n, t, out);
  return out;
}

void bernstein_all_derivatives(int n, double t, int k, std::span<double> out) {
  check_degree("bernstein_all_derivatives", n);
  check_parameter("bernstein_all_derivatives", t);
  if (k < 0) throw InvalidInput(detail::message("bernstein_all_derivatives: order ", k, " is negative"));
  if (out.size() < static_cast<std::size_t>(n) + 1) {
    throw InvalidInput(
        detail::message("bernstein_all_derivatives: output has ", out.size(), " entries, degree ", n, " needs ", n + 1));
  }
  std::fill(out.begin(), out.begin() + n + 1, 0.0);
  if (k > n) return;
  // d/dt B_i^m = m (B_{i-1}^{m-1} - B_i^{m-1}): start from degree n-k, raise the degree k times.
  bernstein_recursion(n - k, t, out.data());
  for (int m = n - k + 1; m <= n; ++m) {
    double previous = 0.0;  // entry i-1 of degree m-1
    for (int i = 0; i < m; ++i) {
      const double current = out[static_cast<std::size_t>(i)];
      out[static_cast<std::size_t>(i)] = m * (previous - current);
      previous = current;
    }
    out[static_cast<std::size_t>(m)] = m * previous;
  }
}

std::vector<double> bernstein_all_derivatives(int n, double t, int k) {
  check_degree("bernstein_all_derivatives", n);
  std::vector<double> values(static_cast<std::size_t>(n) + 1, 0.0);
  bernstein_all_derivatives(n, t, k, values);
  return values;
}

double bernstein_derivative(int n, int i, double t, int k) {
  if (i < 0 || i > n) {
    check_degree("bernstein_derivative", n);
    return 0.0;
  }
  return bernstein_all_derivatives(n, t, k)[static_cast<std::size_t>(i)];
}

BernsteinTable::BernsteinTable(int degree, std::span<const double> parameters)
    : degree_(degree), parameters_(parameters.begin(), parameters.end()) {
  check_degree("BernsteinTable", degree);
  const std::size_t width = static_cast<std::size_t>(degree) + 1;
  weights_.resize(parameters_.size() * width);
  for (std::size_t row = 0; row < parameters_.size(); ++row) {
    check_parameter("BernsteinTable", parameters_[row]);
    bernstein_recursion(degree, parameters_[row], weights_.data() + row * width);
  }
}

BernsteinTable BernsteinTable::uniform(int degree, std::size_t count) {
  if (count < 2) throw InvalidInput(detail::message("BernsteinTable::uniform: count ", count, " < 2"));
  std::vector<double> parameters(count);
  for (std::size_t k = 0; k < count; ++k) parameters[k] = static_cast<double>(k) / static_cast<double>(count - 1);
  return BernsteinTable(degree, parameters);
}

double bernstein_evaluate(std::span<const double> coefficients, double t) {
  if (coefficients.empty()) throw InvalidInput("bernstein_evaluate: no coefficients");
  check_parameter("bernstein_evaluate", t);
  return de_casteljau(coefficients, t);
}

std::vector<double> bernstein_derivative_coefficients(std::span<const double> c) {
  if (c.empty()) throw InvalidInput("bernstein_derivative_coefficients: no coefficients");
  const std::size_t n = c.size() - 1;
  if (n == 0) return {0.0};
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = static_cast<double>(n) * (c[i + 1] - c[i]);
  return d;
}

std::vector<double> bernstein_product(std::span<const double> f, std::span<const double> g) {
  if (f.empty() || g.empty()) throw InvalidInput("bernstein_product: no coefficients");
  const int m = static_cast<int>(f.size()) - 1;
  const int n = static_cast<int>(g.size()) - 1;
  std::vector<double> h(static_cast<std::size_t>(m + n) + 1, 0.0);
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= n; ++j) {
      h[static_cast<std::size_t>(i + j)] += binomial(m, i) * binomial(n, j) / binomial(m + n, i + j) *
                                             f[static_cast<std::size_t>(i)] * g[static_cast<std::size_t>(j)];
    }
  }
  return h;
}

std::vector<double> bernstein_roots(std::span<const double> coefficients) {
  if (coefficients.empty()) throw InvalidInput("bernstein_roots: no coefficients");
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    if (!std::isfinite(coefficients[i])) {
      throw InvalidInput(detail::message("bernstein_roots: coefficient ", i, " is not finite"));
    }
  }
  std::vector<double> roots;
  if (std::all_of(coefficients.begin(), coefficients.end(), [](double c) { return c == 0.0; })) return roots;
  const std::vector<double> derivative = coefficients.size() > 1
                                             ? bernstein_derivative_coefficients(coefficients)
                                             : std::vector<double>{};
  std::vector<double> local(coefficients.begin(), coefficients.end());
  double magnitude = 0.0;
  for (double c : coefficients) magnitude = std::max(magnitude, std::abs(c));
  const double noise = 4.0 * static_cast<double>(coefficients.size()) *
                       std::numeric_limits<double>::epsilon() * 0.5 * magnitude;
  isolate_roots(coefficients, derivative, local, 0.0, 1.0, 0, noise, roots);
  std::sort(roots.begin(), roots.end());
  // Merge duplicates (a root at a split point is found by both halves) and clusters: neighbours
  // closer than 1e-10 keep the first; neighbours between which p is numerically zero (one
  // multiple root seen as several by rounding) become one root at the cluster's middle.
  std::vector<double> merged;
  std::size_t first = 0;
  for (std::size_t last = 0; last < roots.size(); ++last) {
    const bool cluster_ends =
        last + 1 == roots.size() ||
        (roots[last + 1] - roots[last] > 1e-10 &&
         !numerically_zero(coefficients_between(coefficients, roots[last], roots[last + 1]), noise));
    if (!cluster_ends) continue;
    merged.push_back(roots[last] - roots[first] <= 1e-10 ? roots[first] : 0.5 * (roots[first] + roots[last]));
    first = last + 1;
  }
  return merged;
}

}  // namespace patchwork
