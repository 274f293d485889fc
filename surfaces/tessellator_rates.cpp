// The tessellator's first stage: every piece's inner rates from its tolerance (the view's, with a
// camera, and the culling), one rate per edge class, composite edges at T-junctions, and the
// rates raised until every stitched pattern meets its tolerance (surfaces/tessellator.h).

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/assert.h"
#include "core/errors.h"
#include "core/parallel.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork::detail {

// The a-priori bound of every triangle of a pattern, the largest. The halves of inner grid cells
// get the grid's bound `cell` (flatness_bound, which bounds either half of any cell of those steps); a
// triangle whose own bound exceeds the tolerance is refined on `surface`
// (refined_triangle_flatness_bound), so that a stitched triangle is not raised for want of a
// tighter bound. The inner cells that make_pattern_boundary leaves out are such halves: they
// count as `cell` without being listed.
double pattern_bound(const TessellationPattern& boundary, const InnerGrid& inner, const SecondDerivativeBounds& bounds,
                     double cell, const std::function<Vec3(const Vec2&)>& surface, double tolerance) {
  if (boundary.grid) return cell;
  const double du = 1.0 / inner.u;
  const double dv = 1.0 / inner.v;
  const double aspect = static_cast<double>(inner.u) / inner.v;
  const auto points = static_cast<std::uint32_t>(boundary.points.size());
  const auto row = static_cast<std::uint32_t>(inner.u - 1);
  // Point k's (u, v): listed, or interior point k - points on the inner grid (as make_pattern
  // places it, i / N_u and j / N_v).
  const auto uv = [&](std::uint32_t k) {
    if (k < points) return boundary.points[k].uv;
    const std::uint32_t q = k - points;
    return Vec2(static_cast<double>(q % row + 1) / static_cast<double>(inner.u),
                static_cast<double>(q / row + 1) / static_cast<double>(inner.v));
  };
  const bool inner_cells = inner.u > 2 && inner.v > 2;
  double bound = inner_cells ? cell : 0.0;
  for (const Triangle& t : boundary.triangles) {
    const Vec2 a = uv(t[0]);
    const Vec2 b = uv(t[1]);
    const Vec2 c = uv(t[2]);
    if (is_grid_cell_half(a, b, c, du, dv)) {
      bound = std::max(bound, cell);
      continue;
    }
    double own = triangle_flatness_bound(bounds, a, b, c, aspect);
    if (own > tolerance) own = refined_triangle_flatness_bound(bounds, surface, a, b, c, aspect, tolerance);
    bound = std::max(bound, own);
  }
  return bound;
}

void check_options(const TessellationOptions& options, bool bezier_patches) {
  const int modes = options.tolerance.has_value() + options.relative_tolerance.has_value() +
                    options.segments.has_value() + options.camera.has_value();
  if (modes != 1) {
    throw InvalidInput(
        detail::message("tessellate: give exactly one of tolerance, relative tolerance, segments "
                        "and camera (",
                        modes, " given)"));
  }
  if (!(options.crease_angle >= 0.0) || !std::isfinite(options.crease_angle)) {
    throw InvalidInput(detail::message("tessellate: crease angle ", options.crease_angle, " is not >= 0"));
  }
  if (options.tolerance) {
    check_positive(*options.tolerance, "tolerance");
  } else if (options.relative_tolerance) {
    check_positive(*options.relative_tolerance, "relative tolerance");
  } else if (options.segments) {
    if (*options.segments < 1 || *options.segments > (1 << 20)) {
      throw InvalidInput(detail::message("tessellate: segments ", *options.segments, " is not in [1, 2^20]"));
    }
  } else {
    if (!bezier_patches) throw InvalidInput("tessellate: the camera mode needs Bezier patches");
    validate(*options.camera);
    check_positive(options.pixel_tolerance, "pixel tolerance");
  }
}

