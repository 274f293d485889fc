#include "meshes/polygon.h"

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace patchwork {
namespace {

void check(const char* function, std::span<const Vec3> polygon) {
  if (polygon.size() < 3) throw InvalidInput(detail::message(function, ": a polygon needs 3 corners, got ", polygon.size()));
}

// x + y = a + b exactly (Knuth's two-sum; no overflow assumed).
void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// The sign of the exact value of the 2D cross product sum a x b + b x c + c x a, twice the signed
// area of triangle (a, b, c): > 0 counter-clockwise. A floating-point filter (Shewchuk 1997,
// "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
// ccwerrboundA), then, near zero, the six products exactly (fma) summed into a nonoverlapping
// expansion (his grow_expansion), whose largest component has the sign of the sum. Exact unless
// a product overflows or underflows.
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y());
  const double right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  const double bound = 3.3306690738754716e-16 * (std::abs(left) + std::abs(right));  // (3 + 16 eps) eps
  if (det > bound) return 1;
  if (det < -bound) return -1;
  const double factors[6][2] = {{a.x(), b.y()},  {-a.y(), b.x()}, {b.x(), c.y()},
                                {-b.y(), c.x()}, {c.x(), a.y()},  {-c.y(), a.x()}};
  std::array<double, 12> expansion{};  // components in increasing magnitude, nonoverlapping
  std::size_t size = 0;
  const auto grow = [&](double b_part) {
    double q = b_part;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < size; ++i) {
      double sum, error;
      two_sum(q, expansion[i], sum, error);
      if (error != 0.0) expansion[kept++] = error;
      q = sum;
    }
    if (q != 0.0) expansion[kept++] = q;
    size = kept;
  };
  for (const auto& [x, y] : factors) {
    const double product = x * y;
    grow(std::fma(x, y, -product));
    grow(product);
  }
  if (size == 0) return 0;
  return expansion[size - 1] > 0.0 ? 1 : -1;
}

// Whether closed segments ab and cd intersect (collinear overlaps included), exactly.
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int d1 = orient2d(c, d, a), d2 = orient2d(c, d, b), d3 = orient2d(a, b, c), d4 = orient2d(a, b, d);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  const auto on_segment = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on pq, given collinear
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= r.y() &&
           r.y() <= std::max(p.y(), q.y());
  };
  return (d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) || (d3 == 0 && on_segment(a, b, c)) ||
         (d4 == 0 && on_segment(a, b, d));
}

// The polygon projected along the axis of its Newell normal's largest component (polygon.h),
// and +1 or -1: the orientation of the projection (0 if the normal is zero).
struct Projection {
  std::vector<Vec2> points;
  int orientation = 0;
  bool collinear = false;  // every cross product of the fan from corner 0 is zero
};

// A polygon of zero Newell normal (a bow-tie whose lobes cancel, collinear corners) is projected
// along the largest cross product of its fan from corner 0, so its crossings can still be named.
Projection project(std::span<const Vec3> polygon) {
  const Vec3 normal = newell_normal(polygon);
  Vec3 direction = normal;
  for (std::size_t i = 1; direction == Vec3::Zero() && i + 1 < polygon.size(); ++i) {
    direction = (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]);
  }
  Eigen::Index axis = 0;
  direction.cwiseAbs().maxCoeff(&axis);
  const auto u = (axis + 1) % 3, v = (axis + 2) % 3;
  Projection projection;
  projection.collinear = direction == Vec3::Zero();
  projection.points.reserve(polygon.size());
  for (const Vec3& p : polygon) projection.points.emplace_back(p[u], p[v]);
  // The orientation exactly, at the lowest corner (smallest x, then y): a simple polygon turns
  // there the way it runs (the Newell normal, in floating point, can get a thin sliver's sign
  // wrong). Meaningful only for a simple projection, which the callers check.
  const std::vector<Vec2>& q = projection.points;
  const std::size_t k = q.size();
  std::size_t lowest = 0;
  for (std::size_t i = 1; i < k; ++i) {
    if (q[i].x() < q[lowest].x() || (q[i].x() == q[lowest].x() && q[i].y() < q[lowest].y())) lowest = i;
  }
  const double turn = orient2d(q[(lowest + k - 1) % k], q[lowest], q[(lowest + 1) % k]);
  projection.orientation = (turn > 0) - (turn < 0);
  return projection;
}

