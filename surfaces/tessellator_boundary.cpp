// The tessellator's welding and per-piece stage: one welded id per point of the surface (corners
// through shared and collapsed edges and T-junctions, edge classes, interiors), then each
// piece's boundary pattern with its welded ids, positions, normals and tangents.

#include <algorithm>
#include <span>
#include <vector>

#include "core/assert.h"
#include "core/parallel.h"
#include "core/union_find.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork::detail {

// Corners are one point where shared or collapsed edges join them; then every class's inner
// points get a block of ids, then each patch's interior.
void Tessellator::number_welded_points() {
  const auto patch_slots = static_cast<std::uint32_t>(4 * count_);
  UnionFind corners(patch_slots + junctions_);
  const auto slot = [](std::uint32_t p, int c) { return static_cast<std::uint32_t>(4 * p + c); };
  for (const PieceJoin& shared : pieces_.shared) {
    const EdgeRef a = shared.first;
    const EdgeRef b = shared.second;
    if (plans_[a.patch].culled || plans_[b.patch].culled) continue;
    const int ka = static_cast<int>(a.edge);
    const int kb = static_cast<int>(b.edge);
    corners.unite(slot(a.patch, edge_start[ka]), slot(b.patch, shared.reversed ? edge_end[kb] : edge_start[kb]));
    corners.unite(slot(a.patch, edge_end[ka]), slot(b.patch, shared.reversed ? edge_start[kb] : edge_end[kb]));
  }
  for (const EdgeRef& e : pieces_.collapsed) {
    if (plans_[e.patch].culled) continue;
    const int k = static_cast<int>(e.edge);
    corners.unite(slot(e.patch, edge_start[k]), slot(e.patch, edge_end[k]));
  }
  // A T-junction's parts meet the long edge's corners at its ends and each other at the
  // junctions between them.
  for (const CompositeEdge& composite : composites_) {
    const EdgeRef e = composite.edge;
    const int k = static_cast<int>(e.edge);
    const std::size_t last = composite.parts.size() - 1;
    for (std::size_t b = 0; b <= last; ++b) {
      if (!composite.joined[b]) continue;
      const EdgeRef part = composite.parts[b];
      const int kp = static_cast<int>(part.edge);
      const int from = composite.reversed[b] ? edge_end[kp] : edge_start[kp];
      const int to = composite.reversed[b] ? edge_start[kp] : edge_end[kp];
      corners.unite(slot(part.patch, from),
                    b == 0 ? slot(e.patch, edge_start[k])
                           : patch_slots + composite.first_junction + static_cast<std::uint32_t>(b - 1));
      corners.unite(slot(part.patch, to), b == last
                                              ? slot(e.patch, edge_end[k])
                                              : patch_slots + composite.first_junction + static_cast<std::uint32_t>(b));
    }
  }
  corner_ids_.assign(patch_slots + junctions_, no_id);
  corner_owner_.assign(patch_slots + junctions_, false);
  std::uint32_t next = 0;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    for (int c = 0; c < 4; ++c) {
      const std::uint32_t root = corners.find(slot(p, c));
      if (corner_ids_[root] == no_id) corner_ids_[root] = next++;
      corner_ids_[slot(p, c)] = corner_ids_[root];
      corner_owner_[slot(p, c)] = root == slot(p, c);
    }
  }
  // A junction's point is the long edge's own, evaluated by its patch, unless a part's corner
  // is the root of its class.
  for (std::uint32_t j = patch_slots; j < patch_slots + junctions_; ++j) {
    const std::uint32_t root = corners.find(j);
    if (corner_ids_[root] == no_id) corner_ids_[root] = next++;
    corner_ids_[j] = corner_ids_[root];
    corner_owner_[j] = root == j;
  }
  for (EdgeClass& c : classes_) {
    if (c.collapsed) continue;
    c.first_id = next;
    next += static_cast<std::uint32_t>(c.rate - 1);
  }
  boundary_ids_ = next;
  interior_first_.assign(count_, no_id);
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    const InnerGrid inner = inner_grid(rates(p));
    interior_first_[p] = next;
    next += static_cast<std::uint32_t>((inner.u - 1) * (inner.v - 1));
  }
  welded_count_ = next;
}

void PatternTable::build(int threads) {
  const std::size_t first = patterns_.size() - pending_.size();
  try {
    parallel_for(pending_.size(), threads,
                 [&](std::size_t k) { make_pattern_boundary(pending_[k], *patterns_[first + k]); });
  } catch (...) {
    index_.clear();
    patterns_.clear();
    pending_.clear();
    throw;
  }
  pending_.clear();
}

