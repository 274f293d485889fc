#include "surfaces/batched_tessellation.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <string_view>
#include <utility>

#include "core/assert.h"
#include "core/errors.h"
#include "core/huge_pages.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace {

// `from`, each value mapped by `shift`, appended to `to`, which is reserved for `expected` values
// when it is first written to (the first batch's share scaled to the whole set; room that is never
// written takes no memory). Where `to` has no room all the same, it is made anew with twice the
// room (huge pages advised; its old storage freed at once): the peak is then the arrays plus one
// array's old storage, never a second mesh.
template <class T, class Shift>
void append_shifted(std::vector<T>& to, const std::vector<T>& from, double expected, const Shift& shift) {
  if (to.capacity() - to.size() < from.size()) {
    std::vector<T> grown;
    const auto first = static_cast<std::size_t>(to.empty() ? expected : 0.0);
    reserve_huge(grown, std::max({2 * to.capacity(), to.size() + from.size(), first}));
    grown.insert(grown.end(), to.begin(), to.end());
    to.swap(grown);
  }
  for (const T& value : from) to.push_back(shift(value));
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
  RenderMesh& mesh = result.mesh;
  // The budget is checked on the tessellator's triangle estimate, as in the single run, summed
  // over the batches: a batch may have what the estimates of the batches before leave of
  // max_triangles (each batch's estimate is of its own split, so the sum can differ a little
  // from the single run's estimate).
  double estimated = 0.0;
  std::size_t welded = 0;  // position ids before the batch
  // One Tessellation for every batch, so its arrays and scratch (patterns, per-piece arrays)
  // keep their storage from batch to batch; each batch's mesh is appended to the result's.
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
    const std::size_t first_vertex = mesh.vertex_count();
    if (first_vertex + work.mesh.vertex_count() > 0xfffffffeu) {
      throw InvalidInput(
          detail::message("tessellate: ", first_vertex + work.mesh.vertex_count(), " vertices exceed 32-bit indices"));
    }
    const std::vector<std::uint32_t>& ids = work.mesh.position_ids;
    // The batch's position ids are 0 .. welded_vertices - 1 (Tessellation::welded_vertices).
    PATCHWORK_ASSERT(ids.empty() || *std::max_element(ids.begin(), ids.end()) < work.welded_vertices,
                     "position ids below the welded count");
    // The whole set's arrays, guessed from this batch's (a quarter more than its share; only a
    // guess: the arrays grow past it if they must).
    const double share = 1.25 * static_cast<double>(set.count()) / static_cast<double>(batches[b].size());
    const auto expected = [&](const auto& array) { return share * static_cast<double>(array.size()); };
    const auto same = [](const auto& value) { return value; };
    append_shifted(mesh.positions, work.mesh.positions, expected(work.mesh.positions), same);
    append_shifted(mesh.normals, work.mesh.normals, expected(work.mesh.normals), same);
    append_shifted(mesh.uvs, work.mesh.uvs, expected(work.mesh.uvs), same);
    append_shifted(mesh.tangents, work.mesh.tangents, expected(work.mesh.tangents), same);
    append_shifted(mesh.position_ids, ids, expected(ids),
                   [&](std::uint32_t id) { return id + static_cast<std::uint32_t>(welded); });
    append_shifted(mesh.indices, work.mesh.indices, expected(work.mesh.indices),
                   [&](std::uint32_t index) { return index + static_cast<std::uint32_t>(first_vertex); });
    append_shifted(result.triangle_patches, work.triangle_patches, expected(work.triangle_patches),
                   [&](std::uint32_t patch) { return batches[b][patch]; });
    welded += work.welded_vertices;
    result.tolerance = std::max(result.tolerance, work.tolerance);
    result.error_bound = std::max(result.error_bound, work.error_bound);
    result.weld_gap = std::max(result.weld_gap, work.weld_gap);
    result.measured_error = std::max(result.measured_error, work.measured_error);
    result.measure_seconds += work.measure_seconds;
    result.culled_patches += work.culled_patches;
    result.culled_triangles += work.culled_triangles;
  });
  result.welded_vertices = welded;
  result.tessellation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result.measure_seconds;
  return result;
}

}  // namespace patchwork
