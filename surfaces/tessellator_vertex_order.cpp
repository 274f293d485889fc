// The tessellator's last stage: triangles in vertex-cache order and vertices in fetch order
// (meshoptimizer), the triangles' pieces and the position ids carried along.

#include "surfaces/tessellator_stages.h"

#include <meshoptimizer.h>

#include <algorithm>

#include "core/huge_pages.h"

namespace patchwork::detail {

// Triangles reordered for the vertex cache, in one call over the whole mesh (a call per piece
// cost more in set-up than in work once patches are split into 16 pieces), and their patches
// along. meshoptimizer keeps each triangle (up to a rotation of its corners): each output
// triangle is found among the input triangles with its smallest corner.
void Tessellator::optimize_vertex_cache(Tessellation& result) {
  RenderMesh& mesh = result.mesh;
  const std::size_t triangles = mesh.triangle_count();
  if (triangles == 0) return;
  std::vector<std::uint32_t> reordered;
  reserve_huge(reordered, mesh.indices.size());
  reordered.resize(mesh.indices.size());
  meshopt_optimizeVertexCacheFifo(reordered.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertex_count(),
                                  16);
  const auto smallest = [](const std::uint32_t* t) { return std::min({t[0], t[1], t[2]}); };
  std::vector<std::uint32_t> first(mesh.vertex_count() + 1, 0);  // triangles by smallest corner (CSR)
  for (std::size_t t = 0; t < triangles; ++t) ++first[smallest(&mesh.indices[3 * t]) + 1];
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> by_corner(triangles);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t t = 0; t < triangles; ++t)
    by_corner[fill[smallest(&mesh.indices[3 * t])]++] = static_cast<std::uint32_t>(t);
  const auto same = [](const std::uint32_t* a, const std::uint32_t* b) {
    for (int r = 0; r < 3; ++r) {
      if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
    }
    return false;
  };
  std::vector<bool> taken(triangles, false);
  std::vector<std::uint32_t> patches(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* corners = &reordered[3 * t];
    const std::uint32_t v = smallest(corners);
    std::uint32_t source = no_id;
    for (std::uint32_t k = first[v]; k < first[v + 1]; ++k) {
      const std::uint32_t candidate = by_corner[k];
      if (!taken[candidate] && same(corners, &mesh.indices[3 * std::size_t{candidate}])) {
        source = candidate;
        break;
      }
    }
    PATCHWORK_ASSERT(source != no_id, "the vertex-cache order keeps every triangle");
    if (source == no_id) return;  // (not seen) the mesh stays in its first order, still valid
    taken[source] = true;
    patches[t] = result.triangle_patches[source];
  }
  mesh.indices = std::move(reordered);
  result.triangle_patches = std::move(patches);
}

// Vertices in order of first use by the (cache-ordered) triangles.
void Tessellator::optimize_vertex_fetch(RenderMesh& mesh) {
  if (mesh.indices.empty()) return;
  std::vector<unsigned int> remap(mesh.vertex_count());
  const std::size_t used =
      meshopt_optimizeVertexFetchRemap(remap.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertex_count());
  const auto apply = [&](auto& attribute) {
    if (attribute.empty()) return;
    std::remove_reference_t<decltype(attribute)> reordered;
    reserve_huge(reordered, used);
    reordered.resize(used);
    for (std::size_t v = 0; v < attribute.size(); ++v) {
      if (remap[v] != ~0u) reordered[remap[v]] = attribute[v];
    }
    attribute = std::move(reordered);
  };
  apply(mesh.positions);
  apply(mesh.normals);
  apply(mesh.uvs);
  apply(mesh.tangents);
  apply(mesh.position_ids);
  for (std::uint32_t& index : mesh.indices) index = remap[index];
  // Position ids renumbered densely in the new vertex order.
  std::vector<std::uint32_t> dense(mesh.vertex_count(), no_id);
  std::uint32_t next = 0;
  for (std::uint32_t& id : mesh.position_ids) {
    if (dense[id] == no_id) dense[id] = next++;
    id = dense[id];
  }
}

}  // namespace patchwork::detail
