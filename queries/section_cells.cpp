#include "queries/section_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <variant>

#include "core/assert.h"
#include "curves/bernstein.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/rational_bounds.h"

namespace patchwork::detail {
namespace {

// A leaf that needs more segments than this is split instead (its bound falls 4 times per split).
constexpr int max_steps = 64;
// Cells are split at most this deep (a cell then spans 2^-50 of the patch).
constexpr int max_depth = 50;
// Two crossings of one cell closer than this in (u, v) are one (a root at a cell corner is found
// on both lines through it).
constexpr double same_crossing = 1e-9;
// Cells with other than two crossings are split down to this fraction of the tolerance.
constexpr double finest_cell = 1e-3;
// ... or until f's coefficients on the cell are at most this many times the rounding level.
constexpr double noise = 64.0;
// The search of one patch examines at most this many cells; the cells left are uncertified (a
// plane tangent along a curve inside a patch, which the search cannot resolve into arcs).
constexpr std::size_t max_cells = std::size_t{1} << 14;

struct Cell {
  double u0, u1, v0, v1;
  int depth;
};

struct Crossing {
  Vec2 uv;
  int node;
};

// The coefficients of p on [a, b] of [0, 1], reparametrised to [0, 1]: de Casteljau at b keeps
// the left part, then at a / b the right part of that.
void restrict_coefficients(std::vector<double>& c, double a, double b) {
  const int n = static_cast<int>(c.size()) - 1;
  std::vector<double> t;
  if (b < 1.0) {
    t = c;
    for (int k = 1; k <= n; ++k) {
      for (int i = 0; i <= n - k; ++i) t[i] = (1.0 - b) * t[i] + b * t[i + 1];
      c[k] = t[0];
    }
  }
  if (a > 0.0) {
    const double s = a / b;
    t = c;
    for (int k = 1; k <= n; ++k) {
      for (int i = 0; i <= n - k; ++i) t[i] = (1.0 - s) * t[i] + s * t[i + 1];
      c[n - k] = t[n - k];
    }
  }
}

ScalarNet restrict_net(const ScalarNet& f, const Cell& cell) {
  ScalarNet r = f;
  std::vector<double> line;
  for (int j = 0; j <= f.m; ++j) {
    line.assign(r.c.begin() + (f.n + 1) * j, r.c.begin() + (f.n + 1) * (j + 1));
    restrict_coefficients(line, cell.u0, cell.u1);
    std::copy(line.begin(), line.end(), r.c.begin() + (f.n + 1) * j);
  }
  line.resize(static_cast<std::size_t>(f.m + 1));
  for (int i = 0; i <= f.n; ++i) {
    for (int j = 0; j <= f.m; ++j) line[j] = r.at(i, j);
    restrict_coefficients(line, cell.v0, cell.v1);
    for (int j = 0; j <= f.m; ++j) r.c[static_cast<std::size_t>(i + (f.n + 1) * j)] = line[j];
  }
  return r;
}

ScalarNet transposed(const ScalarNet& f) {
  ScalarNet t{f.m, f.n, std::vector<double>(f.c.size())};
  for (int i = 0; i <= f.n; ++i)
    for (int j = 0; j <= f.m; ++j) t.c[static_cast<std::size_t>(j + (f.m + 1) * i)] = f.at(i, j);
  return t;
}

double evaluate_net(const ScalarNet& f, double u, double v) { return bernstein_evaluate(iso_line(f, true, v), u); }

AnyBezierPatch cell_patch(const AnyBezierPatch& patch, const Cell& cell) {
  return std::visit([&](const auto& p) -> AnyBezierPatch { return subpatch(p, cell.u0, cell.u1, cell.v0, cell.v1); },
                    patch);
}

SecondDerivativeBounds second_bounds(const AnyBezierPatch& patch) {
  return std::visit([](const auto& p) { return second_derivative_bounds(p); }, patch);
}

// The control points and weights of a patch of either kind.
void net_of(const AnyBezierPatch& patch, int& n, int& m, std::vector<Vec3>& points, std::vector<double>& weights) {
  if (const auto* p = std::get_if<BezierPatch3>(&patch)) {
    n = p->degree_u();
    m = p->degree_v();
    points = p->control_points();
    weights.assign(points.size(), 1.0);
    return;
  }
  const auto& r = std::get<RationalBezierPatch>(patch);
  n = r.degree_u();
  m = r.degree_v();
  points = r.control_net().control_points();
  weights = r.weights();
}

// The diagonal of the box of the control points (the patch lies in it).
double net_diagonal(const AnyBezierPatch& patch) {
  int n = 0, m = 0;
  std::vector<Vec3> points;
  std::vector<double> weights;
  net_of(patch, n, m, points, weights);
  Eigen::AlignedBox3d box;
  for (const Vec3& q : points) box.extend(q);
  return box.diagonal().norm();
}

// sup |F_u| (along_u) or sup |F_v|: F_u = (H_u - F w_u) / w with H = w F, and
//   H_u - F w_u = n sum_ij (w_(i+1)j (P_(i+1)j - F) - w_ij (P_ij - F)) B_i^(n-1) B_j^m,
// each term at most |w_(i+1)j (P_(i+1)j - c) - w_ij (P_ij - c)| + |w_(i+1)j - w_ij| R for F within R
// of c (c the centre of the points' box, R its half diagonal); w >= min w_ij. With equal weights
// this is n max |P_(i+1)j - P_ij|.
double first_derivative_bound(const AnyBezierPatch& patch, bool along_u) {
  int n = 0, m = 0;
  std::vector<Vec3> P;
  std::vector<double> w;
  net_of(patch, n, m, P, w);
  const int degree = along_u ? n : m;
  if (degree == 0) return 0.0;
  Eigen::AlignedBox3d box;
  for (const Vec3& q : P) box.extend(q);
  const Vec3 c = box.center();
  const double R = 0.5 * box.diagonal().norm();
  const bool equal = std::all_of(w.begin(), w.end(), [&](double x) { return x == w.front(); });
  double largest = 0.0;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      const int i1 = along_u ? i + 1 : i, j1 = along_u ? j : j + 1;
      if (i1 > n || j1 > m) continue;
      const std::size_t a = static_cast<std::size_t>(i + (n + 1) * j), b = static_cast<std::size_t>(i1 + (n + 1) * j1);
      const double term = equal ? (P[b] - P[a]).norm()
                                : (w[b] * (P[b] - c) - w[a] * (P[a] - c)).norm() + std::abs(w[b] - w[a]) * R;
      largest = std::max(largest, term);
    }
  }
  const double w_min = *std::min_element(w.begin(), w.end());
  return degree * largest / (equal ? 1.0 : w_min);
}