void Tessellator::assign_patterns(PatternTable& table) {
  // Old rates' patterns go before they outnumber the pieces (the outputs of the last run point
  // into the table, but every output was cleared).
  table.trim(count_ + 1024);
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    const PatternRates r = rates(p);
    const bool composite = std::any_of(r.segments.begin(), r.segments.end(), [](const EdgeSegments* s) { return s; });
    PatchOutput& out = (*outputs_)[p];
    out.pattern = composite ? &out.own_pattern : table.find_or_add(r);
  }
  try {
    table.build(options_.threads);
  } catch (...) {
    // The failed build emptied the table: no output may keep a pointer into it.
    for (PatchOutput& out : *outputs_)
      if (out.pattern != &out.own_pattern) out.pattern = nullptr;
    throw;
  }
}

// The boundary part of patch p: its points' welded ids, positions and normals, its triangles
// (kept or dropped) and the bound of the whole pattern.
void Tessellator::tessellate_patch(std::uint32_t p) {
  PatchOutput& out = (*outputs_)[p];
  const PatternRates r = rates(p);
  out.inner = inner_grid(r);
  if (out.pattern == &out.own_pattern) make_pattern_boundary(r, out.own_pattern);
  const TessellationPattern& pattern = *out.pattern;
  const std::size_t count = pattern.points.size();
  out.welded.resize(count);
  out.owner.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const PatternPoint& point = pattern.points[k];
    if (point.kind == PatternPoint::Kind::corner) {
      out.welded[k] = corner_ids_[4 * p + point.index];
      out.owner[k] = corner_owner_[4 * p + point.index];
      continue;
    }
    PATCHWORK_ASSERT(point.kind == PatternPoint::Kind::edge, "a boundary pattern lists boundary points only");
    const EdgeSlot& s = slots_[p][point.index];
    if (s.composite != no_id) {
      // Step `step` of the long edge: inside piece b, or the junction at its end.
      const CompositeEdge& composite = composites_[s.composite];
      int step = point.step;
      std::size_t b = 0;
      while (step > composite.segments.rates[b]) step -= composite.segments.rates[b++];
      if (step == composite.segments.rates[b]) {
        const std::size_t j = 4 * count_ + composite.first_junction + b;
        out.welded[k] = corner_ids_[j];
        out.owner[k] = corner_owner_[j];
      } else {
        const EdgeClass& c = classes_[composite.classes[b]];
        const int local = composite.reversed[b] ? c.rate - step : step;
        out.welded[k] = c.first_id + static_cast<std::uint32_t>(local - 1);
        out.owner[k] = c.owner == p;
      }
      continue;
    }
    const EdgeClass& c = classes_[s.edge_class];
    if (c.collapsed) {
      out.welded[k] = corner_ids_[4 * p + edge_start[point.index]];
      out.owner[k] = false;
    } else {
      const int step = s.reversed ? c.rate - point.step : point.step;
      out.welded[k] = c.first_id + static_cast<std::uint32_t>(step - 1);
      out.owner[k] = c.owner == p;
    }
  }
  evaluate_sides(p, r, out);
  // Only boundary triangles can use one welded point twice: interior points are the patch's own.
  const auto welded = [&](std::uint32_t k) {
    return k < count ? out.welded[k] : interior_first_[p] + (k - static_cast<std::uint32_t>(count));
  };
  const auto degenerate = [&](const Triangle& t) {
    return welded(t[0]) == welded(t[1]) || welded(t[1]) == welded(t[2]) || welded(t[0]) == welded(t[2]);
  };
  // The common case, no collapsed edge: every triangle is kept, and read from the pattern.
  out.all_kept = std::none_of(pattern.triangles.begin(), pattern.triangles.end(), degenerate);
  if (!out.all_kept) {
    for (const Triangle& t : pattern.triangles) (degenerate(t) ? out.dropped : out.kept).push_back(t);
    // Interior points outside the inner cells (2 segments in a direction) hang on boundary
    // triangles only, which may all be dropped.
    if (out.inner.u == 2 || out.inner.v == 2) {
      std::vector<bool> used(out.interior_points(), false);
      for (const Triangle& t : out.kept) {
        for (std::uint32_t k : t) {
          if (k >= count) used[k - count] = true;
        }
      }
      for_each_inner_triangle(out.inner, 0, [&](const Triangle& t) {
        for (std::uint32_t q : t) used[q] = true;
      });
      out.unused_interior = std::find(used.begin(), used.end(), false) != used.end();
    }
  }
  // The bound covers the whole pattern, dropped triangles included (their parameter triangles
  // map onto a mesh edge, which must be as close to the surface).
  PatchPlan& plan = plans_[p];
  out.bound = pattern.grid              ? plan.cell_bound(out.inner.u, out.inner.v)
              : plan.checked_rates == r ? plan.checked_bound
                                        : pattern_bound_of(p, r);
}

