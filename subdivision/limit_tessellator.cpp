#include "subdivision/limit_tessellator.h"

#include <cmath>
#include <limits>

#include "core/assert.h"
#include "core/errors.h"
#include "meshes/edge_table.h"

namespace patchwork {

namespace {

// Pattern edge k of a quad runs (boundary_curve direction) from face vertex edge_from[k] to
// edge_to[k]: v0 from 0 to 1, u1 from 1 to 2, v1 from 3 to 2, u0 from 0 to 3. A Loop triangle
// as a quad: v0 from 0 to 1, u1 from 1 to 2, u0 from 0 to 2, v1 collapsed at 2.
constexpr std::array<int, 4> quad_from = {0, 1, 3, 0};
constexpr std::array<int, 4> quad_to = {1, 2, 2, 3};
constexpr std::array<int, 4> triangle_from = {0, 1, 2, 0};
constexpr std::array<int, 4> triangle_to = {1, 2, 2, 2};

// (s, t) of a piece to (u, v) of its face.
Vec2 face_parameters(bool triangle, double s, double t) { return triangle ? Vec2(s * (1.0 - t), t) : Vec2(s, t); }

}  // namespace

LimitPieces limit_pieces(const LimitSurface& surface) {
  const SubdivisionCage& base = surface.base();
  const FaceVertexMesh& mesh = base.mesh;
  const bool triangles = base.options.scheme == SubdivisionScheme::loop;
  LimitPieces result;
  std::vector<std::uint32_t> piece_of(mesh.face_count(), 0xffffffffu);
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (!surface.has_surface(f)) continue;
    piece_of[f] = static_cast<std::uint32_t>(result.piece_faces.size());
    result.piece_faces.push_back(f);
  }
  SurfacePieces& pieces = result.pieces;
  pieces.count = result.piece_faces.size();
  const auto& from = triangles ? triangle_from : quad_from;
  const auto& to = triangles ? triangle_to : quad_to;

  // Corner c of face f walks the face edge (face[k], face[k+1]); the pattern edge on it and the
  // face vertex that edge starts from.
  const detail::EdgeTable table(mesh);
  const auto corner_edge = [&](std::uint32_t c, std::uint32_t& piece, PatchEdge& edge, std::uint32_t& start) {
    const std::uint32_t f = table.face_of(c);
    const auto k = static_cast<int>(c - mesh.first_corner(f));
    const auto size = static_cast<int>(mesh.face_sizes()[f]);
    const auto face = mesh.face(f);
    // The pattern edge whose ends are face vertices k and k + 1.
    for (int e = 0; e < 4; ++e) {
      const int a = from[static_cast<std::size_t>(e)];
      const int b = to[static_cast<std::size_t>(e)];
      if (a == b) continue;
      if ((a == k && b == (k + 1) % size) || (b == k && a == (k + 1) % size)) {
        piece = piece_of[f];
        edge = static_cast<PatchEdge>(e);
        start = face[static_cast<std::size_t>(a)];
        return;
      }
    }
    PATCHWORK_ASSERT(false, "every face edge is a pattern edge");
  };
  for (std::uint32_t c = 0; c < mesh.face_indices().size(); ++c) {
    const std::uint32_t t = table.twin(c);
    if (t >= detail::EdgeTable::crowded || t < c) continue;
    if (piece_of[table.face_of(c)] == 0xffffffffu || piece_of[table.face_of(t)] == 0xffffffffu) continue;
    PieceJoin join{};
    std::uint32_t start_a = 0;
    std::uint32_t start_b = 0;
    corner_edge(c, join.first.patch, join.first.edge, start_a);
    corner_edge(t, join.second.patch, join.second.edge, start_b);
    join.reversed = start_a != start_b;
    pieces.shared.push_back(join);
  }
  if (triangles) {
    for (std::uint32_t p = 0; p < pieces.count; ++p) pieces.collapsed.push_back({p, PatchEdge::v1});
  }

  // Bounds in the piece's parameters (Loop: none known, see the header).
  pieces.bounds.resize(pieces.count);
  for (std::uint32_t p = 0; p < pieces.count; ++p) {
    constexpr double unknown = std::numeric_limits<double>::infinity();
    pieces.bounds[p] =
        triangles ? SecondDerivativeBounds{unknown, unknown, unknown} : surface.face_bounds(result.piece_faces[p]);
  }
  Eigen::AlignedBox3d box;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) box.extend(mesh.position(v));
  pieces.diagonal = box.diagonal().norm();

  const std::vector<std::uint32_t>& faces = result.piece_faces;
  pieces.evaluate = [&surface, faces, triangles](std::uint32_t p, double s, double t) {
    const Vec2 uv = face_parameters(triangles, s, t);
    return surface.position(faces[p], uv.x(), uv.y());
  };
  pieces.evaluate_points = [&surface, faces, triangles](std::uint32_t p, std::span<const double> us,
                                                        std::span<const double> vs, std::span<Vec3> points) {
    for (std::size_t k = 0; k < us.size(); ++k) {
      const Vec2 uv = face_parameters(triangles, us[k], vs[k]);
      points[k] = surface.position(faces[p], uv.x(), uv.y());
    }
  };
  pieces.evaluate_grid = [&surface, faces, triangles](std::uint32_t p, std::span<const double> us,
                                                      std::span<const double> vs, GridSamplesView out) {
    std::size_t index = 0;
    for (double t : vs) {
      for (double s : us) {
        const Vec2 uv = face_parameters(triangles, s, t);
        LimitPoint point = surface.evaluate(faces[p], uv.x(), uv.y());
        if (point.normal.isZero()) {
          // A singular point (du x dv = 0): the normal of a point just inside, towards the middle.
          const Vec2 inside = uv + 1e-7 * (Vec2(triangles ? 1.0 / 3 : 0.5, triangles ? 1.0 / 3 : 0.5) - uv);
          const LimitPoint near = surface.evaluate(faces[p], inside.x(), inside.y());
          point.normal = near.normal;
          point.du = near.du;
          point.dv = near.dv;
        }
        out.points[index] = point.position;
        out.normals[index] = point.normal;
        if (!out.tangents.empty()) {
          Vec3 tangent = point.du - point.du.dot(point.normal) * point.normal;
          tangent = tangent.norm() > 0.0 ? Vec3(tangent.normalized()) : point.normal.unitOrthogonal();
          const double w = point.normal.cross(tangent).dot(point.dv) < 0.0 ? -1.0 : 1.0;
          out.tangents[index] = Vec4(tangent.x(), tangent.y(), tangent.z(), w);
        }
        ++index;
      }
    }
  };
  return result;
}

Tessellation tessellate_limit(const LimitSurface& surface, const TessellationOptions& options) {
  if (options.camera) throw InvalidInput("tessellate_limit: the camera mode is for Bezier patch sets");
  if (surface.base().options.scheme == SubdivisionScheme::loop && !options.segments) {
    throw InvalidInput("tessellate_limit: Loop limit surfaces have no a-priori error bound here; give segments");
  }
  const LimitPieces pieces = limit_pieces(surface);
  if (pieces.pieces.count == 0) throw InvalidInput("tessellate_limit: every face is a hole");
  Tessellation result = tessellate(pieces.pieces, options);
  for (std::uint32_t& p : result.triangle_patches) p = pieces.piece_faces[p];
  return result;
}

}  // namespace patchwork
