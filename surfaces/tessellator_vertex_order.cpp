// The tessellator's last stage: triangles in vertex-cache order and vertices in fetch order
// (meshoptimizer), the triangles' pieces and the position ids carried along.

#include "surfaces/tessellator_stages.h"

#include <meshoptimizer.h>

#include <algorithm>

#include "core/huge_pages.h"
#include "core/parallel.h"

namespace patchwork::detail {

namespace {

// Triangles per vertex-cache chunk. Chunks are ordered on their own, in parallel; the order
// depends on this size only, never on the threads. A chunk boundary costs a few cache misses
// (a 16-entry FIFO refills) against 2^16 triangles of work, and a mesh of fewer triangles is
// one chunk, as when the order was one call over the whole mesh.
constexpr std::size_t vertex_cache_chunk = std::size_t{1} << 16;

// Elements per block of the parallel copies in the vertex-fetch order.
constexpr std::size_t fetch_block = std::size_t{1} << 16;

// Triangles [begin, end) of `mesh` in vertex-cache order into `order.indices` (same places),
// their patches into `order.patches`. The vertices of a chunk that is not the whole mesh are
// numbered in order of first use, so that meshoptimizer's tables are the chunk's size, not the
// mesh's (a whole mesh keeps its numbering: the order is then the one call's of before).
// meshoptimizer keeps each triangle (up to a rotation of its corners): each output triangle is
// found among the chunk's input triangles with its smallest corner (the k-th copy of a triangle
// takes the k-th one's patch).
void order_chunk(const Tessellation& result, std::size_t begin, std::size_t end, VertexOrderScratch& order,
                 VertexOrderScratch::Chunk& chunk) {
  const std::vector<std::uint32_t>& indices = result.mesh.indices;
  const std::size_t triangles = end - begin;
  const bool whole = triangles == result.mesh.triangle_count();
  std::size_t vertices = result.mesh.vertex_count();
  if (!whole) {
    // Sized first: nothing throws while `local` holds the chunk's numbering.
    chunk.global.clear();
    chunk.global.reserve(3 * triangles);
    chunk.indices.resize(3 * triangles);
    for (std::size_t k = 0; k < 3 * triangles; ++k) {
      const std::uint32_t g = indices[3 * begin + k];
      if (chunk.local[g] == no_id) {
        chunk.local[g] = static_cast<std::uint32_t>(chunk.global.size());
        chunk.global.push_back(g);
      }
      chunk.indices[k] = chunk.local[g];
    }
    vertices = chunk.global.size();
    for (const std::uint32_t g : chunk.global) chunk.local[g] = no_id;
  }
  const std::uint32_t* input = whole ? indices.data() : chunk.indices.data();
  const auto global = [&](std::uint32_t v) { return whole ? v : chunk.global[v]; };
  chunk.reordered.resize(3 * triangles);
  meshopt_optimizeVertexCacheFifo(chunk.reordered.data(), input, 3 * triangles, vertices, 16);
  const auto smallest = [](const std::uint32_t* t) { return std::min({t[0], t[1], t[2]}); };
  chunk.first.assign(vertices + 1, 0);  // triangles by smallest corner (CSR)
  for (std::size_t t = 0; t < triangles; ++t) ++chunk.first[smallest(&input[3 * t]) + 1];
  for (std::size_t v = 0; v < vertices; ++v) chunk.first[v + 1] += chunk.first[v];
  chunk.by_corner.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t)
    chunk.by_corner[chunk.first[smallest(&input[3 * t])]++] = static_cast<std::uint32_t>(t);
  // The fill moved each start to the next one's: shift back.
  for (std::size_t v = vertices; v > 0; --v) chunk.first[v] = chunk.first[v - 1];
  chunk.first[0] = 0;
  const auto same = [](const std::uint32_t* a, const std::uint32_t* b) {
    for (int r = 0; r < 3; ++r) {
      if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
    }
    return false;
  };
  chunk.taken.assign(triangles, 0);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* corners = &chunk.reordered[3 * t];
    const std::uint32_t v = smallest(corners);
    std::uint32_t source = no_id;
    for (std::uint32_t k = chunk.first[v]; k < chunk.first[v + 1]; ++k) {
      const std::uint32_t candidate = chunk.by_corner[k];
      if (chunk.taken[candidate] == 0 && same(corners, &input[3 * std::size_t{candidate}])) {
        source = candidate;
        break;
      }
    }
    PATCHWORK_ASSERT(source != no_id, "the vertex-cache order keeps every triangle");
    if (source == no_id) {  // (not seen) the chunk keeps its first order, still valid
      std::copy(indices.begin() + static_cast<std::ptrdiff_t>(3 * begin),
                indices.begin() + static_cast<std::ptrdiff_t>(3 * end),
                order.indices.begin() + static_cast<std::ptrdiff_t>(3 * begin));
      std::copy(result.triangle_patches.begin() + static_cast<std::ptrdiff_t>(begin),
                result.triangle_patches.begin() + static_cast<std::ptrdiff_t>(end),
                order.patches.begin() + static_cast<std::ptrdiff_t>(begin));
      return;
    }
    chunk.taken[source] = 1;
    order.patches[begin + t] = result.triangle_patches[begin + source];
    for (int r = 0; r < 3; ++r) order.indices[3 * (begin + t) + static_cast<std::size_t>(r)] = global(corners[r]);
  }
}

}  // namespace

