#include "meshes/normals.h"

#include <cmath>

#include "core/errors.h"
#include "core/union_find.h"
#include "meshes/edge_table.h"
#include "meshes/polygon.h"

namespace patchwork {
namespace {

std::vector<Vec3> corners_of(const FaceVertexMesh& mesh, std::size_t f) {
  std::vector<Vec3> points;
  for (std::uint32_t v : mesh.face(f)) points.push_back(mesh.position(v));
  return points;
}

// The angle at corner k of face f.
double corner_angle(const FaceVertexMesh& mesh, std::size_t f, std::size_t k) {
  const auto face = mesh.face(f);
  const Vec3 v = mesh.position(face[k]);
  const Vec3 a = mesh.position(face[(k + face.size() - 1) % face.size()]) - v;
  const Vec3 b = mesh.position(face[(k + 1) % face.size()]) - v;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The weight of face f's normal at its corner k.
double corner_weight(const FaceVertexMesh& mesh, std::size_t f, std::size_t k, NormalWeighting weighting,
                     const std::vector<double>& areas) {
  switch (weighting) {
    case NormalWeighting::uniform: return 1.0;
    case NormalWeighting::angle: return corner_angle(mesh, f, k);
    case NormalWeighting::area: return areas[f];
  }
  return 1.0;
}

Vec3 normalized_or_zero(const Vec3& v) {
  const double length = v.norm();
  return length > 0.0 ? Vec3(v / length) : Vec3::Zero();
}

}  // namespace

Vec3 face_normal(const FaceVertexMesh& mesh, std::size_t f) { return normalized_or_zero(newell_normal(corners_of(mesh, f))); }

std::vector<Vec3> face_normals(const FaceVertexMesh& mesh) {
  std::vector<Vec3> normals(mesh.face_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) normals[f] = face_normal(mesh, f);
  return normals;
}

std::vector<Vec3> vertex_normals(const FaceVertexMesh& mesh, NormalWeighting weighting) {
  const std::vector<Vec3> faces = face_normals(mesh);
  std::vector<double> areas(mesh.face_count(), 0.0);
  if (weighting == NormalWeighting::area) {
    for (std::size_t f = 0; f < mesh.face_count(); ++f) areas[f] = polygon_area(corners_of(mesh, f));
  }
  std::vector<Vec3> sums(mesh.vertex_count(), Vec3::Zero());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) sums[face[k]] += corner_weight(mesh, f, k, weighting, areas) * faces[f];
  }
  for (Vec3& n : sums) n = normalized_or_zero(n);
  return sums;
}

SplitNormals split_normals(const FaceVertexMesh& mesh, double crease_angle) {
  if (!(crease_angle >= 0.0)) throw InvalidInput(detail::message("split_normals: crease angle ", crease_angle, " is negative"));
  const std::vector<Vec3> faces = face_normals(mesh);
  const detail::EdgeTable table(mesh);
  // Corners at one vertex join across a smooth edge (two faces, normals within the angle).
  UnionFind groups(mesh.face_indices().size());
  const double cos_limit = std::cos(crease_angle);
  for (std::size_t e = 0; e < table.edge_count(); ++e) {
    if (!table.has_two_uses(e)) continue;
    const auto uses = table.first_two_uses(e);
    if (faces[uses[0].face].dot(faces[uses[1].face]) < cos_limit) continue;
    for (std::uint32_t v : table.vertices(e)) {
      groups.unite(detail::corner_at(mesh, uses[0].face, v), detail::corner_at(mesh, uses[1].face, v));
    }
  }
  // A new vertex per group, numbered as the groups first appear in corner order.
  constexpr std::uint32_t none = 0xffffffffu;
  SplitNormals result;
  std::vector<std::uint32_t> indices(mesh.face_indices().size());
  std::vector<std::uint32_t> vertex_of_group(indices.size(), none);  // by the group's root corner
  std::vector<Vec3> sums;
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    for (std::size_t k = 0; k < mesh.face_sizes()[f]; ++k) {
      const auto c = static_cast<std::uint32_t>(mesh.first_corner(f) + k);
      std::uint32_t& vertex = vertex_of_group[groups.find(c)];
      if (vertex == none) {
        vertex = static_cast<std::uint32_t>(result.source_vertex.size());
        result.source_vertex.push_back(mesh.face_indices()[c]);
        sums.push_back(Vec3::Zero());
      }
      indices[c] = vertex;
      sums[vertex] += corner_angle(mesh, f, k) * faces[f];
    }
  }
  // Isolated vertices are dropped: a split mesh holds only what faces use.
  result.mesh = FaceVertexMesh(mesh.positions()(result.source_vertex, Eigen::all), mesh.face_sizes(), std::move(indices));
  for (Vec3& n : sums) result.normals.push_back(normalized_or_zero(n));
  return result;
}

}  // namespace patchwork
