#include "report/queries_cases.h"

#include <gmpxx.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include "core/errors.h"
#include "queries/patch_evaluation.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/surface_curvature.h"
#include "tests/queries/exact_root_count.h"

namespace patchwork::crosscheck {
namespace {

using Random = std::mt19937_64;

double uniform(Random& random, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random); }

// A point uniform in the box [lo, hi], rounded to a dyadic.
Vec3 dyadic_point_in(Random& random, const Vec3& lo, const Vec3& hi) {
  return Vec3(dyadic(uniform(random, lo.x(), hi.x())), dyadic(uniform(random, lo.y(), hi.y())),
              dyadic(uniform(random, lo.z(), hi.z())));
}

// A unit vector uniform on the sphere (normalised Gaussian).
Vec3 random_direction(Random& random) {
  std::normal_distribution<double> gauss;
  Vec3 d(gauss(random), gauss(random), gauss(random));
  return d.normalized();
}

// 10^x, x uniform in [lo, hi]: a scale spread evenly over decades.
double log_uniform(Random& random, double lo, double hi) { return std::pow(10.0, uniform(random, lo, hi)); }

// The box of all control points, scaled by `factor` about its centre.
std::pair<Vec3, Vec3> scaled_box(const PatchSet& set, double factor) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const BezierPatch3& net : set.control_nets()) {
    for (const Vec3& P : net.control_points()) lo = lo.cwiseMin(P), hi = hi.cwiseMax(P);
  }
  const Vec3 centre = (lo + hi) / 2, half = (hi - lo) / 2 * factor;
  return {centre - half, centre + half};
}

// A uniformly random point of a random patch, as (patch, u, v).
Foot random_foot(Random& random, const PatchSet& set, double margin = 0.0) {
  const auto p = static_cast<std::uint32_t>(std::uniform_int_distribution<std::size_t>(0, set.count() - 1)(random));
  return {p, uniform(random, margin, 1 - margin), uniform(random, margin, 1 - margin)};
}

// ------------------------------------------------------------------------------------------
// Exact polynomials

using exact::Polynomial;

// The power-basis polynomial of one coordinate of Bernstein coefficients, exactly.
Polynomial power_of(const std::vector<double>& bernstein) {
  const std::vector<mpq_class> c = exact::rationals(bernstein);
  return exact::bernstein_to_power(c);
}

Polynomial product(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial c(a.size() + b.size() - 1, mpq_class(0));
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

Polynomial sum(Polynomial a, const Polynomial& b, int sign = 1) {
  if (a.size() < b.size()) a.resize(b.size(), mpq_class(0));
  for (std::size_t j = 0; j < b.size(); ++j) a[j] += sign * b[j];
  return exact::trimmed(std::move(a));
}

// The middle of a root interval, rounded to double.
double middle(const exact::RootInterval& x) { return exact::nearest_double((x.lo + x.hi) / 2); }

// The multiplicity of the root in `x` (an isolating interval of f's distinct roots): the number of
// repeated gcds f, gcd(f, f'), ... that still vanish in it.
int multiplicity_in(const Polynomial& f, const exact::RootInterval& x) {
  int m = 1;
  Polynomial h = exact::trimmed(f);
  while (true) {
    h = exact::trimmed(exact::gcd(h, exact::differentiated(h)));
    if (h.size() <= 1 || exact::distinct_roots(h, x.lo, x.hi) == 0) return m;
    ++m;
  }
}

// The interval [0, 1] and the width roots are narrowed to.
const mpq_class& zero() {
  static const mpq_class value(0);
  return value;
}
const mpq_class& one() {
  static const mpq_class value(1);
  return value;
}
mpq_class root_width() {
  mpq_class w(1);
  w /= mpz_class(1) << 60;
  return w;
}

}  // namespace

Tally& operator+=(Tally& a, const Tally& b) {
  a.right += b.right, a.wrong += b.wrong, a.missed += b.missed, a.twice += b.twice;
  a.max_error = std::max(a.max_error, b.max_error);
  return a;
}

Tally match_answers(std::size_t truths, std::size_t reports,
                    const std::function<double(std::size_t, std::size_t)>& distance, double tolerance) {
  Tally tally;
  std::vector<bool> reached(truths, false);
  for (std::size_t j = 0; j < reports; ++j) {
    std::size_t best = truths;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < truths; ++i) {
      const double d = distance(i, j);
      if (d < best_distance) best = i, best_distance = d;
    }
    if (best == truths || !(best_distance <= tolerance)) {
      ++tally.wrong;
    } else if (reached[best]) {
      ++tally.twice;
    } else {
      reached[best] = true;
      ++tally.right;
      tally.max_error = std::max(tally.max_error, best_distance);
    }
  }
  tally.missed = static_cast<int>(std::count(reached.begin(), reached.end(), false));
  return tally;
}

double dyadic(double x, int bits) { return std::ldexp(std::round(std::ldexp(x, bits)), -bits); }

// ---------------------------------------------------------------------------------------------
// Closest points

