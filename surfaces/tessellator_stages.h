#pragma once
// The tessellator's stages (surfaces/tessellator.h is the interface): the state one run carries
// from stage to stage, and the Tessellator whose members are the stages, one file each:
//   tessellator_rates.cpp         plan the rates: tolerance per piece, culling, edge classes,
//                                 T-junction composites, rates raised to the stitched bounds;
//   tessellator_boundary.cpp      welding: one id per surface point; each piece's boundary
//                                 pattern, evaluated;
//   tessellator_assembly.cpp      render vertices, the weld gap, interiors and triangles written
//                                 straight into the mesh;
//   tessellator_measure.cpp       the measured error;
//   tessellator_vertex_order.cpp  vertex-cache and vertex-fetch order;
//   surface_pieces.cpp            patch sets as pieces (whole or split), and the split estimates;
//   prepared_surface.cpp          what a patch set's tessellations share (bounds, pieces), made
//                                 once; the split chosen per tessellation;
//   tessellator.cpp               run() in that order, and the public tessellate().
// Internal: nothing here is installed or part of the API.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "core/types.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/tessellation_pattern.h"
#include "surfaces/tessellator.h"

namespace patchwork {
class PreparedSurface;
}  // namespace patchwork

namespace patchwork::detail {

using Triangle = std::array<std::uint32_t, 3>;
constexpr std::uint32_t no_id = 0xffffffffu;
// Second-derivative bounds from 4 x 4 sub-nets: close to the true suprema (patch_flatness.h).
constexpr int bound_pieces = 4;

// Edge k of a patch runs (in boundary_curve direction) from corner edge_start(k) to edge_end(k);
// corners are numbered c0 = (0,0), c1 = (1,0), c2 = (1,1), c3 = (0,1).
constexpr std::array<int, 4> edge_start = {0, 1, 3, 0};
constexpr std::array<int, 4> edge_end = {1, 2, 2, 3};

// Segments along edge k for inner rates (nu, nv): v0 and v1 run along u.
inline int along(int edge, int nu, int nv) { return edge % 2 == 0 ? nu : nv; }

// The segments of a T-junction's piece of length `length` (of its long edge) at inner rate n:
// as many as the long edge's patch has along it there, at least one.
inline int piece_rate(int n, double length) { return std::max(1, static_cast<int>(std::ceil(n * length - 1e-9))); }

// Rates with copies of their edges' piece rates: what a pattern is known by (PatternRates only
// points at the pieces, which change as the rates grow).
struct RatesKey {
  PatternRates rates{0, 0, {0, 0, 0, 0}};
  std::array<std::vector<int>, 4> pieces;

  bool operator==(const PatternRates& r) const {
    if (rates.inner_u != r.inner_u || rates.inner_v != r.inner_v || rates.edges != r.edges) return false;
    for (std::size_t k = 0; k < 4; ++k) {
      if (r.segments[k] == nullptr ? !pieces[k].empty() : pieces[k] != r.segments[k]->rates) return false;
    }
    return true;
  }
  void assign(const PatternRates& r) {
    rates = r;
    rates.segments = {};
    for (std::size_t k = 0; k < 4; ++k) {
      pieces[k].clear();
      if (r.segments[k] != nullptr) pieces[k] = r.segments[k]->rates;
    }
  }
};

// What one patch needs before evaluation.
struct PatchPlan {
  bool culled = false;
  // The rates of the stitched pattern whose bound was last computed, and that bound (each round
  // of raise_rates_to_bounds and the evaluation need it; most patterns do not change).
  RatesKey checked_rates;
  double checked_bound = 0.0;
  double tolerance = 0.0;
  // The piece's bounds (SurfacePieces::bounds; not copied: 250 bytes a piece).
  const SecondDerivativeBounds* bounds = nullptr;
  int nu = 1;
  int nv = 1;
  // flatness_bound of the last inner grid asked for (the cell bound costs some 0.5 us; the quick
  // bounds stand where they meet the tolerance).
  int cell_nu = 0;
  int cell_nv = 0;
  double cell = 0.0;
  // What earlier runs learnt about these bounds (Tessellator's grid_memos), or nullptr.
  GridSearchMemo* memo = nullptr;