// Differences of a net along u (k = 1, 2) as the largest absolute value, and the one-sign test.
struct NetDerivatives {
  double su = 0.0;      // sup |f_s|
  double st_min = 0.0;  // inf |f_t| when f_t's coefficients have one strict sign, else 0
  double ss = 0.0, st = 0.0, tt = 0.0;
};

// The bounds of the graph t = g(s) on a leaf's net (f_t of one strict sign, else st_min = 0).
NetDerivatives net_derivatives(const ScalarNet& f) {
  NetDerivatives d;
  const int n = f.n, m = f.m;
  if (m == 0) return d;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double dt = f.at(i, j + 1) - f.at(i, j);
      lo = std::min(lo, dt);
      hi = std::max(hi, dt);
      if (j + 2 <= m) d.tt = std::max(d.tt, std::abs(f.at(i, j + 2) - 2.0 * f.at(i, j + 1) + f.at(i, j)));
      if (i < n) d.st = std::max(d.st, std::abs(f.at(i + 1, j + 1) - f.at(i + 1, j) - f.at(i, j + 1) + f.at(i, j)));
    }
    for (int j = 0; j <= m; ++j) {
      if (i < n) d.su = std::max(d.su, std::abs(f.at(i + 1, j) - f.at(i, j)));
      if (i + 2 <= n) d.ss = std::max(d.ss, std::abs(f.at(i + 2, j) - 2.0 * f.at(i + 1, j) + f.at(i, j)));
    }
  }
  if (lo > 0.0 || hi < 0.0) d.st_min = m * std::min(std::abs(lo), std::abs(hi));
  d.su *= n;
  d.ss *= n * (n - 1.0);
  d.st *= n * static_cast<double>(m);
  d.tt *= m * (m - 1.0);
  return d;
}

