#pragma once
// The plane-distance nets of a ray and a piece (queries/ray_cast.h) and what is decided on them:
// no zero (one sign beyond rounding; Krawczyk), at most one (the Jacobian's interval determinant),
// and Newton to it. Templates over the nets' storage: fixed degree (bicubic pieces, whose loops
// unroll) or any degree up to 31; the arithmetic is the same for both.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "core/types.h"
#include "queries/net_piece.h"

namespace patchwork::detail::ray_nets {

constexpr int max_degree = 31;

// The two scalar nets w_ij a.(P_ij - o), w_ij b.(P_ij - o) of a piece of degree (N, M) fixed at
// compile time (the loops over them unroll: the teapot is all bicubic).
template <int N, int M>
struct FixedScalarNets {
  static constexpr std::integral_constant<int, N> n{};
  static constexpr std::integral_constant<int, M> m{};
  std::array<std::array<double, (N + 1) * (M + 1)>, 2> g;
  double margin = 0.0;
  void resize(std::size_t) {}
};

// The same of any degree, in buffers of the thread's that every piece reuses (no allocation).
struct ScalarNets {
  int n = 0, m = 0;
  std::array<std::vector<double>, 2>& g;
  double margin = 0.0;
  void resize(std::size_t count) {
    g[0].resize(count);
    g[1].resize(count);
  }
};

inline std::array<std::vector<double>, 2>& scratch_coefficients() {
  thread_local std::array<std::vector<double>, 2> buffers;
  return buffers;
}

// Fills `nets` (of the piece's degree) with the piece's two scalar nets and their margin.
template <class Nets>
void fill_scalar_nets(const NetPiece& piece, const Vec3& origin, const Vec3& a, const Vec3& b, Nets& nets) {
  const std::size_t count = piece.net.size();
  nets.resize(count);
  PATCHWORK_ASSERT(count == nets.g[0].size(), "ray_nets: a piece's net does not match its scalar nets' degree");
  double size = 0.0, weighted = 0.0, least_weight = std::numeric_limits<double>::infinity();
  // w a.(P - o) = a.(wP) - w (a.o): no division by the weights.
  const double a_origin = a.dot(origin), b_origin = b.dot(origin);
  const double origin_size = origin.cwiseAbs().maxCoeff();
  for (std::size_t k = 0; k < count; ++k) {
    const Vec4& h = piece.net[k];
    const Vec3 wp = h.head<3>();
    nets.g[0][k] = a.dot(wp) - h[3] * a_origin;
    nets.g[1][k] = b.dot(wp) - h[3] * b_origin;
    const double wp_size = wp.cwiseAbs().maxCoeff();
    weighted = std::max(weighted, wp_size);
    least_weight = std::min(least_weight, h[3]);
    size = std::max(size, wp_size + h[3] * origin_size);
  }
  // max |P| <= max |wP| / min w, with one division (the margin needs a bound, not the value).
  const double coordinates = weighted / least_weight;
  // a.(wP), w (a.o) and their difference round by a few units of w (|P| + |o|) (max norms, times
  // sqrt(3) at most); the margin takes 32 of them.
  // The control points' rounding (detail::rounding_margin, twice) and that of the products.
  nets.margin = 16.0 * (piece.depth + 4) * (piece.n + piece.m + 2) * unit_roundoff * coordinates + 32 * unit_roundoff * size;
}

// All coefficients beyond the margin on one side: no zero of that function in the piece.
template <class Coefficients>
bool one_sign(const Coefficients& g, double margin) {
  bool all_positive = true, all_negative = true;
  for (double c : g) {
    all_positive = all_positive && c > margin;
    all_negative = all_negative && c < -margin;
  }
  return all_positive || all_negative;
}

// The piece misses the ray where its points (g_1, g_2)_k lie in an open half-plane through the
// origin (its projection along the ray misses the ray's point: the Bezier-clipping picture):
// then alpha g_1 + beta g_2, which vanishes wherever both do, has coefficients all beyond rounding
// on one side. (alpha, beta) is the bisector of the narrowest cone about the origin that holds the
// points, built in one pass; only the final test on alpha g_1 + beta g_2 decides, so the cone's
// own rounding cannot drop a piece that holds a zero. Catches pieces whose hull misses the ray
// obliquely, which one_sign (alpha, beta = axes) does not.
template <class Nets>
bool hull_misses_origin(const Nets& nets) {
  const auto& g1 = nets.g[0];
  const auto& g2 = nets.g[1];
  const std::size_t count = g1.size();
  const auto cross = [](double ax, double ay, double bx, double by) { return ax * by - ay * bx; };
  // The cone from (lx, ly) counterclockwise to (hx, hy), narrower than pi.
  double lx = g1[0], ly = g2[0], hx = lx, hy = ly, largest = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const double px = g1[k], py = g2[k];
    largest = std::max({largest, std::abs(px), std::abs(py)});
    if (cross(lx, ly, px, py) >= 0 && cross(px, py, hx, hy) >= 0) continue;
    if (cross(hx, hy, px, py) > 0 && cross(lx, ly, px, py) > 0) {
      hx = px, hy = py;
    } else if (cross(px, py, lx, ly) > 0 && cross(px, py, hx, hy) > 0) {
      lx = px, ly = py;
    } else {
      return false;
    }
  }
  const double low_norm = std::hypot(lx, ly), high_norm = std::hypot(hx, hy);
  double alpha = lx * high_norm + hx * low_norm, beta = ly * high_norm + hy * low_norm;
  const double scale = std::max(std::abs(alpha), std::abs(beta));
  if (!(scale > 0.0) || !std::isfinite(scale)) return false;
  alpha /= scale;
  beta /= scale;
  // Each coefficient is within the margin of its exact value; the combination's two products and
  // sum round by at most 3 units of |alpha| |g_1| + |beta| |g_2| <= (|alpha| + |beta|) largest.
  const double bound = (std::abs(alpha) + std::abs(beta)) * (nets.margin + 4 * unit_roundoff * largest);
  for (std::size_t k = 0; k < count; ++k)
    if (!(alpha * g1[k] + beta * g2[k] > bound)) return false;
  return true;
}

