#pragma once
// A bounding-volume hierarchy over the pieces of a patch set: the index every set query walks
// (ray casting, closest points), so that a query costs O(log n) pieces, not n.
//
// Each patch is cut into k x k pieces (queries/net_piece.h); a piece's box is the box of its
// control points widened by the rounding margin, so it contains the piece's surface. The tree is
// built top down, splitting the pieces at the median of their box centres along the longest
// axis of those centres, down to leaves of at most two pieces; every node's box is the union of
// its pieces' boxes. Nodes are stored depth first: an inner node's first child follows it, the
// second is at `second`. Rays walk a 4-wide float-box tree made from it (queries/wide_bvh.h).

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "queries/net_piece.h"
#include "surfaces/patch_set.h"

namespace patchwork {

namespace detail {
class WideBvh;
}

class PatchBvh {
 public:
  struct Node {
    Eigen::AlignedBox3d box;
    /// Inner node: the index of the second child (the first is the next node). Leaf: the first piece.
    std::uint32_t second_or_first_piece = 0;
    /// Pieces of a leaf (0 for an inner node).
    std::uint32_t piece_count = 0;
    bool leaf() const noexcept { return piece_count > 0; }
  };

  /// The hierarchy of `set`, each patch cut into k x k pieces (k = 0: 8 for up to 1,024 patches,
  /// 4 up to 4,096, 2 up to 65,536, else 1: smaller pieces leave a ray fewer pieces to try). Keeps a pointer to `set`. \pre set outlives the hierarchy.
  /// \throws InvalidInput if k < 0.
  explicit PatchBvh(const PatchSet& set, int pieces_per_side = 0);

  /// The patch set.
  const PatchSet& set() const noexcept { return *set_; }
  /// The nodes, root first.
  const std::vector<Node>& nodes() const noexcept { return nodes_; }
  /// The pieces, in leaf order.
  const std::vector<detail::NetPiece>& pieces() const noexcept { return pieces_; }
  /// The pieces' boxes, in the same order.
  const std::vector<Eigen::AlignedBox3d>& piece_boxes() const noexcept { return boxes_; }
  /// Diagonal of the root box.
  double size() const noexcept { return nodes_.front().box.diagonal().norm(); }
  /// The depth of the tree (1 for a single leaf).
  int depth() const noexcept { return depth_; }
  /// The same tree 4-wide with float boxes, for rays.
  const detail::WideBvh& wide() const noexcept { return *wide_; }

 private:
  // Builds the subtree of order[begin, end) (indices into the pieces and boxes in patch order),
  // moving its pieces into leaf order.
  std::uint32_t build(std::vector<std::uint32_t>& order, std::vector<detail::NetPiece>& source_pieces,
                      const std::vector<Eigen::AlignedBox3d>& source_boxes, std::size_t begin, std::size_t end, int level);

  const PatchSet* set_;
  std::vector<detail::NetPiece> pieces_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  std::vector<Node> nodes_;
  int depth_ = 0;
  // Shared by copies (it holds no pointer to this object).
  std::shared_ptr<const detail::WideBvh> wide_;
};

}  // namespace patchwork
