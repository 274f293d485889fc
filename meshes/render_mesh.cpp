#include "meshes/render_mesh.h"

#include <cmath>

#include "core/errors.h"

namespace patchwork {
namespace {

bool finite(const auto& vector) { return vector.allFinite(); }

template <class Vector>
void check_attribute(const std::vector<Vector>& values, std::size_t vertices, const char* name) {
  if (!values.empty() && values.size() != vertices) {
    throw InvalidInput(detail::message("RenderMesh: ", values.size(), " ", name, " for ", vertices, " vertices"));
  }
  for (std::size_t v = 0; v < values.size(); ++v) {
    if (!finite(values[v])) throw InvalidInput(detail::message("RenderMesh: ", name, " of vertex ", v, " is not finite"));
  }
}

}  // namespace

void validate(const RenderMesh& mesh) {
  const std::size_t vertices = mesh.positions.size();
  if (vertices > 0xfffffffeu) throw InvalidInput(detail::message("RenderMesh: ", vertices, " vertices exceed 32-bit ids"));
  check_attribute(mesh.positions, vertices, "positions");
  check_attribute(mesh.normals, vertices, "normals");
  check_attribute(mesh.uvs, vertices, "uvs");
  check_attribute(mesh.tangents, vertices, "tangents");
  for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
    if (std::abs(mesh.normals[v].norm() - 1.0) > 1e-6) {
      throw InvalidInput(detail::message("RenderMesh: normal of vertex ", v, " has length ", mesh.normals[v].norm()));
    }
  }
  for (std::size_t v = 0; v < mesh.tangents.size(); ++v) {
    const Vec4& t = mesh.tangents[v];
    if (std::abs(t.head<3>().norm() - 1.0) > 1e-6 || std::abs(std::abs(t.w()) - 1.0) != 0.0) {
      throw InvalidInput(detail::message("RenderMesh: tangent of vertex ", v, " is not unit with w = +-1"));
    }
  }
  if (mesh.indices.size() % 3 != 0) {
    throw InvalidInput(detail::message("RenderMesh: ", mesh.indices.size(), " indices are not whole triangles"));
  }
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
    if (mesh.indices[k] >= vertices) {
      throw InvalidInput(detail::message("RenderMesh: triangle ", k / 3, " uses vertex ", mesh.indices[k], " of ",
                                         vertices));
    }
  }
  if (mesh.position_ids.size() != vertices) {
    throw InvalidInput(detail::message("RenderMesh: ", mesh.position_ids.size(), " position ids for ", vertices,
                                       " vertices"));
  }
  std::vector<std::uint32_t> first(vertices, 0xffffffffu);
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::uint32_t id = mesh.position_ids[v];
    if (id >= vertices) throw InvalidInput(detail::message("RenderMesh: vertex ", v, " has position id ", id));
    if (first[id] == 0xffffffffu) {
      first[id] = static_cast<std::uint32_t>(v);
    } else if (mesh.positions[first[id]] != mesh.positions[v]) {
      throw InvalidInput(detail::message("RenderMesh: vertices ", first[id], " and ", v, " share position id ", id,
                                         " but not their position"));
    }
  }
}

FaceVertexMesh welded_faces(const RenderMesh& mesh) {
  validate(mesh);
  // Position ids are renumbered densely in order of first use by a vertex.
  std::vector<std::uint32_t> dense(mesh.vertex_count(), 0xffffffffu);
  std::vector<std::uint32_t> representative;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    std::uint32_t& slot = dense[mesh.position_ids[v]];
    if (slot == 0xffffffffu) {
      slot = static_cast<std::uint32_t>(representative.size());
      representative.push_back(static_cast<std::uint32_t>(v));
    }
  }
  Positions positions(static_cast<Eigen::Index>(representative.size()), 3);
  for (std::size_t k = 0; k < representative.size(); ++k) {
    positions.row(static_cast<Eigen::Index>(k)) = mesh.positions[representative[k]].transpose();
  }
  std::vector<std::uint32_t> indices(mesh.indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = dense[mesh.position_ids[mesh.indices[k]]];
  return FaceVertexMesh::uniform(std::move(positions), 3, std::move(indices));
}

}  // namespace patchwork