  // The bound of the grid cells of steps (1/nu, 1/nv).
  double cell_bound(int grid_nu, int grid_nv) {
    if (grid_nu != cell_nu || grid_nv != cell_nv) {
      cell_nu = grid_nu;
      cell_nv = grid_nv;
      cell = memo ? flatness_bound(*bounds, grid_nu, grid_nv, tolerance, *memo)
                  : flatness_bound(*bounds, 1.0 / grid_nu, 1.0 / grid_nv, tolerance);
    }
    return cell;
  }
};

// The points along a shared, open or collapsed edge, numbered in its owner's boundary_curve
// direction. Every patch side of the class sees the same points.
struct EdgeClass {
  std::uint32_t owner = 0;
  bool collapsed = false;
  int rate = 1;
  std::uint32_t first_id = no_id;  // welded id of step 1
};

// One patch edge's view of its class, or of its composite (a T-junction's long edge).
struct EdgeSlot {
  std::uint32_t edge_class = no_id;
  bool reversed = false;  // runs against the owner's direction
  std::uint32_t composite = no_id;
};

// A T-junction's long edge: its points are those of its parts' classes end to end, and of the
// junctions between them. Junction b (between pieces b and b+1) is welding slot
// 4 * count + first_junction + b; it unites the two parts' corners there.
struct CompositeEdge {
  EdgeRef edge;
  EdgeSegments segments;  // at: 0, the breaks; rates: the classes' rates
  std::vector<std::uint32_t> classes;
  std::vector<bool> reversed;  // class b runs against the long edge
  std::vector<EdgeRef> parts;
  std::vector<bool> joined;  // part b is tessellated and owns class b
  std::uint32_t first_junction = 0;
};

// The boundary patterns (make_pattern_boundary) of a run's pieces, one per rates: a pattern
// depends on its rates alone, and a scene's thousands of pieces have a few hundred rates. Kept in
// the result's scratch, so the next frame makes only its new rates' patterns. Rates with
// composite edges (T-junctions) are not shared: their pieces make their own.
class PatternTable {
 public:
  // The pattern of `rates` (no composite edges), made on first use. Not thread-safe; a pattern
  // added here has its points and triangles once build() has run.
  const TessellationPattern* find_or_add(const PatternRates& rates) {
    const Key key{rates.inner_u, rates.inner_v, rates.edges[0], rates.edges[1], rates.edges[2], rates.edges[3]};
    if (const auto found = index_.find(key); found != index_.end()) return patterns_[found->second].get();
    // Everything that can throw comes before the table changes, so a bad_alloc leaves it whole.
    auto pattern = std::make_unique<TessellationPattern>();
    make_room(patterns_);
    make_room(pending_);
    index_.emplace(key, static_cast<std::uint32_t>(patterns_.size()));
    static_assert(std::is_nothrow_copy_constructible_v<PatternRates>);
    patterns_.push_back(std::move(pattern));
    pending_.push_back(rates);
    return patterns_.back().get();
  }
  // Makes the patterns added since the last build, on `threads` threads. A failure (rates too
  // large for a pattern) empties the table, so no half-made pattern is ever found again.
  void build(int threads);
  // Forgets every pattern once the table holds more than `limit` (a camera that keeps moving
  // brings new rates frame after frame).
  void trim(std::size_t limit) {
    if (patterns_.size() <= limit) return;
    index_.clear();
    patterns_.clear();
    pending_.clear();
  }