// The constant C of the leaf bound (h^2 / 8) C for the graph over s (over_u) or over t, or
// nothing when the other partial derivative of f changes sign on the cell.
std::optional<double> leaf_constant(const ScalarNet& net, const AnyBezierPatch& sub, bool over_u) {
  const NetDerivatives d = net_derivatives(over_u ? net : transposed(net));
  if (d.st_min <= 0.0) return std::nullopt;
  const double A = d.su / d.st_min;                               // >= |g'|
  const double B = (d.ss + 2.0 * d.st * A + d.tt * A * A) / d.st_min;  // >= |g''|
  const SecondDerivativeBounds M = second_bounds(sub);
  const double along = over_u ? M.uu : M.vv, across = over_u ? M.vv : M.uu;
  const double C = along + 2.0 * M.uv * A + across * A * A + first_derivative_bound(sub, !over_u) * B;
  if (!std::isfinite(C)) return std::nullopt;
  return C;
}

// The root of p in [lo, hi] where p changes sign, by bisection to the last bit; the end of smaller
// |p| when rounding hides the change.
double bracketed_root(std::span<const double> p, double lo, double hi) {
  double p_lo = bernstein_evaluate(p, lo);
  const double p_hi = bernstein_evaluate(p, hi);
  if (p_lo == 0.0) return lo;
  if (p_hi == 0.0) return hi;
  if ((p_lo > 0.0) == (p_hi > 0.0)) return std::abs(p_lo) <= std::abs(p_hi) ? lo : hi;
  for (;;) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const double p_mid = bernstein_evaluate(p, mid);
    if (p_mid == 0.0) return mid;
    if ((p_mid > 0.0) == (p_lo > 0.0)) {
      lo = mid;
      p_lo = p_mid;
    } else {
      hi = mid;
    }
  }
  return std::abs(p_lo) <= std::abs(bernstein_evaluate(p, hi)) ? lo : hi;
}

int add_node(SectionState& state, const PatchSection& patch, const Vec2& uv) {
  state.nodes.push_back({evaluate_any(patch.patch, uv.x(), uv.y()), patch.index, uv});
  return static_cast<int>(state.nodes.size()) - 1;
}

// The index (PatchEdge order) of the patch edge on the line, or -1 for an interior line.
int edge_of_line(bool along_u, double at) {
  if (at != 0.0 && at != 1.0) return -1;
  if (along_u) return at == 0.0 ? static_cast<int>(PatchEdge::v0) : static_cast<int>(PatchEdge::v1);
  return at == 0.0 ? static_cast<int>(PatchEdge::u0) : static_cast<int>(PatchEdge::u1);
}

const LineRoots& roots_on(PatchSection& patch, bool along_u, double at, SectionState& state) {
  const int edge = edge_of_line(along_u, at);
  if (edge >= 0) return patch.edge_roots[static_cast<std::size_t>(edge)];
  auto found = patch.lines.find({along_u, at});
  if (found == patch.lines.end()) found = patch.lines.emplace(std::pair(along_u, at), line_roots(patch, along_u, at, state)).first;
  return found->second;
}