void Tessellator::plan_patches() {
  check_options(options_, pieces_.patches != nullptr);
  double tolerance = 0.0;
  if (options_.tolerance) {
    tolerance = *options_.tolerance;
  } else if (options_.relative_tolerance) {
    tolerance = relative_tolerance_times(*options_.relative_tolerance, diagonal_);
  }
  double focal = options_.camera ? focal_length_pixels(*options_.camera) : 0.0;
  const std::vector<bool> back_faces_hidden =
      options_.camera ? hidden_back_faces(*options_.camera) : std::vector<bool>();
  // Patches reaching behind the near limit get the tolerance of this depth.
  const double near_depth = 1e-3 * diagonal_;
  // Each piece's plan on its own (in parallel: each writes only its own plan). A piece that
  // cannot be planned is reported after the loop, the lowest such piece, so the message does not
  // depend on the threads.
  const auto plan_piece = [&](std::size_t p) {
    PatchPlan& plan = plans_[p];
    plan.bounds = &pieces_.bounds[p];
    plan.memo = grid_memos_ ? &(*grid_memos_)[p] : nullptr;
    if (options_.segments) {
      plan.nu = plan.nv = *options_.segments;
      return;
    }
    plan.tolerance = tolerance;
    if (options_.camera) {
      const Camera& camera = *options_.camera;
      const BezierPatch3& patch = (*pieces_.patches)[p];
      plan.tolerance =
          tolerance_on_ladder(options_.pixel_tolerance * std::max(nearest_depth(patch, camera), near_depth) / focal);
      const bool rational = !pieces_.rational.empty() && pieces_.rational[p];
      plan.culled =
          outside_frustum(patch, camera) || (back_faces_hidden[p] && !rational && back_facing(patch, camera.eye));
    }
    // The weld gap of the piece's edges comes on top of its pattern's bound (assemble): plan
    // for the rest, down to half the tolerance (a gap beyond that shows in error_bound).
    const double reserve = pieces_.gaps.empty() ? 0.0 : pieces_.gaps[p];
    if (reserve > 0.0) plan.tolerance = std::max(plan.tolerance - reserve, 0.5 * plan.tolerance);
    GridSize grid{};
    try {
      grid = planned_ && reserve == 0.0 ? (*planned_)[p]
             : grid_memos_ ? grid_for_tolerance(*plan.bounds, plan.tolerance, least_segments(*plan.bounds), (*grid_memos_)[p])
                           : grid_for_tolerance(*plan.bounds, plan.tolerance, least_segments(*plan.bounds));
    } catch (const InvalidInput&) {
      throw InvalidInput(detail::message("tessellate: piece ", p,
                                         " would need more than 2^20 segments per side at "
                                         "tolerance ",
                                         plan.tolerance, " (over 10^12 triangles; the limit is ",
                                         options_.max_triangles, ")"));
    }
    plan.nu = static_cast<int>(grid.segments_u);
    plan.nv = static_cast<int>(grid.segments_v);
  };
  std::atomic<std::size_t> first_failure{count_};
  parallel_for(count_, options_.threads, [&](std::size_t p) {
    try {
      plan_piece(p);
    } catch (const InvalidInput&) {
      std::size_t seen = first_failure.load();
      while (p < seen && !first_failure.compare_exchange_weak(seen, p)) {
      }
    }
  });
  if (first_failure.load() < count_) plan_piece(first_failure.load());  // throws again, alone
  for (std::size_t p = 0; p < count_; ++p) {
    if (!plans_[p].culled) continue;
    ++culled_;
    culled_triangles_ += 2 * static_cast<std::int64_t>(plans_[p].nu) * plans_[p].nv;
  }
}

// Per piece, whether it may be left out where it faces away from the camera (BackFaceCulling).
std::vector<bool> Tessellator::hidden_back_faces(const Camera& camera) const {
  if (options_.back_face_culling != BackFaceCulling::automatic) {
    return std::vector<bool>(count_, options_.back_face_culling == BackFaceCulling::always);
  }
  std::vector<bool> hidden(count_, false);
  if (solids_.empty()) return hidden;
  // Outside the box of a solid's control points is outside the solid (its convex hull).
  std::vector<Eigen::AlignedBox3d> boxes;
  for (std::size_t p = 0; p < count_; ++p) {
    const std::int32_t solid = solids_[p];
    if (solid < 0) continue;
    if (boxes.size() <= static_cast<std::size_t>(solid)) boxes.resize(static_cast<std::size_t>(solid) + 1);
    for (const Vec3& q : (*pieces_.patches)[p].control_points()) boxes[static_cast<std::size_t>(solid)].extend(q);
  }
  for (std::size_t p = 0; p < count_; ++p) {
    const std::int32_t solid = solids_[p];
    hidden[p] = solid >= 0 && !boxes[static_cast<std::size_t>(solid)].contains(camera.eye);
  }
  return hidden;
}