NurbsSurface sphere_surface(const Sphere& sphere) { return nurbs_sphere(sphere.center, sphere.radius); }

PatchSet nurbs_patch_set(const NurbsSurface& surface) {
  const NurbsBezierPatches pieces = bezier_patches(surface);
  return PatchSet(pieces.patches, pieces.joins);
}

std::vector<PointFamily> sphere_point_families(const Sphere& sphere, int count, std::uint64_t seed) {
  Random random(seed);
  const Vec3 c = sphere.center;
  const double r = sphere.radius;
  std::vector<PointFamily> families{
      {"box around it", {}}, {"near the surface", {}}, {"centre and near it", {}}, {"on the surface", {}}};
  for (int k = 0; k < count; ++k) {
    families[0].points.push_back(dyadic_point_in(random, c - Vec3::Constant(2 * r), c + Vec3::Constant(2 * r)));
    const double d = (k % 2 == 0 ? 1 : -1) * log_uniform(random, -6, -2) * r;
    families[1].points.push_back(c + (r + d) * random_direction(random));
    // The centre itself first: every point of the sphere is a foot.
    families[2].points.push_back(k == 0 ? c : Vec3(c + log_uniform(random, -9, -3) * r * random_direction(random)));
    families[3].points.push_back(c + r * random_direction(random));
  }
  return families;
}

std::vector<PointFamily> teapot_point_families(const PatchSet& teapot, int count, std::uint64_t seed) {
  Random random(seed);
  const auto [lo, hi] = scaled_box(teapot, 2.0);
  const double size = teapot.size();
  std::vector<PointFamily> families{
      {"box twice the teapot's", {}}, {"near the surface", {}}, {"on the axis x = y = 0", {}}, {"on the surface", {}}};
  for (int k = 0; k < count; ++k) {
    families[0].points.push_back(dyadic_point_in(random, lo, hi));
    const Foot near = random_foot(random, teapot);
    const double d = (k % 2 == 0 ? 1 : -1) * log_uniform(random, -5, -2) * size;
    families[1].points.push_back(detail::patch_point(teapot, near.patch, near.u, near.v) +
                                 d * detail::patch_unit_normal(teapot, near.patch, near.u, near.v));
    families[2].points.push_back(Vec3(0, 0, dyadic(uniform(random, -0.5, 3.6))));
    const Foot on = random_foot(random, teapot);
    families[3].points.push_back(detail::patch_point(teapot, on.patch, on.u, on.v));
  }
  return families;
}

double sphere_distance(const Sphere& sphere, const Vec3& q) {
  return std::abs((q - sphere.center).norm() - sphere.radius);
}

SampledPatches sample_patches(const PatchSet& set, int n) {
  SampledPatches samples;
  samples.n = n;
  const double step = 1.0 / (n - 1);
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) samples.points.push_back(detail::patch_point(set, p, i * step, j * step));
    }
    // |F_u| <= n max |P_(i+1)j - P_ij| on a polynomial patch (the hodograph's hull); a point is within
    // half a step in u and in v of a sample. Rational patches: the same bound on the homogeneous
    // net would not hold for F, so their reach is infinite (the grid gives no lower bound there).
    const BezierPatch3& net = set.control_nets()[p];
    double du = 0, dv = 0;
    for (int j = 0; j <= net.degree_v(); ++j) {
      for (int i = 0; i <= net.degree_u(); ++i) {
        if (i < net.degree_u()) du = std::max(du, (net.control_point(i + 1, j) - net.control_point(i, j)).norm());
        if (j < net.degree_v()) dv = std::max(dv, (net.control_point(i, j + 1) - net.control_point(i, j)).norm());
      }
    }
    samples.reach.push_back(set.is_rational(p) ? std::numeric_limits<double>::infinity()
                                               : (net.degree_u() * du + net.degree_v() * dv) * step / 2);
  }
  return samples;
}

DistanceTruth distance_truth(const PatchSet& set, const SampledPatches& samples, const Vec3& q,
                             std::span<const Foot> feet) {
  const std::size_t per_patch = static_cast<std::size_t>(samples.n) * static_cast<std::size_t>(samples.n);
  double best = std::numeric_limits<double>::infinity();
  double lower = best;
  std::vector<std::pair<double, std::size_t>> nearest(set.count());
  for (std::size_t p = 0; p < set.count(); ++p) {
    nearest[p] = {std::numeric_limits<double>::infinity(), 0};
    for (std::size_t k = 0; k < per_patch; ++k) {
      const double d = (samples.points[p * per_patch + k] - q).squaredNorm();
      if (d < nearest[p].first) nearest[p] = {d, k};
    }
    nearest[p].first = std::sqrt(nearest[p].first);
    best = std::min(best, nearest[p].first);
    lower = std::min(lower, nearest[p].first - samples.reach[p]);
  }
  for (const Foot& foot : feet) best = std::min(best, detail::newton_foot(set, foot.patch, foot.u, foot.v, q).distance);
  const double step = 1.0 / (samples.n - 1);
  for (std::size_t p = 0; p < set.count(); ++p) {
    if (!(nearest[p].first - samples.reach[p] < best)) continue;
    const double u = static_cast<double>(nearest[p].second % static_cast<std::size_t>(samples.n)) * step;
    const double v = static_cast<double>(nearest[p].second / static_cast<std::size_t>(samples.n)) * step;
    best = std::min(best, detail::newton_foot(set, static_cast<std::uint32_t>(p), u, v, q).distance);
  }
  return {best, std::max(0.0, lower)};
}

