#include "measure/hausdorff.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "core/parallel.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_grid.h"

namespace patchwork {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalTriangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 from_cgal(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

// A triangle is degenerate when its area is negligible against its longest edge: CGAL's closest
// point projects onto the triangle's plane and has none then.
bool degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !((b - a).cross(c - a).norm() > 1e-12 * longest);
}

// Triangles in an AABB tree, each with the index of what it stands for.
class TriangleTree {
 public:
  void add(const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t id) {
    triangles_.emplace_back(to_cgal(a), to_cgal(b), to_cgal(c));
    ids_.push_back(id);
  }
  std::size_t size() const noexcept { return triangles_.size(); }
  // Builds the tree (after the last add): queries are then thread-safe.
  void build() {
    tree_ = std::make_unique<Tree>(triangles_.cbegin(), triangles_.cend());
    tree_->accelerate_distance_queries();
  }
  struct Hit {
    Vec3 point;
    std::uint32_t id;
    std::size_t slot;
  };
  Hit closest(const Vec3& p) const {
    const auto [point, primitive] = tree_->closest_point_and_primitive(to_cgal(p));
    const auto slot = static_cast<std::size_t>(primitive - triangles_.cbegin());
    return {from_cgal(point), ids_[slot], slot};
  }

 private:
  std::vector<CgalTriangle> triangles_;
  std::vector<std::uint32_t> ids_;
  std::unique_ptr<Tree> tree_;
};

// Barycentric coordinates of q (on or near the plane of a, b, c), by least squares.
Vec3 barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e0 = b - a;
  const Vec3 e1 = c - a;
  const Vec3 d = q - a;
  const double d00 = e0.dot(e0);
  const double d01 = e0.dot(e1);
  const double d11 = e1.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  const double s = (d11 * e0.dot(d) - d01 * e1.dot(d)) / det;
  const double t = (d00 * e1.dot(d) - d01 * e0.dot(d)) / det;
  return {1.0 - s - t, s, t};
}

Vec2 clamp_unit(const Vec2& uv) { return uv.cwiseMax(0.0).cwiseMin(1.0); }

// The point s e0 + t e1 of a triangle's barycentric domain s, t >= 0, s + t <= 1 nearest to
// (s, t) in the max norm sense used by the compass search (clamp, then scale back).
Vec2 clamp_barycentric(Vec2 st) {
  st = st.cwiseMax(0.0);
  const double sum = st.sum();
  return sum > 1.0 ? Vec2(st / sum) : st;
}

