#pragma once
// The undirected edges of a polygon soup with every use by a face: the one table that analyze(),
// orient(), repair(), split_normals(), EdgeListMesh and HalfedgeMesh start from. Works on any
// face list (non-manifold edges, faces repeating a vertex, even an edge from a vertex to itself).
//
//   corner c          a position in face_indices(); it walks the edge from its vertex to the
//                     next corner's (the last corner of a face to the first)
//   edge numbering    in order of first use, that is of the first corner walking the edge
//   vertices(e)       (a, b) as that first corner walks it
//   uses(e)           every corner walking e, ascending, each with its face
//   twin(c)           the other corner walking c's edge when exactly two do (the corner table's
//                     "opposite"), `none` when c walks it alone, `crowded` when three or more do
//
// Built in O(corners + vertices) without hashing: corners are bucketed by the smaller vertex of
// their edge (a counting sort) and matched by the larger one within each (short) bucket; an edge
// is numbered by the rank of its first corner in a bitmap. At a million faces the time goes into
// touching fresh memory, so the table keeps little: a twin per corner and a first use per edge
// (about 6 bytes per corner; 4 more for each corner's face when the faces differ in size), the
// uses of crowded (non-manifold) edges apart.

#include <array>
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork::detail {

/// One face's walk along an edge: the face and the corner the walk starts from.
struct EdgeUse {
  std::uint32_t face;
  std::uint32_t corner;
};

/// The edge table of a face list. It refers to the mesh it was built from, which must outlive it.
class EdgeTable {
 public:
  static constexpr std::uint32_t none = 0xffffffffu;
  static constexpr std::uint32_t crowded = 0xfffffffeu;

  /// The table of `mesh`; its per-corner arrays get room for `capacity` entries (see release()).
  /// \throws TopologyError if the mesh has 2^32 - 2 corners or more (corner ids are 32-bit).
  explicit EdgeTable(const FaceVertexMesh& mesh, std::size_t capacity = 0);

  /// The table's large arrays, their memory touched already, for a caller to reuse (HalfedgeMesh
  /// turns them into its own): twin per corner, first_use per edge (in an array with a corner's
  /// room), and an array with room for a vertex's worth of entries. Afterwards only face_of(),
  /// next_corner() and prev_corner() may be called.
  struct Arrays {
    std::vector<std::uint32_t> twin;
    std::vector<std::uint32_t> first_use;
    std::vector<std::uint32_t> spare;
  };
  Arrays release() noexcept;

  /// The walks along one edge in corner order, as EdgeUse values.
  class Uses {
   public:
    class iterator {
     public:
      using iterator_category = std::forward_iterator_tag;
      using value_type = EdgeUse;
      using difference_type = std::ptrdiff_t;
      using pointer = void;
      using reference = EdgeUse;
      iterator() = default;
      iterator(const EdgeTable* table, std::uint32_t corner, std::size_t crowded_at)
          : table_(table), corner_(corner), crowded_at_(crowded_at) {}
      EdgeUse operator*() const noexcept { return {table_->face_of(corner_), corner_}; }
      iterator& operator++() noexcept;
      iterator operator++(int) noexcept {
        iterator old = *this;
        ++*this;
        return old;
      }
      bool operator==(const iterator& other) const noexcept { return corner_ == other.corner_; }

     private:
      const EdgeTable* table_ = nullptr;
      std::uint32_t corner_ = none;
      std::size_t crowded_at_ = 0;  // position in crowded_uses_ when the edge is crowded
    };
    iterator begin() const noexcept { return first_; }
    iterator end() const noexcept { return {}; }

   private:
    friend class EdgeTable;
    explicit Uses(iterator first) : first_(first) {}
    iterator first_;
  };

  std::size_t edge_count() const noexcept { return first_use_.size(); }
  /// The corner of the first walk along edge e.
  std::uint32_t first_use(std::size_t e) const noexcept { return first_use_[e]; }
  /// The other corner walking c's edge if exactly two do; none if c alone, crowded if more.
  std::uint32_t twin(std::uint32_t c) const noexcept { return twin_[c]; }
  /// The walks along edge e in corner order (a face walking it twice is there twice).
  Uses uses(std::size_t e) const noexcept;
  /// The number of walks along edge e: 1 on the boundary, 2 inside a manifold.
  std::size_t use_count(std::size_t e) const noexcept;
  /// Whether edge e has exactly two walks.
  bool has_two_uses(std::size_t e) const noexcept { return twin_[first_use_[e]] < crowded; }
  /// The first two walks along edge e. \pre e has two walks or more.
  std::array<EdgeUse, 2> first_two_uses(std::size_t e) const noexcept;
  /// Whether corner c is the first to walk its edge.
  bool is_first_use(std::uint32_t c) const noexcept { return (leaders_[c / 64] >> (c % 64) & 1) != 0; }
  /// The edge that corner c walks.
  std::uint32_t edge_of(std::uint32_t c) const noexcept;
  /// The vertices of edge e as its first use walks it.
  std::array<std::uint32_t, 2> vertices(std::size_t e) const noexcept {
    const std::uint32_t c = first_use_[e];
    return {mesh_->face_indices()[c], mesh_->face_indices()[next_corner(c)]};
  }
  /// The face of corner c.
  std::uint32_t face_of(std::uint32_t c) const noexcept {
    switch (face_size_) {
      case 3: return c / 3;  // triangles and quads: division by a constant is a multiplication
      case 4: return c / 4;
      case 0: return corner_face_[c];
      default: return c / face_size_;
    }
  }
  /// The corner after c in its face (the first after the last).
  std::uint32_t next_corner(std::uint32_t c) const noexcept {
    const std::uint32_t f = face_of(c);
    if (face_size_ != 0) return c + 1 < (f + 1) * face_size_ ? c + 1 : f * face_size_;
    return c + 1 < mesh_->first_corner(f + 1) ? c + 1 : static_cast<std::uint32_t>(mesh_->first_corner(f));
  }
  /// The corner before c in its face (the last before the first).
  std::uint32_t prev_corner(std::uint32_t c) const noexcept {
    const std::uint32_t f = face_of(c);
    const auto first = face_size_ != 0 ? f * face_size_ : static_cast<std::uint32_t>(mesh_->first_corner(f));
    if (c > first) return c - 1;
    return (face_size_ != 0 ? (f + 1) * face_size_ : static_cast<std::uint32_t>(mesh_->first_corner(f + 1))) - 1;
  }

 private:
  // The edge whose first use is corner `first`: the rank of its bit.
  std::uint32_t rank_of(std::uint32_t first) const noexcept;

  const FaceVertexMesh* mesh_;
  std::uint32_t face_size_ = 0;             // the size of every face, 0 if they differ
  std::vector<std::uint32_t> corner_face_;  // per corner, only if the face sizes differ
  std::vector<std::uint32_t> twin_;         // per corner
  std::vector<std::uint64_t> leaders_;      // bit c: corner c is a first use
  std::vector<std::uint32_t> rank_;         // first uses before word w of leaders_
  std::vector<std::uint32_t> first_use_;    // per edge
  // The walks along crowded edges: (edge, corner) ascending, and (corner, edge) ascending.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> crowded_uses_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> crowded_corners_;
};

/// Calls visit(c) for every corner c of face f at vertex v, in order (one unless f repeats v).
template <class Visit>
void for_each_corner_at(const FaceVertexMesh& mesh, std::uint32_t f, std::uint32_t v, Visit visit) {
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  for (auto c = static_cast<std::uint32_t>(mesh.first_corner(f)); c < mesh.first_corner(f + 1); ++c) {
    if (index[c] == v) visit(c);
  }
}

/// The first corner of face f at vertex v. \pre face f has a corner at v.
std::uint32_t corner_at(const FaceVertexMesh& mesh, std::uint32_t f, std::uint32_t v);

}  // namespace patchwork::detail
