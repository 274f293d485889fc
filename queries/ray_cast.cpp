#include "queries/ray_cast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "queries/double_box_walk.h"
#include "queries/patch_evaluation.h"
#include "queries/query_arguments.h"
#include "queries/ray_piece_nets.h"
#include "queries/wide_bvh.h"
#include "surfaces/rational_bezier_patch.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

using namespace detail::ray_nets;

struct Ray {
  Vec3 origin, direction, a, b;
  double t_min, t_max;
};

// F, F_u and F_v at one (u, v).
struct FirstDerivatives {
  Vec3 point, du, dv;
};

// The sums over a net (Point: Vec3 or the homogeneous Vec4) with the Bernstein values and
// derivatives of both directions: F, F_u, F_v of a polynomial net (or H, H_u, H_v).
template <class Point>
std::array<Point, 3> bernstein_sums(const std::vector<Point>& net, int n, int m, double u, double v) {
  std::array<double, max_degree + 1> bu, du, bv, dv;  // entries 0..degree written below
  bernstein_with_derivatives(n, u, bu.data(), du.data());
  bernstein_with_derivatives(m, v, bv.data(), dv.data());
  std::array<Point, 3> out{Point::Zero(), Point::Zero(), Point::Zero()};
  for (int j = 0; j <= m; ++j) {
    Point row = Point::Zero(), row_u = Point::Zero();
    for (int i = 0; i <= n; ++i) {
      const Point& c = net[static_cast<std::size_t>(i + (n + 1) * j)];
      row += bu[static_cast<std::size_t>(i)] * c;
      row_u += du[static_cast<std::size_t>(i)] * c;
    }
    out[0] += bv[static_cast<std::size_t>(j)] * row;
    out[1] += bv[static_cast<std::size_t>(j)] * row_u;
    out[2] += dv[static_cast<std::size_t>(j)] * row;
  }
  return out;
}

// F, F_u, F_v of patch p by Bernstein sums (the sums are backward stable for (u, v) in the
// square, as de Casteljau is, and allocate nothing: a hit's Newton steps and normal need no more).
FirstDerivatives first_derivatives(const PatchSet& set, std::uint32_t p, double u, double v) {
  if (const RationalBezierPatch* rational = set.rational(p)) {
    const BezierPatch4& h = rational->homogeneous();
    const auto [hp, hu, hv] = bernstein_sums(h.control_points(), h.degree_u(), h.degree_v(), u, v);
    const Vec3 point = hp.head<3>() / hp[3];
    return {point, (hu.head<3>() - hu[3] * point) / hp[3], (hv.head<3>() - hv[3] * point) / hp[3]};
  }
  const BezierPatch3& net = set.control_nets()[p];
  const auto [point, du, dv] = bernstein_sums(net.control_points(), net.degree_u(), net.degree_v(), u, v);
  return {point, du, dv};
}

// Newton on the patch itself from (u, v): the plane distances (a.(F-o), b.(F-o)) to zero. The
// parameters may leave the square by a hair (a hit on an edge); the caller decides. Returns the
// derivatives at the (u, v) it leaves (a step below 1e-15 is not taken: it is below the
// parameters' resolution near 1, and the derivatives in hand serve the hit).
FirstDerivatives polish(const PatchSet& set, std::uint32_t p, const Ray& ray, double& u, double& v) {
  FirstDerivatives d = first_derivatives(set, p, u, v);
  for (int iteration = 0; iteration < 3; ++iteration) {
    const Vec3 r = d.point - ray.origin;
    const double j00 = ray.a.dot(d.du), j01 = ray.a.dot(d.dv), j10 = ray.b.dot(d.du), j11 = ray.b.dot(d.dv);
    const double det = j00 * j11 - j01 * j10;
    if (!(std::abs(det) > 0.0)) break;
    const double r0 = ray.a.dot(r), r1 = ray.b.dot(r);
    const double du = (j11 * r0 - j01 * r1) / det, dv = (j00 * r1 - j10 * r0) / det;
    if (!std::isfinite(du) || !std::isfinite(dv) || std::abs(du) + std::abs(dv) <= 1e-15) break;
    u = std::clamp(u - du, -1e-6, 1 + 1e-6);
    v = std::clamp(v - dv, -1e-6, 1 + 1e-6);
    d = first_derivatives(set, p, u, v);
  }
  return d;
}