Verdict judge_distance(std::optional<double> distance, double gap, double truth, double tolerance) {
  if (!distance) return Verdict::missed;
  if (*distance > truth + tolerance || !(gap <= tolerance)) return Verdict::wrong;
  return Verdict::right;
}

// ---------------------------------------------------------------------------------------------
// Curves against surfaces

std::vector<CurveFamily> sphere_curve_families(const Sphere& sphere, int count, std::uint64_t seed) {
  Random random(seed);
  const Vec3 c = sphere.center;
  const double r = sphere.radius;
  const Vec3 lo = c - Vec3::Constant(1.6 * r), hi = c + Vec3::Constant(1.6 * r);
  std::vector<CurveFamily> families{{"lines, random", {}}, {"cubics, random", {}}, {"tangent lines", {}}};
  for (int k = 0; k < count; ++k) {
    families[0].cases.push_back({BezierCurve3({dyadic_point_in(random, lo, hi), dyadic_point_in(random, lo, hi)}), {}});
    std::vector<Vec3> P;
    for (int i = 0; i < 4; ++i) P.push_back(dyadic_point_in(random, lo, hi));
    families[1].cases.push_back({BezierCurve3(P), {}});
  }
  // Tangent at the poles and at the corners of the patches on the equator (exact: the points and
  // the directions are dyadic), then at random points (rounded: the exact line misses or cuts the
  // sphere by a few units of rounding; the contact stays one answer).
  const std::array<Vec3, 6> axes{Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                                 -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  for (int k = 0; k < count; ++k) {
    Vec3 p, d;
    if (k < 12) {
      // Axis k % 6 and one orthogonal to it ((i + 2) % 6 and (i + 4) % 6 are never i's pair).
      const Vec3& n = axes[static_cast<std::size_t>(k % 6)];
      d = r * axes[static_cast<std::size_t>((k % 6 + 2 + 2 * (k / 6)) % 6)];
      p = c + r * n;
    } else {
      const Vec3 n = random_direction(random);
      d = r * n.cross(random_direction(random)).normalized();
      // Not rounded further: the line p -+ d is tangent but for the rounding of p and d (some
      // 1e-16), so an exact crossing or miss is within some 1e-8 of t = 1/2.
      p = c + r * n;
    }
    families[2].cases.push_back({BezierCurve3({p - d, p + d}), 0.5});
  }
  return families;
}

std::vector<CurveFamily> teapot_curve_families(const PatchSet& teapot, int count, std::uint64_t seed) {
  Random random(seed);
  const auto [lo, hi] = scaled_box(teapot, 1.3);
  const double size = teapot.size();
  std::vector<CurveFamily> families{
      {"lines, random", {}}, {"cubics, random", {}}, {"lines through shared edges", {}}, {"tangent lines", {}}};
  for (int k = 0; k < count; ++k) {
    families[0].cases.push_back({BezierCurve3({dyadic_point_in(random, lo, hi), dyadic_point_in(random, lo, hi)}), {}});
    std::vector<Vec3> P;
    for (int i = 0; i < 4; ++i) P.push_back(dyadic_point_in(random, lo, hi));
    families[1].cases.push_back({BezierCurve3(P), {}});
  }
  const std::vector<SharedEdge>& shared = teapot.shared_edges();
  for (int k = 0; k < count && !shared.empty(); ++k) {
    const EdgeRef& edge = shared[static_cast<std::size_t>(k) % shared.size()].first;
    // The edge's midpoint: u or v is 0 or 1 by the edge, the other 1/2.
    const double t = 0.5;
    const std::array<Vec2, 4> uv{Vec2(t, 0), Vec2(1, t), Vec2(t, 1), Vec2(0, t)};
    const Vec2 at = uv[static_cast<std::size_t>(edge.edge)];
    const Vec3 p = detail::patch_point(teapot, edge.patch, at.x(), at.y());
    const Vec3 d = 0.3 * size * random_direction(random);
    families[2].cases.push_back({BezierCurve3({p - d, p + d}), {}});
  }
  while (static_cast<int>(families[3].cases.size()) < count) {
    const Foot f = random_foot(random, teapot, 0.05);
    const SurfaceCurvature K = curvature(teapot.patches()[f.patch], f.u, f.v);
    // Convex: both principal curvatures of one sign and not small, so the line only touches.
    if (!K.defined || K.at_pole || !(K.gaussian > 1e-2)) continue;
    const Vec3 p = detail::patch_point(teapot, f.patch, f.u, f.v);
    const Vec3 d = 0.25 * size * ((random() % 2 == 0) ? K.d1 : K.d2);
    families[3].cases.push_back({BezierCurve3({p - d, p + d}), 0.5});
  }
  return families;
}

std::vector<double> sphere_hit_parameters(const BezierCurve3& curve, const Sphere& sphere) {
  Polynomial f;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> coordinate;
    for (const Vec3& P : curve.control_points()) coordinate.push_back(P[axis]);
    const Polynomial x = sum(power_of(coordinate), Polynomial{mpq_class(sphere.center[axis])}, -1);
    f = sum(f, product(x, x));
  }
  f = sum(f, Polynomial{mpq_class(sphere.radius) * mpq_class(sphere.radius)}, -1);
  std::vector<double> roots;
  if (f.empty()) return roots;  // the curve lies on the sphere: not among the cases
  for (const exact::RootInterval& x : exact::isolated_roots(f, zero(), one(), root_width())) {
    roots.push_back(middle(x));
  }
  return roots;
}

