// The tessellator's assembly: boundary points to render vertices (split where attributes differ),
// the weld gap, blocks of vertices and triangles per piece, and the interiors and triangles
// written in parallel straight into the mesh (streaming stores for large outputs).

#include "surfaces/tessellator_stages.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/assert.h"
#include "core/errors.h"
#include "core/huge_pages.h"
#include "core/parallel.h"
#include "core/streaming_store.h"

namespace patchwork::detail {

Vec2 Tessellator::uv_of(std::uint32_t p, Vec2 uv) const {
  std::size_t patches = count_;
  if (!pieces_.domains.empty()) {
    const SurfacePieces::Domain& domain = pieces_.domains[p];
    uv = Vec2(domain.u0, domain.v0) + domain.size * uv;
    patches = pieces_.patch_count;
  }
  if (options_.uv != UvMode::atlas) return uv;
  // Patches in a grid of equal cells, each inset by a gutter of 2% of the cell.
  const std::uint32_t patch = patch_of(p);
  const auto columns = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(patches))));
  const std::size_t rows = (patches + columns - 1) / columns;
  const Vec2 cell(1.0 / static_cast<double>(columns), 1.0 / static_cast<double>(rows));
  const Vec2 origin(static_cast<double>(patch % columns) * cell.x(), static_cast<double>(patch / columns) * cell.y());
  return origin + 0.02 * cell + 0.96 * uv.cwiseProduct(cell);
}

