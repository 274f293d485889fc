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
#include "report/queries_cases_shared.h"
#include "tests/queries/exact_root_count.h"

namespace patchwork::crosscheck {
using namespace cases;  // the shared random source and exact polynomials
namespace {


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

}  // namespace patchwork::crosscheck
