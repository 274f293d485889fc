#pragma once
// The vertex list / face list (seed Def 53): positions as a row-major N x 3 matrix and polygons
// of any size as face sizes plus flat vertex indices, the shape OpenSubdiv's descriptor and
// glTF buffers want.
//
//   positions      [x0 y0 z0; x1 y1 z1; ...]
//   face_sizes     [3, 4, ...]            polygon f has face_sizes[f] corners
//   face_indices   [0 1 2  2 1 3 4 ...]   the corners of all faces, one after the other
//
// A face lists its vertices counter-clockwise seen from the side its normal points to (Def 45).
// The type holds any polygon soup; whether it is a manifold mesh is for analyze() to say and for
// HalfedgeMesh to require.

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/types.h"
#include "meshes/ids.h"

namespace patchwork {

using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

class FaceVertexMesh {
 public:
  /// The empty mesh (no vertices, no faces).
  FaceVertexMesh() : offsets_(1, 0) {}
  /// \throws TopologyError if a face has fewer than 3 corners, an index is out of range, or the
  ///         sizes do not add up to the number of indices; InvalidInput if a position is not finite.
  FaceVertexMesh(Positions positions, std::vector<std::uint32_t> face_sizes, std::vector<std::uint32_t> face_indices);
  /// All faces of one size (3 for triangles) from a flat index list.
  static FaceVertexMesh uniform(Positions positions, std::uint32_t face_size, std::vector<std::uint32_t> face_indices);

  const Positions& positions() const noexcept { return positions_; }
  const std::vector<std::uint32_t>& face_sizes() const noexcept { return face_sizes_; }
  const std::vector<std::uint32_t>& face_indices() const noexcept { return face_indices_; }

  /// Number of vertices (rows of positions, referenced by a face or not).
  std::size_t vertex_count() const noexcept { return static_cast<std::size_t>(positions_.rows()); }
  /// Number of faces.
  std::size_t face_count() const noexcept { return face_sizes_.size(); }
  /// The vertex indices of face f, in order.
  std::span<const std::uint32_t> face(std::size_t f) const noexcept {
    return {face_indices_.data() + offsets_[f], face_sizes_[f]};
  }
  /// The position in face_indices() of face f's first corner; first_corner(face_count()) is the
  /// number of corners. Corner c of face f is followed by c + 1, the last by first_corner(f).
  std::size_t first_corner(std::size_t f) const noexcept { return offsets_[f]; }
  /// Position of vertex v.
  Vec3 position(std::size_t v) const { return positions_.row(static_cast<Eigen::Index>(v)).transpose(); }

  /// Checks the invariants the constructor established. \throws std::logic_error if broken.
  void validate() const;

  friend bool operator==(const FaceVertexMesh& a, const FaceVertexMesh& b) {
    return a.positions_ == b.positions_ && a.face_sizes_ == b.face_sizes_ && a.face_indices_ == b.face_indices_;
  }

 private:
  Positions positions_;
  std::vector<std::uint32_t> face_sizes_;
  std::vector<std::uint32_t> face_indices_;
  std::vector<std::size_t> offsets_;  // offsets_[f] = first index of face f; size F + 1 (also when empty)
};

namespace detail {
std::optional<std::uint32_t> smallest_repeated_vertex(std::span<const std::uint32_t> face);
}  // namespace detail

/// The smallest vertex that `face` lists more than once, or nullopt if its corners are distinct.
inline std::optional<std::uint32_t> repeated_vertex(std::span<const std::uint32_t> face) {
  // Small faces (nearly all) answer by comparing pairs, inline and without allocating.
  if (face.size() == 3 && face[0] != face[1] && face[1] != face[2] && face[0] != face[2]) return std::nullopt;
  if (face.size() > 16) return detail::smallest_repeated_vertex(face);
  for (std::size_t k = 0; k < face.size(); ++k) {
    for (std::size_t j = k + 1; j < face.size(); ++j) {
      if (face[k] == face[j]) return detail::smallest_repeated_vertex(face);
    }
  }
  return std::nullopt;
}

}  // namespace patchwork