std::vector<double> sphere_hit_truth(const CurveCase& c, const Sphere& sphere) {
  std::vector<double> truth;
  if (c.contact_t) truth.push_back(*c.contact_t);
  for (const double t : sphere_hit_parameters(c.curve, sphere)) {
    if (!c.contact_t || std::abs(t - *c.contact_t) > kParameterTolerance) truth.push_back(t);
  }
  std::sort(truth.begin(), truth.end());
  return truth;
}

namespace {

// Newton on G(t, u, v) = F(u, v) - C(t) from a start; the converged (t, u, v) if |G| falls below
// `residual` inside the domains (to 1e-9).
std::optional<ReportedHit> newton_hit(const PatchSet& set, const BezierCurve3& curve, ReportedHit x, double residual) {
  // One Newton step on the 3 x 3 system; the new point and its residual |G| before the step.
  const auto step = [&](ReportedHit& y) {
    const PartialDerivatives<3> F = detail::patch_derivatives(set, y.patch, y.u, y.v, 1);
    const Vec3 G = F.at(0, 0) - curve.evaluate(y.t);
    Eigen::Matrix3d J;
    J << F.at(1, 0), F.at(0, 1), -derivative(curve, y.t, 1);
    const Vec3 d = J.colPivHouseholderQr().solve(G);
    if (d.allFinite()) y.u -= d.x(), y.v -= d.y(), y.t -= d.z();
    return G.norm();
  };
  for (int iteration = 0; iteration < 40; ++iteration) {
    ReportedHit next = x;
    if (step(next) <= residual) {
      // Converged at x; polish a few steps more while |G| does not grow, so that the root does
      // not depend (beyond rounding) on which answer Newton started from.
      for (int polish = 0; polish < 3; ++polish) {
        ReportedHit further = next;
        const double before = step(further);
        if (!(before <= residual)) break;
        x = next, next = further;
      }
      const double slack = 1e-9;
      const bool inside =
          x.t >= -slack && x.t <= 1 + slack && x.u >= -slack && x.u <= 1 + slack && x.v >= -slack && x.v <= 1 + slack;
      if (inside) return x;
      return std::nullopt;
    }
    x = next;
    if (!(std::abs(x.t) <= 2 && std::abs(x.u) <= 2 && std::abs(x.v) <= 2)) return std::nullopt;
  }
  return std::nullopt;
}

// The parameter s in [0, 1] and barycentric (a, b) where segment p q crosses triangle (A, B, C)
// (Moeller and Trumbore 1997), if it does.
std::optional<Eigen::Vector3d> segment_triangle(const Vec3& p, const Vec3& q, const Vec3& A, const Vec3& B,
                                                const Vec3& C) {
  const Vec3 d = q - p, e1 = B - A, e2 = C - A;
  const Vec3 h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const Vec3 s = p - A;
  const double a = s.dot(h) / det;
  if (a < 0 || a > 1) return std::nullopt;
  const Vec3 g = s.cross(e1);
  const double b = d.dot(g) / det;
  if (b < 0 || a + b > 1) return std::nullopt;
  const double t = e2.dot(g) / det;
  if (t < 0 || t > 1) return std::nullopt;
  return Eigen::Vector3d(t, a, b);
}

// Adds t to the sorted truths unless one is within `merge` of it.
void add_truth(std::vector<double>& truths, double t, double merge) {
  for (const double x : truths) {
    if (std::abs(x - t) <= merge) return;
  }
  truths.insert(std::lower_bound(truths.begin(), truths.end(), t), t);
}

}  // namespace