// The mesh in three steps. (1) The boundary points of every patch become render vertices, in
// patch order: a welded point becomes several vertices only where its attributes differ
// between the patches around it. (2) Every patch gets a block of vertices for its interior
// points and a block of triangles, so (3) the patches write their interiors and triangles in
// parallel, straight into the mesh. `result`'s arrays are reused (resized, not reallocated,
// when they have room).
void Tessellator::assemble(Tessellation& result) {
  // Boundary welded ids come before every interior one (number_welded_points).
  std::uint32_t interior_base = welded_count_;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (!plans_[p].culled) interior_base = std::min(interior_base, interior_first_[p]);
  }
  welded_positions_ = &result.scratch.get().welded_positions;
  welded_positions_->assign(interior_base, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  // Each welded point has one owning patch (number_welded_points: the root of its corner class,
  // or its edge class's owner), so the patches write their points in parallel.
  parallel_for(count_, options_.threads, [&](std::size_t p) {
    const PatchOutput& out = (*outputs_)[p];
    for (std::size_t k = 0; k < out.welded.size(); ++k) {
      if (out.owner[k]) (*welded_positions_)[out.welded[k]] = out.positions[k];
    }
  });
  // A welded point takes its owner's position; where the patches' edges differ (PatchSet joins
  // edges whose control points agree within its tolerance) that moves it off this patch's own
  // surface point. Every mesh point of a triangle is an affine combination of its corners, so
  // it moves by at most the largest corner move: |S - L'| <= bound + max |d|.
  parallel_for(count_, options_.threads, [&](std::size_t p) {
    PatchOutput& out = (*outputs_)[p];
    double moved = 0.0;
    for (std::size_t k = 0; k < out.welded.size(); ++k) {
      if (out.owner[k]) continue;
      // A welded point without an owner would be NaN: never let it pass as a finite gap.
      const double d = ((*welded_positions_)[out.welded[k]] - out.positions[k]).norm();
      if (!(d <= moved)) moved = d;
    }
    PATCHWORK_ASSERT(std::isfinite(moved), "every welded point has a position");
    out.weld_gap = moved;
  });
  // (1) Boundary vertices, chained per welded point: first_vertex[id] -> next_vertex[...] -> ...
  // At a pole hundreds of points share one welded id, and a vertex can only serve points with
  // its UV, so there the chains are per (id, UV), their heads in a hash table. A vertex is known
  // by the boundary point it was made from; its attributes are copied once the mesh has its size.
  detail::TessellatorScratch& scratch = result.scratch.get();
  std::vector<VertexSource>& sources = scratch.sources;
  std::size_t boundary_points = 0;
  for (const PatchOutput& out : *outputs_) boundary_points += out.boundary_points();
  sources.clear();
  sources.reserve(boundary_points);
  std::vector<std::uint8_t>& pole = scratch.pole;
  pole.assign(interior_base, 0);
  for (const EdgeRef& e : pieces_.collapsed) {
    if (!plans_[e.patch].culled) pole[corner_ids_[4 * e.patch + edge_start[static_cast<int>(e.edge)]]] = 1;
  }
  std::size_t pole_points = 0;
  for (const PatchOutput& out : *outputs_) {
    for (const std::uint32_t id : out.welded) pole_points += pole[id];
  }
  detail::ChainHeads& heads = scratch.heads;
  heads.reset(pole_points);
  std::vector<std::uint32_t>& first_vertex = scratch.first_vertex;
  first_vertex.assign(interior_base, no_id);
  std::vector<std::uint32_t>& next_vertex = scratch.next_vertex;
  next_vertex.clear();
  next_vertex.reserve(boundary_points);
  std::vector<std::uint32_t>& dense_position = scratch.dense_position;
  dense_position.assign(interior_base, no_id);
  std::uint32_t positions_used = 0;
  const double cos_crease = std::cos(options_.crease_angle);
  const bool with_uv = options_.uv != UvMode::none;
  bool unused_interior = false;
  double error_bound = 0.0;
  double weld_gap = 0.0;
  double tolerance = 0.0;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    PatchOutput& out = (*outputs_)[p];
    error_bound = std::max(error_bound, out.bound + out.weld_gap);
    weld_gap = std::max(weld_gap, out.weld_gap);
    tolerance = std::max(tolerance, plans_[p].tolerance);
    unused_interior = unused_interior || out.unused_interior;
    out.vertex.assign(out.boundary_points(), no_id);
    const auto vertex = [&](std::uint32_t k) {
      const std::uint32_t id = out.welded[k];
      const Vec2 uv = with_uv ? uv_of(p, out.pattern->points[k].uv) : Vec2::Zero();
      std::uint32_t& head = pole[id] != 0 ? heads.head(id, uv) : first_vertex[id];
      for (std::uint32_t v = head; v != no_id; v = next_vertex[v]) {
        const PatchOutput& other = (*outputs_)[sources[v].patch];
        const std::uint32_t j = sources[v].point;
        const bool same =
            other.normals[j].dot(out.normals[k]) >= cos_crease &&
            (!with_uv || uv_of(sources[v].patch, other.pattern->points[j].uv) == uv) &&
            (!options_.tangents || (other.tangents[j].w() == out.tangents[k].w() &&
                                    other.tangents[j].head<3>().dot(out.tangents[k].head<3>()) >= cos_crease));
        if (same) return v;
      }
      const auto v = static_cast<std::uint32_t>(sources.size());
      if (dense_position[id] == no_id) dense_position[id] = positions_used++;
      sources.push_back({p, k, dense_position[id]});
      next_vertex.push_back(head);
      head = v;
      return v;
    };
    for (const Triangle& t : out.kept_triangles()) {
      for (std::uint32_t k : t) {
        if (k < out.boundary_points() && out.vertex[k] == no_id) out.vertex[k] = vertex(k);
      }
    }
  }
  // (2) Blocks of vertices and triangles.
  std::size_t vertices = sources.size();
  std::size_t triangles = 0;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    PatchOutput& out = (*outputs_)[p];
    out.first_vertex = static_cast<std::uint32_t>(vertices);
    out.first_triangle = triangles;
    vertices += out.interior_points();
    triangles += out.triangle_count();
  }
  if (vertices > 0xfffffffeu) {
    throw InvalidInput(detail::message("tessellate: ", vertices, " vertices exceed 32-bit indices"));
  }
  result.culled_patches = culled_;
  result.culled_triangles = culled_triangles_;
  result.error_bound = error_bound;
  result.weld_gap = weld_gap;
  result.tolerance = tolerance;
  result.measured_error = 0.0;
  RenderMesh& mesh = result.mesh;
  const auto resize = [](auto& array, std::size_t size) { resize_keeping_storage(array, size); };
  resize(mesh.positions, vertices);
  resize(mesh.normals, vertices);
  resize(mesh.uvs, with_uv ? vertices : 0);
  resize(mesh.tangents, options_.tangents ? vertices : 0);
  resize(mesh.position_ids, vertices);
  resize(mesh.indices, 3 * triangles);
  resize(result.triangle_patches, triangles);
  for (std::size_t v = 0; v < sources.size(); ++v) {
    const VertexSource& source = sources[v];
    const PatchOutput& out = (*outputs_)[source.patch];
    mesh.positions[v] = (*welded_positions_)[out.welded[source.point]];
    mesh.normals[v] = out.normals[source.point];
    if (with_uv) mesh.uvs[v] = uv_of(source.patch, out.pattern->points[source.point].uv);
    if (options_.tangents) mesh.tangents[v] = out.tangents[source.point];
    mesh.position_ids[v] = source.position_id;
  }
  for (PatchOutput& out : *outputs_) {
    out.positions.clear();
    out.normals.clear();
    out.tangents.clear();
  }
  // (3) Interiors and triangles, in parallel. Interior positions get ids after the boundary's,
  // in welded order.
  const std::size_t output_bytes =
      vertices * (2 * sizeof(Vec3) + (with_uv ? sizeof(Vec2) : 0) + sizeof(std::uint32_t)) +
      triangles * 4 * sizeof(std::uint32_t);
  streaming_ = options_.streaming_stores.value_or(output_bytes >= streamed_output_bytes);
  parallel_for(count_, options_.threads, [&](std::size_t q) {
    const auto p = static_cast<std::uint32_t>(q);
    if (!plans_[p].culled) write_patch(p, mesh, result.triangle_patches, positions_used - interior_base);
  });
  result.welded_vertices = positions_used + (welded_count_ - interior_base);
  unused_interior_ = unused_interior;
}