// Climbs value(x) from x by a compass search: the eight neighbours at distance `step`, the best
// taken while it improves, then the step halves, down to `min_step`. Returns the best point.
template <class Value, class Project>
std::pair<Vec2, double> compass_maximum(Vec2 x, double best, double step, double min_step, const Value& value,
                                        const Project& project) {
  static constexpr std::array<std::array<double, 2>, 8> kDirections = {
      {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
  while (step >= min_step) {
    bool moved = false;
    for (const auto& direction : kDirections) {
      const Vec2 trial = project(Vec2(x + step * Vec2(direction[0], direction[1])));
      if (trial == x) continue;
      const double candidate = value(trial);
      if (candidate > best) {
        best = candidate;
        x = trial;
        moved = true;
      }
    }
    if (!moved) step *= 0.5;
  }
  return {x, best};
}

// The barycentric lattice of order k: (i/k, j/k) with i + j <= k, as (s, t) for s e0 + t e1.
std::vector<Vec2> lattice_points(int k) {
  std::vector<Vec2> points;
  for (int i = 0; i <= k; ++i) {
    for (int j = 0; i + j <= k; ++j) points.emplace_back(static_cast<double>(i) / k, static_cast<double>(j) / k);
  }
  return points;
}

// A mesh point's closest surface point found so far.
struct SurfaceFoot {
  double distance = std::numeric_limits<double>::infinity();
  std::uint32_t patch = 0;
  Vec2 uv = Vec2::Zero();
  Vec3 point = Vec3::Zero();
};

// A surface point's distance to the mesh.
struct MeshFoot {
  double distance = 0.0;
  Vec3 point = Vec3::Zero();
  std::uint32_t triangle = 0;
};

// Everything the measurement reads, built once.
class Meter {
 public:
  Meter(std::span<const BezierPatch3> patches, std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
        const HausdorffOptions& options)
      : patches_(patches), positions_(positions), indices_(indices), options_(options) {
    grids_.resize(patches.size());
    boxes_.resize(patches.size());
    const int g = options.grid_segments;
    parallel_for(patches.size(), options.threads, [&](std::size_t p) {
      const PatchGridWeights weights = PatchGridWeights::uniform(
          patches[p].degree_u(), patches[p].degree_v(), static_cast<std::size_t>(g), static_cast<std::size_t>(g));
      grids_[p] = evaluate_grid(patches[p], weights).points;
      boxes_[p] = control_box(patches[p]);
    });
    // The proxy: every grid cell as two triangles, mapped back to (patch, cell, half).
    for (std::size_t p = 0; p < patches.size(); ++p) {
      for (int b = 0; b < g; ++b) {
        for (int a = 0; a < g; ++a) {
          const std::array<Vec2, 4> corners = {grid_uv(a, b), grid_uv(a + 1, b), grid_uv(a + 1, b + 1),
                                               grid_uv(a, b + 1)};
          for (const auto& half : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
            const std::array<Vec2, 3> uv = {corners[half[0]], corners[half[1]], corners[half[2]]};
            const Vec3 x0 = grid_point(p, uv[0]);
            const Vec3 x1 = grid_point(p, uv[1]);
            const Vec3 x2 = grid_point(p, uv[2]);
            if (degenerate(x0, x1, x2)) continue;
            proxy_.add(x0, x1, x2, static_cast<std::uint32_t>(proxy_uv_.size()));
            proxy_uv_.push_back({uv, static_cast<std::uint32_t>(p)});
          }
        }
      }
    }
    for (std::size_t t = 0; t < triangle_count(); ++t) {
      const auto [a, b, c] = corners(t);
      if (!degenerate(a, b, c)) mesh_.add(a, b, c, static_cast<std::uint32_t>(t));
    }
    if (mesh_.size() == 0) throw InvalidInput("hausdorff_distance: every triangle of the mesh is degenerate");
    if (proxy_.size() == 0) throw InvalidInput("hausdorff_distance: every patch is degenerate (no area)");
    proxy_.build();
    mesh_.build();
  }

  std::size_t triangle_count() const noexcept { return indices_.size() / 3; }
  std::array<Vec3, 3> corners(std::size_t t) const {
    return {positions_[indices_[3 * t]], positions_[indices_[3 * t + 1]], positions_[indices_[3 * t + 2]]};
  }
  Vec3 mesh_point(std::size_t t, const Vec2& st) const {
    const auto [a, b, c] = corners(t);
    return a + st.x() * (b - a) + st.y() * (c - a);
  }

  // The surface point nearest to y near the proxy's closest point (Newton on that patch).
  SurfaceFoot surface_foot(const Vec3& y) const {
    const TriangleTree::Hit hit = proxy_.closest(y);
    const ProxyTriangle& proxy = proxy_uv_[hit.id];
    const Vec3 x0 = grid_point(proxy.patch, proxy.uv[0]);
    const Vec3 x1 = grid_point(proxy.patch, proxy.uv[1]);
    const Vec3 x2 = grid_point(proxy.patch, proxy.uv[2]);
    const Vec3 weights = barycentric(hit.point, x0, x1, x2);
    const Vec2 start = weights[0] * proxy.uv[0] + weights[1] * proxy.uv[1] + weights[2] * proxy.uv[2];
    return newton_foot(proxy.patch, y, clamp_unit(start));
  }

  // surface_foot, then every other patch whose box is nearer than the distance found.
  SurfaceFoot verified_surface_foot(const Vec3& y, SurfaceFoot best) const {
    for (std::size_t p = 0; p < patches_.size(); ++p) {
      if (p == best.patch || boxes_[p].exteriorDistance(y) >= best.distance) continue;
      const std::vector<Vec3>& grid = grids_[p];
      std::size_t nearest = 0;
      for (std::size_t k = 1; k < grid.size(); ++k) {
        if ((grid[k] - y).squaredNorm() < (grid[nearest] - y).squaredNorm()) nearest = k;
      }
      const int stride = options_.grid_segments + 1;
      const Vec2 start = grid_uv(static_cast<int>(nearest) % stride, static_cast<int>(nearest) / stride);
      const SurfaceFoot other = newton_foot(static_cast<std::uint32_t>(p), y, start);
      if (other.distance < best.distance) best = other;
    }
    return best;
  }

  MeshFoot mesh_foot(const Vec3& x) const {
    const TriangleTree::Hit hit = mesh_.closest(x);
    return {(hit.point - x).norm(), hit.point, hit.id};
  }

  const BezierPatch3& patch(std::size_t p) const { return patches_[p]; }
  std::size_t patch_count() const noexcept { return patches_.size(); }
  int grid_segments() const noexcept { return options_.grid_segments; }
  Vec3 grid_point(std::size_t p, int a, int b) const {
    return grids_[p][static_cast<std::size_t>(a + (options_.grid_segments + 1) * b)];
  }
  Vec2 grid_uv(int a, int b) const {
    const double g = options_.grid_segments;
    return {a / g, b / g};
  }

 private:
  struct ProxyTriangle {
    std::array<Vec2, 3> uv;
    std::uint32_t patch;
  };

  Vec3 grid_point(std::size_t p, const Vec2& uv) const {
    const double g = options_.grid_segments;
    return grid_point(p, static_cast<int>(std::lround(uv.x() * g)), static_cast<int>(std::lround(uv.y() * g)));
  }

  SurfaceFoot newton_foot(std::uint32_t p, const Vec3& y, const Vec2& start) const {
    const Vec2 uv = closest_parameters(patches_[p], y, start);
    const Vec3 x = patches_[p].evaluate(uv.x(), uv.y());
    return {(x - y).norm(), p, uv, x};
  }

  std::span<const BezierPatch3> patches_;
  std::span<const Vec3> positions_;
  std::span<const std::uint32_t> indices_;
  HausdorffOptions options_;
  std::vector<std::vector<Vec3>> grids_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  TriangleTree proxy_;
  std::vector<ProxyTriangle> proxy_uv_;
  TriangleTree mesh_;
};

// The indices of the `count` largest values (ties by index), largest first.
std::vector<std::size_t> largest(const std::vector<double>& values, std::size_t count) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  count = std::min(count, order.size());
  const auto by_value = [&](std::size_t a, std::size_t b) {
    return values[a] > values[b] || (values[a] == values[b] && a < b);
  };
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(), by_value);
  order.resize(count);
  return order;
}

