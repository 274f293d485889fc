#pragma once
// A 4-wide tree of float boxes over a PatchBvh's pieces: which pieces a ray's boxes reach, four
// box tests at a time (the binary tree's double boxes cost a node visit and a test each).
//
// It is the binary tree collapsed: each node takes the children of its binary node, then
// repeatedly replaces its largest (by surface area) expandable child by that child's two
// children, up to four. A child is a node or a piece.
//
// No box is ever missed although floats round: boxes are stored relative to the root box's
// centre c, and every box is the double box less c, widened by `pad` (2^-18 of the scene's
// diagonal) and by the subtraction's rounding, then rounded outward to floats (std::nextafter
// where the cast rounded inward), so it contains the double box with room to spare. A ray is
// tested as a float ray (q, e) that starts where the double ray enters the root box (a clip
// widened by its own rounding, so an empty clip is never wrong, however far the ray), less c:
// the double ray's points between entry and exit are within `pad` of the float ray's (rounding
// moves q and e by 2^-24 of their size, and subnormals by 2^-150; `reaches` checks the bound
// for each ray and returns false where it does not hold, so that the caller walks the double
// tree instead), and the float slab test is made conservative as in pbrt (Pharr et al., 3rd ed.,
// 3.9.2): each slab parameter carries at most three roundings, so the far end is stretched by
// 2^-20 relative (more than 2 gamma_3) and by the least normal float before it is compared.

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "queries/patch_bvh.h"

namespace patchwork::detail {

class WideBvh {
 public:
  struct alignas(16) Node {
    /// bounds[0] low corners, bounds[1] high corners, [axis][child]; an empty slot is an empty
    /// box (low +inf, high -inf), which no ray reaches.
    float bounds[2][3][4];
    /// Per child: a node index, or a piece index with `piece_flag` set.
    std::array<std::uint32_t, 4> child;
  };
  static constexpr std::uint32_t piece_flag = 0x80000000u;

  /// The 4-wide tree of the hierarchy's nodes and pieces (the same piece indices).
  explicit WideBvh(const PatchBvh& bvh);

  /// Appends to `pieces` every piece whose box the ray o + t d (t_min <= t <= t_max) may reach
  /// (a superset of those whose double boxes it reaches). False (nothing appended) when the ray
  /// is so far from the scene, relative to its size, that the float boxes' pad cannot cover
  /// rounding: the caller tests the double boxes instead.
  bool reaches(const Vec3& origin, const Vec3& direction, double t_min, double t_max, std::vector<std::uint32_t>& pieces) const;

  /// The nodes, root first.
  const std::vector<Node>& nodes() const noexcept { return nodes_; }
  /// What every box is widened by before rounding.
  double pad() const noexcept { return pad_; }
  /// The point the float boxes are relative to (the root box's centre).
  const Vec3& centre() const noexcept { return centre_; }

 private:
  std::vector<Node> nodes_;
  Eigen::AlignedBox3d root_;
  Vec3 centre_;
  int depth_ = 0;
  double pad_ = 0.0;
};

/// Bit k set: the float ray q + s e, 0 <= s <= far_end, may reach child k's box of `node`
/// (`inverse` = 1 / e, `negative` = e's sign bits, q relative to the boxes' centre): four slab
/// tests at once with SSE where the compiler has it.
unsigned node_mask(const WideBvh::Node& node, const float* q, const float* inverse, const int* negative, float far_end);
/// The same test one box at a time, without SSE (what node_mask does without it).
unsigned node_mask_scalar(const WideBvh::Node& node, const float* q, const float* inverse, const int* negative, float far_end);

}  // namespace patchwork::detail