HitTruth teapot_hit_truth(const PatchSet& set, const SampledPatches& samples, const CurveCase& c,
                          std::span<const ReportedHit> reports) {
  const double size = set.size();
  const double merge = kParameterTolerance / 100;
  HitTruth truth;
  if (c.contact_t) truth.t.push_back(*c.contact_t);
  for (const ReportedHit& hit : reports) {
    const bool inside = hit.t >= 0 && hit.t <= 1 && hit.u >= 0 && hit.u <= 1 && hit.v >= 0 && hit.v <= 1;
    if (!inside || hit.patch >= set.count()) continue;
    // A report is a hit if it lies on both within 1e-7 of the size and Newton from it reaches an
    // exact root (to 1e-12) no farther than the tolerance: near a tangent contact the line stays
    // within 1e-7 of the surface for a while, and only Newton tells a crossing from a near miss.
    const double gap = (detail::patch_point(set, hit.patch, hit.u, hit.v) - c.curve.evaluate(hit.t)).norm();
    if (!(gap <= 1e-7 * size)) continue;
    const auto root = newton_hit(set, c.curve, hit, 1e-12 * size);
    if (!root || std::abs(root->t - hit.t) > kParameterTolerance) continue;
    const double t = std::clamp(root->t, 0.0, 1.0);
    add_truth(truth.t, t,
              c.contact_t && std::abs(t - *c.contact_t) <= kParameterTolerance ? kParameterTolerance : merge);
  }
  // The dense check: the curve's polyline against the sampled grid's triangles.
  const int pieces = c.curve.degree() <= 1 ? 1 : 32;
  const int n = samples.n;
  const double step = 1.0 / (n - 1);
  const std::size_t per_patch = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  for (int k = 0; k < pieces; ++k) {
    const double t0 = static_cast<double>(k) / pieces, t1 = static_cast<double>(k + 1) / pieces;
    const Vec3 p = c.curve.evaluate(t0), q = c.curve.evaluate(t1);
    const Eigen::AlignedBox3d segment_box = Eigen::AlignedBox3d(p.cwiseMin(q), p.cwiseMax(q));
    for (std::uint32_t patch = 0; patch < set.count(); ++patch) {
      const Vec3* grid = &samples.points[patch * per_patch];
      Eigen::AlignedBox3d box;
      for (std::size_t i = 0; i < per_patch; ++i) box.extend(grid[i]);
      if (!box.intersects(segment_box)) continue;
      for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
          const auto at = [&](int a, int b) -> const Vec3& { return grid[a + n * b]; };
          const std::array<std::array<int, 6>, 2> triangles{
              {{i, j, i + 1, j, i + 1, j + 1}, {i, j, i + 1, j + 1, i, j + 1}}};
          for (const auto& tri : triangles) {
            const auto x = segment_triangle(p, q, at(tri[0], tri[1]), at(tri[2], tri[3]), at(tri[4], tri[5]));
            if (!x) continue;
            const double t = t0 + (*x)[0] * (t1 - t0);
            const double w = 1 - (*x)[1] - (*x)[2];
            const double u = (w * tri[0] + (*x)[1] * tri[2] + (*x)[2] * tri[4]) * step;
            const double v = (w * tri[1] + (*x)[1] * tri[3] + (*x)[2] * tri[5]) * step;
            const auto confirmed = newton_hit(set, c.curve, {patch, t, u, v}, 1e-12 * size);
            if (confirmed) {
              add_truth(truth.t, std::clamp(confirmed->t, 0.0, 1.0), merge);
              continue;
            }
            // Unconfirmed crossings near a true hit are that hit seen by the coarse mesh (a tangent
            // contact gives 0 or 2 of them).
            bool near = false;
            for (const double known : truth.t) near = near || std::abs(known - t) <= 1e-2;
            if (!near) ++truth.unresolved;
          }
        }
      }
    }
  }
  return truth;
}

// ---------------------------------------------------------------------------------------------
// Planar curves