struct Interval {
  double low, high;
};

inline Interval operator*(const Interval& x, const Interval& y) {
  const double p[4] = {x.low * y.low, x.low * y.high, x.high * y.low, x.high * y.high};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}

// The range of d g / ds (dir 0) or d g / dt over the piece: the differenced net's extremes.
template <class Coefficients, class Degree>
Interval derivative_range(const Coefficients& g, Degree n, Degree m, int dir) {
  Interval r{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const int degree = dir == 0 ? n : m;
  if (degree == 0) return {0.0, 0.0};
  for (int j = 0; j <= m - (dir == 1); ++j) {
    for (int i = 0; i <= n - (dir == 0); ++i) {
      const std::size_t k = static_cast<std::size_t>(i + (n + 1) * j);
      const std::size_t next = dir == 0 ? k + 1 : k + static_cast<std::size_t>(n + 1);
      const double c = degree * (g[next] - g[k]);
      r.low = std::min(r.low, c);
      r.high = std::max(r.high, c);
    }
  }
  return r;
}

// The ranges of the Jacobian of (g_1, g_2) over the piece: [f][d] is d g_f / d(s or t).
using JacobianRanges = std::array<std::array<Interval, 2>, 2>;

template <class Nets>
JacobianRanges jacobian_ranges(const Nets& nets) {
  JacobianRanges r;
  for (int f = 0; f < 2; ++f)
    for (int d = 0; d < 2; ++d)
      r[static_cast<std::size_t>(f)][static_cast<std::size_t>(d)] = derivative_range(nets.g[static_cast<std::size_t>(f)], nets.n, nets.m, d);
  return r;
}

// The Jacobian of (g_1, g_2) is regular wherever the differenced nets allow: at most one zero.
inline bool certified_unique(const JacobianRanges& range) {
  const Interval g1s = range[0][0], g1t = range[0][1], g2s = range[1][0], g2t = range[1][1];
  const Interval p = g1s * g2t, q = g1t * g2s;
  const double low = p.low - q.high, high = p.high - q.low;
  const double slack = 8 * unit_roundoff * (std::abs(p.low) + std::abs(p.high) + std::abs(q.low) + std::abs(q.high));
  return low > slack || high < -slack;
}

// Bernstein values b and derivatives d of one degree at x.
// (Degree: an int, or a std::integral_constant for loops that unroll.)
template <class Degree>
void bernstein_with_derivatives(Degree degree, double x, double* b, double* d) {
  if (degree > max_degree) {
    throw InvalidInput(message("ray_cast: a patch of degree ", degree, " (at most ", max_degree, " is supported)"));
  }
  // The values of degree - 1 first; those of degree and the derivatives follow from them.
  // Only the first `degree` entries are written and read (no zeroing of the whole array: this
  // runs for every Newton step of every ray).
  std::array<double, max_degree + 1> lower;
  lower[0] = 1.0;
  for (int k = 1; k < degree; ++k) {
    lower[static_cast<std::size_t>(k)] = x * lower[static_cast<std::size_t>(k - 1)];
    for (int i = k - 1; i > 0; --i)
      lower[static_cast<std::size_t>(i)] = (1 - x) * lower[static_cast<std::size_t>(i)] + x * lower[static_cast<std::size_t>(i - 1)];
    lower[0] *= (1 - x);
  }
  for (int i = 0; i <= degree; ++i) {
    const double left = i > 0 ? lower[static_cast<std::size_t>(i - 1)] : 0.0;
    const double right = i < degree ? lower[static_cast<std::size_t>(i)] : 0.0;
    b[i] = degree == 0 ? 1.0 : (1 - x) * right + x * left;
    d[i] = degree * (left - right);
  }
}

// Values and first derivatives (g, g_s, g_t) of both scalar nets at one (s, t).
using ScalarValues = std::array<std::array<double, 3>, 2>;

// Values and first derivatives (g, g_s, g_t) of both scalar nets at local (s, t).
template <class Nets>
ScalarValues scalar_derivatives(const Nets& nets, double s, double t) {
  std::array<double, max_degree + 1> bu, du, bv, dv;  // entries 0..degree written below
  bernstein_with_derivatives(nets.n, s, bu.data(), du.data());
  bernstein_with_derivatives(nets.m, t, bv.data(), dv.data());
  std::array<std::array<double, 3>, 2> out{};
  for (std::size_t f = 0; f < 2; ++f) {
    const auto& g = nets.g[f];
    for (int j = 0; j <= nets.m; ++j) {
      double row = 0.0, row_s = 0.0;
      for (int i = 0; i <= nets.n; ++i) {
        const double c = g[static_cast<std::size_t>(i + (nets.n + 1) * j)];
        row += bu[static_cast<std::size_t>(i)] * c;
        row_s += du[static_cast<std::size_t>(i)] * c;
      }
      out[f][0] += bv[static_cast<std::size_t>(j)] * row;
      out[f][1] += bv[static_cast<std::size_t>(j)] * row_s;
      out[f][2] += dv[static_cast<std::size_t>(j)] * row;
    }
  }
  return out;
}

// Krawczyk's test on the piece X = [0,1]^2 for G = (g_1, g_2), with c = (1/2, 1/2), Y = G'(c)^-1
// and the Jacobian's ranges J over X: K = c - Y G(c) + (I - Y J)(X - c). Every zero of G in X lies
// in K, so K and X apart prove there is none, and the piece is dropped without halving.
// `at_centre` is scalar_derivatives(nets, 1/2, 1/2).
template <class Nets>
bool krawczyk_excludes(const Nets& nets, const JacobianRanges& range, const ScalarValues& at_centre) {
  const double j00 = at_centre[0][1], j01 = at_centre[0][2], j10 = at_centre[1][1], j11 = at_centre[1][2];
  const double det = j00 * j11 - j01 * j10;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const double y[2][2] = {{j11 / det, -j01 / det}, {-j10 / det, j00 / det}};
  for (int r = 0; r < 2; ++r) {
    // Row r of c - Y G(c), and the radius of row r of (I - Y J)(X - c) with X - c = [-1/2, 1/2]^2.
    const double centre = 0.5 - (y[r][0] * at_centre[0][0] + y[r][1] * at_centre[1][0]);
    double radius = 0.0, scale = std::abs(centre) + 1.0;
    for (int c = 0; c < 2; ++c) {
      Interval entry{r == c ? 1.0 : 0.0, r == c ? 1.0 : 0.0};
      for (int k = 0; k < 2; ++k) {
        const Interval product = Interval{y[r][k], y[r][k]} * range[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)];
        entry.low -= product.high;
        entry.high -= product.low;
        scale += std::abs(product.low) + std::abs(product.high);
      }
      radius += 0.5 * std::max(std::abs(entry.low), std::abs(entry.high));
    }
    // Rounding in G(c), Y and the products, and the nets' own margin carried through Y.
    const double slack = 64 * unit_roundoff * scale + nets.margin * (std::abs(y[r][0]) + std::abs(y[r][1]));
    if (centre - radius - slack > 1.0 || centre + radius + slack < 0.0) return true;
  }
  return false;
}