 private:
  // Room for one more push_back, growing geometrically (reserve(size + 1) would copy every time).
  template <class T>
  static void make_room(std::vector<T>& v) {
    if (v.size() == v.capacity()) v.reserve(std::max<std::size_t>(16, 2 * v.capacity()));
  }
  using Key = std::array<int, 6>;
  struct KeyHash {
    std::size_t operator()(const Key& key) const noexcept {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (const int k : key) h = (h ^ static_cast<std::uint32_t>(k)) * 0xC2B2AE3D27D4EB4Full;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> index_;
  std::vector<std::unique_ptr<TessellationPattern>> patterns_;
  std::vector<PatternRates> pending_;  // of the last patterns_, not yet made
};

// One patch's part of the tessellation. Only what touches its boundary is kept per patch (the
// boundary points, their attributes and the triangles with a corner among them); the interior
// points and inner cells are regular (make_pattern_boundary) and are written straight into the
// output, so a large grid costs no intermediate copies.
struct PatchOutput {
  InnerGrid inner{1, 1, true};
  // make_pattern_boundary of the piece's rates: shared (PatternTable) or own_pattern.
  const TessellationPattern* pattern = nullptr;
  TessellationPattern own_pattern;    // a pattern with composite edges
  std::vector<std::uint32_t> welded;  // per boundary point
  std::vector<bool> owner;            // this patch supplies the welded point's position
  std::vector<Vec3> positions;        // per boundary point, until assembled
  std::vector<Vec3> normals;
  std::vector<Vec4> tangents;
  bool all_kept = true;               // kept_triangles() is the pattern's every triangle
  std::vector<Triangle> kept;         // else the boundary triangles kept, pattern-local
  std::vector<Triangle> dropped;      // use one welded point twice (at a collapsed edge)
  std::vector<std::uint32_t> vertex;  // render vertex of each boundary point (no_id: unused)
  std::uint32_t first_vertex = 0;     // render vertex of interior point 0 (then row by row)
  std::size_t first_triangle = 0;
  // Some interior point is in no kept triangle (possible only next to collapsed edges when the
  // inner grid has 2 segments in a direction): the assembled mesh has unused vertices to drop.
  bool unused_interior = false;
  double bound = 0.0;
  // Largest distance from a boundary point's own surface point to its welded position.
  double weld_gap = 0.0;

  // Empties every array, keeping its storage for the next run.
  void clear() {
    pattern = nullptr;
    own_pattern.points.clear();
    own_pattern.triangles.clear();
    welded.clear();
    owner.clear();
    positions.clear();
    normals.clear();
    tangents.clear();
    all_kept = true;
    kept.clear();
    dropped.clear();
    vertex.clear();
    unused_interior = false;
    bound = 0.0;
    weld_gap = 0.0;
  }
  std::uint32_t boundary_points() const {
    return pattern == nullptr ? 0 : static_cast<std::uint32_t>(pattern->points.size());
  }
  // The boundary triangles that are in the mesh (pattern-local indices).
  std::span<const Triangle> kept_triangles() const {
    if (!all_kept) return kept;
    if (pattern == nullptr) return {};
    return pattern->triangles;
  }
  std::size_t interior_points() const {
    return static_cast<std::size_t>(inner.u - 1) * static_cast<std::size_t>(inner.v - 1);
  }
  std::size_t inner_cells() const {
    return static_cast<std::size_t>(std::max(inner.u - 2, 0)) * static_cast<std::size_t>(std::max(inner.v - 2, 0));
  }
  std::size_t triangle_count() const { return kept_triangles().size() + 2 * inner_cells(); }
  // The (u, v) of pattern point k (boundary points listed, interior points on the inner grid).
  Vec2 uv(std::uint32_t k) const {
    if (k < boundary_points()) return pattern->points[k].uv;
    const std::uint32_t q = k - boundary_points();
    const auto row = static_cast<std::uint32_t>(inner.u - 1);
    return {static_cast<double>(q % row + 1) / inner.u, static_cast<double>(q / row + 1) / inner.v};
  }
};

// A boundary render vertex: the boundary point it was made from, and its position id.
struct VertexSource {
  std::uint32_t patch;
  std::uint32_t point;
  std::uint32_t position_id;
};

// Heads of the vertex chains by (welded id, UV): an open-addressing table (linear probing) sized
// for the boundary points of a run.
class ChainHeads {
 public:
  // Empties the table, with room for `keys` keys.
  void reset(std::size_t keys) {
    std::size_t capacity = 16;
    while (capacity < 2 * keys) capacity *= 2;
    slots_.assign(capacity, Slot{});
  }
  // The head for (id, uv), no_id if new.
  std::uint32_t& head(std::uint32_t id, const Vec2& uv) {
    // + 0.0: -0 and +0 are one key.
    const auto x = std::bit_cast<std::uint64_t>(uv.x() + 0.0);
    const auto y = std::bit_cast<std::uint64_t>(uv.y() + 0.0);
    std::uint64_t h = (id + 1) * 0x9E3779B97F4A7C15ull;
    h = (h ^ x) * 0xC2B2AE3D27D4EB4Full;
    h = (h ^ (h >> 29) ^ y) * 0x165667B19E3779F9ull;
    h ^= h >> 32;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = h & mask;; s = (s + 1) & mask) {
      Slot& slot = slots_[s];
      if (slot.id == no_id) {
        slot.id = id;
        slot.uv = uv;
        return slot.head;
      }
      if (slot.id == id && slot.uv == uv) return slot.head;
    }
  }