// The distance of a point from the ray.
double off_ray(const Ray& ray, const Vec3& point) {
  const Vec3 r = point - ray.origin;
  return std::hypot(ray.a.dot(r), ray.b.dot(r));
}

struct HitCandidate {
  RayHit hit;
  double off_ray;
};

// The lengths one ray's answers are resolved to. The scene's size sets them, unless the ray's own
// rounding is larger: a point on the ray is placed to a few units u of |o| and of the scene's
// coordinates (a ray from 10^12 away is 10^-4 uncertain). Pieces below `tiny_piece` are settled
// without halving; a point within `on_ray` of the ray is on it, and hits within `same_point` of
// each other are one; a tangent contact, known to about the square root of its rounding, merges
// its candidates within `contact`.
struct Resolution {
  double tiny_piece, on_ray, same_point, contact;
};

Resolution resolution_of(const PatchBvh& bvh, const Vec3& origin) {
  const Eigen::AlignedBox3d& root = bvh.nodes().front().box;
  const double coordinates = root.min().cwiseAbs().cwiseMax(root.max().cwiseAbs()).maxCoeff();
  const double scene = bvh.size();
  const double noise = 8 * unit_roundoff * (origin.cwiseAbs().maxCoeff() + coordinates);
  const double point = std::max(1e-9 * scene, 16 * noise);
  return {std::max(1e-7 * scene, 64 * noise), point, point, std::max(1e-4 * scene, 4 * std::sqrt(noise * scene))};
}

// Adds the hit at (u, v) of patch p, whose derivatives there are `d` (those of the clamped (u, v)
// are computed here where clamping moves it).
void add_hit(const PatchSet& set, const Ray& ray, std::uint32_t p, double u, double v, FirstDerivatives d, bool grazing,
             std::vector<HitCandidate>& hits) {
  // A root outside the square by more than rounding belongs to the neighbour across the edge.
  if (u < -1e-12 || u > 1 + 1e-12 || v < -1e-12 || v > 1 + 1e-12) return;
  RayHit hit;
  hit.patch = p;
  hit.u = std::clamp(u, 0.0, 1.0);
  hit.v = std::clamp(v, 0.0, 1.0);
  if (hit.u != u || hit.v != v) d = first_derivatives(set, p, hit.u, hit.v);
  // The point and the normal from one evaluation; the limit normal where F_u x F_v vanishes.
  hit.point = d.point;
  hit.t = ray.direction.dot(hit.point - ray.origin) / ray.direction.squaredNorm();
  if (!(hit.t >= ray.t_min && hit.t <= ray.t_max)) return;
  // Within about 1e-8 (in the parameters) of a collapsed edge F_u x F_v is rounding, not a
  // direction (at the edge itself F_u or F_v is a sum of rounding errors): the limit normal
  // there. The scale is the longer tangent's, squared, which a collapsed edge leaves standing;
  // far from the origin the sums' rounding (surface_normal.h's rule) can exceed that.
  const Vec3 cross = d.du.cross(d.dv);
  const double scale = std::max(d.du.squaredNorm(), d.dv.squaredNorm());
  const RationalBezierPatch* rational = set.rational(p);
  const detail::DegeneracyThresholds limits =
      rational ? detail::degeneracy_thresholds(*rational) : detail::degeneracy_thresholds(set.control_nets()[p]);
  const bool regular = cross.norm() > 1e-8 * scale && !detail::first_normal_vanishes(d.du, d.dv, limits);
  hit.normal = regular ? cross.normalized() : detail::patch_unit_normal(set, p, hit.u, hit.v);
  hit.grazing = grazing || std::abs(hit.normal.dot(ray.direction.normalized())) < 1e-6;
  hits.push_back({hit, off_ray(ray, hit.point)});
}