// Positions, normals (and tangents) of the boundary points, each side (with its corners) as a
// one-row grid.
void Tessellator::evaluate_sides(std::uint32_t p, const PatternRates& r, PatchOutput& out) const {
  const std::size_t count = out.pattern->points.size();
  out.positions.resize(count);
  out.normals.resize(count);
  if (options_.tangents) out.tangents.resize(count);
  if (pieces_.evaluate_samples) {
    // The boundary points' (u, v) are the sides' parameters (make_pattern_boundary takes them
    // from edge_step_parameter, as the grids below): the owned ones in one call, the rest
    // shared or evaluated by share_samples.
    thread_local std::vector<std::uint32_t> owned;
    owned.clear();
    for (std::uint32_t k = 0; k < count; ++k) {
      if (out.owner[k]) {
        owned.push_back(k);
        (*sample_owners_)[out.welded[k]] = std::uint64_t{p} << 32 | k;
      }
    }
    evaluate_points_of(p, owned, out);
    return;
  }
  // Each thread's buffers keep their storage from side to side.
  thread_local std::vector<Vec3> points;
  thread_local std::vector<Vec3> normals;
  thread_local std::vector<Vec4> tangents;
  thread_local std::vector<double> ts;
  tangents.clear();
  // Sides v0 and v1 with their corners; sides u1 and u0 without.
  for (int k = 0; k < 4; ++k) {
    const int e = r.edges[k];
    const bool along_u = k % 2 == 0;
    // The pattern's parameters: even steps, or even within each piece of a composite edge.
    ts.clear();
    for (int step = along_u ? 0 : 1; step <= (along_u ? e : e - 1); ++step)
      ts.push_back(edge_step_parameter(r, k, step));
    if (ts.empty()) continue;
    points.resize(ts.size());
    normals.resize(ts.size());
    if (options_.tangents) tangents.resize(ts.size());
    const std::array<double, 1> fixed = {k == 1 || k == 2 ? 1.0 : 0.0};
    const GridSamplesView samples{points, normals, tangents};
    if (along_u) {
      pieces_.evaluate_grid(p, ts, fixed, samples);
    } else {
      pieces_.evaluate_grid(p, fixed, ts, samples);
    }
    const std::uint32_t first = first_edge_point(r, k);
    for (std::size_t s = 0; s < ts.size(); ++s) {
      std::uint32_t point;
      if (!along_u) {
        point = first + static_cast<std::uint32_t>(s);
      } else if (s == 0) {
        point = k == 0 ? 0u : 3u;
      } else if (s + 1 == ts.size()) {
        point = k == 0 ? 1u : 2u;
      } else {
        point = first + static_cast<std::uint32_t>(s - 1);
      }
      PATCHWORK_ASSERT(point < count, "side points are boundary points");
      out.positions[point] = points[s];
      out.normals[point] = normals[s];
      if (options_.tangents) out.tangents[point] = tangents[s];
    }
  }
}

// The samples of piece p's boundary points `points` (indices into its pattern), in one
// evaluate_samples call, into out's arrays at those indices.
void Tessellator::evaluate_points_of(std::uint32_t p, std::span<const std::uint32_t> points, PatchOutput& out) const {
  if (points.empty()) return;
  thread_local std::vector<Vec2> uvs;
  thread_local std::vector<Vec3> positions;
  thread_local std::vector<Vec3> normals;
  thread_local std::vector<Vec4> tangents;
  const std::size_t n = points.size();
  uvs.resize(n);
  positions.resize(n);
  normals.resize(n);
  tangents.resize(options_.tangents ? n : 0);
  for (std::size_t i = 0; i < n; ++i) uvs[i] = out.pattern->points[points[i]].uv;
  pieces_.evaluate_samples(p, uvs, {positions, normals, tangents});
  for (std::size_t i = 0; i < n; ++i) {
    out.positions[points[i]] = positions[i];
    out.normals[points[i]] = normals[i];
    if (options_.tangents) out.tangents[points[i]] = tangents[i];
  }
}

void Tessellator::share_samples(std::uint32_t p) const {
  PatchOutput& out = (*outputs_)[p];
  thread_local std::vector<std::uint32_t> rest;
  rest.clear();
  for (std::uint32_t k = 0; k < out.boundary_points(); ++k) {
    if (out.owner[k]) continue;
    const std::uint64_t at = (*sample_owners_)[out.welded[k]];
    PATCHWORK_ASSERT(at != ~std::uint64_t{0}, "every welded boundary point has an owner");
    if (at == ~std::uint64_t{0}) {
      rest.push_back(k);
      continue;
    }
    const auto q = static_cast<std::uint32_t>(at >> 32);
    const auto j = static_cast<std::uint32_t>(at);
    const PatchOutput& owner = (*outputs_)[q];
    // The same point of the same patch (not a pole's other directions, not a closed patch's
    // other side): the owner's samples are this point's.
    if (patch_of(q) == patch_of(p) &&
        patch_parameter(q, owner.pattern->points[j].uv) == patch_parameter(p, out.pattern->points[k].uv)) {
      out.positions[k] = owner.positions[j];
      out.normals[k] = owner.normals[j];
      if (options_.tangents) out.tangents[k] = owner.tangents[j];
    } else {
      rest.push_back(k);
    }
  }
  evaluate_points_of(p, rest, out);
}

}  // namespace patchwork::detail