 private:
  struct Slot {
    std::uint32_t id = no_id;
    std::uint32_t head = no_id;
    Vec2 uv = Vec2::Zero();
  };
  std::vector<Slot> slots_;
};

// Arrays of the vertex order (tessellator_vertex_order.cpp) kept between runs into one
// Tessellation: each reordered array is written into its spare here and then swapped with the
// mesh's, so a mesh of about the same size from frame to frame allocates (and faults in) nothing.
struct VertexOrderScratch {
  // Per worker: a table from mesh vertex to the chunk's own numbering (no_id where unused; reset
  // after each chunk), and the chunk's arrays.
  struct Chunk {
    std::vector<std::uint32_t> local;
    std::vector<std::uint32_t> global;
    std::vector<std::uint32_t> indices;
    std::vector<std::uint32_t> reordered;
    std::vector<std::uint32_t> first;
    std::vector<std::uint32_t> by_corner;
    std::vector<std::uint8_t> taken;
  };
  std::vector<Chunk> chunks;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> patches;
  std::vector<std::uint32_t> remap;
  std::vector<std::uint32_t> dense;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<Vec4> tangents;
  std::vector<std::uint32_t> position_ids;
};

// What a run needs besides its output, kept for the next run into the same Tessellation.
struct TessellatorScratch {
  // What the grid searches of a PreparedSurface's pieces learnt, for the next run: per split k
  // (1, 2, 4) one memo per piece, valid for the prepared surface whose identity() is
  // `memo_owner` (0: none).
  std::uint64_t memo_owner = 0;
  std::array<std::vector<GridSearchMemo>, 3> grid_memos;
  std::vector<PatchOutput> outputs;
  PatternTable patterns;
  std::vector<std::uint64_t> sample_owners;
  std::vector<Vec3> welded_positions;
  std::vector<VertexSource> sources;
  std::vector<std::uint8_t> pole;  // by welded id: a collapsed edge's point
  // The last run's triangle estimate, as its budget was checked (tessellate_in_batches counts
  // the budget over its batches with it).
  double estimated_triangles = 0.0;
  std::vector<std::uint32_t> first_vertex;
  ChainHeads heads;
  std::vector<std::uint32_t> next_vertex;
  std::vector<std::uint32_t> dense_position;
  VertexOrderScratch order;
};

// Outputs from this size on are written with streaming stores: far beyond the per-core caches
// (a tessellation this large is not read back while it is written).
constexpr std::size_t streamed_output_bytes = std::size_t{64} << 20;

// The fewest segments per direction a piece gets: two on a curved piece, so that coarse
// tolerances keep the topology (with one, a tube of two patches, the teapot's handle, would
// flatten into a doubled ribbon), one on a flat piece. (One on the curved pieces of split patches
// would keep the topology too, but cost the teapot triangles in stitching, measured once: 8,466 against 8,388
// at 1e-3.)
inline std::int64_t least_segments(const SecondDerivativeBounds& M) {
  const bool flat = M.uu == 0.0 && M.uv == 0.0 && M.vv == 0.0;
  return flat ? 1 : 2;
}

// The camera's tolerances on a ladder: the largest 2^(k/16), k whole (each rounded down), that
// is at most t (t positive and finite). A patch's tolerance tau z_min / f_px drifts from frame to frame
// as the camera moves; on the ladder it stays put until the patch's depth has changed by 4.4%,
// so the grid search's memo (GridSearchMemo's answers) serves frame after frame. The mesh is
// finer by at most that factor: the tolerance asked for still holds.
inline double tolerance_on_ladder(double t) {
  // 2^(-k/16), k = 0 .. 16, rounded down (so that every step is at most its exact value).
  static const std::array<double, 17> steps = [] {
    std::array<double, 17> s{};
    for (int k = 0; k <= 16; ++k) s[static_cast<std::size_t>(k)] = std::nextafter(std::exp2(-k / 16.0), 0.0);
    s[0] = 1.0;
    s[16] = 0.5;
    return s;
  }();
  if (!(t > 0.0) || !std::isfinite(t)) return t;  // the grid search refuses these
  int exponent = 0;
  const double mantissa = std::frexp(t, &exponent);  // t = mantissa 2^exponent, mantissa in [1/2, 1)
  std::size_t k = 1;
  while (steps[k] > mantissa) ++k;  // steps[16] = 1/2 <= mantissa ends it
  const double step = std::ldexp(steps[k], exponent);
  return step <= t ? step : t;  // (a subnormal t: ldexp rounds)
}

// The parameters k / rate for k = from..to (a side's or the interior's points), into `ts`.
inline void ramp(int from, int to, int rate, std::vector<double>& ts) {
  ts.clear();
  for (int k = from; k <= to; ++k) ts.push_back(static_cast<double>(k) / rate);
}

inline void check_positive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw InvalidInput(message("tessellate: ", name, " ", value, " is not positive and finite"));
  }
}

