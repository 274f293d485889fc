#include "queries/patch_bvh.h"

#include <algorithm>

#include "core/errors.h"
#include "core/parallel.h"
#include "queries/wide_bvh.h"

namespace patchwork {

PatchBvh::PatchBvh(const PatchSet& set, int pieces_per_side) : set_(&set) {
  if (pieces_per_side < 0)
    throw InvalidInput(detail::message("PatchBvh: pieces_per_side must be >= 0, not ", pieces_per_side));
  const std::size_t count = set.count();
  const int k = pieces_per_side > 0 ? pieces_per_side : count <= 1024 ? 8 : count <= 4096 ? 4 : count <= 65536 ? 2 : 1;
  const std::size_t per_patch = static_cast<std::size_t>(k) * static_cast<std::size_t>(k);
  std::vector<detail::NetPiece> pieces(count * per_patch);
  std::vector<Eigen::AlignedBox3d> boxes(pieces.size());
  parallel_for(count, 0, [&](std::size_t p) {
    std::vector<detail::NetPiece> split = detail::split_pieces(detail::whole_piece(set, static_cast<std::uint32_t>(p)), k);
    for (std::size_t i = 0; i < per_patch; ++i) {
      boxes[p * per_patch + i] = detail::control_box(split[i]);
      pieces[p * per_patch + i] = std::move(split[i]);
    }
  });
  std::vector<std::uint32_t> order(pieces.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  nodes_.reserve(2 * pieces.size());
  pieces_.reserve(pieces.size());
  boxes_.reserve(pieces.size());
  build(order, pieces, boxes, 0, order.size(), 1);
  wide_ = std::make_shared<const detail::WideBvh>(*this);
}

std::uint32_t PatchBvh::build(std::vector<std::uint32_t>& order, std::vector<detail::NetPiece>& source_pieces,
                              const std::vector<Eigen::AlignedBox3d>& source_boxes, std::size_t begin, std::size_t end,
                              int level) {
  depth_ = std::max(depth_, level);
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (std::size_t i = begin; i < end; ++i) {
    box.extend(source_boxes[order[i]]);
    centres.extend(source_boxes[order[i]].center());
  }
  nodes_[index].box = box;
  if (end - begin <= 2) {
    nodes_[index].second_or_first_piece = static_cast<std::uint32_t>(pieces_.size());
    nodes_[index].piece_count = static_cast<std::uint32_t>(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
      pieces_.push_back(std::move(source_pieces[order[i]]));
      boxes_.push_back(source_boxes[order[i]]);
    }
    return index;
  }
  int axis = 0;
  centres.diagonal().maxCoeff(&axis);
  const std::size_t middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(middle),
                   order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::uint32_t a, std::uint32_t b) {
                     return source_boxes[a].center()[axis] < source_boxes[b].center()[axis];
                   });
  build(order, source_pieces, source_boxes, begin, middle, level + 1);
  const std::uint32_t second = build(order, source_pieces, source_boxes, middle, end, level + 1);
  nodes_[index].second_or_first_piece = second;
  return index;
}

}  // namespace patchwork