// Classes for every edge of every patch that is tessellated: a shared edge whose two patches
// are both tessellated is one class; every other edge is its own.
void Tessellator::build_edge_classes() {
  const auto add_class = [&](std::uint32_t owner, bool collapsed) {
    classes_.push_back({owner, collapsed, 1, no_id});
    return static_cast<std::uint32_t>(classes_.size() - 1);
  };
  for (const PieceJoin& shared : pieces_.shared) {
    const EdgeRef a = shared.first;
    const EdgeRef b = shared.second;
    if (plans_[a.patch].culled || plans_[b.patch].culled) continue;
    // An edge paired twice (three patches on one edge) keeps its first pairing.
    if (slots_[a.patch][static_cast<int>(a.edge)].edge_class != no_id ||
        slots_[b.patch][static_cast<int>(b.edge)].edge_class != no_id) {
      continue;
    }
    const std::uint32_t c = add_class(a.patch, false);
    slots_[a.patch][static_cast<int>(a.edge)] = {c, false};
    slots_[b.patch][static_cast<int>(b.edge)] = {c, shared.reversed};
  }
  // A T-junction's parts keep their own classes; the long edge sees them end to end. A culled
  // part leaves its piece to a class of the long edge's patch.
  for (const TJunction& t : pieces_.t_junctions) {
    EdgeSlot& slot = slots_[t.edge.patch][static_cast<int>(t.edge.edge)];
    if (plans_[t.edge.patch].culled || slot.edge_class != no_id || slot.composite != no_id) continue;
    CompositeEdge composite;
    composite.edge = t.edge;
    composite.segments.at.push_back(0.0);
    for (std::size_t b = 0; b < t.parts.size(); ++b) {
      const EdgeRef part = t.parts[b];
      EdgeSlot& part_slot = slots_[part.patch][static_cast<int>(part.edge)];
      const bool joined = !plans_[part.patch].culled && part_slot.edge_class == no_id && part_slot.composite == no_id;
      const std::uint32_t c = add_class(joined ? part.patch : t.edge.patch, false);
      if (joined) part_slot = {c, false};
      composite.classes.push_back(c);
      composite.reversed.push_back(joined && t.reversed[b]);
      composite.parts.push_back(part);
      composite.joined.push_back(joined);
      composite.segments.at.push_back(b + 1 == t.parts.size() ? 1.0 : t.breaks[b]);
      composite.segments.rates.push_back(1);
    }
    composite.first_junction = junctions_;
    junctions_ += static_cast<std::uint32_t>(t.parts.size() - 1);
    slot.composite = static_cast<std::uint32_t>(composites_.size());
    composites_.push_back(std::move(composite));
  }
  std::vector<std::array<bool, 4>> collapsed(count_, {false, false, false, false});
  for (const EdgeRef& e : pieces_.collapsed) collapsed[e.patch][static_cast<int>(e.edge)] = true;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    for (int k = 0; k < 4; ++k) {
      if (slots_[p][k].edge_class == no_id && slots_[p][k].composite == no_id) {
        slots_[p][k] = {add_class(p, collapsed[p][k]), false};
      }
    }
  }
  update_edge_rates();
}

// A class's rate is the largest rate any of its patches needs along it; a collapsed edge
// follows its patch's inner rate, so its triangles fan evenly into the pole.
// A composite edge asks each of its pieces for the long edge's rate over the piece's length.
void Tessellator::update_edge_rates() {
  for (EdgeClass& c : classes_) c.rate = 1;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    for (int k = 0; k < 4; ++k) {
      const int n = along(k, plans_[p].nu, plans_[p].nv);
      const EdgeSlot& slot = slots_[p][k];
      if (slot.composite == no_id) {
        EdgeClass& c = classes_[slot.edge_class];
        c.rate = std::max(c.rate, n);
        continue;
      }
      const CompositeEdge& composite = composites_[slot.composite];
      for (std::size_t b = 0; b < composite.classes.size(); ++b) {
        EdgeClass& c = classes_[composite.classes[b]];
        c.rate = std::max(c.rate, piece_rate(n, composite.segments.at[b + 1] - composite.segments.at[b]));
      }
    }
  }
  for (CompositeEdge& composite : composites_) {
    for (std::size_t b = 0; b < composite.classes.size(); ++b)
      composite.segments.rates[b] = classes_[composite.classes[b]].rate;
  }
}

PatternRates Tessellator::rates(std::uint32_t p) const {
  PatternRates r{plans_[p].nu, plans_[p].nv, {}, {}};
  for (int k = 0; k < 4; ++k) {
    const EdgeSlot& slot = slots_[p][k];
    if (slot.composite == no_id) {
      r.edges[k] = classes_[slot.edge_class].rate;
      continue;
    }
    const EdgeSegments& pieces = composites_[slot.composite].segments;
    r.segments[k] = &pieces;
    r.edges[k] = std::accumulate(pieces.rates.begin(), pieces.rates.end(), 0);
  }
  return r;
}