/// The checks of `options` that need no surface: exactly one mode, and its values (a tolerance,
/// relative tolerance or pixel tolerance positive and finite, segments in [1, 2^20], the camera
/// valid and, `bezier_patches`, pieces that have them), the crease angle >= 0.
/// \throws InvalidInput naming the first that fails.
void check_options(const TessellationOptions& options, bool bezier_patches = true);

/// The absolute tolerance of a relative one on a surface of box diagonal `diagonal`.
/// \throws InvalidInput if it is not positive and finite.
inline double relative_tolerance_times(double relative, double diagonal) {
  const double tolerance = relative * diagonal;
  check_positive(tolerance, "tolerance (relative tolerance times the box diagonal)");
  return tolerance;
}

// Whether parameter triangle (a, b, c) is one half of a grid cell of steps (du, dv), split along
// its diagonal from the low to the high corner (either half, in any vertex order).
inline bool is_grid_cell_half(const Vec2& a, const Vec2& b, const Vec2& c, double du, double dv) {
  const Vec2 low = a.cwiseMin(b).cwiseMin(c);
  const Vec2 high = a.cwiseMax(b).cwiseMax(c);
  constexpr double slack = 1e-12;
  if (std::abs(high.x() - low.x() - du) > slack * du || std::abs(high.y() - low.y() - dv) > slack * dv) return false;
  const auto is = [](const Vec2& p, double x, double y) { return p.x() == x && p.y() == y; };
  const auto has = [&](double x, double y) { return is(a, x, y) || is(b, x, y) || is(c, x, y); };
  return has(low.x(), low.y()) && has(high.x(), high.y()) && (has(high.x(), low.y()) || has(low.x(), high.y()));
}