// The four sides of a cell in PatchEdge order: (along_u, at, from, to).
std::array<std::tuple<bool, double, double, double>, 4> sides_of(const Cell& cell) {
  return {{{true, cell.v0, cell.u0, cell.u1},
           {false, cell.u1, cell.v0, cell.v1},
           {true, cell.v1, cell.u0, cell.u1},
           {false, cell.u0, cell.v0, cell.v1}}};
}

// The crossings on a cell's boundary. A side on a collapsed edge in the plane (a pole) has no
// isolated roots: the pole is a crossing when the others are odd in number (the curve ends there).
std::vector<Crossing> cell_crossings(PatchSection& patch, const Cell& cell, SectionState& state, bool& pole) {
  std::vector<Crossing> result;
  pole = false;
  Vec2 pole_uv = Vec2::Zero();
  int pole_axis = 0;  // the coordinate that is constant along the pole's side
  for (const auto& [along_u, at, from, to] : sides_of(cell)) {
    const LineRoots& line = roots_on(patch, along_u, at, state);
    const int edge = edge_of_line(along_u, at);
    if (line.zero && edge >= 0 && patch.edges[static_cast<std::size_t>(edge)].collapsed) {
      pole = true;
      const double mid = 0.5 * (from + to);
      pole_uv = along_u ? Vec2(mid, at) : Vec2(at, mid);
      pole_axis = along_u ? 1 : 0;
      continue;
    }
    for (std::size_t k = 0; k < line.t.size(); ++k) {
      const double t = line.t[k];
      if (t < from || t > to) continue;
      const Vec2 uv = along_u ? Vec2(t, at) : Vec2(at, t);
      const auto same = std::find_if(result.begin(), result.end(), [&](const Crossing& c) {
        return (c.uv - uv).cwiseAbs().maxCoeff() <= same_crossing;
      });
      if (same == result.end()) {
        result.push_back({uv, line.nodes[k]});
      } else if (same->node != line.nodes[k]) {
        state.same_nodes.emplace_back(same->node, line.nodes[k]);
      }
    }
  }
  if (!pole) return result;
  // The other sides' lines end at the pole, where their roots (if any) are the pole again.
  const int axis = pole_axis;
  std::erase_if(result, [&](const Crossing& c) { return std::abs(c.uv[axis] - pole_uv[axis]) <= same_crossing; });
  if (result.size() % 2 == 1) result.push_back({pole_uv, add_node(state, patch, pole_uv)});
  return result;
}

// The graph of the leaf's arc from a to b, or false when it needs more than max_steps segments.
bool trace_leaf(const PatchSection& patch, const Cell& cell, const ScalarNet& net, const AnyBezierPatch& sub,
                const Crossing& a, const Crossing& b, SectionState& state) {
  const double du = cell.u1 - cell.u0, dv = cell.v1 - cell.v0;
  int best_steps = max_steps + 1;
  bool best_over_u = true;
  double best_bound = 0.0;
  for (const bool over_u : {true, false}) {
    const double length = over_u ? std::abs(b.uv.x() - a.uv.x()) / du : std::abs(b.uv.y() - a.uv.y()) / dv;
    if (length <= 0.0) continue;
    const std::optional<double> C = leaf_constant(net, sub, over_u);
    if (!C) continue;
    double steps = std::max(1.0, std::ceil(length * std::sqrt(*C / (8.0 * state.tolerance))));
    if (length * length * *C / (8.0 * steps * steps) > state.tolerance) steps += 1.0;  // rounding
    if (steps < best_steps) {
      best_steps = static_cast<int>(steps);
      best_over_u = over_u;
      best_bound = length * length * *C / (8.0 * steps * steps);
    }
  }
  if (best_steps > max_steps) return false;
  PATCHWORK_ASSERT(best_steps >= 1 && best_bound <= state.tolerance, "a leaf's segments meet the tolerance");
  const int axis = best_over_u ? 0 : 1;
  const Crossing& first = a.uv[axis] <= b.uv[axis] ? a : b;
  const Crossing& last = a.uv[axis] <= b.uv[axis] ? b : a;
  SectionPiece piece{first.node, last.node, {}, best_bound};
  for (int k = 1; k < best_steps; ++k) {
    const double x = first.uv[axis] + (last.uv[axis] - first.uv[axis]) * k / best_steps;
    // The line through the sample across the graph's parameter: u = x (over u) or v = x.
    const std::vector<double> line = iso_line(patch.f, !best_over_u, x);
    const double y = best_over_u ? bracketed_root(line, cell.v0, cell.v1) : bracketed_root(line, cell.u0, cell.u1);
    const Vec2 uv = best_over_u ? Vec2(x, y) : Vec2(y, x);
    piece.inner.push_back({evaluate_any(patch.patch, uv.x(), uv.y()), patch.index, uv});
  }
  state.pieces.push_back(std::move(piece));
  return true;
}