// Triangles reordered for the vertex cache, and their patches along: one meshoptimizer call
// per chunk of vertex_cache_chunk consecutive triangles, chunks in parallel. (A call per piece
// cost more in set-up than in work once patches are split into 16 pieces; one call over a whole
// scene was a serial stage of a frame.)
void Tessellator::optimize_vertex_cache(Tessellation& result, VertexOrderScratch& order, int threads) {
  RenderMesh& mesh = result.mesh;
  const std::size_t triangles = mesh.triangle_count();
  if (triangles == 0) return;
  resize_keeping_storage(order.indices, mesh.indices.size());
  resize_keeping_storage(order.patches, triangles);
  const std::size_t chunks = (triangles + vertex_cache_chunk - 1) / vertex_cache_chunk;
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(thread_count(threads)), chunks);
  order.chunks.resize(std::max(order.chunks.size(), workers));
  // Worker w takes chunks w, w + workers, ...: each has its own tables.
  parallel_for(workers, threads, [&](std::size_t w) {
    VertexOrderScratch::Chunk& chunk = order.chunks[w];
    if (chunks > 1 && chunk.local.size() < mesh.vertex_count()) chunk.local.resize(mesh.vertex_count(), no_id);
    for (std::size_t c = w; c < chunks; c += workers) {
      order_chunk(result, c * vertex_cache_chunk, std::min(triangles, (c + 1) * vertex_cache_chunk), order, chunk);
    }
  });
  std::swap(mesh.indices, order.indices);
  std::swap(result.triangle_patches, order.patches);
}

// Vertices in order of first use by the (cache-ordered) triangles. The order is one pass; the
// copies into it run in parallel blocks.
void Tessellator::optimize_vertex_fetch(RenderMesh& mesh, VertexOrderScratch& order, int threads) {
  if (mesh.indices.empty()) return;
  const std::size_t vertices = mesh.vertex_count();
  resize_keeping_storage(order.remap, vertices);
  const std::size_t used =
      meshopt_optimizeVertexFetchRemap(order.remap.data(), mesh.indices.data(), mesh.indices.size(), vertices);
  const std::vector<std::uint32_t>& remap = order.remap;
  const bool with_uvs = !mesh.uvs.empty();
  const bool with_tangents = !mesh.tangents.empty();
  resize_keeping_storage(order.positions, used);
  resize_keeping_storage(order.normals, used);
  resize_keeping_storage(order.uvs, with_uvs ? used : 0);
  resize_keeping_storage(order.tangents, with_tangents ? used : 0);
  resize_keeping_storage(order.position_ids, used);
  const auto blocks = [](std::size_t n) { return (n + fetch_block - 1) / fetch_block; };
  parallel_for(blocks(vertices), threads, [&](std::size_t b) {
    const std::size_t end = std::min(vertices, (b + 1) * fetch_block);
    for (std::size_t v = b * fetch_block; v < end; ++v) {
      const std::uint32_t to = remap[v];
      if (to == ~0u) continue;
      order.positions[to] = mesh.positions[v];
      order.normals[to] = mesh.normals[v];
      if (with_uvs) order.uvs[to] = mesh.uvs[v];
      if (with_tangents) order.tangents[to] = mesh.tangents[v];
      order.position_ids[to] = mesh.position_ids[v];
    }
  });
  std::swap(mesh.positions, order.positions);
  std::swap(mesh.normals, order.normals);
  std::swap(mesh.uvs, order.uvs);
  std::swap(mesh.tangents, order.tangents);
  std::swap(mesh.position_ids, order.position_ids);
  parallel_for(blocks(mesh.indices.size()), threads, [&](std::size_t b) {
    const std::size_t end = std::min(mesh.indices.size(), (b + 1) * fetch_block);
    for (std::size_t k = b * fetch_block; k < end; ++k) mesh.indices[k] = remap[mesh.indices[k]];
  });
  // Position ids renumbered densely in the new vertex order.
  order.dense.assign(vertices, no_id);
  std::uint32_t next = 0;
  for (std::uint32_t& id : mesh.position_ids) {
    if (order.dense[id] == no_id) order.dense[id] = next++;
    id = order.dense[id];
  }
}

}  // namespace patchwork::detail