// Whether the projected polygon is strictly convex, decided exactly in O(k): every corner turns
// the same way (orient2d) and the edges' directions go round once (dy changes sign twice; a
// pentagram, whose turns agree too, goes round twice). Its orientation then is that turn.
std::optional<int> strictly_convex(const std::vector<Vec2>& q) {
  const std::size_t k = q.size();
  int sign = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const double turn = orient2d(q[(i + k - 1) % k], q[i], q[(i + 1) % k]);
    const int t = (turn > 0) - (turn < 0);
    if (t == 0 || (sign != 0 && t != sign)) return std::nullopt;
    sign = t;
  }
  int changes = 0;
  int last = 0;
  for (std::size_t i = 0; i <= k; ++i) {
    const double dy = q[(i + 1) % k].y() - q[i % k].y();
    const int d = (dy > 0) - (dy < 0);
    if (d == 0) continue;
    if (last != 0 && d != last) ++changes;
    last = d;
  }
  // Counted over one round plus the first edge again, so the wrap-around change is in.
  if (changes != 2) return std::nullopt;
  return sign;
}

// Whether the closed polygon `points` has a repeated corner or two edges that meet other than
// neighbours at their shared corner; if so, `what` says which.
bool self_intersects(const std::vector<Vec2>& points, std::string* what) {
  const std::size_t k = points.size();
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i + 1; j < k; ++j) {
      if (points[i] == points[j]) {
        if (what) *what = detail::message("corners ", i, " and ", j, " coincide");
        return true;
      }
    }
  }
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i + 1; j < k; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == k - 1);
      if (neighbours) continue;
      if (segments_intersect(points[i], points[(i + 1) % k], points[j], points[(j + 1) % k])) {
        if (what) *what = detail::message("edges (", i, ", ", (i + 1) % k, ") and (", j, ", ", (j + 1) % k, ") cross");
        return true;
      }
    }
  }
  return false;
}

}  // namespace

Vec3 newell_normal(std::span<const Vec3> polygon) {
  check("newell_normal", polygon);
  Vec3 normal = Vec3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % polygon.size()];
    normal += (p - q).cross(p + q);  // = 2 p x q
  }
  return 0.25 * normal;  // sum p x q / 2 is the vector area
}

double polygon_area(std::span<const Vec3> polygon) { return newell_normal(polygon).norm(); }

bool is_planar(std::span<const Vec3> polygon, double tolerance) {
  check("is_planar", polygon);
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : polygon) centroid += p;
  centroid /= static_cast<double>(polygon.size());
  const Vec3 normal = newell_normal(polygon);
  if (normal.norm() == 0.0) {
    for (const Vec3& p : polygon) {
      if ((p - centroid).norm() > tolerance) return false;
    }
    return true;
  }
  const Vec3 unit = normal.normalized();
  for (const Vec3& p : polygon) {
    if (std::abs(unit.dot(p - centroid)) > tolerance) return false;
  }
  return true;
}

bool is_simple(std::span<const Vec3> polygon) {
  check("is_simple", polygon);
  const Projection projection = project(polygon);
  return projection.orientation != 0 && !self_intersects(projection.points, nullptr);
}

int orientation(std::span<const Vec3> polygon, const Vec3& normal) {
  const double side = newell_normal(polygon).dot(normal);
  return (side > 0.0) - (side < 0.0);
}