// Patch p's interior vertices and all its triangles, into their blocks of `mesh`.
// The regular parts go out a row at a time from small buffers, with streaming stores where
// the output is far larger than the caches (streaming_, core/streaming_store.h).
void Tessellator::write_patch(std::uint32_t p, RenderMesh& mesh, std::vector<std::uint32_t>& triangle_patches,
                 std::uint32_t position_offset) const {
  static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 is two packed doubles");
  const bool stream = streaming_;
  const auto put = [stream](void* destination, const void* source, std::size_t bytes) {
    if (stream) {
      stream_copy(destination, source, bytes);
    } else if (bytes > 0) {
      std::memcpy(destination, source, bytes);
    }
  };
  const PatchOutput& out = (*outputs_)[p];
  const std::size_t interior = out.interior_points();
  // Each thread's buffers keep their storage from piece to piece (a frame writes thousands).
  thread_local std::vector<double> us;
  thread_local std::vector<double> vs;
  thread_local std::vector<std::uint32_t> ids;
  thread_local std::vector<double> uvs;
  thread_local std::vector<std::uint32_t> first_row;
  thread_local std::vector<std::uint32_t> cells;
  if (interior > 0) {
    const std::size_t first = out.first_vertex;
    ramp(1, out.inner.u - 1, out.inner.u, us);
    ramp(1, out.inner.v - 1, out.inner.v, vs);
    const std::span<Vec4> tangents =
        options_.tangents ? std::span<Vec4>(mesh.tangents).subspan(first, interior) : std::span<Vec4>();
    pieces_.evaluate_grid(p, us, vs,
                          {std::span<Vec3>(mesh.positions).subspan(first, interior),
                           std::span<Vec3>(mesh.normals).subspan(first, interior), tangents, stream});
    const std::size_t row = us.size();
    const std::uint32_t position = interior_first_[p] + position_offset;
    ids.resize(row);
    for (std::size_t j = 0; j < vs.size(); ++j) {
      for (std::size_t k = 0; k < row; ++k) ids[k] = position + static_cast<std::uint32_t>(j * row + k);
      put(mesh.position_ids.data() + first + j * row, ids.data(), row * sizeof(std::uint32_t));
    }
    if (options_.uv != UvMode::none) {
      // uv_of is affine in (u, v).
      const Vec2 origin = uv_of(p, Vec2(0, 0));
      const Vec2 scale = uv_of(p, Vec2(1, 1)) - origin;
      uvs.resize(2 * row);
      for (std::size_t k = 0; k < row; ++k) uvs[2 * k] = origin.x() + scale.x() * us[k];
      for (std::size_t j = 0; j < vs.size(); ++j) {
        const double y = origin.y() + scale.y() * vs[j];
        for (std::size_t k = 0; k < row; ++k) uvs[2 * k + 1] = y;
        put(mesh.uvs.data() + first + j * row, uvs.data(), row * sizeof(Vec2));
      }
    }
  }
  const std::uint32_t boundary = out.boundary_points();
  const std::uint32_t interior_shift = out.first_vertex - boundary;
  std::uint32_t* index = mesh.indices.data() + 3 * out.first_triangle;
  for (const Triangle& t : out.kept_triangles()) {
    for (std::uint32_t k : t) *index++ = k < boundary ? out.vertex[k] : k + interior_shift;
  }
  // The inner cells row by row: each row's indices are the first row's shifted by the points
  // of a row (for_each_inner_triangle's numbering).
  if (out.inner.u > 2 && out.inner.v > 2) {
    first_row.clear();
    for_each_inner_triangle({out.inner.u, 3, out.inner.grid}, out.first_vertex,
                            [&](const Triangle& t) { first_row.insert(first_row.end(), t.begin(), t.end()); });
    cells.resize(first_row.size());
    const auto points_per_row = static_cast<std::uint32_t>(out.inner.u - 1);
    for (int j = 0; j + 2 < out.inner.v; ++j) {
      const std::uint32_t shift = points_per_row * static_cast<std::uint32_t>(j);
      for (std::size_t k = 0; k < cells.size(); ++k) cells[k] = first_row[k] + shift;
      put(index, cells.data(), cells.size() * sizeof(std::uint32_t));
      index += cells.size();
    }
  }
  PATCHWORK_ASSERT(index == mesh.indices.data() + 3 * (out.first_triangle + out.triangle_count()),
                   "every triangle of the patch written");
  ids.assign(std::min<std::size_t>(out.triangle_count(), 1024), patch_of(p));
  for (std::size_t t = 0; t < out.triangle_count(); t += ids.size()) {
    put(triangle_patches.data() + out.first_triangle + t, ids.data(),
        std::min(ids.size(), out.triangle_count() - t) * sizeof(std::uint32_t));
  }
  if (stream) stream_fence();
}

}  // namespace patchwork::detail