void check_input(std::span<const BezierPatch3> patches, std::span<const Vec3> positions,
                 std::span<const std::uint32_t> indices, const HausdorffOptions& options) {
  if (patches.empty()) throw InvalidInput("hausdorff_distance: no patches");
  if (indices.empty() || indices.size() % 3 != 0) {
    throw InvalidInput(
        detail::message("hausdorff_distance: ", indices.size(), " indices is not a positive multiple of 3"));
  }
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] >= positions.size()) {
      throw InvalidInput(detail::message("hausdorff_distance: triangle ", k / 3, " uses vertex ", indices[k], " of ",
                                         positions.size()));
    }
  }
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!positions[k].allFinite())
      throw InvalidInput(detail::message("hausdorff_distance: vertex ", k, " is not finite"));
  }
  if (options.grid_segments < 1 || options.grid_segments > 4096 || options.lattice < 1 || options.lattice > 64 ||
      options.refine < 0) {
    throw InvalidInput(detail::message("hausdorff_distance: options out of range (grid_segments ",
                                       options.grid_segments, ", lattice ", options.lattice, ", refine ",
                                       options.refine, ")"));
  }
}

}  // namespace

Vec2 closest_parameters(const BezierPatch3& patch, const Vec3& point, Vec2 start) {
  Vec2 uv = clamp_unit(start);
  double value = (patch.evaluate(uv.x(), uv.y()) - point).squaredNorm();
  for (int iteration = 0; iteration < 32 && value > 0.0; ++iteration) {
    const PartialDerivatives<3> d = partial_derivatives(patch, uv.x(), uv.y(), 2);
    const Vec3 r = d.at(0, 0) - point;
    const Vec3& su = d.at(1, 0);
    const Vec3& sv = d.at(0, 1);
    const Vec2 gradient(r.dot(su), r.dot(sv));
    Eigen::Matrix2d gauss_newton;
    gauss_newton << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    Eigen::Matrix2d hessian = gauss_newton;
    hessian(0, 0) += r.dot(d.at(2, 0));
    hessian(0, 1) += r.dot(d.at(1, 1));
    hessian(1, 0) += r.dot(d.at(1, 1));
    hessian(1, 1) += r.dot(d.at(0, 2));
    // Newton where the Hessian is positive definite, else Gauss-Newton; a tiny diagonal keeps a
    // collapsed edge (F_u = 0 at a pole) solvable.
    const bool convex = hessian(0, 0) > 0.0 && hessian.determinant() > 0.0;
    Eigen::Matrix2d system = convex ? hessian : gauss_newton;
    system.diagonal().array() += 1e-14 * (system.trace() + 1e-300);
    Vec2 step = -system.inverse() * gradient;
    // A parameter pinned at its bound with the step pushing outwards stays there.
    for (int k = 0; k < 2; ++k) {
      if ((uv[k] <= 0.0 && step[k] < 0.0) || (uv[k] >= 1.0 && step[k] > 0.0)) step[k] = 0.0;
    }
    if (!step.allFinite() || step.norm() < 1e-16) break;
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      const Vec2 trial = clamp_unit(uv + step);
      const double trial_value = (patch.evaluate(trial.x(), trial.y()) - point).squaredNorm();
      if (trial_value < value) {
        uv = trial;
        value = trial_value;
        improved = true;
        break;
      }
      step *= 0.5;
    }
    if (!improved) break;
  }
  return uv;
}

