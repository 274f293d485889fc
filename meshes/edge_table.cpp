#include "meshes/edge_table.h"

#include <algorithm>
#include <bit>
#include <limits>

#include "core/assert.h"
#include "core/errors.h"

namespace patchwork::detail {
namespace {

constexpr std::size_t not_crowded = std::numeric_limits<std::size_t>::max();

// The number of set bits (a portable popcount: the baseline x86-64 target has no instruction
// for it, and the library call costs more than these few operations).
std::uint32_t bit_count(std::uint64_t x) noexcept {
  x = x - ((x >> 1) & 0x5555555555555555u);
  x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return static_cast<std::uint32_t>((x * 0x0101010101010101u) >> 56);
}

// A corner being matched: the larger vertex of its edge, and the corner.
struct Walk {
  std::uint32_t larger;
  std::uint32_t corner;
};

// The results of matching, written by corner.
struct Matches {
  std::uint32_t* twin;
  std::uint64_t* leaders;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& crowded;  // (first corner, corner)
};

// One edge's walks (ascending corners): twins, the first use's bit, or the crowd.
void record_edge(const Walk* walks, std::size_t count, Matches& out) {
  const std::uint32_t first = walks[0].corner;
  out.leaders[first / 64] |= std::uint64_t{1} << (first % 64);
  if (count == 1) {
    out.twin[first] = EdgeTable::none;
  } else if (count == 2) {
    out.twin[first] = walks[1].corner;
    out.twin[walks[1].corner] = first;
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      out.twin[walks[k].corner] = EdgeTable::crowded;
      out.crowded.emplace_back(first, walks[k].corner);
    }
  }
}

// The walks whose edges share the smaller vertex, ascending by corner: grouped by the larger.
void match_bucket(std::vector<Walk>& walks, Matches& out) {
  constexpr std::size_t small = 16;
  const std::size_t n = walks.size();
  if (n > small) {
    std::sort(walks.begin(), walks.end(), [](Walk a, Walk b) {  // corners unique: no allocation as stable_sort
      return a.larger != b.larger ? a.larger < b.larger : a.corner < b.corner;
    });
    for (std::size_t run = 0; run < n;) {
      std::size_t end = run + 1;
      while (end < n && walks[end].larger == walks[run].larger) ++end;
      record_edge(walks.data() + run, end - run, out);
      run = end;
    }
    return;
  }
  // Few walks (nearly always): group them in place by comparing pairs, keeping corner order.
  bool grouped[small] = {};
  Walk group[small];
  for (std::size_t k = 0; k < n; ++k) {
    if (grouped[k]) continue;
    std::size_t count = 0;
    group[count++] = walks[k];
    for (std::size_t j = k + 1; j < n; ++j) {
      if (!grouped[j] && walks[j].larger == walks[k].larger) {
        grouped[j] = true;
        group[count++] = walks[j];
      }
    }
    record_edge(group, count, out);
  }
}

}  // namespace

EdgeTable::EdgeTable(const FaceVertexMesh& mesh, std::size_t capacity) : mesh_(&mesh) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  const std::size_t corners = index.size();
  if (corners >= crowded) throw TopologyError(message("edge table: ", corners, " corners exceed 32-bit corner ids"));
  const std::vector<std::uint32_t>& sizes = mesh.face_sizes();
  if (!sizes.empty() && std::all_of(sizes.begin(), sizes.end(), [&](std::uint32_t k) { return k == sizes[0]; })) {
    face_size_ = sizes[0];
  } else {
    corner_face_.resize(corners);
    for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
      std::fill(corner_face_.begin() + static_cast<std::ptrdiff_t>(mesh.first_corner(f)),
                corner_face_.begin() + static_cast<std::ptrdiff_t>(mesh.first_corner(f + 1)), f);
    }
  }
  // Calls visit(c, smaller vertex of c's edge) for every corner in order.
  const auto for_each_corner = [&](auto visit) {
    for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
      const auto begin = static_cast<std::uint32_t>(mesh.first_corner(f));
      const auto end = static_cast<std::uint32_t>(mesh.first_corner(f + 1));
      for (std::uint32_t c = begin; c + 1 < end; ++c) visit(c, std::min(index[c], index[c + 1]));
      visit(end - 1, std::min(index[end - 1], index[begin]));
    }
  };
  // 1. Bucket the corners by the smaller vertex of their edge (a counting sort, ascending in each
  // bucket): start[v + 2] counts, then start[v + 1] is where bucket v begins, and after the
  // scatter start[v], start[v + 1] bound it.
  std::vector<std::uint32_t> start(mesh.vertex_count() + 2, 0);
  for_each_corner([&](std::uint32_t, std::uint32_t smaller) { ++start[smaller + 2]; });
  for (std::size_t v = 2; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<std::uint32_t> bucketed;  // becomes first_use_
  bucketed.reserve(std::max(capacity, corners));
  bucketed.resize(corners);
  for_each_corner([&](std::uint32_t c, std::uint32_t smaller) { bucketed[start[smaller + 1]++] = c; });
  // 2. Match each bucket by the larger vertex.
  twin_.reserve(std::max(capacity, corners));
  twin_.resize(corners);
  leaders_.assign(corners / 64 + 1, 0);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> crowded_pairs;
  Matches matches{twin_.data(), leaders_.data(), crowded_pairs};
  std::vector<Walk> walks;
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    walks.clear();
    for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
      const std::uint32_t c = bucketed[k];
      const std::uint32_t a = index[c];
      walks.push_back({a == v ? index[next_corner(c)] : a, c});
    }
    match_bucket(walks, matches);
  }
  // 3. Edge e is the e-th first use in corner order: the rank of its bit. (The lists reuse the
  // buckets' memory: fresh pages cost more than the work here.)
  rank_ = std::move(start);
  rank_.resize(leaders_.size() + 1);
  rank_[0] = 0;
  for (std::size_t w = 0; w < leaders_.size(); ++w) rank_[w + 1] = rank_[w] + bit_count(leaders_[w]);
  first_use_ = std::move(bucketed);
  first_use_.clear();
  for (std::size_t w = 0; w < leaders_.size(); ++w) {
    for (std::uint64_t bits = leaders_[w]; bits != 0; bits &= bits - 1) {
      first_use_.push_back(static_cast<std::uint32_t>(64 * w + static_cast<std::size_t>(std::countr_zero(bits))));
    }
  }
  // 4. Crowded edges by edge and by corner.
  for (auto& [first, corner] : crowded_pairs) first = rank_of(first);
  crowded_uses_ = std::move(crowded_pairs);
  std::sort(crowded_uses_.begin(), crowded_uses_.end());
  crowded_corners_.reserve(crowded_uses_.size());
  for (const auto& [edge, corner] : crowded_uses_) crowded_corners_.emplace_back(corner, edge);
  std::sort(crowded_corners_.begin(), crowded_corners_.end());
}

