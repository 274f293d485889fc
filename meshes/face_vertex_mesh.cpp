#include "meshes/face_vertex_mesh.h"

#include <algorithm>
#include <stdexcept>

#include "core/errors.h"

namespace patchwork {

FaceVertexMesh::FaceVertexMesh(Positions positions, std::vector<std::uint32_t> face_sizes,
                               std::vector<std::uint32_t> face_indices)
    : positions_(std::move(positions)), face_sizes_(std::move(face_sizes)), face_indices_(std::move(face_indices)) {
  if (positions_.rows() >= Eigen::Index{0xffffffff}) {
    throw InvalidInput(detail::message("FaceVertexMesh: ", positions_.rows(), " vertices exceed 32-bit ids"));
  }
  for (Eigen::Index v = 0; v < positions_.rows(); ++v) {
    if (!positions_.row(v).allFinite()) {
      throw InvalidInput(detail::message("FaceVertexMesh: position of vertex ", v, " is not finite"));
    }
  }
  offsets_.resize(face_sizes_.size() + 1);
  offsets_[0] = 0;
  for (std::size_t f = 0; f < face_sizes_.size(); ++f) {
    if (face_sizes_[f] < 3) throw TopologyError(detail::message("FaceVertexMesh: face ", f, " has ", face_sizes_[f], " corners (at least 3)"));
    offsets_[f + 1] = offsets_[f] + face_sizes_[f];
  }
  if (offsets_.back() != face_indices_.size()) {
    throw TopologyError(detail::message("FaceVertexMesh: face sizes add up to ", offsets_.back(), " corners but ",
                                        face_indices_.size(), " indices are given"));
  }
  const auto vertices = static_cast<std::uint64_t>(positions_.rows());
  for (std::size_t f = 0; f < face_sizes_.size(); ++f) {
    for (std::size_t k = offsets_[f]; k < offsets_[f + 1]; ++k) {
      if (face_indices_[k] >= vertices) {
        throw TopologyError(detail::message("FaceVertexMesh: face ", f, " uses vertex ", face_indices_[k], " but there are ",
                                            vertices, " vertices"));
      }
    }
  }
}

FaceVertexMesh FaceVertexMesh::uniform(Positions positions, std::uint32_t face_size, std::vector<std::uint32_t> face_indices) {
  if (face_size < 3) throw TopologyError(detail::message("FaceVertexMesh::uniform: face size ", face_size, " (at least 3)"));
  if (face_indices.size() % face_size != 0) {
    throw TopologyError(detail::message("FaceVertexMesh::uniform: ", face_indices.size(), " indices is not a multiple of ", face_size));
  }
  std::vector<std::uint32_t> sizes(face_indices.size() / face_size, face_size);
  return FaceVertexMesh(std::move(positions), std::move(sizes), std::move(face_indices));
}

void FaceVertexMesh::validate() const {
  if (offsets_.size() != face_sizes_.size() + 1 || offsets_.back() != face_indices_.size()) {
    throw std::logic_error("FaceVertexMesh::validate: offsets do not match the face sizes");
  }
  for (std::uint32_t index : face_indices_) {
    if (index >= static_cast<std::uint64_t>(positions_.rows())) throw std::logic_error("FaceVertexMesh::validate: index out of range");
  }
}

std::optional<std::uint32_t> detail::smallest_repeated_vertex(std::span<const std::uint32_t> face) {
  std::vector<std::uint32_t> corners(face.begin(), face.end());
  std::sort(corners.begin(), corners.end());
  const auto repeated = std::adjacent_find(corners.begin(), corners.end());
  if (repeated == corners.end()) return std::nullopt;
  return *repeated;
}

}  // namespace patchwork
