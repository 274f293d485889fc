#include "surfaces/tessellator.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "core/assert.h"
#include "core/errors.h"
#include "core/huge_pages.h"
#include "core/parallel.h"
#include "core/streaming_store.h"
#include "core/union_find.h"
#include "surfaces/patch_bounding_box.h"
#include "surfaces/patch_flatness.h"
#include "surfaces/patch_grid.h"
#include "surfaces/surface_integrals.h"
#include "surfaces/tessellation_pattern.h"

namespace patchwork {
namespace {

using Triangle = std::array<std::uint32_t, 3>;
constexpr std::uint32_t no_id = 0xffffffffu;
// Second-derivative bounds from 4 x 4 sub-nets: close to the true suprema (patch_flatness.h).
constexpr int bound_pieces = 4;

// Edge k of a patch runs (in boundary_curve direction) from corner edge_start(k) to edge_end(k);
// corners are numbered c0 = (0,0), c1 = (1,0), c2 = (1,1), c3 = (0,1).
constexpr std::array<int, 4> edge_start = {0, 1, 3, 0};
constexpr std::array<int, 4> edge_end = {1, 2, 2, 3};

// Segments along edge k for inner rates (nu, nv): v0 and v1 run along u.
int along(int edge, int nu, int nv) { return edge % 2 == 0 ? nu : nv; }

// The segments of a T-junction's piece of length `length` (of its long edge) at inner rate n:
// as many as the long edge's patch has along it there, at least one.
int piece_rate(int n, double length) { return std::max(1, static_cast<int>(std::ceil(n * length - 1e-9))); }

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
  SecondDerivativeBounds bounds{0, 0, 0};
  int nu = 1;
  int nv = 1;
  // flatness_bound of the last inner grid asked for (the cell bound costs some 0.5 us; the quick
  // bounds stand where they meet the tolerance).
  int cell_nu = 0;
  int cell_nv = 0;
  double cell = 0.0;