// Stitched triangles can reach further than grid cells; raise the inner rates of any patch
// whose worst triangle exceeds its tolerance until none does (rates only grow, so this ends).
void Tessellator::raise_rates_to_bounds() {
  // Within a round each piece reads the edge rates (changed only between rounds) and writes
  // its own plan: the pieces run in parallel.
  std::vector<std::uint8_t> raised_piece(count_);
  for (int round = 0; round < 64; ++round) {
    std::fill(raised_piece.begin(), raised_piece.end(), std::uint8_t{0});
    parallel_for(count_, options_.threads, [&](std::size_t piece) {
      const auto p = static_cast<std::uint32_t>(piece);
      PatchPlan& plan = plans_[p];
      if (plan.culled) return;
      const InnerGrid inner = inner_grid(rates(p));
      const int nu = inner.u;
      const int nv = inner.v;
      // A plain grid meets the tolerance by construction (its rates only grew); only
      // stitched patterns need their triangles checked.
      if (inner.grid || stitched_bound(p) <= plan.tolerance) return;
      // Raise one direction: the one whose pattern then meets the tolerance with fewer cells,
      // else the one whose bound falls further.
      struct Candidate {
        int nu;
        int nv;
        double bound;
      };
      std::array<Candidate, 2> candidates = {Candidate{nu + std::max(1, nu / 8), nv, 0.0},
                                             Candidate{nu, nv + std::max(1, nv / 8), 0.0}};
      for (Candidate& c : candidates) {
        PatternRates r = rates(p);
        r.inner_u = c.nu;
        r.inner_v = c.nv;
        std::array<EdgeSegments, 4> raised;
        for (std::size_t k = 0; k < 4; ++k) {
          const int n = along(static_cast<int>(k), c.nu, c.nv);
          if (r.segments[k] == nullptr) {
            r.edges[k] = std::max(r.edges[k], n);
            continue;
          }
          raised[k] = *r.segments[k];
          for (std::size_t b = 0; b < raised[k].rates.size(); ++b) {
            raised[k].rates[b] = std::max(raised[k].rates[b], piece_rate(n, raised[k].at[b + 1] - raised[k].at[b]));
          }
          r.segments[k] = &raised[k];
          r.edges[k] = std::accumulate(raised[k].rates.begin(), raised[k].rates.end(), 0);
        }
        c.bound = pattern_bound_of(p, r);
      }
      const auto meets = [&](const Candidate& c) { return c.bound <= plan.tolerance; };
      const Candidate& a = candidates[0];
      const Candidate& b = candidates[1];
      const bool take_u = meets(a) && meets(b)   ? a.nu * a.nv <= b.nu * b.nv
                          : meets(a) || meets(b) ? meets(a)
                                                 : a.bound <= b.bound;
      plan.nu = take_u ? a.nu : b.nu;
      plan.nv = take_u ? a.nv : b.nv;
      raised_piece[p] = 1;
    });
    if (std::find(raised_piece.begin(), raised_piece.end(), std::uint8_t{1}) == raised_piece.end()) return;
    update_edge_rates();
  }
  throw NumericalError("tessellate: the stitched rates did not settle within 64 rounds");
}

// The bound of patch p's stitched pattern at its current rates (computed once per rates).
double Tessellator::stitched_bound(std::uint32_t p) {
  PatchPlan& plan = plans_[p];
  const PatternRates r = rates(p);
  if (!(plan.checked_rates == r)) {
    plan.checked_rates.assign(r);
    plan.checked_bound = pattern_bound_of(p, r);
  }
  return plan.checked_bound;
}

// The bound of patch p's pattern at rates r, its stitched triangles refined against its
// tolerance where it has one (pattern_bound).
double Tessellator::pattern_bound_of(std::uint32_t p, const PatternRates& r) {
  PatchPlan& plan = plans_[p];
  const InnerGrid inner = inner_grid(r);
  const auto surface = [this, p](const Vec2& uv) { return pieces_.evaluate(p, uv.x(), uv.y()); };
  const double target = options_.segments ? std::numeric_limits<double>::infinity() : plan.tolerance;
  // Each thread's pattern keeps its storage from call to call.
  thread_local TessellationPattern boundary;
  make_pattern_boundary(r, boundary);
  return pattern_bound(boundary, inner, *plan.bounds, plan.cell_bound(inner.u, inner.v), surface, target);
}

double Tessellator::check_triangle_budget() const {
  double triangles = 0.0;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (plans_[p].culled) continue;
    const PatternRates r = rates(p);
    triangles +=
        2.0 * std::max(r.inner_u, 2) * std::max(r.inner_v, 2) + r.edges[0] + r.edges[1] + r.edges[2] + r.edges[3];
  }
  if (triangles > static_cast<double>(options_.max_triangles)) {
    throw InvalidInput(detail::message("tessellate: about ", static_cast<std::int64_t>(triangles),
                                       " triangles needed, more than the limit of ", options_.max_triangles));
  }
  return triangles;
}

}  // namespace patchwork::detail