namespace {

// A polynomial curve on [0, 1] as a rational one with every weight 1.
RationalBezierCurve2 polynomial(std::vector<Vec2> P) {
  const std::size_t n = P.size();
  return RationalBezierCurve2(std::move(P), std::vector<double>(n, 1.0));
}

// The curve with (x, y) -> (y, -x) applied k times, then moved by `offset` (exact on dyadics).
RationalBezierCurve2 turned(const RationalBezierCurve2& curve, int k, const Vec2& offset) {
  std::vector<Vec2> P;
  std::vector<double> w;
  for (int i = 0; i <= curve.degree(); ++i) {
    Vec2 p = curve.control_point(i);
    for (int j = 0; j < k; ++j) p = Vec2(p.y(), -p.x());
    P.push_back(p + offset);
    w.push_back(curve.weight(i));
  }
  return RationalBezierCurve2(P, w);
}

// The curve run backwards.
RationalBezierCurve2 reversed(const RationalBezierCurve2& curve) {
  std::vector<Vec2> P;
  std::vector<double> w;
  for (int i = curve.degree(); i >= 0; --i) P.push_back(curve.control_point(i)), w.push_back(curve.weight(i));
  return RationalBezierCurve2(P, w);
}

// The piece of a polynomial curve over [t0, t1] (reparametrised to [0, 1]): control point i is the
// blossom at (t0 x (n - i), t1 x i) (de Casteljau with t1 in i of the n steps), in rationals, so
// dyadic ends and points give the exact piece (checked: every point must round to itself).
RationalBezierCurve2 piece(const RationalBezierCurve2& curve, double t0, double t1) {
  const int n = curve.degree();
  std::vector<Vec2> P;
  for (int i = 0; i <= n; ++i) {
    std::vector<std::array<mpq_class, 2>> level;
    for (int k = 0; k <= n; ++k)
      level.push_back({mpq_class(curve.control_point(k).x()), mpq_class(curve.control_point(k).y())});
    for (int step = 0; step < n; ++step) {
      const mpq_class t(step < i ? t1 : t0);
      for (std::size_t k = 0; k + 1 < level.size(); ++k) {
        for (int c = 0; c < 2; ++c) level[k][c] = (1 - t) * level[k][c] + t * level[k + 1][c];
      }
      level.pop_back();
    }
    const Vec2 p(level[0][0].get_d(), level[0][1].get_d());
    if (mpq_class(p.x()) != level[0][0] || mpq_class(p.y()) != level[0][1]) {
      throw NumericalError("crosscheck piece: a control point is not a double");
    }
    P.push_back(p);
  }
  return polynomial(P);
}

Vec2 random_dyadic2(Random& random) { return Vec2(dyadic(uniform(random, 0, 1), 6), dyadic(uniform(random, 0, 1), 6)); }

}  // namespace

std::vector<PairFamily> curve_pair_families(int count, std::uint64_t seed) {
  Random random(seed);
  std::vector<PairFamily> families{{"cubic pairs, random", {}},      {"rational cubic pairs, random", {}},
                                   {"tangent (multiplicity 2)", {}}, {"inflection contact (multiplicity 3)", {}},
                                   {"near-parallel crossings", {}},  {"overlapping", {}},
                                   {"meeting at end points", {}}};
  for (int k = 0; k < count; ++k) {
    std::vector<Vec2> A, B;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random)), B.push_back(random_dyadic2(random));
    families[0].pairs.push_back({polynomial(A), polynomial(B), false, {}});
    std::vector<double> wa, wb;
    for (int i = 0; i < 4; ++i) {
      wa.push_back(0.5 + 0.25 * static_cast<double>(random() % 7));  // 1/2 .. 2
      wb.push_back(0.5 + 0.25 * static_cast<double>(random() % 7));
    }
    families[1].pairs.push_back({RationalBezierCurve2(A, wa), RationalBezierCurve2(B, wb), true, {}});
  }
  // x = 3t and y = (2t - 1)^2 (t + 1): Bernstein y (1, 0, -1, 2), touching y = 0 at t = 1/2.
  const RationalBezierCurve2 touching = polynomial({Vec2(0, 1), Vec2(1, 0), Vec2(2, -1), Vec2(3, 2)});
  // x = 3t and y = (2t - 1)^3 (Bernstein -1, 1, -1, 1): the inflection tangent is y = 0.
  const RationalBezierCurve2 inflection = polynomial({Vec2(0, -1), Vec2(1, 1), Vec2(2, -1), Vec2(3, 1)});
  const RationalBezierCurve2 parabola({Vec2(0, 1), Vec2(0.5, -1), Vec2(1, 1)}, {1.0, 1.0, 1.0});
  const RationalBezierCurve2 axis({Vec2(-1, 0), Vec2(4, 0)}, {1.0, 1.0});
  // The rotations and translations below keep every point dyadic and every contact exact.
  for (int k = 0; k < 4; ++k) {
    const Vec2 offset(0.25 * k, -0.125 * k);
    families[2].pairs.push_back({turned(touching, k, offset), turned(axis, k, offset), false, {}});
    families[2].pairs.push_back({turned(parabola, k, offset), turned(axis, k, offset), false, {}});
    // The curve and its mirror image in y = 0: they touch at (3/2, 0) only.
    const RationalBezierCurve2 mirror = polynomial({Vec2(0, -1), Vec2(1, 0), Vec2(2, 1), Vec2(3, -2)});
    families[2].pairs.push_back({turned(touching, k, offset), turned(mirror, k, offset), false, {}});
    families[3].pairs.push_back({turned(inflection, k, offset), turned(axis, k, offset), false, {}});
    // y = (2t - 1)^3 against y = c (2s - 1)^3, same x: A - B = (1 - c)(2t - 1)^3.
    const double scale = std::array<double, 4>{-1.0, 0.5, 2.0, -0.5}[static_cast<std::size_t>(k)];  // never 1
    const RationalBezierCurve2 flatter = polynomial({Vec2(0, -scale), Vec2(1, scale), Vec2(2, -scale), Vec2(3, scale)});
    families[3].pairs.push_back({turned(inflection, k, offset), turned(flatter, k, offset), false, {}});
    // Lines at an angle of about 2^-(10 + 8k), crossing at t = s = 2/3 (as in the tests):
    // t e = e/4 + s (e - e/8 - e/4).
    const double e = std::ldexp(1.0, -(10 + 8 * k));
    families[4].pairs.push_back(
        {polynomial({Vec2(0, 0), Vec2(1, e)}), polynomial({Vec2(0, e / 4), Vec2(1, e - e / 8)}), false, {}});
    // A cubic and the same cubic lifted by e (-3/2, -1/2, 1/2, 3/2), that is e (3t - 3/2): they cross at
    // t = s = 1/2 at an angle of about 3e.
    const RationalBezierCurve2 lifted =
        polynomial({Vec2(0, 1 - 1.5 * e), Vec2(1, 0 - 0.5 * e), Vec2(2, -1 + 0.5 * e), Vec2(3, 2 + 1.5 * e)});
    families[4].pairs.push_back({turned(touching, k, offset), turned(lifted, k, offset), false, {}});
  }
  // Overlaps: a cubic against its middle half, reversed or not, and two pieces sharing [3/8, 5/8].
  for (int k = 0; k < count / 10 + 4; ++k) {
    // x increasing along the control points: x(t) is monotone, so the curve is a graph over x
    // and its pieces meet only where they overlap (a loop would add crossings the truth, which
    // only knows the overlap, leaves out).
    std::vector<Vec2> A;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random));
    std::sort(A.begin(), A.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); });
    for (int i = 1; i < 4; ++i) A[i].x() = std::max(A[i].x(), A[i - 1].x() + 1.0 / 64);
    const RationalBezierCurve2 curve = polynomial(A);
    if (k % 2 == 0) {
      const RationalBezierCurve2 middle_half = piece(curve, 0.25, 0.75);
      families[5].pairs.push_back({curve, k % 4 == 0 ? middle_half : reversed(middle_half), false, Vec2(0.25, 0.75)});
    } else {
      // first = curve on [0, 5/8], second = curve on [3/8, 1]: the overlap is first's [3/5, 1].
      families[5].pairs.push_back({piece(curve, 0, 0.625), piece(curve, 0.375, 1), false, Vec2(0.6, 1.0)});
    }
  }
  // End points: end to end at an angle, and an end on the other's inside (at t = 1/2).
  for (int k = 0; k < count / 10 + 4; ++k) {
    std::vector<Vec2> A, B;
    for (int i = 0; i < 4; ++i) A.push_back(random_dyadic2(random)), B.push_back(random_dyadic2(random));
    const RationalBezierCurve2 first = polynomial(A);
    B[0] = k % 2 == 0 ? A[3] : first.evaluate(0.5);
    families[6].pairs.push_back({first, polynomial(B), false, {}});
  }
  return families;
}