// The a-priori bound of every triangle of a pattern given by its boundary part
// (make_pattern_boundary) and inner grid, the largest (the halves of inner grid cells get the
// grid's bound `cell`; a triangle whose own bound exceeds the tolerance is refined on `surface`).
double pattern_bound(const TessellationPattern& boundary, const InnerGrid& inner, const SecondDerivativeBounds& bounds,
                     double cell, const std::function<Vec3(const Vec2&)>& surface, double tolerance);

// --- tessellator_measure.cpp: the measured error ---------------------------------------------

/// The measured error of tessellated piece p: the largest |S(u, v) - L(u, v)| over the
/// measure_sample_weights of every triangle of its pattern (out.kept, out.dropped and the inner
/// cells), S from pieces.evaluate_points (pieces.evaluate where that is empty), L interpolating
/// the positions of the triangle's corners: welded_positions[out.welded[k]] for boundary point k,
/// interior[q] for interior point q (the piece's interior mesh positions, row by row, as
/// assembled). Samples that are the same point of two triangles are evaluated once, and corners
/// whose mesh position is the piece's own surface point are not evaluated (their distance is
/// zero but for rounding); see tessellator_measure.cpp.
double measured_piece_error(const SurfacePieces& pieces, std::uint32_t p, const PatchOutput& out,
                            std::span<const Vec3> welded_positions, std::span<const Vec3> interior);

class Tessellator {
 public:
  // `planned`: the grid of every piece at the options' tolerance, when the caller has found them
  // already (tessellate(PatchSet) does, to choose the split).
  // `diagonal`, `solids`: in place of pieces.diagonal and pieces.solids (a PreparedSurface keeps
  // one set of pieces for either diagonal, and its solids apart, made on first use).
  // `grid_memos`: one per piece, what earlier runs' grid searches learnt about its bounds (a
  // PreparedSurface's per-frame call keeps them in the result's scratch); nullptr: none.
  Tessellator(const SurfacePieces& pieces, const TessellationOptions& options,
              const std::vector<GridSize>* planned = nullptr, std::optional<double> diagonal = std::nullopt,
              const std::vector<std::int32_t>* solids = nullptr, std::vector<GridSearchMemo>* grid_memos = nullptr)
      : pieces_(pieces),
        options_(options),
        planned_(planned),
        grid_memos_(grid_memos),
        diagonal_(diagonal.value_or(pieces.diagonal)),
        solids_(solids != nullptr ? *solids : pieces.solids),
        count_(pieces.count),
        plans_(count_),
        slots_(count_) {
    PATCHWORK_ASSERT(pieces.bounds.size() == count_, "one bound per piece");
    PATCHWORK_ASSERT(planned == nullptr || (planned->size() == count_ && !options.camera), "one grid per piece");
    PATCHWORK_ASSERT(grid_memos == nullptr || grid_memos->size() == count_, "one grid memo per piece");
  }

  // Tessellates into `result`, reusing its arrays' storage. Without `keep_scratch` (a result
  // that is not passed in again) the per-piece scratch and the plan are freed once the mesh is
  // assembled and measured, before the vertex order, whose tables are then the peak's only
  // addition to the mesh (at 524,288 pieces the scratch was 1.1 GB of a 2.65 GB peak).
  void run(Tessellation& result, bool keep_scratch = true);

 private:
  // --- rates ------------------------------------------------------------------------------

  void plan_patches();

  // Per piece, whether it may be left out where it faces away from the camera (BackFaceCulling).
  std::vector<bool> hidden_back_faces(const Camera& camera) const;

  // Classes for every edge of every patch that is tessellated: a shared edge whose two patches
  // are both tessellated is one class; every other edge is its own.
  void build_edge_classes();

  // A class's rate is the largest rate any of its patches needs along it; a collapsed edge
  // follows its patch's inner rate, so its triangles fan evenly into the pole.
  // A composite edge asks each of its pieces for the long edge's rate over the piece's length.
  void update_edge_rates();

  PatternRates rates(std::uint32_t p) const;

  // Stitched triangles can reach further than grid cells; raise the inner rates of any patch
  // whose worst triangle exceeds its tolerance until none does (rates only grow, so this ends).
  void raise_rates_to_bounds();

