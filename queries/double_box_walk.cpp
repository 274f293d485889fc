#include "queries/double_box_walk.h"

#include <array>
#include <cmath>
#include <limits>

namespace patchwork::detail {
namespace {

// What the box tests of one ray share, worked out once per ray.
struct Slabs {
  Vec3 origin;
  Vec3 inverse;
  double t_min, t_max;
  // Per axis: the direction has no finite inverse there (0, or so small that 1/d overflows).
  std::array<bool, 3> parallel;
  // Per axis: the direction is exactly 0 there.
  std::array<bool, 3> still;
  // Per axis: the direction is negative (the box's max face is met first).
  std::array<bool, 3> negative;
};

Slabs slabs_of(const Vec3& origin, const Vec3& direction, double t_min, double t_max) {
  Slabs s{origin, direction.cwiseInverse(), t_min, t_max, {}, {}, {}};
  for (int c = 0; c < 3; ++c) {
    s.parallel[static_cast<std::size_t>(c)] = !std::isfinite(s.inverse[c]);
    s.still[static_cast<std::size_t>(c)] = direction[c] == 0.0;
    s.negative[static_cast<std::size_t>(c)] = direction[c] < 0.0;
  }
  return s;
}

// Whether the ray's parameter interval inside a box is not empty, conservatively (file comment
// of the header). An axis where the direction has no finite inverse keeps the ray if the origin
// is within the slab, or if the direction is not exactly 0 there (it moves, if by little); a
// NaN from 0 * inf, where the inverse is huge but finite, drops out of std::max and std::min,
// which keeps the ray.
bool slab(const Eigen::AlignedBox3d& box, const Slabs& s) {
  constexpr double widen = 2 * std::numeric_limits<double>::epsilon(), tiny = std::numeric_limits<double>::min();
  double t0 = s.t_min, t1 = s.t_max;
  for (int c = 0; c < 3; ++c) {
    const auto k = static_cast<std::size_t>(c);
    if (s.parallel[k]) {
      if (s.still[k] && (s.origin[c] < box.min()[c] || s.origin[c] > box.max()[c])) return false;
      continue;
    }
    const double near = ((s.negative[k] ? box.max()[c] : box.min()[c]) - s.origin[c]) * s.inverse[c];
    const double far = ((s.negative[k] ? box.min()[c] : box.max()[c]) - s.origin[c]) * s.inverse[c];
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