// A piece with no certified answer: false (halve it) unless it is tiny, when its centre moved
// onto the ray by Newton is a tangent contact if it is on the ray.
bool settle_uncertified(const PatchSet& set, const Ray& ray, const detail::NetPiece& piece, const Resolution& resolution,
                        std::vector<HitCandidate>& hits) {
  // Small in space (a wedge at a pole is small long before its parameter range is), or in
  // both parameters.
  // The control box is widened by the rounding margin, which grows with depth and coordinates:
  // its own size is what is compared (else a small scene far from the origin halves forever).
  const bool tiny = detail::control_box(piece).diagonal().norm() <= resolution.tiny_piece + 4 * detail::rounding_margin(piece) ||
                    ((piece.u1 - piece.u0) <= 0x1p-30 && (piece.v1 - piece.v0) <= 0x1p-30);
  if (!tiny) return false;
  // Uncertified down to the smallest pieces: a tangent contact if the centre is on the ray.
  double u = 0.5 * (piece.u0 + piece.u1), v = 0.5 * (piece.v0 + piece.v1);
  FirstDerivatives d = polish(set, piece.patch, ray, u, v);
  if (u != std::clamp(u, 0.0, 1.0) || v != std::clamp(v, 0.0, 1.0)) {
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    d = first_derivatives(set, piece.patch, u, v);
  }
  if (off_ray(ray, d.point) <= resolution.on_ray) add_hit(set, ray, piece.patch, u, v, d, true, hits);
  return true;
}

// The hits of one piece whose scalar nets are `nets`; false when it must be halved.
template <class Nets>
bool settle_piece(const PatchSet& set, const Ray& ray, const detail::NetPiece& piece, const Resolution& resolution, const Nets& nets,
                  std::vector<HitCandidate>& hits) {
  if (one_sign(nets.g[0], nets.margin) || one_sign(nets.g[1], nets.margin) || hull_misses_origin(nets)) return true;
  const JacobianRanges ranges = jacobian_ranges(nets);
  const ScalarValues at_centre = scalar_derivatives(nets, 0.5, 0.5);
  if (krawczyk_excludes(nets, ranges, at_centre)) return true;
  if (certified_unique(ranges)) {
    double s = 0.5, t = 0.5;
    if (local_newton(nets, at_centre, s, t)) {
      const Vec2 uv = piece.global(s, t);
      double u = uv[0], v = uv[1];
      const FirstDerivatives d = polish(set, piece.patch, ray, u, v);
      add_hit(set, ray, piece.patch, u, v, d, false, hits);
      return true;
    }
    // Newton left the piece: a hit near its edge, or none; halving decides.
  }
  return settle_uncertified(set, ray, piece, resolution, hits);
}

// The hits in one piece, halving where one hit per piece cannot be certified.
void piece_hits(const PatchSet& set, const Ray& ray, const detail::NetPiece& root, const Resolution& resolution, std::vector<HitCandidate>& hits,
                std::int64_t& examined) {
  // The pieces still to settle, in storage of the thread's that every call reuses.
  thread_local std::vector<detail::NetPiece> stack;
  stack.clear();
  // The hits of one piece; false when it must be halved. Bicubic nets in fixed-size arrays.
  const auto settle = [&](const detail::NetPiece& piece) {
    ++examined;
    if (piece.n == 3 && piece.m == 3) {
      FixedScalarNets<3, 3> nets;
      fill_scalar_nets(piece, ray.origin, ray.a, ray.b, nets);
      return settle_piece(set, ray, piece, resolution, nets, hits);
    }
    ScalarNets nets{piece.n, piece.m, scratch_coefficients(), 0.0};
    fill_scalar_nets(piece, ray.origin, ray.a, ray.b, nets);
    return settle_piece(set, ray, piece, resolution, nets, hits);
  };
  const auto halve = [&](const detail::NetPiece& piece) {
    int dir = detail::longer_direction(piece);
    if ((dir == 0 ? piece.u1 - piece.u0 : piece.v1 - piece.v0) <= 0x1p-30) dir = 1 - dir;
    for (detail::NetPiece& half : detail::halves(piece, dir)) stack.push_back(std::move(half));
  };
  if (!settle(root)) halve(root);
  while (!stack.empty()) {
    const detail::NetPiece piece = std::move(stack.back());
    stack.pop_back();
    if (!settle(piece)) halve(piece);
  }
}