namespace {

// The homogeneous coordinates (X, Y, w) of a planar rational curve, power basis, exactly.
std::array<Polynomial, 3> homogeneous_power(const RationalBezierCurve2& curve) {
  std::array<std::vector<double>, 3> c;
  for (int i = 0; i <= curve.degree(); ++i) {
    const auto& h = curve.homogeneous().control_points()[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)].push_back(h[k]);
  }
  return {exact::trimmed(power_of(c[0])), exact::trimmed(power_of(c[1])), exact::trimmed(power_of(c[2]))};
}

// det M by Gaussian elimination in rationals (M square; destroyed).
mpq_class determinant(std::vector<std::vector<mpq_class>> M) {
  const std::size_t n = M.size();
  mpq_class det = 1;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    while (pivot < n && M[pivot][col] == 0) ++pivot;
    if (pivot == n) return 0;
    if (pivot != col) std::swap(M[pivot], M[col]), det = -det;
    det *= M[col][col];
    for (std::size_t row = col + 1; row < n; ++row) {
      if (M[row][col] == 0) continue;
      const mpq_class factor = M[row][col] / M[col][col];
      for (std::size_t k = col; k < n; ++k) M[row][k] -= factor * M[col][k];
    }
  }
  return det;
}

// Res_t(P, Q) of two polynomials in t of formal degrees p, q (Sylvester's matrix).
mpq_class resultant(const Polynomial& P, const Polynomial& Q, std::size_t p, std::size_t q) {
  const std::size_t n = p + q;
  std::vector<std::vector<mpq_class>> M(n, std::vector<mpq_class>(n, mpq_class(0)));
  const auto coefficient = [](const Polynomial& f, std::size_t j) { return j < f.size() ? f[j] : mpq_class(0); };
  for (std::size_t row = 0; row < q; ++row) {
    for (std::size_t j = 0; j <= p; ++j) M[row][row + j] = coefficient(P, p - j);
  }
  for (std::size_t row = 0; row < p; ++row) {
    for (std::size_t j = 0; j <= q; ++j) M[q + row][row + j] = coefficient(Q, q - j);
  }
  return determinant(std::move(M));
}

