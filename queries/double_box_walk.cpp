#include "queries/double_box_walk.h"

#include <array>
#include <cmath>
#include <limits>

namespace patchwork::detail {
namespace {

// What the box tests of one ray share, worked out once per ray.
struct Slabs {
  Vec3 origin, direction;
  double t_min, t_max;
  // Per axis: the direction is negative (the box's max face is met first).
  std::array<bool, 3> negative;
};

Slabs slabs_of(const Vec3& origin, const Vec3& direction, double t_min, double t_max) {
  Slabs s{origin, direction, t_min, t_max, {}};
  for (int c = 0; c < 3; ++c) s.negative[static_cast<std::size_t>(c)] = direction[c] < 0.0;
  return s;
}

// Whether the ray's parameter interval inside a box is not empty, conservatively (file comment
// of the header). The slab parameters are divisions, two roundings whatever the direction's
// size (a product with 1 / d would round three times, and 1 / d itself loses bits where it is
// subnormal, |d| > 2^1022). An axis the direction does not move along keeps the ray if the
// origin is within the slab. A NaN (inf - inf, where a parameter overflows) drops out of
// std::max and std::min, which keeps the ray.
bool slab(const Eigen::AlignedBox3d& box, const Slabs& s) {
  constexpr double widen = 2 * std::numeric_limits<double>::epsilon(), tiny = std::numeric_limits<double>::min();
  double t0 = s.t_min, t1 = s.t_max;
  for (int c = 0; c < 3; ++c) {
    const auto k = static_cast<std::size_t>(c);
    if (s.direction[c] == 0.0) {
      if (s.origin[c] < box.min()[c] || s.origin[c] > box.max()[c]) return false;
      continue;
    }
    const double near = ((s.negative[k] ? box.max()[c] : box.min()[c]) - s.origin[c]) / s.direction[c];
    const double far = ((s.negative[k] ? box.min()[c] : box.max()[c]) - s.origin[c]) / s.direction[c];
    t0 = std::max(t0, near - (widen * std::abs(near) + tiny));
    t1 = std::min(t1, far + (widen * std::abs(far) + tiny));
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

void double_box_pieces(const PatchBvh& bvh, const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                       std::vector<std::uint32_t>& pieces) {
  const Slabs slabs = slabs_of(origin, direction, t_min, t_max);
  thread_local std::vector<std::uint32_t> stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::uint32_t index = stack.back();
    stack.pop_back();
    const PatchBvh::Node& node = bvh.nodes()[index];
    if (!slab(node.box, slabs)) continue;
    if (!node.leaf()) {
      stack.push_back(node.second_or_first_piece);
      stack.push_back(index + 1);
      continue;
    }
    for (std::uint32_t k = 0; k < node.piece_count; ++k)
      if (slab(bvh.piece_boxes()[node.second_or_first_piece + k], slabs)) pieces.push_back(node.second_or_first_piece + k);
  }
}

}  // namespace patchwork::detail