// A cell side on which f vanishes: a polyline along the iso-line, once per side of the set.
void report_side(const PatchSection& patch, const Cell& cell, int side, SectionState& state) {
  const auto [along_u, at, from, to] = sides_of(cell)[static_cast<std::size_t>(side)];
  const int edge = edge_of_line(along_u, at);
  auto key = std::tuple(patch.index, along_u, at, from, to);
  if (edge >= 0) {
    const EdgeInfo& info = patch.edges[static_cast<std::size_t>(edge)];
    const PatchEdge e = info.canonical_edge;
    const bool canonical_along_u = e == PatchEdge::v0 || e == PatchEdge::v1;
    const double canonical_at = e == PatchEdge::v0 || e == PatchEdge::u0 ? 0.0 : 1.0;
    key = info.reversed ? std::tuple(info.canonical_patch, canonical_along_u, canonical_at, 1.0 - to, 1.0 - from)
                        : std::tuple(info.canonical_patch, canonical_along_u, canonical_at, from, to);
  }
  if (!state.sides.insert(key).second) return;
  const SecondDerivativeBounds M = second_bounds(cell_patch(patch.patch, cell));
  const double second = along_u ? M.uu : M.vv;
  double steps = std::max(1.0, std::ceil(std::sqrt(second / (8.0 * state.tolerance))));
  if (second / (8.0 * steps * steps) > state.tolerance) steps += 1.0;  // rounding
  // Copies: clang 14 does not let a lambda capture structured bindings.
  const bool side_along_u = along_u;
  const double side_at = at;
  const auto uv_at = [&](double t) { return side_along_u ? Vec2(t, side_at) : Vec2(side_at, t); };
  SectionPiece piece{add_node(state, patch, uv_at(from)), add_node(state, patch, uv_at(to)), {},
                     second / (8.0 * steps * steps)};
  for (int k = 1; k < static_cast<int>(steps); ++k) {
    const Vec2 uv = uv_at(from + (to - from) * k / steps);
    piece.inner.push_back({evaluate_any(patch.patch, uv.x(), uv.y()), patch.index, uv});
  }
  state.pieces.push_back(std::move(piece));
}

