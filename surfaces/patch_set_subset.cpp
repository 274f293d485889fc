// PatchSet::subset and for_each_subset: sets of whole shells with the adjacency their set found
// among them (surfaces/patch_set.h), renumbered, not searched again.

#include <algorithm>
#include <functional>
#include <optional>
#include <utility>

#include "core/errors.h"
#include "surfaces/patch_set.h"

namespace patchwork {

PatchSet PatchSet::subset(std::span<const std::uint32_t> patches) const {
  const std::vector<std::vector<std::uint32_t>> one{std::vector<std::uint32_t>(patches.begin(), patches.end())};
  std::optional<PatchSet> made;
  for_each_subset(one, [&](std::size_t, PatchSet& sub) { made.emplace(std::move(sub)); });
  return std::move(*made);
}

void PatchSet::for_each_subset(std::span<const std::vector<std::uint32_t>> parts,
                               const std::function<void(std::size_t, PatchSet&)>& use) const {
  constexpr std::uint32_t outside = 0xffffffffu;
  std::vector<std::uint32_t> part_of(nets_.size(), outside);  // this set's patch -> its part
  std::vector<std::uint32_t> index(nets_.size(), outside);    // -> its place in the part
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::vector<std::uint32_t>& patches = parts[k];
    if (patches.empty()) throw InvalidInput(detail::message("PatchSet::subset: part ", k, " has no patches"));
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const std::uint32_t p = patches[i];
      if (p >= nets_.size()) {
        throw InvalidInput(detail::message("PatchSet::subset: patch ", p, " of ", nets_.size(), " does not exist"));
      }
      if (i > 0 && p <= patches[i - 1]) {
        throw InvalidInput(
            detail::message("PatchSet::subset: patch ", p, " after ", patches[i - 1], ": the patches are not increasing"));
      }
      if (part_of[p] != outside) {
        throw InvalidInput(detail::message("PatchSet::subset: patch ", p, " is in parts ", part_of[p], " and ", k));
      }
      part_of[p] = static_cast<std::uint32_t>(k);
      index[p] = static_cast<std::uint32_t>(i);
    }
  }
  const auto cut = [&](std::uint32_t in, std::uint32_t out) {
    return InvalidInput(detail::message("PatchSet::subset: patch ", in, " is joined to patch ", out,
                                        ", which is not in its part (the part cuts a shell)"));
  };
  // Each element of this set to the part it belongs to, in one pass over each kind.
  std::vector<std::vector<std::uint32_t>> shared_in(parts.size()), junctions_in(parts.size()),
      collapsed_in(parts.size()), open_in(parts.size()), loops_in(parts.size());
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> touching_in(parts.size());  // (point, group)
  for (std::uint32_t i = 0; i < shared_.size(); ++i) {
    const SharedEdge& s = shared_[i];
    const std::uint32_t a = part_of[s.first.patch], b = part_of[s.second.patch];
    if (a != b) throw a != outside ? cut(s.first.patch, s.second.patch) : cut(s.second.patch, s.first.patch);
    if (a != outside) shared_in[a].push_back(i);
  }
  for (std::uint32_t i = 0; i < t_junctions_.size(); ++i) {
    const TJunction& t = t_junctions_[i];
    const std::uint32_t a = part_of[t.edge.patch];
    for (const EdgeRef& e : t.parts) {
      if (part_of[e.patch] != a) throw a != outside ? cut(t.edge.patch, e.patch) : cut(e.patch, t.edge.patch);
    }
    if (a != outside) junctions_in[a].push_back(i);
  }
  for (std::uint32_t i = 0; i < collapsed_.size(); ++i) {
    if (part_of[collapsed_[i].patch] != outside) collapsed_in[part_of[collapsed_[i].patch]].push_back(i);
  }
  for (std::uint32_t i = 0; i < open_.size(); ++i) {
    if (part_of[open_[i].patch] != outside) open_in[part_of[open_[i].patch]].push_back(i);
  }
  // A loop's corners are joined through shared and collapsed edges and T-junctions (see the
  // constructor): it lies in one shell, so in one part or none.
  for (std::uint32_t i = 0; i < loops_.size(); ++i) {
    const std::uint32_t a = part_of[loops_[i].edges.front().patch];
    if (a != outside) loops_in[a].push_back(i);
  }
  // A group of a touching point is edge-connected, so in one shell; a point's groups may be in
  // several parts.
  for (std::uint32_t i = 0; i < touching_.size(); ++i) {
    for (std::uint32_t g = 0; g < touching_[i].groups.size(); ++g) {
      const std::uint32_t a = part_of[touching_[i].groups[g].front()];
      if (a != outside) touching_in[a].emplace_back(i, g);
    }
  }
  const auto renumbered = [&](EdgeRef e) { return EdgeRef{index[e.patch], e.edge}; };
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::vector<std::uint32_t>& patches = parts[k];
    PatchSet sub;
    sub.nets_.reserve(patches.size());
    for (const std::uint32_t p : patches) sub.nets_.push_back(nets_[p]);
    if (rational_count_ > 0) {
      sub.rational_.reserve(patches.size());
      for (const std::uint32_t p : patches) sub.rational_.push_back(rational_[p]);
      sub.rational_count_ = static_cast<std::size_t>(
          std::count_if(sub.rational_.begin(), sub.rational_.end(), [](const auto& r) { return r.has_value(); }));
      if (sub.rational_count_ == 0) sub.rational_.clear();
    }
    sub.size_ = control_box_diagonal(sub.nets_);
    sub.tolerance_ = tolerance_;
    sub.shared_.reserve(shared_in[k].size());
    for (const std::uint32_t i : shared_in[k]) {
      SharedEdge edge = shared_[i];
      edge.first = renumbered(edge.first);
      edge.second = renumbered(edge.second);
      sub.shared_.push_back(edge);
    }
    for (const std::uint32_t i : junctions_in[k]) {
      TJunction junction = t_junctions_[i];
      junction.edge = renumbered(junction.edge);
      for (EdgeRef& part : junction.parts) part = renumbered(part);
      sub.t_junctions_.push_back(std::move(junction));
    }
    for (const std::uint32_t i : collapsed_in[k]) sub.collapsed_.push_back(renumbered(collapsed_[i]));
    for (const std::uint32_t i : open_in[k]) sub.open_.push_back(renumbered(open_[i]));
    for (const std::uint32_t i : loops_in[k]) {
      BoundaryLoop kept{{}, loops_[i].closed};
      kept.edges.reserve(loops_[i].edges.size());
      for (const EdgeRef& e : loops_[i].edges) kept.edges.push_back(renumbered(e));
      sub.loops_.push_back(std::move(kept));
    }
    // The entries of one point are consecutive (points in order, then their groups).
    const auto& entries = touching_in[k];
    for (std::size_t e = 0; e < entries.size();) {
      const std::uint32_t i = entries[e].first;
      TouchingPoint kept{touching_[i].point, {}};
      for (; e < entries.size() && entries[e].first == i; ++e) {
        const std::vector<std::uint32_t>& group = touching_[i].groups[entries[e].second];
        std::vector<std::uint32_t> members;
        members.reserve(group.size());
        for (const std::uint32_t p : group) members.push_back(index[p]);
        kept.groups.push_back(std::move(members));
      }
      if (kept.groups.size() < 2) continue;
      std::sort(kept.groups.begin(), kept.groups.end());
      sub.touching_.push_back(std::move(kept));
    }
    use(k, sub);
  }
}

}  // namespace patchwork
