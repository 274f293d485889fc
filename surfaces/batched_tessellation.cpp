#include "surfaces/batched_tessellation.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <string_view>
#include <utility>

#include "core/errors.h"
#include "core/huge_pages.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace {

// `parts`' arrays `member` end to end in `merged`, each part's freed (and its pages given back)
// once copied, so the peak is the parts and what of `merged` is written so far, not both whole. `shift(k, value)` maps
// part k's values.
template <class T, class Member, class Shift>
void append_parts(std::vector<RenderMesh>& parts, Member member, std::vector<T>& merged, const Shift& shift) {
  std::size_t total = 0;
  for (const RenderMesh& part : parts) total += (part.*member).size();
  merged.clear();
  reserve_huge(merged, total);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    std::vector<T>& values = parts[k].*member;
    for (const T& value : values) merged.push_back(shift(k, value));
    std::vector<T>().swap(values);
    return_free_memory();
  }
}

}  // namespace

std::vector<std::vector<std::uint32_t>> tessellation_batches(const PatchSet& set, std::size_t batch_patches) {
  if (batch_patches == 0) throw InvalidInput("tessellation_batches: a batch of 0 patches");
  std::vector<std::vector<std::uint32_t>> batches;
  std::vector<std::uint32_t> batch;
  for (Shell& shell : shells(set)) {
    batch.insert(batch.end(), shell.patches.begin(), shell.patches.end());
    if (batch.size() >= batch_patches) {
      std::sort(batch.begin(), batch.end());
      batches.push_back(std::move(batch));
      batch.clear();
    }
  }
  if (!batch.empty()) {
    std::sort(batch.begin(), batch.end());
    batches.push_back(std::move(batch));
  }
  return batches;
}

Tessellation tessellate_in_batches(const PatchSet& set, const TessellationOptions& options, std::size_t batch_patches) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<std::uint32_t>> batches = tessellation_batches(set, batch_patches);
  if (batches.size() == 1 || options.camera || options.uv == UvMode::atlas) return tessellate(set, options);
  // Bad options are reported as the single run reports them, not as a batch's.
  detail::check_options(options);
  TessellationOptions batch_options = options;
  if (options.relative_tolerance) {
    // What the tessellator computes for the whole set (a relative tolerance is of its tight box).
    batch_options.relative_tolerance.reset();
    batch_options.tolerance =
        detail::relative_tolerance_times(*options.relative_tolerance, detail::tight_or_control_diagonal(set, true));
  }
  Tessellation result;
  std::vector<RenderMesh> parts;
  parts.reserve(batches.size());
  std::vector<std::vector<std::uint32_t>> patches_of_parts;
  patches_of_parts.reserve(batches.size());
  // The budget is checked on the tessellator's triangle estimate, as in the single run, summed
  // over the batches: a batch may have what the estimates of the batches before leave of
  // max_triangles (each batch's estimate is of its own split, so the sum can differ a little
  // from the single run's estimate).
  double estimated = 0.0;
  // One Tessellation for every batch, so its scratch (patterns, per-piece arrays) keeps its
  // storage from batch to batch; each batch's mesh is moved out of it.
  Tessellation work;
  set.for_each_subset(batches, [&](std::size_t b, const PatchSet& subset) {
    batch_options.max_triangles = options.max_triangles - static_cast<std::int64_t>(estimated);
    try {
      const PreparedSurface prepared(subset);
      tessellate(prepared, batch_options, work);
    } catch (const InvalidInput& error) {
      std::string_view what = error.what();
      if (what.starts_with("tessellate: ")) what.remove_prefix(12);
      throw InvalidInput(detail::message("tessellate: batch ", b + 1, " of ", batches.size(), " (", batches[b].size(),
                                         " patches from patch ", batches[b].front(),
                                         " of the set, numbered from 0 in the batch; the batches before need about ",
                                         static_cast<std::int64_t>(estimated), " of the ", options.max_triangles,
                                         " triangles allowed): ", what));
    }
    estimated += work.scratch.get().estimated_triangles;
    result.tolerance = std::max(result.tolerance, work.tolerance);
    result.error_bound = std::max(result.error_bound, work.error_bound);
    result.weld_gap = std::max(result.weld_gap, work.weld_gap);
    result.measured_error = std::max(result.measured_error, work.measured_error);
    result.measure_seconds += work.measure_seconds;
    result.culled_patches += work.culled_patches;
    result.culled_triangles += work.culled_triangles;
    result.welded_vertices += work.welded_vertices;
    for (std::uint32_t& patch : work.triangle_patches) patch = batches[b][patch];
    patches_of_parts.push_back(std::move(work.triangle_patches));
    work.triangle_patches = {};
    parts.push_back(std::move(work.mesh));
    work.mesh = RenderMesh();
  });
  work = Tessellation();
  // The parts' first vertices and position ids.
  std::vector<std::uint32_t> first_vertex(parts.size(), 0);
  std::vector<std::uint32_t> first_id(parts.size(), 0);
  std::size_t vertices = 0;
  std::size_t ids = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    first_vertex[k] = static_cast<std::uint32_t>(vertices);
    first_id[k] = static_cast<std::uint32_t>(ids);
    vertices += parts[k].vertex_count();
    ids += parts[k].position_ids.empty() ? 0 : 1 + *std::max_element(parts[k].position_ids.begin(), parts[k].position_ids.end());
    if (vertices > 0xfffffffeu) {
      throw InvalidInput(detail::message("tessellate: ", vertices, " vertices exceed 32-bit indices"));
    }
  }
  const auto same = [](std::size_t, const auto& value) { return value; };
  RenderMesh& mesh = result.mesh;
  append_parts(parts, &RenderMesh::positions, mesh.positions, same);
  append_parts(parts, &RenderMesh::normals, mesh.normals, same);
  append_parts(parts, &RenderMesh::uvs, mesh.uvs, same);
  append_parts(parts, &RenderMesh::tangents, mesh.tangents, same);
  append_parts(parts, &RenderMesh::position_ids, mesh.position_ids,
               [&](std::size_t k, std::uint32_t id) { return id + first_id[k]; });
  append_parts(parts, &RenderMesh::indices, mesh.indices,
               [&](std::size_t k, std::uint32_t index) { return index + first_vertex[k]; });
  std::size_t total_triangles = 0;
  for (const std::vector<std::uint32_t>& patches : patches_of_parts) total_triangles += patches.size();
  reserve_huge(result.triangle_patches, total_triangles);
  for (std::vector<std::uint32_t>& patches : patches_of_parts) {
    result.triangle_patches.insert(result.triangle_patches.end(), patches.begin(), patches.end());
    std::vector<std::uint32_t>().swap(patches);
  }
  result.tessellation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result.measure_seconds;
  return result;
}

}  // namespace patchwork