HausdorffDistance hausdorff_distance(std::span<const BezierPatch3> patches, std::span<const Vec3> positions,
                                     std::span<const std::uint32_t> indices, const HausdorffOptions& options) {
  check_input(patches, positions, indices, options);
  const Meter meter(patches, positions, indices, options);
  const std::size_t triangles = meter.triangle_count();
  const int threads = options.threads;
  const auto refine = static_cast<std::size_t>(options.refine);
  const std::vector<Vec2> lattice = lattice_points(options.lattice);
  HausdorffDistance result;

  // Mesh -> surface, first pass: every vertex (once) and every centroid.
  std::vector<SurfaceFoot> vertex_feet(positions.size());
  std::vector<char> used(positions.size(), 0);
  for (std::uint32_t index : indices) used[index] = 1;
  parallel_for(positions.size(), threads, [&](std::size_t v) {
    if (used[v]) vertex_feet[v] = meter.surface_foot(positions[v]);
  });
  std::vector<SurfaceFoot> centroid_feet(triangles);
  parallel_for(triangles, threads, [&](std::size_t t) {
    centroid_feet[t] = meter.surface_foot(meter.mesh_point(t, Vec2(1.0 / 3, 1.0 / 3)));
  });
  // A triangle's score: the largest distance among its corners and centroid.
  std::vector<double> triangle_score(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    double score = centroid_feet[t].distance;
    for (int k = 0; k < 3; ++k) score = std::max(score, vertex_feet[indices[3 * t + k]].distance);
    triangle_score[t] = score;
  }
  result.mesh_samples = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1)) + triangles;

  // Surface -> mesh, first pass: the patch grids, and each triangle's parameter-triangle centroid.
  const int g = meter.grid_segments();
  const std::size_t grid_size = static_cast<std::size_t>(g + 1) * static_cast<std::size_t>(g + 1);
  struct SurfaceSample {
    std::uint32_t patch;
    Vec2 uv;
    MeshFoot foot;
    std::int64_t triangle;  // the mesh triangle whose parameter triangle it lies in, or -1
  };
  std::vector<SurfaceSample> surface_samples(meter.patch_count() * grid_size + triangles);
  parallel_for(meter.patch_count(), threads, [&](std::size_t p) {
    for (int b = 0; b <= g; ++b) {
      for (int a = 0; a <= g; ++a) {
        const std::size_t k = p * grid_size + static_cast<std::size_t>(a + (g + 1) * b);
        surface_samples[k] = {static_cast<std::uint32_t>(p), meter.grid_uv(a, b),
                              meter.mesh_foot(meter.grid_point(p, a, b)), -1};
      }
    }
  });
  // The parameter triangle under mesh triangle t, when its corners' feet share a patch.
  const auto parameter_triangle = [&](std::size_t t) -> std::optional<std::array<Vec2, 3>> {
    const SurfaceFoot& f0 = vertex_feet[indices[3 * t]];
    const SurfaceFoot& f1 = vertex_feet[indices[3 * t + 1]];
    const SurfaceFoot& f2 = vertex_feet[indices[3 * t + 2]];
    if (f0.patch != f1.patch || f0.patch != f2.patch) return std::nullopt;
    return std::array<Vec2, 3>{f0.uv, f1.uv, f2.uv};
  };
  parallel_for(triangles, threads, [&](std::size_t t) {
    SurfaceSample& sample = surface_samples[meter.patch_count() * grid_size + t];
    const auto uv = parameter_triangle(t);
    const std::uint32_t p = vertex_feet[indices[3 * t]].patch;
    sample = {p, Vec2::Zero(), MeshFoot{-1.0, Vec3::Zero(), 0}, static_cast<std::int64_t>(t)};
    if (!uv) return;
    sample.uv = ((*uv)[0] + (*uv)[1] + (*uv)[2]) / 3.0;
    sample.foot = meter.mesh_foot(meter.patch(p).evaluate(sample.uv.x(), sample.uv.y()));
  });
  result.surface_samples = meter.patch_count() * grid_size + triangles;

  // Surface -> mesh, refined: the largest samples' neighbourhoods on a lattice, then climbed.
  {
    std::vector<double> distances(surface_samples.size());
    for (std::size_t k = 0; k < surface_samples.size(); ++k) distances[k] = surface_samples[k].foot.distance;
    const std::vector<std::size_t> top = largest(distances, std::max<std::size_t>(refine, 1));
    std::vector<HausdorffWitness> witnesses(top.size());
    parallel_for(top.size(), threads, [&](std::size_t r) {
      const SurfaceSample& sample = surface_samples[top[r]];
      const BezierPatch3& patch = meter.patch(sample.patch);
      Vec2 best_uv = sample.uv;
      double best = sample.foot.distance;
      double step = 1.0 / g;
      if (sample.triangle >= 0) {
        const std::array<Vec2, 3> uv = *parameter_triangle(static_cast<std::size_t>(sample.triangle));
        for (const Vec2& st : lattice) {
          const Vec2 candidate = clamp_unit(uv[0] + st.x() * (uv[1] - uv[0]) + st.y() * (uv[2] - uv[0]));
          const double d = meter.mesh_foot(patch.evaluate(candidate.x(), candidate.y())).distance;
          if (d > best) best = d, best_uv = candidate;
        }
        step = std::max({(uv[1] - uv[0]).norm(), (uv[2] - uv[0]).norm(), 1e-9}) / options.lattice;
      }
      const auto value = [&](const Vec2& uv) { return meter.mesh_foot(patch.evaluate(uv.x(), uv.y())).distance; };
      std::tie(best_uv, best) = compass_maximum(best_uv, best, step, step * 1e-6, value, clamp_unit);
      const Vec3 x = patch.evaluate(best_uv.x(), best_uv.y());
      const MeshFoot foot = meter.mesh_foot(x);
      witnesses[r] = {foot.distance, x, sample.patch, best_uv.x(), best_uv.y(), foot.point, foot.triangle};
    });
    for (const HausdorffWitness& w : witnesses) {
      if (w.distance > result.surface_to_mesh.distance) result.surface_to_mesh = w;
    }
  }

  // Mesh -> surface, refined: the largest triangles on a lattice, climbed in barycentric
  // coordinates, then checked against the other patches.
  {
    const std::vector<std::size_t> top = largest(triangle_score, std::max<std::size_t>(refine, 1));
    std::vector<HausdorffWitness> witnesses(top.size());
    parallel_for(top.size(), threads, [&](std::size_t r) {
      const std::size_t t = top[r];
      Vec2 best_st(1.0 / 3, 1.0 / 3);
      double best = -1.0;
      for (const Vec2& st : lattice) {
        const double d = meter.surface_foot(meter.mesh_point(t, st)).distance;
        if (d > best) best = d, best_st = st;
      }
      const auto value = [&](const Vec2& st) { return meter.surface_foot(meter.mesh_point(t, st)).distance; };
      const double step = 1.0 / options.lattice;
      std::tie(best_st, best) = compass_maximum(best_st, best, step, step * 1e-6, value, clamp_barycentric);
      const Vec3 y = meter.mesh_point(t, best_st);
      const SurfaceFoot foot = meter.verified_surface_foot(y, meter.surface_foot(y));
      witnesses[r] = {
          foot.distance, foot.point, foot.patch, foot.uv.x(), foot.uv.y(), y, static_cast<std::uint32_t>(t)};
    });
    for (const HausdorffWitness& w : witnesses) {
      if (w.distance > result.mesh_to_surface.distance) result.mesh_to_surface = w;
    }
  }
  return result;
}

}  // namespace patchwork