  // The bound of the grid cells of steps (1/nu, 1/nv).
  double cell_bound(int grid_nu, int grid_nv) {
    if (grid_nu != cell_nu || grid_nv != cell_nv) {
      cell_nu = grid_nu;
      cell_nv = grid_nv;
      cell = flatness_bound(bounds, 1.0 / grid_nu, 1.0 / grid_nv, tolerance);
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
  std::vector<bool> joined;    // part b is tessellated and owns class b
  std::uint32_t first_junction = 0;
};

}  // namespace

namespace detail {

// One patch's part of the tessellation. Only what touches its boundary is kept per patch (the
// boundary points, their attributes and the triangles with a corner among them); the interior
// points and inner cells are regular (make_pattern_boundary) and are written straight into the
// output, so a large grid costs no intermediate copies.
struct PatchOutput {
  InnerGrid inner{1, 1, true};
  TessellationPattern pattern;        // make_pattern_boundary
  std::vector<std::uint32_t> welded;  // per boundary point
  std::vector<bool> owner;            // this patch supplies the welded point's position
  std::vector<Vec3> positions;        // per boundary point, until assembled
  std::vector<Vec3> normals;
  std::vector<Vec4> tangents;
  std::vector<Triangle> kept;         // boundary triangles, pattern-local
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
    pattern.points.clear();
    pattern.triangles.clear();
    welded.clear();
    owner.clear();
    positions.clear();
    normals.clear();
    tangents.clear();
    kept.clear();
    dropped.clear();
    vertex.clear();
    unused_interior = false;
    bound = 0.0;
    weld_gap = 0.0;
  }
  std::uint32_t boundary_points() const { return static_cast<std::uint32_t>(pattern.points.size()); }
  std::size_t interior_points() const {
    return static_cast<std::size_t>(inner.u - 1) * static_cast<std::size_t>(inner.v - 1);
  }
  std::size_t inner_cells() const {
    return static_cast<std::size_t>(std::max(inner.u - 2, 0)) * static_cast<std::size_t>(std::max(inner.v - 2, 0));
  }
  std::size_t triangle_count() const { return kept.size() + 2 * inner_cells(); }
  // The (u, v) of pattern point k (boundary points listed, interior points on the inner grid).
  Vec2 uv(std::uint32_t k) const {
    if (k < boundary_points()) return pattern.points[k].uv;
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

// What a run needs besides its output, kept for the next run into the same Tessellation.
struct TessellatorScratch {
  std::vector<PatchOutput> outputs;
  std::vector<Vec3> welded_positions;
  std::vector<VertexSource> sources;
  std::vector<std::uint8_t> pole;  // by welded id: a collapsed edge's point
  std::vector<std::uint32_t> first_vertex;
  ChainHeads heads;
  std::vector<std::uint32_t> next_vertex;
  std::vector<std::uint32_t> dense_position;
};

TessellatorScratchHandle::TessellatorScratchHandle() noexcept = default;
TessellatorScratchHandle::~TessellatorScratchHandle() = default;
TessellatorScratchHandle::TessellatorScratchHandle(const TessellatorScratchHandle&) noexcept {}
TessellatorScratchHandle& TessellatorScratchHandle::operator=(const TessellatorScratchHandle&) noexcept {
  return *this;
}
TessellatorScratchHandle::TessellatorScratchHandle(TessellatorScratchHandle&&) noexcept = default;
TessellatorScratchHandle& TessellatorScratchHandle::operator=(TessellatorScratchHandle&&) noexcept = default;
TessellatorScratch& TessellatorScratchHandle::get() {
  if (!scratch_) scratch_ = std::make_unique<TessellatorScratch>();
  return *scratch_;
}
void TessellatorScratchHandle::release() noexcept { scratch_.reset(); }
}  // namespace detail

namespace {

using detail::PatchOutput;
using detail::VertexSource;

// Outputs from this size on are written with streaming stores: far beyond the per-core caches
// (a tessellation this large is not read back while it is written).
constexpr std::size_t streamed_output_bytes = std::size_t{64} << 20;

// The fewest segments per direction a piece gets: two on a curved piece, so that coarse
// tolerances keep the topology (with one, a tube of two patches, the teapot's handle, would
// flatten into a doubled ribbon), one on a flat piece. (One on the curved pieces of split patches
// would keep the topology too, but cost the teapot triangles in stitching, measured once: 8,466 against 8,388
// at 1e-3.)
std::int64_t least_segments(const SecondDerivativeBounds& M) {
  const bool flat = M.uu == 0.0 && M.uv == 0.0 && M.vv == 0.0;
  return flat ? 1 : 2;
}

// The parameters k / rate for k = from..to (a side's or the interior's points).
std::vector<double> ramp(int from, int to, int rate) {
  std::vector<double> ts;
  ts.reserve(static_cast<std::size_t>(std::max(to - from + 1, 0)));
  for (int k = from; k <= to; ++k) ts.push_back(static_cast<double>(k) / rate);
  return ts;
}

void check_positive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw InvalidInput(detail::message("tessellate: ", name, " ", value, " is not positive and finite"));
  }
}

// Whether parameter triangle (a, b, c) is one half of a grid cell of steps (du, dv), split along
// its diagonal from the low to the high corner (either half, in any vertex order).
bool is_grid_cell_half(const Vec2& a, const Vec2& b, const Vec2& c, double du, double dv) {
  const Vec2 low = a.cwiseMin(b).cwiseMin(c);
  const Vec2 high = a.cwiseMax(b).cwiseMax(c);
  constexpr double slack = 1e-12;
  if (std::abs(high.x() - low.x() - du) > slack * du || std::abs(high.y() - low.y() - dv) > slack * dv) return false;
  const auto is = [](const Vec2& p, double x, double y) { return p.x() == x && p.y() == y; };
  const auto has = [&](double x, double y) { return is(a, x, y) || is(b, x, y) || is(c, x, y); };
  return has(low.x(), low.y()) && has(high.x(), high.y()) && (has(high.x(), low.y()) || has(low.x(), high.y()));
}

// The a-priori bound of every triangle of a pattern, the largest. The halves of inner grid cells
// get the grid's bound `cell` (flatness_bound, which bounds either half of any cell of those steps); a
// triangle whose own bound exceeds the tolerance is refined on `surface`
// (refined_triangle_flatness_bound), so that a stitched triangle is not raised for want of a
// tighter bound.
double pattern_bound(const TessellationPattern& pattern, const SecondDerivativeBounds& bounds, int nu, int nv,
                     double cell, const std::function<Vec3(const Vec2&)>& surface, double tolerance) {
  if (pattern.grid) return cell;
  const double du = 1.0 / nu;
  const double dv = 1.0 / nv;
  const double aspect = static_cast<double>(nu) / nv;
  double bound = 0.0;
  for (const Triangle& t : pattern.triangles) {
    const Vec2& a = pattern.points[t[0]].uv;
    const Vec2& b = pattern.points[t[1]].uv;
    const Vec2& c = pattern.points[t[2]].uv;
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

class Tessellator {
 public:
  // `planned`: the grid of every piece at the options' tolerance, when the caller has found them
  // already (tessellate(PatchSet) does, to choose the split).
  Tessellator(const SurfacePieces& pieces, const TessellationOptions& options,
              const std::vector<GridSize>* planned = nullptr)
      : pieces_(pieces), options_(options), planned_(planned), count_(pieces.count), plans_(count_), slots_(count_) {
    PATCHWORK_ASSERT(pieces.bounds.size() == count_, "one bound per piece");
    PATCHWORK_ASSERT(planned == nullptr || (planned->size() == count_ && !options.camera), "one grid per piece");
  }

  // Tessellates into `result`, reusing its arrays' storage.
  void run(Tessellation& result) {
    plan_patches();
    build_edge_classes();
    // Raising only adds triangles: a plan over the budget is refused before its stitched
    // patterns are built and bounded (at a tolerance that needs billions of triangles, that
    // alone would take minutes and gigabytes).
    check_triangle_budget();
    if (!options_.segments) raise_rates_to_bounds();
    check_triangle_budget();
    number_welded_points();
    // The per-patch arrays of the last run into `result` keep their storage (a caller tessellating
    // again and again then allocates next to nothing).
    outputs_ = &result.scratch.get().outputs;
    outputs_->resize(count_);
    parallel_for(count_, options_.threads, [&](std::size_t p) {
      (*outputs_)[p].clear();
      if (!plans_[p].culled) tessellate_patch(static_cast<std::uint32_t>(p));
    });
    assemble(result);
    if (options_.measure) result.measured_error = measure(result.mesh);
    if (options_.optimize) optimize_vertex_cache(result);
    // The vertex-fetch order also drops unused vertices (PatchOutput::unused_interior).
    if (options_.optimize || unused_interior_) optimize_vertex_fetch(result.mesh);
    if (unused_interior_) {
      const auto& ids = result.mesh.position_ids;
      result.welded_vertices = ids.empty() ? 0 : 1 + *std::max_element(ids.begin(), ids.end());
    }
  }

 private:
  // --- rates ------------------------------------------------------------------------------

  void plan_patches() {
    const int modes = options_.tolerance.has_value() + options_.relative_tolerance.has_value() +
                      options_.segments.has_value() + options_.camera.has_value();
    if (modes != 1) {
      throw InvalidInput(
          detail::message("tessellate: give exactly one of tolerance, relative tolerance, segments "
                          "and camera (",
                          modes, " given)"));
    }
    if (!(options_.crease_angle >= 0.0) || !std::isfinite(options_.crease_angle)) {
      throw InvalidInput(detail::message("tessellate: crease angle ", options_.crease_angle, " is not >= 0"));
    }
    double tolerance = 0.0;
    if (options_.tolerance) {
      check_positive(*options_.tolerance, "tolerance");
      tolerance = *options_.tolerance;
    } else if (options_.relative_tolerance) {
      check_positive(*options_.relative_tolerance, "relative tolerance");
      tolerance = *options_.relative_tolerance * pieces_.diagonal;
      check_positive(tolerance, "tolerance (relative tolerance times the box diagonal)");
    } else if (options_.segments) {
      if (*options_.segments < 1 || *options_.segments > (1 << 20)) {
        throw InvalidInput(detail::message("tessellate: segments ", *options_.segments, " is not in [1, 2^20]"));
      }
    } else {
      if (pieces_.patches == nullptr) throw InvalidInput("tessellate: the camera mode needs Bezier patches");
      validate(*options_.camera);
      check_positive(options_.pixel_tolerance, "pixel tolerance");
    }
    double focal = options_.camera ? focal_length_pixels(*options_.camera) : 0.0;
    const std::vector<bool> back_faces_hidden = options_.camera ? hidden_back_faces(*options_.camera) : std::vector<bool>();
    // Patches reaching behind the near limit get the tolerance of this depth.
    const double near_depth = 1e-3 * pieces_.diagonal;
    for (std::size_t p = 0; p < count_; ++p) {
      PatchPlan& plan = plans_[p];
      plan.bounds = pieces_.bounds[p];
      if (options_.segments) {
        plan.nu = plan.nv = *options_.segments;
        continue;
      }
      plan.tolerance = tolerance;
      if (options_.camera) {
        const Camera& camera = *options_.camera;
        const BezierPatch3& patch = (*pieces_.patches)[p];
        plan.tolerance = options_.pixel_tolerance * std::max(nearest_depth(patch, camera), near_depth) / focal;
        plan.culled = outside_frustum(patch, camera) || (back_faces_hidden[p] && back_facing(patch, camera.eye));
      }
      // The weld gap of the piece's edges comes on top of its pattern's bound (assemble): plan
      // for the rest, down to half the tolerance (a gap beyond that shows in error_bound).
      const double reserve = pieces_.gaps.empty() ? 0.0 : pieces_.gaps[p];
      if (reserve > 0.0) plan.tolerance = std::max(plan.tolerance - reserve, 0.5 * plan.tolerance);
      GridSize grid{};
      try {
        grid = planned_ && reserve == 0.0 ? (*planned_)[p]
                                          : grid_for_tolerance(plan.bounds, plan.tolerance, least_segments(plan.bounds));
      } catch (const InvalidInput&) {
        throw InvalidInput(detail::message("tessellate: piece ", p,
                                           " would need more than 2^20 segments per side at "
                                           "tolerance ",
                                           plan.tolerance, " (over 10^12 triangles; the limit is ",
                                           options_.max_triangles, ")"));
      }
      plan.nu = static_cast<int>(grid.segments_u);
      plan.nv = static_cast<int>(grid.segments_v);
      if (plan.culled) {
        ++culled_;
        culled_triangles_ += 2 * grid.segments_u * grid.segments_v;
      }
    }
  }

  // Per piece, whether it may be left out where it faces away from the camera (BackFaceCulling).
  std::vector<bool> hidden_back_faces(const Camera& camera) const {
    if (options_.back_face_culling != BackFaceCulling::automatic) {
      return std::vector<bool>(count_, options_.back_face_culling == BackFaceCulling::always);
    }
    std::vector<bool> hidden(count_, false);
    if (pieces_.solids.empty()) return hidden;
    // Outside the box of a solid's control points is outside the solid (its convex hull).
    std::vector<Eigen::AlignedBox3d> boxes;
    for (std::size_t p = 0; p < count_; ++p) {
      const std::int32_t solid = pieces_.solids[p];
      if (solid < 0) continue;
      if (boxes.size() <= static_cast<std::size_t>(solid)) boxes.resize(static_cast<std::size_t>(solid) + 1);
      for (const Vec3& q : (*pieces_.patches)[p].control_points()) boxes[static_cast<std::size_t>(solid)].extend(q);
    }
    for (std::size_t p = 0; p < count_; ++p) {
      const std::int32_t solid = pieces_.solids[p];
      hidden[p] = solid >= 0 && !boxes[static_cast<std::size_t>(solid)].contains(camera.eye);
    }
    return hidden;
  }

  // Classes for every edge of every patch that is tessellated: a shared edge whose two patches
  // are both tessellated is one class; every other edge is its own.
  void build_edge_classes() {
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
  void update_edge_rates() {
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
      for (std::size_t b = 0; b < composite.classes.size(); ++b) composite.segments.rates[b] = classes_[composite.classes[b]].rate;
    }
  }

  PatternRates rates(std::uint32_t p) const {
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
  void raise_rates_to_bounds() {
    for (int round = 0; round < 64; ++round) {
      bool raised = false;
      for (std::uint32_t p = 0; p < count_; ++p) {
        PatchPlan& plan = plans_[p];
        if (plan.culled) continue;
        const InnerGrid inner = inner_grid(rates(p));
        const int nu = inner.u;
        const int nv = inner.v;
        // A plain grid meets the tolerance by construction (its rates only grew); only
        // stitched patterns need their triangles checked.
        if (inner.grid || stitched_bound(p) <= plan.tolerance) continue;
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
        raised = true;
      }
      if (!raised) return;
      update_edge_rates();
    }
    throw NumericalError("tessellate: the stitched rates did not settle within 64 rounds");
  }

  // The bound of patch p's stitched pattern at its current rates (computed once per rates).
  double stitched_bound(std::uint32_t p) {
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
  double pattern_bound_of(std::uint32_t p, const PatternRates& r) {
    PatchPlan& plan = plans_[p];
    const InnerGrid inner = inner_grid(r);
    const auto surface = [this, p](const Vec2& uv) { return pieces_.evaluate(p, uv.x(), uv.y()); };
    const double target = options_.segments ? std::numeric_limits<double>::infinity() : plan.tolerance;
    return pattern_bound(make_pattern(r), plan.bounds, inner.u, inner.v, plan.cell_bound(inner.u, inner.v), surface,
                         target);
  }

  void check_triangle_budget() const {
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
  }

  // --- welding ----------------------------------------------------------------------------

  // Corners are one point where shared or collapsed edges join them; then every class's inner
  // points get a block of ids, then each patch's interior.
  void number_welded_points() {
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
        corners.unite(slot(part.patch, from), b == 0 ? slot(e.patch, edge_start[k]) : patch_slots + composite.first_junction + static_cast<std::uint32_t>(b - 1));
        corners.unite(slot(part.patch, to), b == last ? slot(e.patch, edge_end[k]) : patch_slots + composite.first_junction + static_cast<std::uint32_t>(b));
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
    interior_first_.assign(count_, no_id);
    for (std::uint32_t p = 0; p < count_; ++p) {
      if (plans_[p].culled) continue;
      const InnerGrid inner = inner_grid(rates(p));
      interior_first_[p] = next;
      next += static_cast<std::uint32_t>((inner.u - 1) * (inner.v - 1));
    }
    welded_count_ = next;
  }

  // --- per patch ----------------------------------------------------------------------------

  // The boundary part of patch p: its points' welded ids, positions and normals, its triangles
  // (kept or dropped) and the bound of the whole pattern.
  void tessellate_patch(std::uint32_t p) {
    PatchOutput& out = (*outputs_)[p];
    const PatternRates r = rates(p);
    out.inner = inner_grid(r);
    make_pattern_boundary(r, out.pattern);
    const TessellationPattern& pattern = out.pattern;
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
    if (std::none_of(pattern.triangles.begin(), pattern.triangles.end(), degenerate)) {
      std::swap(out.kept, out.pattern.triangles);  // the common case: no collapsed edge
    } else {
      for (const Triangle& t : pattern.triangles) (degenerate(t) ? out.dropped : out.kept).push_back(t);
      out.pattern.triangles.clear();
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
    out.bound = pattern.grid                        ? plan.cell_bound(out.inner.u, out.inner.v)
                : plan.checked_rates == r           ? plan.checked_bound
                                                    : pattern_bound_of(p, r);
  }

  // Positions, normals (and tangents) of the boundary points, each side (with its corners) as a
  // one-row grid.
  void evaluate_sides(std::uint32_t p, const PatternRates& r, PatchOutput& out) const {
    const std::size_t count = out.pattern.points.size();
    out.positions.resize(count);
    out.normals.resize(count);
    if (options_.tangents) out.tangents.resize(count);
    std::vector<Vec3> points;
    std::vector<Vec3> normals;
    std::vector<Vec4> tangents;
    // Sides v0 and v1 with their corners; sides u1 and u0 without.
    for (int k = 0; k < 4; ++k) {
      const int e = r.edges[k];
      const bool along_u = k % 2 == 0;
      // The pattern's parameters: even steps, or even within each piece of a composite edge.
      std::vector<double> ts;
      for (int step = along_u ? 0 : 1; step <= (along_u ? e : e - 1); ++step) ts.push_back(edge_step_parameter(r, k, step));
      if (ts.empty()) continue;
      points.resize(ts.size());
      normals.resize(ts.size());
      if (options_.tangents) tangents.resize(ts.size());
      const std::vector<double> fixed = {k == 1 || k == 2 ? 1.0 : 0.0};
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

  // --- assembly -----------------------------------------------------------------------------

  // The patch a piece belongs to (itself unless the pieces are split patches).
  std::uint32_t patch_of(std::uint32_t p) const { return pieces_.domains.empty() ? p : pieces_.domains[p].patch; }

  Vec2 uv_of(std::uint32_t p, Vec2 uv) const {
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
  void assemble(Tessellation& result) {
    // Boundary welded ids come before every interior one (number_welded_points).
    std::uint32_t interior_base = welded_count_;
    for (std::uint32_t p = 0; p < count_; ++p) {
      if (!plans_[p].culled) interior_base = std::min(interior_base, interior_first_[p]);
    }
    welded_positions_ = &result.scratch.get().welded_positions;
    welded_positions_->assign(interior_base, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    for (const PatchOutput& out : *outputs_) {
      for (std::size_t k = 0; k < out.welded.size(); ++k) {
        if (out.owner[k]) (*welded_positions_)[out.welded[k]] = out.positions[k];
      }
    }
    // A welded point takes its owner's position; where the patches' edges differ (PatchSet joins
    // edges whose control points agree within its tolerance) that moves it off this patch's own
    // surface point. Every mesh point of a triangle is an affine combination of its corners, so
    // it moves by at most the largest corner move: |S - L'| <= bound + max |d|.
    for (PatchOutput& out : *outputs_) {
      double moved = 0.0;
      for (std::size_t k = 0; k < out.welded.size(); ++k) {
        if (out.owner[k]) continue;
        // A welded point without an owner would be NaN: never let it pass as a finite gap.
        const double d = ((*welded_positions_)[out.welded[k]] - out.positions[k]).norm();
        if (!(d <= moved)) moved = d;
      }
      PATCHWORK_ASSERT(std::isfinite(moved), "every welded point has a position");
      out.weld_gap = moved;
    }
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
        const Vec2 uv = with_uv ? uv_of(p, out.pattern.points[k].uv) : Vec2::Zero();
        std::uint32_t& head = pole[id] != 0 ? heads.head(id, uv) : first_vertex[id];
        for (std::uint32_t v = head; v != no_id; v = next_vertex[v]) {
          const PatchOutput& other = (*outputs_)[sources[v].patch];
          const std::uint32_t j = sources[v].point;
          const bool same =
              other.normals[j].dot(out.normals[k]) >= cos_crease &&
              (!with_uv || uv_of(sources[v].patch, other.pattern.points[j].uv) == uv) &&
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
      for (const Triangle& t : out.kept) {
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
    const auto resize = [](auto& array, std::size_t size) {
      if (array.capacity() < size) {
        array = {};
        reserve_huge(array, size);
      }
      array.resize(size);
    };
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
      if (with_uv) mesh.uvs[v] = uv_of(source.patch, out.pattern.points[source.point].uv);
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
  void write_patch(std::uint32_t p, RenderMesh& mesh, std::vector<std::uint32_t>& triangle_patches,
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
    if (interior > 0) {
      const std::size_t first = out.first_vertex;
      const std::vector<double> us = ramp(1, out.inner.u - 1, out.inner.u);
      const std::vector<double> vs = ramp(1, out.inner.v - 1, out.inner.v);
      const std::span<Vec4> tangents =
          options_.tangents ? std::span<Vec4>(mesh.tangents).subspan(first, interior) : std::span<Vec4>();
      pieces_.evaluate_grid(p, us, vs,
                            {std::span<Vec3>(mesh.positions).subspan(first, interior),
                             std::span<Vec3>(mesh.normals).subspan(first, interior), tangents, stream});
      const std::size_t row = us.size();
      const std::uint32_t position = interior_first_[p] + position_offset;
      std::vector<std::uint32_t> ids(row);
      for (std::size_t j = 0; j < vs.size(); ++j) {
        for (std::size_t k = 0; k < row; ++k) ids[k] = position + static_cast<std::uint32_t>(j * row + k);
        put(mesh.position_ids.data() + first + j * row, ids.data(), row * sizeof(std::uint32_t));
      }
      if (options_.uv != UvMode::none) {
        // uv_of is affine in (u, v).
        const Vec2 origin = uv_of(p, Vec2(0, 0));
        const Vec2 scale = uv_of(p, Vec2(1, 1)) - origin;
        std::vector<double> uvs(2 * row);
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
    for (const Triangle& t : out.kept) {
      for (std::uint32_t k : t) *index++ = k < boundary ? out.vertex[k] : k + interior_shift;
    }
    // The inner cells row by row: each row's indices are the first row's shifted by the points
    // of a row (for_each_inner_triangle's numbering).
    if (out.inner.u > 2 && out.inner.v > 2) {
      std::vector<std::uint32_t> first_row;
      for_each_inner_triangle({out.inner.u, 3, out.inner.grid}, out.first_vertex,
                              [&](const Triangle& t) { first_row.insert(first_row.end(), t.begin(), t.end()); });
      std::vector<std::uint32_t> cells(first_row.size());
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
    const std::vector<std::uint32_t> ids_of_patch(std::min<std::size_t>(out.triangle_count(), 1024), patch_of(p));
    for (std::size_t t = 0; t < out.triangle_count(); t += ids_of_patch.size()) {
      put(triangle_patches.data() + out.first_triangle + t, ids_of_patch.data(),
          std::min(ids_of_patch.size(), out.triangle_count() - t) * sizeof(std::uint32_t));
    }
    if (stream) stream_fence();
  }

  // --- measurement --------------------------------------------------------------------------

  static constexpr const auto& samples = measure_sample_weights;

  // The sampled error over the inner cells of patch p (make_pattern_boundary leaves them out).
  // Their samples fall on a grid of sixths of a cell (every sample weight is a multiple of 1/6),
  // so each row of cells is evaluated as one grid, 7 fine rows by 6 fine columns a cell, with
  // the grid kernel instead of point by point (ten times faster at large rates).
  //   cell (i, j):  (i, j+1) ---- (i+1, j+1)     lower triangle (i, j), (i+1, j), (i+1, j+1)
  //                    |  upper  /  |             upper triangle (i, j), (i+1, j+1), (i, j+1)
  //                    |      /     |             sample (a, b) in sixths of the cell
  //                 (i, j) ---- (i+1, j)
  template <class Position>
  double inner_cells_error(std::uint32_t p, const PatchOutput& out, const Position& position) const {
    const int nu = out.inner.u;
    const int nv = out.inner.v;
    if (nu < 3 || nv < 3) return 0.0;
    // Where each sample of the lower and the upper triangle lies, in sixths of the cell.
    std::array<std::array<std::size_t, 2>, 10> lower{};
    std::array<std::array<std::size_t, 2>, 10> upper{};
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const auto sixths = [](double x) { return static_cast<std::size_t>(std::lround(6.0 * x)); };
      lower[k] = {sixths(samples[k][1] + samples[k][2]), sixths(samples[k][2])};
      upper[k] = {sixths(samples[k][1]), sixths(samples[k][1] + samples[k][2])};
    }
    const auto cells_u = static_cast<std::size_t>(nu - 2);
    std::vector<double> us(6 * cells_u + 1);
    for (std::size_t k = 0; k < us.size(); ++k) us[k] = (1.0 + static_cast<double>(k) / 6.0) / nu;
    std::vector<double> vs(7);
    std::vector<Vec3> points(us.size() * vs.size());
    std::vector<Vec3> normals(points.size());
    const auto row = static_cast<std::uint32_t>(nu - 1);
    const std::uint32_t boundary = out.boundary_points();
    double error = 0.0;
    for (int j = 1; j + 1 < nv; ++j) {
      for (std::size_t k = 0; k < vs.size(); ++k) vs[k] = (j + static_cast<double>(k) / 6.0) / nv;
      pieces_.evaluate_grid(p, us, vs, {points, normals, {}});
      for (int i = 1; i + 1 < nu; ++i) {
        const std::uint32_t a = boundary + static_cast<std::uint32_t>(i - 1) + row * static_cast<std::uint32_t>(j - 1);
        const std::array<std::uint32_t, 4> corner = {a, a + 1, a + row + 1,
                                                     a + row};  // (i,j) (i+1,j) (i+1,j+1) (i,j+1)
        const std::size_t first = 6 * static_cast<std::size_t>(i - 1);
        for (const bool is_lower : {true, false}) {
          const Triangle t =
              is_lower ? Triangle{corner[0], corner[1], corner[2]} : Triangle{corner[0], corner[2], corner[3]};
          const auto& at = is_lower ? lower : upper;
          for (std::size_t k = 0; k < samples.size(); ++k) {
            Vec3 linear = Vec3::Zero();
            for (int c = 0; c < 3; ++c) linear += samples[k][c] * position(t[c]);
            error = std::max(error, (points[first + at[k][0] + us.size() * at[k][1]] - linear).norm());
          }
        }
      }
    }
    return error;
  }

  // e_par: |S(u,v) - L(u,v)| at the samples of every parameter triangle, L the linear
  // interpolant of the mesh positions.
  double measure(const RenderMesh& mesh) const {
    std::vector<std::uint32_t> tessellated;
    for (std::uint32_t p = 0; p < count_; ++p) {
      if (!plans_[p].culled) tessellated.push_back(p);
    }
    std::vector<double> errors(tessellated.size(), 0.0);
    parallel_for(tessellated.size(), options_.threads, [&](std::size_t q) {
      const std::uint32_t p = tessellated[q];
      const PatchOutput& out = (*outputs_)[p];
      const std::uint32_t boundary = out.boundary_points();
      const auto position = [&](std::uint32_t k) -> const Vec3& {
        return k < boundary ? (*welded_positions_)[out.welded[k]] : mesh.positions[out.first_vertex + (k - boundary)];
      };
      double error = 0.0;
      const auto sample = [&](const Triangle& t) {
        for (const auto& w : samples) {
          Vec2 uv = Vec2::Zero();
          Vec3 linear = Vec3::Zero();
          for (int c = 0; c < 3; ++c) {
            uv += w[c] * out.uv(t[c]);
            linear += w[c] * position(t[c]);
          }
          error = std::max(error, (pieces_.evaluate(p, uv.x(), uv.y()) - linear).norm());
        }
      };
      for (const Triangle& t : out.kept) sample(t);
      for (const Triangle& t : out.dropped) sample(t);
      error = std::max(error, inner_cells_error(p, out, position));
      errors[q] = error;
    });
    return errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end());
  }

  // Triangles reordered for the vertex cache, in one call over the whole mesh (a call per piece
  // cost more in set-up than in work once patches are split into 16 pieces), and their patches
  // along. meshoptimizer keeps each triangle (up to a rotation of its corners): each output
  // triangle is found among the input triangles with its smallest corner.
  static void optimize_vertex_cache(Tessellation& result) {
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
  static void optimize_vertex_fetch(RenderMesh& mesh) {
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

  const SurfacePieces& pieces_;
  const TessellationOptions& options_;
  const std::vector<GridSize>* planned_;
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
  std::vector<PatchOutput>* outputs_ = nullptr;    // in the result's scratch
  std::vector<Vec3>* welded_positions_ = nullptr;  // of the boundary points, by welded id (in the scratch)
  bool unused_interior_ = false;
  bool streaming_ = false;  // write_patch streams its output (assemble)
  std::size_t culled_ = 0;
  std::int64_t culled_triangles_ = 0;
};

}  // namespace

Tessellation tessellate(const SurfacePieces& pieces, const TessellationOptions& options) {
  Tessellation result;
  Tessellator(pieces, options).run(result);
  result.scratch.release();
  return result;
}

namespace {

// The 4 x 4 sub-net bounds of every patch (what the rates of whole and split patches rest on).
std::vector<std::vector<SecondDerivativeBounds>> cell_bounds(const PatchSet& set) {
  if (!(set.size() > 0.0)) {
    throw InvalidInput("tessellate: every control point is the same point: there is no surface to tessellate");
  }
  std::vector<std::vector<SecondDerivativeBounds>> cells;
  for (const BezierPatch3& patch : set.patches()) cells.push_back(piece_second_derivative_bounds(patch, bound_pieces));
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
  return bounding_box(std::span<const BezierPatch3>(set.patches()), 1e-6 * set.size()).diagonal().norm();
}

// Per patch, the largest gap of its joined edges (SurfacePieces::gaps): the control-point gap of
// its shared edges and T-junctions (which bounds the curves' distance point for point, the
// curves being convex combinations of their control points) and the spread of its collapsed
// edges' control points around the point they weld to.
std::vector<double> edge_gaps(const PatchSet& set) {
  std::vector<double> gaps(set.patches().size(), 0.0);
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
    const std::vector<Vec3> row = row_from_edge(set.patches()[e.patch], e.edge, 0);
    for (const Vec3& q : row) widen(e.patch, (q - row.front()).norm());
  }
  return gaps;
}

// Per patch, the solid it bounds, or -1 (SurfacePieces::solids).
std::vector<std::int32_t> solids_of(const PatchSet& set) {
  std::vector<std::int32_t> solids(set.patches().size(), -1);
  std::int32_t next = 0;
  for (const Shell& shell : shells(set)) {
    if (!shell.closed || !shell.consistently_oriented) continue;
    double volume = 0.0;
    for (std::uint32_t p : shell.patches) volume += volume_contribution(set.patches()[p]);
    if (!(volume > 0.0)) continue;
    for (std::uint32_t p : shell.patches) solids[p] = next;
    ++next;
  }
  return solids;
}

// Pieces of `set`, each patch split k x k (k = 1: the patches themselves).
SurfacePieces pieces_of(const PatchSet& set, const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k,
                        double diagonal, bool with_solids = true) {
  const std::vector<BezierPatch3>& patches = set.patches();
  SurfacePieces pieces;
  pieces.diagonal = diagonal;
  if (k == 1) {
    pieces.count = patches.size();
    pieces.patches = &patches;
    for (const SharedEdge& shared : set.shared_edges())
      pieces.shared.push_back({shared.first, shared.second, shared.reversed});
    pieces.collapsed = set.collapsed_edges();
    pieces.t_junctions = set.t_junctions();
    pieces.gaps = edge_gaps(set);
    if (with_solids) pieces.solids = solids_of(set);
    for (std::size_t p = 0; p < patches.size(); ++p) pieces.bounds.push_back(split_bounds(cells[p], 1, 0, 0));
    pieces.evaluate_grid = [&patches](std::uint32_t p, std::span<const double> us, std::span<const double> vs,
                                      GridSamplesView out) {
      const BezierPatch3& patch = patches[p];
      evaluate_grid(patch, PatchGridWeights(patch.degree_u(), patch.degree_v(), us, vs), out);
    };
    pieces.evaluate = [&patches](std::uint32_t p, double u, double v) { return patches[p].evaluate(u, v); };
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
  const std::vector<SurfacePieces::Domain>& domains = pieces.domains;
  pieces.evaluate_grid = [&patches, domains](std::uint32_t q, std::span<const double> us, std::span<const double> vs,
                                             GridSamplesView out) {
    const SurfacePieces::Domain& d = domains[q];
    std::vector<double> patch_us(us.begin(), us.end());
    std::vector<double> patch_vs(vs.begin(), vs.end());
    for (double& u : patch_us) u = d.u0 + d.size * u;
    for (double& v : patch_vs) v = d.v0 + d.size * v;
    const BezierPatch3& patch = patches[d.patch];
    evaluate_grid(patch, PatchGridWeights(patch.degree_u(), patch.degree_v(), patch_us, patch_vs), out);
  };
  pieces.evaluate = [&patches, domains](std::uint32_t q, double u, double v) {
    const SurfacePieces::Domain& d = domains[q];
    return patches[d.patch].evaluate(d.u0 + d.size * u, d.v0 + d.size * v);
  };
  return pieces;
}

// The grid of every piece of a k x k split at tolerance eps, as plan_patches finds them (in the
// pieces' order), and their cell count; shared-edge rates and stitching come on top.
struct SplitEstimate {
  std::vector<GridSize> grids;
  std::int64_t cells = 0;
};

SplitEstimate estimated_split(const std::vector<std::vector<SecondDerivativeBounds>>& cells, int k, double eps) {
  SplitEstimate estimate;
  for (const auto& patch_cells : cells) {
    for (int b = 0; b < k; ++b) {
      for (int a = 0; a < k; ++a) {
        const SecondDerivativeBounds M = split_bounds(patch_cells, k, a, b);
        estimate.grids.push_back(grid_for_tolerance(M, eps, least_segments(M)));
        estimate.cells += estimate.grids.back().segments_u * estimate.grids.back().segments_v;
      }
    }
  }
  return estimate;
}

}  // namespace

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

Tessellation tessellate(const PatchSet& set, const TessellationOptions& options) {
  Tessellation result;
  tessellate(set, options, result);
  result.scratch.release();
  return result;
}

void tessellate(const PatchSet& set, const TessellationOptions& options, Tessellation& result) {
  const bool relative = options.relative_tolerance.has_value();
  const std::vector<std::vector<SecondDerivativeBounds>> cells = cell_bounds(set);
  // The solids cost a volume integral per patch: only automatic back-face culling needs them.
  const bool with_solids = options.camera && options.back_face_culling == BackFaceCulling::automatic;
  const SurfacePieces whole = pieces_of(set, cells, 1, tight_or_control_diagonal(set, relative), with_solids);
  // Splitting: only with a valid tolerance and no other mode (plan_patches reports the rest).
  const int modes =
      options.tolerance.has_value() + relative + options.segments.has_value() + options.camera.has_value();
  const double eps = options.tolerance ? *options.tolerance
                     : relative        ? *options.relative_tolerance * whole.diagonal
                                       : 0.0;
  int best_k = 1;
  SplitEstimate best;
  // Split pieces do not join T-junctions: such sets are tessellated whole.
  if (options.split_patches && modes == 1 && std::isfinite(eps) && eps > 0.0 && set.t_junctions().empty()) {
    try {
      best = estimated_split(cells, 1, eps);
      for (int k : {2, 4}) {
        SplitEstimate candidate = estimated_split(cells, k, eps);
        if (candidate.cells < best.cells) best = std::move(candidate), best_k = k;
      }
    } catch (const InvalidInput&) {
      // A tolerance too fine for any grid: the whole patches give the error message.
      best_k = 1;
      best.grids.clear();
    }
  }
  // The grids found for the choice are the plan's (the same bounds at the same tolerance).
  const std::vector<GridSize>* planned = best.grids.empty() ? nullptr : &best.grids;
  if (best_k == 1) return Tessellator(whole, options, planned).run(result);
  const SurfacePieces split = pieces_of(set, cells, best_k, whole.diagonal);
  Tessellator(split, options, planned).run(result);
}

}  // namespace patchwork