// A cell whose coefficients are >= 0 (or <= 0) touches the plane only where they vanish: along a
// side whose coefficients all vanish, or at a corner.
void report_touching(const PatchSection& patch, const Cell& cell, const ScalarNet& net, SectionState& state) {
  const int n = net.n, m = net.m;
  const auto zero = [&](int i, int j) { return std::abs(net.at(i, j)) <= patch.zero; };
  std::array<bool, 4> side_zero{true, true, true, true};
  for (int i = 0; i <= n; ++i) {
    side_zero[0] = side_zero[0] && zero(i, 0);
    side_zero[2] = side_zero[2] && zero(i, m);
  }
  for (int j = 0; j <= m; ++j) {
    side_zero[1] = side_zero[1] && zero(n, j);
    side_zero[3] = side_zero[3] && zero(0, j);
  }
  const auto tangent_at = [&](const Vec2& uv) {
    state.tangent_candidates.push_back({{evaluate_any(patch.patch, uv.x(), uv.y()), patch.index, uv}, 0.0});
  };
  const auto sides = sides_of(cell);
  for (int s = 0; s < 4; ++s) {
    if (!side_zero[static_cast<std::size_t>(s)]) continue;
    const auto [along_u, at, from, to] = sides[static_cast<std::size_t>(s)];
    const int edge = edge_of_line(along_u, at);
    const double mid = 0.5 * (from + to);
    if (edge >= 0 && patch.edges[static_cast<std::size_t>(edge)].collapsed) {
      tangent_at(along_u ? Vec2(mid, at) : Vec2(at, mid));
    } else if (edge < 0 || !patch.edges[static_cast<std::size_t>(edge)].neighbour_in_plane) {
      report_side(patch, cell, s, state);
    }
  }
  // Corner k lies between sides k - 1 and k (PatchEdge order: corner 0 at (u0, v0)).
  const std::array<std::pair<int, int>, 4> corners{{{0, 0}, {n, 0}, {n, m}, {0, m}}};
  const std::array<Vec2, 4> corner_uv{Vec2(cell.u0, cell.v0), Vec2(cell.u1, cell.v0), Vec2(cell.u1, cell.v1),
                                      Vec2(cell.u0, cell.v1)};
  for (std::size_t k = 0; k < 4; ++k) {
    if (side_zero[k] || side_zero[(k + 3) % 4] || !zero(corners[k].first, corners[k].second)) continue;
    tangent_at(corner_uv[k]);
  }
}

// Where to split [a, b] (fractions near the middle first): the first place where `clear` holds.
template <class Clear>
double split_point(double a, double b, Clear clear) {
  for (const double fraction : {0.5, 0.4375, 0.5625, 0.375, 0.625, 0.3125, 0.6875}) {
    const double x = a + fraction * (b - a);
    if (clear(x)) return x;
  }
  return 0.5 * (a + b);
}

}  // namespace

ScalarNet signed_distance_net(const AnyBezierPatch& patch, const Vec3& p, const Vec3& n) {
  int du = 0, dv = 0;
  std::vector<Vec3> points;
  std::vector<double> weights;
  net_of(patch, du, dv, points, weights);
  ScalarNet f{du, dv, std::vector<double>(points.size())};
  for (std::size_t k = 0; k < points.size(); ++k) f.c[k] = weights[k] * n.dot(points[k] - p);
  return f;
}

std::vector<double> iso_line(const ScalarNet& f, bool along_u, double at) {
  const std::vector<double> B = bernstein_all(along_u ? f.m : f.n, at);
  std::vector<double> line(static_cast<std::size_t>(along_u ? f.n + 1 : f.m + 1), 0.0);
  for (int j = 0; j <= f.m; ++j)
    for (int i = 0; i <= f.n; ++i) {
      if (along_u) line[i] += B[j] * f.at(i, j);
      else line[j] += B[i] * f.at(i, j);
    }
  return line;
}

Vec3 evaluate_any(const AnyBezierPatch& patch, double u, double v) {
  return std::visit([&](const auto& p) -> Vec3 { return p.evaluate(u, v); }, patch);
}

LineRoots line_roots(const PatchSection& patch, bool along_u, double at, SectionState& state) {
  LineRoots result;
  const std::vector<double> line = iso_line(patch.f, along_u, at);
  result.zero = std::all_of(line.begin(), line.end(), [&](double c) { return std::abs(c) <= patch.zero; });
  if (result.zero) return result;
  result.t = bernstein_roots(line);
  for (const double t : result.t) result.nodes.push_back(add_node(state, patch, along_u ? Vec2(t, at) : Vec2(at, t)));
  return result;
}

