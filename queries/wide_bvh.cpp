#include "queries/wide_bvh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/assert.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace patchwork::detail {
namespace {

// A child of the binary tree while collapsing: a node, or a piece.
struct Item {
  bool piece;
  std::uint32_t index;
};

// The float below x (or x itself when it is a float); never above x.
float round_down(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

// The float above x (or x itself); never below x.
float round_up(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

struct Collapser {
  const PatchBvh& bvh;
  double pad;
  Vec3 centre;
  std::vector<WideBvh::Node>& nodes;

  const Eigen::AlignedBox3d& box(const Item& item) const {
    return item.piece ? bvh.piece_boxes()[item.index] : bvh.nodes()[item.index].box;
  }
  // A binary node's two children: nodes, or a leaf's pieces (a one-piece leaf is its piece).
  std::vector<Item> children(std::uint32_t index) const {
    const PatchBvh::Node& node = bvh.nodes()[index];
    if (!node.leaf()) return {item_of(index + 1), item_of(node.second_or_first_piece)};
    std::vector<Item> out;
    for (std::uint32_t k = 0; k < node.piece_count; ++k) out.push_back({true, node.second_or_first_piece + k});
    return out;
  }
  Item item_of(std::uint32_t index) const {
    const PatchBvh::Node& node = bvh.nodes()[index];
    if (node.leaf() && node.piece_count == 1) return {true, node.second_or_first_piece};
    return {false, index};
  }
  static double area(const Eigen::AlignedBox3d& box) {
    const Vec3 e = box.diagonal();
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }

  // Builds the wide node standing for binary node `index` (not a one-piece leaf); its index.
  std::uint32_t build(std::uint32_t index) {
    std::vector<Item> items = children(index);
    while (items.size() < 4) {
      // The largest child that is a node opens into its two.
      std::size_t best = items.size();
      for (std::size_t k = 0; k < items.size(); ++k)
        if (!items[k].piece && (best == items.size() || area(box(items[k])) > area(box(items[best])))) best = k;
      if (best == items.size()) break;
      const std::vector<Item> opened = children(items[best].index);
      items.erase(items.begin() + static_cast<std::ptrdiff_t>(best));
      items.insert(items.end(), opened.begin(), opened.end());
    }
    const auto here = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(empty_node());
    for (std::size_t k = 0; k < items.size(); ++k) {
      // The child's subtree is built first (`nodes` may reallocate).
      const std::uint32_t child = items[k].piece ? (items[k].index | WideBvh::piece_flag) : build(items[k].index);
      set_child(here, k, box(items[k]), child);
    }
    return here;
  }
  // A node whose four slots are empty boxes (low +inf, high -inf).
  static WideBvh::Node empty_node() {
    WideBvh::Node node;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 4; ++k) {
        node.bounds[0][c][k] = std::numeric_limits<float>::infinity();
        node.bounds[1][c][k] = -std::numeric_limits<float>::infinity();
      }
    }
    node.child.fill(0);
    return node;
  }
  // Slot k of node `at`: `box` less the centre, widened by the pad and rounded outward, and its
  // child. The difference with the centre rounds by at most u (|b| + |centre|), taken off too.
  void set_child(std::uint32_t at, std::size_t k, const Eigen::AlignedBox3d& b, std::uint32_t child) {
    constexpr double u = std::numeric_limits<double>::epsilon() / 2;
    for (int c = 0; c < 3; ++c) {
      const double low = b.min()[c] - centre[c], high = b.max()[c] - centre[c];
      const double slack = pad + 4 * u * (std::abs(b.min()[c]) + std::abs(b.max()[c]) + std::abs(centre[c]) + pad);
      nodes[at].bounds[0][c][k] = round_down(low - slack);
      nodes[at].bounds[1][c][k] = round_up(high + slack);
    }
    nodes[at].child[k] = child;
  }
};

// The parameter interval [t0, t1] of o + t d inside `box`, clipped to [t0, t1]; false if empty.
// Conservative: each slab parameter (b - o) / d rounds twice, by at most 2u relative (and the
// smallest subnormal where it underflows), so each end is moved out by 4u of itself and 2^-1022;
// the interval holds every t whose exact point is in the box, however far the ray.
bool clip(const Eigen::AlignedBox3d& box, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  constexpr double u = std::numeric_limits<double>::epsilon() / 2, tiny = std::numeric_limits<double>::min();
  const double t_min = t0, t_max = t1;
  for (int c = 0; c < 3; ++c) {
    if (d[c] == 0.0) {
      if (o[c] < box.min()[c] || o[c] > box.max()[c]) return false;
      continue;
    }
    const double a = (box.min()[c] - o[c]) / d[c], b = (box.max()[c] - o[c]) / d[c];
    const double near = std::min(a, b), far = std::max(a, b);
    t0 = std::max(t0, near - (4 * u * std::abs(near) + tiny));
    t1 = std::min(t1, far + (4 * u * std::abs(far) + tiny));
  }
  t0 = std::max(t0, t_min), t1 = std::min(t1, t_max);
  return t0 <= t1;
}

}  // namespace

// The pbrt stretch: 2^-20 > 2 gamma_3 + the product's own rounding (2^-24); the tiny term covers
// products that underflow.
constexpr float stretch = 1.0f + 0x1p-20f, tiny = std::numeric_limits<float>::min();