EdgeTable::Arrays EdgeTable::release() noexcept {
  Arrays arrays{std::move(twin_), std::move(first_use_), std::move(rank_)};
  leaders_ = {};
  crowded_uses_ = {};
  crowded_corners_ = {};
  return arrays;
}

std::uint32_t EdgeTable::edge_of(std::uint32_t c) const noexcept {
  const std::uint32_t t = twin_[c];
  if (t == crowded) {
    return std::lower_bound(crowded_corners_.begin(), crowded_corners_.end(), std::pair<std::uint32_t, std::uint32_t>(c, 0))
        ->second;
  }
  return rank_of(t < c ? t : c);  // none is larger than any corner
}

std::uint32_t EdgeTable::rank_of(std::uint32_t first) const noexcept {
  return rank_[first / 64] + bit_count(leaders_[first / 64] & ((std::uint64_t{1} << (first % 64)) - 1));
}

EdgeTable::Uses EdgeTable::uses(std::size_t e) const noexcept {
  const std::uint32_t first = first_use_[e];
  if (twin_[first] != crowded) return Uses({this, first, not_crowded});
  const auto at = std::lower_bound(crowded_uses_.begin(), crowded_uses_.end(),
                                   std::pair<std::uint32_t, std::uint32_t>(static_cast<std::uint32_t>(e), 0));
  return Uses({this, first, static_cast<std::size_t>(at - crowded_uses_.begin())});
}

EdgeTable::Uses::iterator& EdgeTable::Uses::iterator::operator++() noexcept {
  if (crowded_at_ == not_crowded) {
    const std::uint32_t t = table_->twin_[corner_];
    corner_ = t > corner_ && t < crowded ? t : none;  // from the first use to the second, then the end
    return *this;
  }
  const auto& list = table_->crowded_uses_;
  ++crowded_at_;
  corner_ = crowded_at_ < list.size() && list[crowded_at_].first == list[crowded_at_ - 1].first
                ? list[crowded_at_].second
                : none;
  return *this;
}

std::size_t EdgeTable::use_count(std::size_t e) const noexcept {
  const std::uint32_t t = twin_[first_use_[e]];
  if (t != crowded) return t == none ? 1 : 2;
  return static_cast<std::size_t>(std::distance(uses(e).begin(), uses(e).end()));
}

std::array<EdgeUse, 2> EdgeTable::first_two_uses(std::size_t e) const noexcept {
  const std::uint32_t first = first_use_[e];
  if (twin_[first] < crowded) return {EdgeUse{face_of(first), first}, EdgeUse{face_of(twin_[first]), twin_[first]}};
  auto it = uses(e).begin();
  return {*it, *std::next(it)};
}

std::uint32_t corner_at(const FaceVertexMesh& mesh, std::uint32_t f, std::uint32_t v) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  const auto end = static_cast<std::uint32_t>(mesh.first_corner(f + 1));
  auto c = static_cast<std::uint32_t>(mesh.first_corner(f));
  while (c < end && index[c] != v) ++c;
  PATCHWORK_ASSERT(c < end, "the face has a corner at v");
  return c;
}

}  // namespace patchwork::detail