  // The bound of patch p's stitched pattern at its current rates (computed once per rates).
  double stitched_bound(std::uint32_t p);

  // The bound of patch p's pattern at rates r, its stitched triangles refined against its
  // tolerance where it has one (pattern_bound).
  double pattern_bound_of(std::uint32_t p, const PatternRates& r);

  // The triangle estimate the budget is checked on (2 max(nu,2) max(nv,2) plus the edge rates
  // a piece), which it returns. \throws InvalidInput above options_.max_triangles.
  double check_triangle_budget() const;

  // --- welding ----------------------------------------------------------------------------

  // Corners are one point where shared or collapsed edges join them; then every class's inner
  // points get a block of ids, then each patch's interior.
  void number_welded_points();

  // --- per patch ----------------------------------------------------------------------------

  // Every tessellated piece's boundary pattern: shared from `table` (made there if new) or,
  // with composite edges, the piece's own (made by tessellate_patch).
  void assign_patterns(PatternTable& table);

  // The boundary part of patch p: its points' welded ids, positions and normals, its triangles
  // (kept or dropped) and the bound of the whole pattern.
  void tessellate_patch(std::uint32_t p);

  // Positions, normals (and tangents) of the boundary points, each side (with its corners) as a
  // one-row grid. With `sharing_samples_`, only the points the piece owns (the rest come from
  // share_samples), each recorded in sample_owners_.
  void evaluate_sides(std::uint32_t p, const PatternRates& r, PatchOutput& out) const;

  // The boundary points patch p does not own: copied from their owner where that is the same
  // patch at the same parameters (split pieces share their inner edges and corners; the
  // evaluation there is the same), evaluated otherwise. After every piece's tessellate_patch.
  void share_samples(std::uint32_t p) const;

  // The samples of piece p's boundary points `points` (pattern indices) into out's arrays.
  void evaluate_points_of(std::uint32_t p, std::span<const std::uint32_t> points, PatchOutput& out) const;

  // Piece q's parameter point uv in its patch's parameters (as SurfacePieces' evaluators map it).
  Vec2 patch_parameter(std::uint32_t q, const Vec2& uv) const {
    if (pieces_.domains.empty()) return uv;
    const SurfacePieces::Domain& d = pieces_.domains[q];
    return Vec2(d.u0, d.v0) + d.size * uv;
  }

  // --- assembly -----------------------------------------------------------------------------

  // The patch a piece belongs to (itself unless the pieces are split patches).
  std::uint32_t patch_of(std::uint32_t p) const { return pieces_.domains.empty() ? p : pieces_.domains[p].patch; }

  Vec2 uv_of(std::uint32_t p, Vec2 uv) const;

  // The mesh in three steps. (1) The boundary points of every patch become render vertices, in
  // patch order: a welded point becomes several vertices only where its attributes differ
  // between the patches around it. (2) Every patch gets a block of vertices for its interior
  // points and a block of triangles, so (3) the patches write their interiors and triangles in
  // parallel, straight into the mesh. `result`'s arrays are reused (resized, not reallocated,
  // when they have room).
  void assemble(Tessellation& result);

  // Patch p's interior vertices and all its triangles, into their blocks of `mesh`.
  // The regular parts go out a row at a time from small buffers, with streaming stores where
  // the output is far larger than the caches (streaming_, core/streaming_store.h).
  void write_patch(std::uint32_t p, RenderMesh& mesh, std::vector<std::uint32_t>& triangle_patches,
                   std::uint32_t position_offset) const;

  // --- measurement --------------------------------------------------------------------------

  // e_par: |S(u,v) - L(u,v)| at the samples of every parameter triangle, L the linear
  // interpolant of the mesh positions: the largest measured_piece_error, pieces in parallel.
  double measure(const RenderMesh& mesh) const;

  // Triangles reordered for the vertex cache, and their patches along: one meshoptimizer call
  // per chunk of vertex_cache_chunk consecutive triangles, chunks in parallel (tessellator_vertex_order.cpp).
  static void optimize_vertex_cache(Tessellation& result, VertexOrderScratch& scratch, int threads);

