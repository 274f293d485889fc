// Patch sets as the tessellator's pieces: whole patches with their shared and collapsed edges,
// T-junctions, weld gaps and solids, or each patch split k x k (surfaces/tessellator.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "core/errors.h"
#include "core/parallel.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_grid.h"
#include "surfaces/rational_bounds.h"
#include "surfaces/surface_integrals.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork {
namespace detail {

// The 4 x 4 sub-net bounds of every patch (what the rates of whole and split patches rest on).
std::vector<std::vector<SecondDerivativeBounds>> cell_bounds(const PatchSet& set) {
  if (!(set.size() > 0.0)) {
    throw InvalidInput("tessellate: every control point is the same point: there is no surface to tessellate");
  }
  // Each patch into its own slot, on every core (the same bounds on any number of threads).
  std::vector<std::vector<SecondDerivativeBounds>> cells(set.count());
  parallel_for(set.count(), 0, [&](std::size_t p) {
    const RationalBezierPatch* rational = set.rational(static_cast<std::uint32_t>(p));
    cells[p] = rational != nullptr ? piece_second_derivative_bounds(*rational, bound_pieces)
                                   : piece_second_derivative_bounds(set.control_nets()[p], bound_pieces);
  });
  return cells;
}

// The bounds of piece (a, b) of a k x k split, in the piece's parameters: the largest cell bound
// over the piece, times (1/k)^2 by the chain rule. k = 1 is the whole patch.
SecondDerivativeBounds split_bounds(const std::vector<SecondDerivativeBounds>& cells, int k, int a, int b) {
  const int span = bound_pieces / k;
  std::optional<SecondDerivativeBounds> M;
  for (int y = b * span; y < (b + 1) * span; ++y) {
    for (int x = a * span; x < (a + 1) * span; ++x) {
      const SecondDerivativeBounds& c = cells[static_cast<std::size_t>(x + bound_pieces * y)];
      M = M ? merged_bounds(*M, c) : c;
    }
  }
  return scaled_bounds(*M, 1.0 / k);
}

double tight_or_control_diagonal(const PatchSet& set, bool tight_diagonal) {
  if (!tight_diagonal) return set.size();
  return bounding_box(set, 1e-6 * set.size()).diagonal().norm();
}

// Per patch, the largest gap of its joined edges (SurfacePieces::gaps): the gap of its shared
// edges and T-junctions (EdgeContinuity::gap bounds the curves' distance point for point; for
// polynomial edges it is the control-point gap, the curves being convex combinations of their
// control points) and the spread of its collapsed edges' control points around the point they
// weld to (a rational edge's points are convex combinations of them too).
std::vector<double> edge_gaps(const PatchSet& set) {
  std::vector<double> gaps(set.count(), 0.0);
  const auto widen = [&](std::uint32_t p, double gap) { gaps[p] = std::max(gaps[p], gap); };
  for (const SharedEdge& s : set.shared_edges()) {
    widen(s.first.patch, s.continuity.gap);
    widen(s.second.patch, s.continuity.gap);
  }
  for (const TJunction& t : set.t_junctions()) {
    widen(t.edge.patch, t.gap);
    for (const EdgeRef& part : t.parts) widen(part.patch, t.gap);
  }
  for (const EdgeRef& e : set.collapsed_edges()) {
    const std::vector<Vec3> row = row_from_edge(set.control_nets()[e.patch], e.edge, 0);
    for (const Vec3& q : row) widen(e.patch, (q - row.front()).norm());
  }
  return gaps;
}

// Per patch, the solid it bounds, or -1 (SurfacePieces::solids).
std::vector<std::int32_t> solids_of(const PatchSet& set) {
  std::vector<std::int32_t> solids(set.count(), -1);
  std::int32_t next = 0;
  for (const Shell& shell : shells(set)) {
    if (!shell.closed || !shell.consistently_oriented) continue;
    // Only polynomial pieces are ever culled as back-facing: a shell of rational patches alone
    // needs no volume.
    if (std::all_of(shell.patches.begin(), shell.patches.end(), [&](std::uint32_t p) { return set.is_rational(p); })) {
      continue;
    }
    double volume = 0.0;
    try {
      for (std::uint32_t p : shell.patches) {
        // A rational patch's share by quadrature, to an absolute tolerance far below the size
        // of a volume of this set (only the sign is used); where the quadrature cannot reach
        // it, the shell is not taken for a solid (no culling, never a hole).
        const RationalBezierPatch* rational = set.rational(p);
        const double tolerance = 1e-9 * std::pow(set.size(), 3) / static_cast<double>(shell.patches.size());
        volume += rational != nullptr ? volume_contribution(*rational, tolerance).value
                                      : volume_contribution(set.control_nets()[p]);
      }
    } catch (const NumericalError&) {
      continue;
    }
    if (!(volume > 0.0)) continue;
    for (std::uint32_t p : shell.patches) solids[p] = next;
    ++next;
  }
  return solids;
}

// Pieces of `set`, each patch split k x k (k = 1: the patches themselves).
SurfacePieces pieces_of(const PatchSet& set, const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k,
                        double diagonal, bool with_solids) {
  const std::vector<BezierPatch3>& patches = set.control_nets();
  SurfacePieces pieces;
  pieces.diagonal = diagonal;
  // Piece p of patch `patch` on the grid us x vs (in the patch's parameters), of its kind.
  // The weights of each thread's last grid keep their storage: the tessellator evaluates every
  // piece's sides as small grids, and fresh tables cost more than the evaluation.
  const auto grid_of = [&set](std::uint32_t patch, std::span<const double> us, std::span<const double> vs,
                              GridSamplesView out) {
    thread_local PatchGridWeights weights(0, 0, std::array<double, 1>{0.0}, std::array<double, 1>{0.0});
    if (const RationalBezierPatch* rational = set.rational(patch)) {
      weights.assign(rational->degree_u(), rational->degree_v(), us, vs);
      evaluate_grid(*rational, weights, out);
      return;
    }
    const BezierPatch3& net = set.control_nets()[patch];
    weights.assign(net.degree_u(), net.degree_v(), us, vs);
    evaluate_grid(net, weights, out);
  };
  const auto samples_of = [&set](std::uint32_t patch, std::span<const Vec2> uvs, GridSamplesView out) {
    if (const RationalBezierPatch* rational = set.rational(patch)) {
      evaluate_samples(*rational, uvs, out);
    } else {
      evaluate_samples(set.control_nets()[patch], uvs, out);
    }
  };
  const auto point_of = [&set](std::uint32_t patch, double u, double v) {
    const RationalBezierPatch* rational = set.rational(patch);
    return rational != nullptr ? rational->evaluate(u, v) : evaluate_point(set.control_nets()[patch], u, v);
  };
  const auto points_of = [&set](std::uint32_t patch, std::span<const double> us, std::span<const double> vs,
                                std::span<Vec3> points) {
    if (const RationalBezierPatch* rational = set.rational(patch)) {
      evaluate_points(*rational, us, vs, points);
    } else {
      evaluate_points(set.control_nets()[patch], us, vs, points);
    }
  };
  if (k == 1) {
    pieces.count = patches.size();
    pieces.patches = &patches;
    if (set.rational_count() > 0) {
      for (std::uint32_t p = 0; p < patches.size(); ++p) pieces.rational.push_back(set.is_rational(p));
    }
    for (const SharedEdge& shared : set.shared_edges())
      pieces.shared.push_back({shared.first, shared.second, shared.reversed});
    pieces.collapsed = set.collapsed_edges();
    pieces.t_junctions = set.t_junctions();
    pieces.gaps = edge_gaps(set);
    if (with_solids) pieces.solids = solids_of(set);
    for (std::size_t p = 0; p < patches.size(); ++p) pieces.bounds.push_back(split_bounds(cells[p], 1, 0, 0));
    pieces.evaluate_grid = grid_of;
    pieces.evaluate_samples = samples_of;
    pieces.evaluate = point_of;
    pieces.evaluate_points = points_of;
    return pieces;
  }
  // Piece (a, b) of patch p is number p k^2 + a + k b.
  const auto kk = static_cast<std::uint32_t>(k * k);
  const auto piece = [k, kk](std::uint32_t p, int a, int b) { return p * kk + static_cast<std::uint32_t>(a + k * b); };
  // The k pieces along a patch edge, in its boundary_curve direction (u along v0 and v1, v along u0 and u1).
  const auto along = [&](const EdgeRef& edge, int i) -> EdgeRef {
    const int last = k - 1;
    switch (edge.edge) {
      case PatchEdge::v0:
        return {piece(edge.patch, i, 0), PatchEdge::v0};
      case PatchEdge::v1:
        return {piece(edge.patch, i, last), PatchEdge::v1};
      case PatchEdge::u0:
        return {piece(edge.patch, 0, i), PatchEdge::u0};
      case PatchEdge::u1:
        return {piece(edge.patch, last, i), PatchEdge::u1};
    }
    return edge;
  };
  pieces.count = patches.size() * kk;
  pieces.patch_count = patches.size();
  const std::vector<double> patch_gaps = edge_gaps(set);
  if (std::any_of(patch_gaps.begin(), patch_gaps.end(), [](double g) { return g > 0.0; })) {
    for (double g : patch_gaps) pieces.gaps.insert(pieces.gaps.end(), kk, g);
  }
  const double size = 1.0 / k;  // exact for k = 2, 4: the split lines a/k are exact too
  // Sized once: at 10^5 patches these are hundreds of MB that doubling would copy and hold twice.
  pieces.domains.reserve(pieces.count);
  pieces.bounds.reserve(pieces.count);
  pieces.shared.reserve(patches.size() * 2 * static_cast<std::size_t>(k * (k - 1)) +
                        set.shared_edges().size() * static_cast<std::size_t>(k));
  pieces.collapsed.reserve(set.collapsed_edges().size() * static_cast<std::size_t>(k));
  for (std::uint32_t p = 0; p < patches.size(); ++p) {
    for (int b = 0; b < k; ++b) {
      for (int a = 0; a < k; ++a) {
        pieces.domains.push_back({p, a * size, b * size, size});
        pieces.bounds.push_back(split_bounds(cells[p], k, a, b));
        if (a + 1 < k)
          pieces.shared.push_back({{piece(p, a, b), PatchEdge::u1}, {piece(p, a + 1, b), PatchEdge::u0}, false});
        if (b + 1 < k)
          pieces.shared.push_back({{piece(p, a, b), PatchEdge::v1}, {piece(p, a, b + 1), PatchEdge::v0}, false});
      }
    }
  }
  for (const SharedEdge& shared : set.shared_edges()) {
    for (int i = 0; i < k; ++i) {
      pieces.shared.push_back(
          {along(shared.first, i), along(shared.second, shared.reversed ? k - 1 - i : i), shared.reversed});
    }
  }
  for (const EdgeRef& collapsed : set.collapsed_edges()) {
    for (int i = 0; i < k; ++i) pieces.collapsed.push_back(along(collapsed, i));
  }
  // One copy of the domains shared by the evaluators (each held its own: at 10^5 patches split
  // 4 x 4 that is 17 MB a copy); `pieces.domains` stays the public one.
  const auto shared_domains = std::make_shared<const std::vector<SurfacePieces::Domain>>(pieces.domains);
  pieces.evaluate_grid = [grid_of, shared_domains](std::uint32_t q, std::span<const double> us,
                                                   std::span<const double> vs, GridSamplesView out) {
    const SurfacePieces::Domain& d = (*shared_domains)[q];
    thread_local std::vector<double> patch_us;
    thread_local std::vector<double> patch_vs;
    patch_us.resize(us.size());
    patch_vs.resize(vs.size());
    for (std::size_t k = 0; k < us.size(); ++k) patch_us[k] = d.u0 + d.size * us[k];
    for (std::size_t k = 0; k < vs.size(); ++k) patch_vs[k] = d.v0 + d.size * vs[k];
    grid_of(d.patch, patch_us, patch_vs, out);
  };
  pieces.evaluate_samples = [samples_of, shared_domains](std::uint32_t q, std::span<const Vec2> uvs,
                                                         GridSamplesView out) {
    const SurfacePieces::Domain& d = (*shared_domains)[q];
    thread_local std::vector<Vec2> patch_uvs;
    patch_uvs.resize(uvs.size());
    for (std::size_t k = 0; k < uvs.size(); ++k) patch_uvs[k] = Vec2(d.u0, d.v0) + d.size * uvs[k];
    samples_of(d.patch, patch_uvs, out);
  };
  pieces.evaluate = [point_of, shared_domains](std::uint32_t q, double u, double v) {
    const SurfacePieces::Domain& d = (*shared_domains)[q];
    return point_of(d.patch, d.u0 + d.size * u, d.v0 + d.size * v);
  };
  // The parameters mapped as evaluate_grid maps them, a chunk at a time on the stack.
  pieces.evaluate_points = [points_of, shared_domains](std::uint32_t q, std::span<const double> us,
                                                       std::span<const double> vs, std::span<Vec3> points) {
    const SurfacePieces::Domain& d = (*shared_domains)[q];
    std::array<double, 256> patch_us;
    std::array<double, 256> patch_vs;
    for (std::size_t first = 0; first < us.size(); first += patch_us.size()) {
      const std::size_t count = std::min(patch_us.size(), us.size() - first);
      for (std::size_t k = 0; k < count; ++k) {
        patch_us[k] = d.u0 + d.size * us[first + k];
        patch_vs[k] = d.v0 + d.size * vs[first + k];
      }
      points_of(d.patch, {patch_us.data(), count}, {patch_vs.data(), count}, points.subspan(first, count));
    }
  };
  return pieces;
}

SplitEstimate estimated_split(const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k, double eps,
                              int threads, std::vector<GridSearchMemo>* memos) {
  SplitEstimate estimate;
  const auto kk = static_cast<std::size_t>(k * k);
  estimate.grids.resize(cells.size() * kk);
  PATCHWORK_ASSERT(memos == nullptr || memos->size() == estimate.grids.size(), "one grid memo per piece");
  // Each patch fills its own k x k slots: the same grids on any number of threads.
  parallel_for(cells.size(), threads, [&](std::size_t p) {
    for (int b = 0; b < k; ++b) {
      for (int a = 0; a < k; ++a) {
        const SecondDerivativeBounds M = split_bounds(cells[p], k, a, b);
        const std::size_t slot = p * kk + static_cast<std::size_t>(a + k * b);
        estimate.grids[slot] = memos ? grid_for_tolerance(M, eps, least_segments(M), (*memos)[slot])
                                     : grid_for_tolerance(M, eps, least_segments(M));
      }
    }
  });
  for (const GridSize& grid : estimate.grids) estimate.cells += grid.segments_u * grid.segments_v;
  return estimate;
}

}  // namespace detail

using detail::cell_bounds;
using detail::pieces_of;
using detail::tight_or_control_diagonal;

SurfacePieces surface_pieces(const PatchSet& set, bool tight_diagonal) {
  const auto cells = cell_bounds(set);
  return pieces_of(set, cells, 1, tight_or_control_diagonal(set, tight_diagonal));
}

SurfacePieces split_surface_pieces(const PatchSet& set, int k, bool tight_diagonal) {
  if (k != 2 && k != 4) throw InvalidInput(detail::message("split_surface_pieces: k = ", k, " is not 2 or 4"));
  if (!set.t_junctions().empty()) {
    throw InvalidInput(detail::message("split_surface_pieces: the set has ", set.t_junctions().size(),
                                       " T-junctions, which split pieces do not join"));
  }
  const auto cells = cell_bounds(set);
  return pieces_of(set, cells, k, tight_or_control_diagonal(set, tight_diagonal));
}

}  // namespace patchwork