// Asks for the cache lines of [data, data + bytes) ahead of their use (a hint; nothing on
// compilers without the builtin).
void prefetch(const void* data, std::size_t bytes) {
#if defined(__GNUC__)
  const char* const begin = static_cast<const char*>(data);
  for (std::size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(begin + offset);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace

RayHits ray_cast(const PatchBvh& bvh, const Vec3& origin, const Vec3& direction, const RayOptions& options) {
  require_finite(origin, "ray_cast", "origin");
  require_direction(direction, "ray_cast", "direction");
  if (!(options.t_min <= options.t_max) || std::isnan(options.t_min))
    throw InvalidInput(detail::message("ray_cast: t_min (", options.t_min, ") must not exceed t_max (", options.t_max, ")"));
  Ray ray{origin, direction, Vec3::Zero(), Vec3::Zero(), options.t_min, options.t_max};
  const Vec3 unit = direction.normalized();
  const Vec3 helper = std::abs(unit.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  ray.a = unit.cross(helper).normalized();
  ray.b = unit.cross(ray.a).normalized();
  const Resolution resolution = resolution_of(bvh, origin);

  RayHits result;
  // Storage of the thread's that every ray reuses (a ray allocates only its result).
  thread_local std::vector<HitCandidate> found;
  thread_local std::vector<HitCandidate> kept;
  thread_local std::vector<std::uint32_t> candidates;
  found.clear();
  kept.clear();
  candidates.clear();
  // The float boxes four at a time; the double boxes for a ray too far out for their pad.
  if (!bvh.wide().reaches(origin, direction, options.t_min, options.t_max, candidates))
    detail::double_box_pieces(bvh, origin, direction, options.t_min, options.t_max, candidates);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    // The pieces are scattered in memory (each net its own allocation) and most rays meet few
    // twice: fetch the next piece's net and the one after's header while this one is settled.
    if (k + 2 < candidates.size()) prefetch(&bvh.pieces()[candidates[k + 2]], sizeof(detail::NetPiece));
    if (k + 1 < candidates.size()) {
      const std::vector<Vec4>& net = bvh.pieces()[candidates[k + 1]].net;
      prefetch(net.data(), net.size() * sizeof(Vec4));
    }
    piece_hits(bvh.set(), ray, bvh.pieces()[candidates[k]], resolution, found, result.pieces);
  }
  // One hit per point: the same point found from two pieces or two patches (a shared edge), and
  // the cluster of tiny pieces around a tangent contact; the one nearest the ray stands for it.
  std::sort(found.begin(), found.end(), [](const HitCandidate& x, const HitCandidate& y) { return x.hit.t < y.hit.t; });
  const double same = resolution.same_point, contact = resolution.contact;
  for (const HitCandidate& c : found) {
    if (!kept.empty()) {
      HitCandidate& last = kept.back();
      const double apart = (c.hit.point - last.hit.point).norm();
      if (apart <= same || ((c.hit.grazing || last.hit.grazing) && apart <= contact)) {
        const bool grazing = c.hit.grazing || last.hit.grazing;
        if (c.off_ray < last.off_ray) last = c;
        last.hit.grazing = grazing;
        continue;
      }
    }
    kept.push_back(c);
  }
  for (const HitCandidate& c : kept) result.hits.push_back(c.hit);
  return result;
}

RayHits ray_cast(const PatchSet& set, const Vec3& origin, const Vec3& direction, const RayOptions& options) {
  require_finite(origin, "ray_cast", "origin");
  require_direction(direction, "ray_cast", "direction");
  return ray_cast(PatchBvh(set), origin, direction, options);
}

}  // namespace patchwork