  // Vertices in order of first use by the (cache-ordered) triangles.
  static void optimize_vertex_fetch(RenderMesh& mesh, VertexOrderScratch& scratch, int threads);

  const SurfacePieces& pieces_;
  const TessellationOptions& options_;
  const std::vector<GridSize>* planned_;
  std::vector<GridSearchMemo>* grid_memos_;
  double diagonal_;
  const std::vector<std::int32_t>& solids_;
  std::size_t count_;
  std::vector<PatchPlan> plans_;
  std::vector<std::array<EdgeSlot, 4>> slots_;
  std::vector<CompositeEdge> composites_;
  std::uint32_t junctions_ = 0;
  std::vector<EdgeClass> classes_;
  std::vector<std::uint32_t> corner_ids_;
  std::vector<bool> corner_owner_;
  std::vector<std::uint32_t> interior_first_;
  std::uint32_t welded_count_ = 0;
  std::uint32_t boundary_ids_ = 0;  // welded ids below this are boundary points
  // Boundary points are evaluated by their owners only, the others share (share_samples): with
  // the scattered-sample evaluator (SurfacePieces::evaluate_samples) only.
  bool sharing_samples_ = false;
  // Per boundary welded id, its owner's piece (high 32 bits) and point (in the scratch).
  std::vector<std::uint64_t>* sample_owners_ = nullptr;
  std::vector<PatchOutput>* outputs_ = nullptr;    // in the result's scratch
  std::vector<Vec3>* welded_positions_ = nullptr;  // of the boundary points, by welded id (in the scratch)
  bool unused_interior_ = false;
  bool streaming_ = false;  // write_patch streams its output (assemble)
  std::size_t culled_ = 0;
  std::int64_t culled_triangles_ = 0;
};

// The by-value forms of tessellate: `run` into a fresh result, whose scratch is then freed.
template <class Run>
Tessellation fresh_tessellation(const Run& run) {
  Tessellation result;
  run(result);
  result.scratch.release();
  return result;
}

/// tessellate(prepared, options, result); `keep_scratch` false for a result that is not passed
/// in again (Tessellator::run).
void tessellate_prepared(const PreparedSurface& prepared, const TessellationOptions& options, Tessellation& result,
                         bool keep_scratch);

// --- surface_pieces.cpp: patch sets as pieces -------------------------------------------------

/// The 4 x 4 sub-net bounds of every patch (what the rates of whole and split patches rest on).
/// \throws InvalidInput if every control point is the same point.
std::vector<std::vector<SecondDerivativeBounds>> cell_bounds(const PatchSet& set);

/// The diagonal of the surface's tight box (tight_diagonal) or of the control points' box.
double tight_or_control_diagonal(const PatchSet& set, bool tight_diagonal);

/// Per patch, the solid it bounds, or -1 (SurfacePieces::solids).
std::vector<std::int32_t> solids_of(const PatchSet& set);

/// The pieces of `set`, each patch split k x k (k = 1: the patches themselves, with the set's
/// T-junctions and, with_solids, its solids for back-face culling).
SurfacePieces pieces_of(const PatchSet& set, const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k,
                        double diagonal, bool with_solids = true);

/// The grid of every piece of a k x k split at tolerance eps, as plan_patches finds them (in the
/// pieces' order), and their cell count; shared-edge rates and stitching come on top.
struct SplitEstimate {
  std::vector<GridSize> grids;
  std::int64_t cells = 0;
};

/// The split estimate of `cells` at k x k and tolerance eps, on `threads` threads (0: all
/// cores; the result does not depend on it), with one grid memo per piece (k x k a patch, in
/// the order of the split pieces) if `memos` is given. \throws InvalidInput as grid_for_tolerance does.
SplitEstimate estimated_split(const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k, double eps,
                              int threads, std::vector<GridSearchMemo>* memos = nullptr);

}  // namespace patchwork::detail
