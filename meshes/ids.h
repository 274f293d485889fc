#pragma once
// Strong 32-bit element ids for meshes: an index with its kind in the type, no mesh pointer.
// Printed as v12, h7, e3, f5; the invalid id (all ones) prints as v-, h-, ...

#include <compare>
#include <cstdint>
#include <functional>
#include <ostream>

namespace patchwork {

template <class Tag>
struct Id {
  static constexpr std::uint32_t invalid_value = 0xffffffffu;
  std::uint32_t value = invalid_value;

  constexpr Id() = default;
  constexpr explicit Id(std::uint32_t v) : value(v) {}
  /// Whether the id refers to an element (is not the invalid id).
  constexpr bool valid() const noexcept { return value != invalid_value; }
  /// The index as a size_t, for containers.
  constexpr std::size_t index() const noexcept { return value; }
  auto operator<=>(const Id&) const = default;
};

struct VertexTag {
  static constexpr char prefix = 'v';
};
struct HalfedgeTag {
  static constexpr char prefix = 'h';
};
struct EdgeTag {
  static constexpr char prefix = 'e';
};
struct FaceTag {
  static constexpr char prefix = 'f';
};

using VertexId = Id<VertexTag>;
using HalfedgeId = Id<HalfedgeTag>;
using EdgeId = Id<EdgeTag>;
using FaceId = Id<FaceTag>;

template <class Tag>
std::ostream& operator<<(std::ostream& out, Id<Tag> id) {
  out << Tag::prefix;
  if (id.valid()) {
    out << id.value;
  } else {
    out << '-';
  }
  return out;
}

}  // namespace patchwork

template <class Tag>
struct std::hash<patchwork::Id<Tag>> {
  std::size_t operator()(patchwork::Id<Tag> id) const noexcept { return std::hash<std::uint32_t>{}(id.value); }
};