// Newton on (g_1, g_2) = 0 in the piece's local parameters from its centre, where the values
// are `at_centre`; the zero if it converges (a step below 1e-13) within the piece (widened by a hair, so a hit on the
// piece's edge is found from either side).
template <class Nets>
bool local_newton(const Nets& nets, const ScalarValues& at_centre, double& s, double& t) {
  const double hair = 1e-9;
  s = t = 0.5;
  double previous_step = std::numeric_limits<double>::infinity();
  bool converged = false;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const ScalarValues g = iteration == 0 ? at_centre : scalar_derivatives(nets, s, t);
    const double det = g[0][1] * g[1][2] - g[0][2] * g[1][1];
    if (!(std::abs(det) > 0.0)) return false;
    const double ds = (g[0][0] * g[1][2] - g[0][2] * g[1][0]) / det;
    const double dt = (g[0][1] * g[1][0] - g[0][0] * g[1][1]) / det;
    s -= ds;
    t -= dt;
    if (!(s > -0.25 && s < 1.25 && t > -0.25 && t < 1.25)) return false;
    const double step = std::abs(ds) + std::abs(dt);
    if (step <= 1e-13) {
      converged = true;
      break;
    }
    // Converging (the step at most a quarter of the last: what is left is then below a third of
    // the step, and quadratic convergence makes it far less) to a point outside the piece by
    // more than twice the step: no need to finish. Not a claim that there is no zero: false
    // only means halving.
    const double outside = std::max({-s, s - 1, -t, t - 1});
    if (step <= 0.25 * previous_step && outside > 2 * step + hair) return false;
    previous_step = step;
  }
  // Only a converged zero is one (20 steps without converging: a cycle, and halving decides).
  return converged && s >= -hair && s <= 1 + hair && t >= -hair && t <= 1 + hair;
}


}  // namespace patchwork::detail::ray_nets