unsigned node_mask_scalar(const WideBvh::Node& node, const float* q, const float* inverse, const int* negative, float far_end) {
  float near[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far[4] = {far_end, far_end, far_end, far_end};
  for (int c = 0; c < 3; ++c) {
    const float* low = node.bounds[negative[c]][c];
    const float* high = node.bounds[1 - negative[c]][c];
    for (int k = 0; k < 4; ++k) {
      // Written as the SSE instructions behave: a NaN parameter leaves near and far as they are.
      const float a = (low[k] - q[c]) * inverse[c], b = (high[k] - q[c]) * inverse[c];
      near[k] = a > near[k] ? a : near[k];
      far[k] = b < far[k] ? b : far[k];
    }
  }
  unsigned mask = 0;
  for (int k = 0; k < 4; ++k) {
    const float reach = far[k] * stretch;
    mask |= near[k] <= reach + tiny ? 1u << k : 0u;
  }
  return mask;
}

unsigned node_mask(const WideBvh::Node& node, const float* q, const float* inverse, const int* negative, float far_end) {
#if defined(__SSE2__)
  // max(x, near) and min(x, far) return their second operand where x is NaN.
  __m128 near = _mm_setzero_ps(), far = _mm_set1_ps(far_end);
  for (int c = 0; c < 3; ++c) {
    const __m128 origin = _mm_set1_ps(q[c]), scale = _mm_set1_ps(inverse[c]);
    const __m128 a = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[negative[c]][c]), origin), scale);
    const __m128 b = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[1 - negative[c]][c]), origin), scale);
    near = _mm_max_ps(a, near);
    far = _mm_min_ps(b, far);
  }
  const __m128 reach = _mm_add_ps(_mm_mul_ps(far, _mm_set1_ps(stretch)), _mm_set1_ps(tiny));
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(near, reach)));
#else
  return node_mask_scalar(node, q, inverse, negative, far_end);
#endif
}

WideBvh::WideBvh(const PatchBvh& bvh) : root_(bvh.nodes().front().box), centre_(root_.center()), depth_(bvh.depth()) {
  // The pad: 2^-18 of the scene's diagonal (the boxes are stored relative to its centre, so it
  // does not grow with the scene's distance from the origin), where `reaches` needs at most
  // 2^-21 (see there).
  pad_ = 0x1p-18 * root_.diagonal().norm();
  Collapser collapser{bvh, pad_, centre_, nodes_};
  const PatchBvh::Node& root = bvh.nodes().front();
  if (root.piece_count <= 1 && (root.leaf() || bvh.pieces().empty())) {
    // No piece, or one: a node holding it alone.
    nodes_.push_back(collapser.empty_node());
    if (root.piece_count == 1) collapser.set_child(0, 0, root.box, piece_flag | root.second_or_first_piece);
    return;
  }
  collapser.build(0);
}

bool WideBvh::reaches(const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                      std::vector<std::uint32_t>& pieces) const {
  constexpr double u_double = std::numeric_limits<double>::epsilon() / 2;
  constexpr double u_float = std::numeric_limits<float>::epsilon() / 2;
  // Where the double ray is inside the root box widened by the pad: [t0, t1].
  Eigen::AlignedBox3d padded = root_;
  padded.min().array() -= pad_;
  padded.max().array() += pad_;
  double t0 = t_min, t1 = t_max;
  if (!clip(padded, origin, direction, t0, t1)) return true;
  // The float ray q + s e, s in [0, S]: q the entry point, e the direction scaled to max norm 1,
  // s = (t - t0) max|d|.
  const double scale = direction.cwiseAbs().maxCoeff();
  const Vec3 unit = direction / scale;
  // Relative to the boxes' centre.
  const Vec3 q = origin + t0 * direction - centre_;
  const double span = (t1 - t0) * scale * (1 + 0x1p-40);
  float qf[3], inverse[3], far_end = round_up(span);
  int negative[3];
  // The bound on how far the double ray's points between t0 and t1 are from the float ray's:
  // q and e rounded to floats (2^-24 of |q|, and of |e| over the span, plus 2^-150 each where
  // they are subnormal), and the double rounding of q (o + t0 d - centre) and of the span (a few
  // 2^-53 of |o|, |t d| and the box, which holds the centre).
  double off = 0x1p-149 * (1 + span);
  const double box_size = padded.min().cwiseAbs().cwiseMax(padded.max().cwiseAbs()).maxCoeff();
  for (int c = 0; c < 3; ++c) {
    qf[c] = static_cast<float>(q[c]);
    const float e = static_cast<float>(unit[c]);
    inverse[c] = 1.0f / e;
    negative[c] = std::signbit(e) ? 1 : 0;
    off = std::max(off, 2 * u_float * (std::abs(static_cast<double>(qf[c])) + span * std::abs(unit[c])) +
                            8 * u_double * (std::abs(origin[c]) + (std::abs(t0) + std::abs(t1)) * std::abs(direction[c]) + box_size));
  }
  // Twice over (the bound's own rounding is far below that), within an eighth of the pad; NaN or
  // inf fail too.
  if (!(2 * off <= 0x1p-2 * pad_) || !std::isfinite(far_end)) return false;
  // Depth-first stack: at most 3 entries a level (the binary tree's depth is below 64).
  std::array<std::uint32_t, 256> stack;
  PATCHWORK_ASSERT(3 * static_cast<std::size_t>(depth_) + 1 <= stack.size(), "WideBvh: tree too deep for the walk's stack");
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    unsigned mask = node_mask(node, qf, inverse, negative, far_end);
    while (mask != 0) {
      const int k = std::countr_zero(mask);
      mask &= mask - 1;
      const std::uint32_t child = node.child[static_cast<std::size_t>(k)];
      if (child & piece_flag) {
        pieces.push_back(child & ~piece_flag);
      } else {
        stack[top++] = child;
      }
    }
  }
  return true;
}

}  // namespace patchwork::detail
