#include "meshes/polygon.h"

#include <cmath>

#include "core/errors.h"

namespace patchwork {
namespace {

void check(const char* function, std::span<const Vec3> polygon) {
  if (polygon.size() < 3) throw InvalidInput(detail::message(function, ": a polygon needs 3 corners, got ", polygon.size()));
}

// Orientation of the 2D triangle (a, b, c): > 0 counter-clockwise.
double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Whether closed segments ab and cd intersect (collinear overlaps included).
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = orient2d(c, d, a), d2 = orient2d(c, d, b), d3 = orient2d(a, b, c), d4 = orient2d(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on_segment = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on pq, given collinear
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= r.y() &&
           r.y() <= std::max(p.y(), q.y());
  };
  return (d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) || (d3 == 0 && on_segment(a, b, c)) ||
         (d4 == 0 && on_segment(a, b, d));
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
  const Vec3 normal = newell_normal(polygon);
  if (normal.norm() == 0.0) return false;
  // Project onto the plane: two axes orthogonal to the normal.
  const Vec3 n = normal.normalized();
  const Vec3 x = n.unitOrthogonal();
  const Vec3 y = n.cross(x);
  std::vector<Vec2> points;
  for (const Vec3& p : polygon) points.emplace_back(x.dot(p), y.dot(p));
  const std::size_t k = points.size();
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i + 1; j < k; ++j) {
      if (points[i] == points[j]) return false;
    }
  }
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i + 1; j < k; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == k - 1);
      if (neighbours) continue;
      if (segments_intersect(points[i], points[(i + 1) % k], points[j], points[(j + 1) % k])) return false;
    }
  }
  return true;
}

int orientation(std::span<const Vec3> polygon, const Vec3& normal) {
  const double side = newell_normal(polygon).dot(normal);
  return (side > 0.0) - (side < 0.0);
}

}  // namespace patchwork