// The two equations of A(t) = B(s) at a fixed s, as polynomials in t:
// X_A(t) w_B(s) - X_B(s) w_A(t) and Y_A(t) w_B(s) - Y_B(s) w_A(t).
std::pair<Polynomial, Polynomial> equations_at(const std::array<Polynomial, 3>& A, const std::array<Polynomial, 3>& B,
                                               const mpq_class& s) {
  const mpq_class wB = exact::value(B[2], s);
  const auto scaled = [](const Polynomial& f, const mpq_class& c) {
    Polynomial g = f;
    for (mpq_class& x : g) x *= c;
    return g;
  };
  return {sum(scaled(A[0], wB), scaled(A[2], exact::value(B[0], s)), -1),
          sum(scaled(A[1], wB), scaled(A[2], exact::value(B[1], s)), -1)};
}

// The resultant in s: degree at most 2 n_A n_B, so interpolated exactly from that many + 1 values
// (Newton's divided differences at s = 0, 1, 2, ...).
Polynomial resultant_in_s(const CurvePair& pair) {
  const auto A = homogeneous_power(pair.first), B = homogeneous_power(pair.second);
  // Formal degrees in t: the largest over the sample points (the same for all but finitely many s).
  const std::size_t points = static_cast<std::size_t>(2 * pair.first.degree() * pair.second.degree() + 1);
  std::vector<mpq_class> xs, ys;
  std::size_t p = 0, q = 0;
  std::vector<std::pair<Polynomial, Polynomial>> equations;
  for (std::size_t k = 0; k < points; ++k) {
    xs.emplace_back(static_cast<long>(k));
    equations.push_back(equations_at(A, B, xs.back()));
    p = std::max(p, equations.back().first.size());
    q = std::max(q, equations.back().second.size());
  }
  if (p <= 1 || q <= 1) return {};  // a constant equation: degenerate, not among the cases
  for (const auto& [P, Q] : equations) ys.push_back(resultant(P, Q, p - 1, q - 1));
  // Divided differences, then the Newton form expanded.
  std::vector<mpq_class> c = ys;
  for (std::size_t j = 1; j < points; ++j) {
    for (std::size_t i = points - 1; i >= j; --i) c[i] = (c[i] - c[i - 1]) / (xs[i] - xs[i - j]);
  }
  Polynomial result{c[points - 1]};
  for (std::size_t i = points - 1; i-- > 0;) {
    result = sum(product(result, Polynomial{-xs[i], mpq_class(1)}), Polynomial{c[i]});
  }
  return exact::trimmed(result);
}

// The t in [-1/4, 5/4] where |A(t) - B(s)| is least (dense sampling, then Gauss-Newton), and that
// distance.
std::pair<double, double> partner(const RationalBezierCurve2& A, const Vec2& point) {
  double best_t = 0, best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 3000; ++k) {
    const double t = -0.25 + 1.5 * k / 3000.0;
    const double d = (A.evaluate(t) - point).norm();
    if (d < best) best = d, best_t = t;
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Vec2 r = A.evaluate(best_t) - point;
    const Vec2 d1 = derivative(A, best_t, 1);
    if (d1.squaredNorm() == 0) break;
    const double next = best_t - r.dot(d1) / d1.squaredNorm();
    const double dn = (A.evaluate(next) - point).norm();
    if (!(dn < best)) break;
    best = dn, best_t = next;
  }
  return {best_t, best};
}

}  // namespace

PairTruth pair_truth(const CurvePair& pair) {
  PairTruth truth;
  const Polynomial R = resultant_in_s(pair);
  if (R.empty()) {
    truth.overlap = true;
    return truth;
  }
  const double size = 4.0;  // the cases lie within [-1, 4]^2
  for (const exact::RootInterval& x : exact::isolated_roots(R, zero(), one(), root_width())) {
    const double s = middle(x);
    const auto [t, distance] = partner(pair.first, pair.second.evaluate(s));
    if (!(distance <= 1e-9 * size)) continue;  // a root whose t is complex or beyond the sampled range
    if (t > 1e-9 && t < 1 - 1e-9) {
      truth.points.emplace_back(t, s);
      truth.multiplicity.push_back(multiplicity_in(R, x));
      continue;
    }
    if (t < -1e-9 || t > 1 + 1e-9) continue;
    // Within rounding of an end of A: decide exactly whether the end lies on B at a rational s.
    const double end = t < 0.5 ? 0.0 : 1.0;
    const auto A = homogeneous_power(pair.first);
    const auto B = homogeneous_power(pair.second);
    const mpq_class te(end);
    const bool exact_root = x.lo == x.hi;
    const bool on =
        exact_root &&
        exact::value(A[0], te) * exact::value(B[2], x.lo) == exact::value(B[0], x.lo) * exact::value(A[2], te) &&
        exact::value(A[1], te) * exact::value(B[2], x.lo) == exact::value(B[1], x.lo) * exact::value(A[2], te);
    if (on) {
      truth.points.emplace_back(end, s);
      truth.multiplicity.push_back(multiplicity_in(R, x));
    } else {
      ++truth.undecided;
    }
  }
  return truth;
}

}  // namespace patchwork::crosscheck