std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(std::span<const Vec3> polygon) {
  check("triangulate_polygon", polygon);
  const auto k = static_cast<std::uint32_t>(polygon.size());
  if (k == 3) return {{0, 1, 2}};
  const Projection projection = project(polygon);
  if (projection.collinear) {
    throw InvalidInput("triangulate_polygon: the polygon has zero area (its corners are collinear)");
  }
  // The common case in O(k): a convex polygon is the fan from corner 0, as ear clipping from
  // corner 1 on would give.
  if (strictly_convex(projection.points)) {
    std::vector<std::array<std::uint32_t, 3>> fan;
    fan.reserve(k - 2);
    for (std::uint32_t i = 1; i + 1 < k; ++i) fan.push_back({0, i, i + 1});
    return fan;
  }
  std::string what;
  if (self_intersects(projection.points, &what)) {
    throw InvalidInput("triangulate_polygon: the polygon is not simple (" + what + ")");
  }
  if (projection.orientation == 0) throw InvalidInput("triangulate_polygon: the polygon has zero area");
  const std::vector<Vec2>& p = projection.points;
  const int s = projection.orientation;  // orientation tests as if the projection ran counter-clockwise
  std::vector<std::uint32_t> previous(k), next(k);
  for (std::uint32_t i = 0; i < k; ++i) {
    previous[i] = (i + k - 1) % k;
    next[i] = (i + 1) % k;
  }
  // Corner i is an ear when it is strictly convex and no other remaining corner lies in the
  // closed triangle (previous, i, next): then previous-next is a diagonal (the polygon stays
  // simple), and the triangle is not degenerate. A simple polygon of >= 4 corners has two ears
  // (Meisters 1975), so every round finds one.
  const auto is_ear = [&](std::uint32_t i) {
    const std::uint32_t a = previous[i], c = next[i];
    if (s * orient2d(p[a], p[i], p[c]) <= 0) return false;
    for (std::uint32_t r = next[c]; r != a; r = next[r]) {
      if (s * orient2d(p[a], p[i], p[r]) >= 0 && s * orient2d(p[i], p[c], p[r]) >= 0 &&
          s * orient2d(p[c], p[a], p[r]) >= 0) {
        return false;
      }
    }
    return true;
  };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(k - 2);
  // Starting at corner 1 and moving on after each ear, a convex polygon gives the fan from
  // corner 0: (0, 1, 2), (0, 2, 3), ... as before.
  std::uint32_t i = 1;
  std::uint32_t tried = 0;  // corners tried since the last ear
  for (std::uint32_t remaining = k; remaining > 3;) {
    if (is_ear(i)) {
      triangles.push_back({previous[i], i, next[i]});
      next[previous[i]] = next[i];
      previous[next[i]] = previous[i];
      i = next[i];
      --remaining;
      tried = 0;
    } else {
      // Cannot happen with exact orientation tests; guards against their underflow.
      if (++tried > remaining) {
        throw NumericalError("triangulate_polygon: no ear found (orientation tests underflowed)");
      }
      i = next[i];
    }
  }
  triangles.push_back({previous[i], i, next[i]});
  return triangles;
}

namespace {

// The message of a face that triangulate_polygon refused, naming the face.
std::string failed_face(std::size_t f, std::size_t corners, const std::string& what) {
  const std::string reason = what.substr(std::string("triangulate_polygon: ").size());
  return detail::message("triangulate_faces: face ", f, " (", corners, " corners) cannot be triangulated: ", reason);
}

}  // namespace

std::vector<std::uint32_t> triangulate_faces(const FaceVertexMesh& mesh) {
  std::vector<std::uint32_t> indices;
  if (mesh.face_indices().size() >= 2 * mesh.face_count()) {
    indices.reserve(3 * (mesh.face_indices().size() - 2 * mesh.face_count()));
  }
  std::vector<Vec3> corners;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const std::span<const std::uint32_t> face = mesh.face(f);
    corners.clear();
    for (const std::uint32_t v : face) corners.push_back(mesh.position(v));
    std::vector<std::array<std::uint32_t, 3>> triangles;
    try {
      triangles = triangulate_polygon(corners);
    } catch (const InvalidInput& e) {
      throw InvalidInput(failed_face(f, face.size(), e.what()));
    } catch (const NumericalError& e) {
      throw NumericalError(failed_face(f, face.size(), e.what()));
    }
    for (const auto& triangle : triangles) {
      for (const std::uint32_t corner : triangle) indices.push_back(face[corner]);
    }
  }
  return indices;
}

}  // namespace patchwork