void search_patch(PatchSection& patch, SectionState& state) {
  double largest = 0.0;
  for (const double c : patch.f.c) largest = std::max(largest, std::abs(c));
  const double clear = 1e-9 * largest;  // split lines keep this far (in f) from the curve at their ends
  std::vector<Cell> stack{{0.0, 1.0, 0.0, 1.0, 0}};
  std::size_t examined = 0;
  while (!stack.empty()) {
    if (examined == max_cells) {
      state.uncertified += stack.size();
      break;
    }
    const Cell cell = stack.back();
    stack.pop_back();
    ++examined;
    ++state.cells;
    const ScalarNet net = restrict_net(patch.f, cell);
    const bool positive = std::any_of(net.c.begin(), net.c.end(), [&](double c) { return c > patch.zero; });
    const bool negative = std::any_of(net.c.begin(), net.c.end(), [&](double c) { return c < -patch.zero; });
    if (!positive && !negative) {  // f vanishes on a cell of a patch not in the plane: rounding
      ++state.uncertified;
      continue;
    }
    if (!positive || !negative) {
      report_touching(patch, cell, net, state);
      continue;
    }
    bool pole = false;
    const std::vector<Crossing> crossings = cell_crossings(patch, cell, state, pole);
    const AnyBezierPatch sub = cell_patch(patch.patch, cell);
    if (!pole) {
      const bool graph = net_derivatives(net).st_min > 0.0 || net_derivatives(transposed(net)).st_min > 0.0;
      if (graph && crossings.empty()) continue;
      if (graph && crossings.size() == 2 && trace_leaf(patch, cell, net, sub, crossings[0], crossings[1], state)) continue;
    }
    // Two crossings join by a segment once the box is within the tolerance. No crossing (a loop
    // inside, a touching point, or nothing), one or more than two are split further, down to
    // finest_cell of the tolerance or until f's coefficients on the cell (the smaller sign's, with
    // no crossing) are rounding noise, a tangent point or a crossing of the curve with itself.
    const double diagonal = net_diagonal(sub);
    double above = 0.0, below = 0.0;
    for (const double c : net.c) {
      above = std::max(above, c);
      below = std::max(below, -c);
    }
    const double size_of_f = crossings.empty() ? std::min(above, below) : std::max(above, below);
    const bool finest = cell.depth >= max_depth || diagonal <= finest_cell * state.tolerance || size_of_f <= noise * patch.zero;
    if (finest || (crossings.size() == 2 && diagonal <= state.tolerance)) {
      // The section in the cell and any segment between its crossings lie in the box of the
      // control points, within its diagonal of each other.
      if (crossings.empty()) {  // loops inside, or none: the box meets the plane (mixed signs)
        const Vec2 uv(0.5 * (cell.u0 + cell.u1), 0.5 * (cell.v0 + cell.v1));
        state.tangent_candidates.push_back({{evaluate_any(patch.patch, uv.x(), uv.y()), patch.index, uv}, diagonal});
        continue;
      }
      // Two crossings: one segment; more (the curve crosses itself): a star from the first.
      if (crossings.size() == 1 || diagonal > state.tolerance) ++state.uncertified;
      for (std::size_t k = 1; k < crossings.size(); ++k)
        state.pieces.push_back({crossings[0].node, crossings[k].node, {}, diagonal});
      continue;
    }
    const double us = split_point(cell.u0, cell.u1, [&](double u) {
      return std::abs(evaluate_net(patch.f, u, cell.v0)) > clear && std::abs(evaluate_net(patch.f, u, cell.v1)) > clear;
    });
    const double vs = split_point(cell.v0, cell.v1, [&](double v) {
      return std::abs(evaluate_net(patch.f, cell.u0, v)) > clear && std::abs(evaluate_net(patch.f, cell.u1, v)) > clear &&
             std::abs(evaluate_net(patch.f, us, v)) > clear;
    });
    const int depth = cell.depth + 1;
    stack.push_back({cell.u0, us, cell.v0, vs, depth});
    stack.push_back({us, cell.u1, cell.v0, vs, depth});
    stack.push_back({cell.u0, us, vs, cell.v1, depth});
    stack.push_back({us, cell.u1, vs, cell.v1, depth});
  }
}

}  // namespace patchwork::detail
