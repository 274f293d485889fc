#pragma once
// A set of Bezier patches and their adjacency, found from the geometry alone.
//
// Every patch has four boundary edges (PatchEdge); an edge is
//   - collapsed when all its control points coincide (within the tolerance): the teapot's poles;
//   - shared when another patch has an edge with the same control points, in the same or the
//     reverse order (the lower degree elevated first when the degrees differ), and, where a
//     patch is rational, proportional weights;
//   - part of a T-junction when it and other patches' edges lie end to end along a longer edge
//     (TJunction: each is the long edge's de Casteljau piece between two parameters);
//   - open otherwise: a boundary of the set.
// The tolerance is relative to the diagonal of the box of all control points.
//
// Orientation. Walking a patch's boundary counter-clockwise in (u, v) traverses v0 with u
// increasing, u1 with v increasing, v1 with u decreasing and u0 with v decreasing. Two patches
// are consistently oriented along a shared edge when they walk it in opposite directions.
// Open edges chain into boundary loops in that walking direction. A touching point is a point
// where patches meet at corners without a chain of shared edges around it (the teapot's handle
// touches its body at one point).

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "surfaces/bezier_patch.h"
#include "surfaces/edge_continuity.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// One edge of one patch.
struct EdgeRef {
  std::uint32_t patch;
  PatchEdge edge;
  friend bool operator==(const EdgeRef&, const EdgeRef&) = default;
};

/// Two patch edges with the same control points (and proportional weights where rational).
struct SharedEdge {
  EdgeRef first;
  EdgeRef second;
  /// The second edge's boundary curve runs opposite to the first's.
  bool reversed;
  /// The two patches walk the edge in opposite directions (consistent orientation).
  bool consistently_oriented;
  EdgeContinuity continuity;
};

/// A patch edge against a chain of shorter edges of other patches, end to end along it: a
/// T-junction where two parts meet (the layout of adaptive subdivision and of hand-made sets).
/// Part k is the piece [breaks[k-1], breaks[k]] of boundary_curve(edge) (breaks[-1] = 0,
/// breaks[parts - 1] = 1): its control points agree within the tolerance with those of that
/// piece (de Casteljau), so the part's edge is the long edge's piece, reparametrised linearly.
struct TJunction {
  EdgeRef edge;
  /// The parts in the direction of boundary_curve(edge), at least two.
  std::vector<EdgeRef> parts;
  /// Where part k ends along boundary_curve(edge): 0 < breaks[0] < ... < breaks.back() = 1.
  std::vector<double> breaks;
  /// Part k's boundary curve runs against the long edge's.
  std::vector<bool> reversed;
  /// Every part walks the edge opposite to the long edge's patch.
  bool consistently_oriented;
  /// Largest distance between corresponding control points of a part and its piece.
  double gap;
};

/// A closed chain of open edges, in walking order.
struct BoundaryLoop {
  std::vector<EdgeRef> edges;
  /// The chain returns to its start (false: it ends at an open end, a non-manifold corner or
  /// an orientation flip).
  bool closed;
};

/// A point where patches meet without being connected by shared edges around it.
struct TouchingPoint {
  Vec3 point;
  /// The patches at the point, grouped by edge-connectedness around it (at least two groups).
  std::vector<std::vector<std::uint32_t>> groups;
};

/// Two patch edges known to be one edge of the surface (a NURBS surface's neighbouring Bezier
/// pieces), and the continuity C^ck the knots give there, in the surface's own parameter.
struct KnownJoin {
  EdgeRef first;
  EdgeRef second;
  /// second's boundary curve runs opposite to first's.
  bool reversed;
  int ck;
};

class PatchSet {
 public:
  /// Analyses the adjacency of `patches` with tolerance relative_tolerance * (box diagonal).
  /// \throws InvalidInput if there is no patch, more than 2^32 - 1, or the tolerance is
  ///         negative or not finite.
  explicit PatchSet(std::vector<BezierPatch3> patches, double relative_tolerance = 1e-9);
  /// Polynomial and rational patches together. A rational patch whose weights are all equal is
  /// the polynomial patch of its control points and is kept as one. Edges of rational patches
  /// are shared when their control points agree within the tolerance and their weights are
  /// proportional within relative_tolerance (edge_continuity.h bounds the gap that leaves);
  /// they take no part in T-junctions (a rational edge is shared whole, or open).
  /// \throws InvalidInput as the polynomial constructor does.
  explicit PatchSet(std::span<const AnyBezierPatch> patches, double relative_tolerance = 1e-9);
  /// Patches with joins known beforehand: each is a shared edge as given, its ck the join's
  /// (gap and G^1 measured as for any shared edge), not searched for; the other edges are matched
  /// by their points as above (a closed surface's seam, where two surfaces meet).
  /// A join with a collapsed edge is dropped (a pole joins nothing).
  /// \throws InvalidInput as above, or if a join names a patch that does not exist or an edge
  ///         twice, or edges whose control points do not agree within twice the tolerance.
  PatchSet(std::span<const AnyBezierPatch> patches, std::span<const KnownJoin> joins, double relative_tolerance = 1e-9);

  /// The patches, in the order given, when none is rational.
  /// \throws InvalidInput if some patch is rational (its control points alone are not the
  ///         surface: see control_nets, patch and rational_patch).
  const std::vector<BezierPatch3>& patches() const;
  /// The control points P_ij of every patch, in the order given: the patch itself where it is
  /// polynomial; a rational patch lies in their convex hull (its weights are positive).
  const std::vector<BezierPatch3>& control_nets() const noexcept { return nets_; }
  /// The number of patches.
  std::size_t count() const noexcept { return nets_.size(); }
  /// The number of rational patches (those with weights that are not all equal).
  std::size_t rational_count() const noexcept { return rational_count_; }
  /// Patch p is rational (false for p >= count()).
  bool is_rational(std::uint32_t p) const noexcept { return p < rational_.size() && rational_[p].has_value(); }
  /// Patch p's rational form where it is rational, else null (also for p >= count()).
  const RationalBezierPatch* rational(std::uint32_t p) const noexcept { return is_rational(p) ? &*rational_[p] : nullptr; }
  /// Patch p, of its kind. \throws InvalidInput if p >= count().
  AnyBezierPatch patch(std::uint32_t p) const;
  /// Patch p as a rational patch (every weight 1 where it is polynomial).
  /// \throws InvalidInput if p >= count().
  RationalBezierPatch rational_patch(std::uint32_t p) const;
  /// The absolute tolerance used for comparisons.
  double tolerance() const noexcept { return tolerance_; }
  /// Diagonal of the box of all control points.
  double size() const noexcept { return size_; }

  /// Pairs of coinciding edges.
  const std::vector<SharedEdge>& shared_edges() const noexcept { return shared_; }
  /// Edges that collapse to a point.
  const std::vector<EdgeRef>& collapsed_edges() const noexcept { return collapsed_; }
  /// Edges against chains of other patches' edges (T-junctions); neither they nor their parts
  /// are open.
  const std::vector<TJunction>& t_junctions() const noexcept { return t_junctions_; }
  /// Edges that no other patch shares, whole or in parts: the boundary of the set.
  const std::vector<EdgeRef>& open_edges() const noexcept { return open_; }
  /// Open edges chained into loops.
  const std::vector<BoundaryLoop>& boundary_loops() const noexcept { return loops_; }
  /// Points where patches touch without sharing edges around the point.
  const std::vector<TouchingPoint>& touching_points() const noexcept { return touching_; }
  /// The edge shared with `edge`, if any.
  std::optional<EdgeRef> neighbour(EdgeRef edge) const;

  /// The set of `patches` (increasing indices into this set, whole shells: every shared edge and
  /// T-junction of one of them joins only patches among them), with the adjacency this set found
  /// among them, not searched again: patch k of the subset is patches[k], every edge, loop and
  /// touching point renumbered so (a touching point keeps its groups in the subset, and is left
  /// out with fewer than two). The absolute tolerance stays this set's; size() is the diagonal
  /// of the box of the subset's control points. Linear in this set (for many subsets, see
  /// for_each_subset).
  /// \throws InvalidInput if `patches` is empty, not increasing, names a patch that does not
  ///         exist, or cuts a shell.
  PatchSet subset(std::span<const std::uint32_t> patches) const;
  /// subset(parts[k]) for k = 0, 1, ... in order, each handed to use(k, subset) and destroyed
  /// before the next is made; no patch may be in two parts. Linear in this set and the parts
  /// together (subset() once per part would be linear in the set each time).
  /// \throws InvalidInput as subset() does for any part, or if a patch is in two parts, before
  ///         `use` is first called; whatever `use` throws.
  void for_each_subset(std::span<const std::vector<std::uint32_t>> parts,
                       const std::function<void(std::size_t, PatchSet&)>& use) const;

 private:
  PatchSet() = default;
  // The diagonal of the box of every control point of `nets` (not empty).
  static double control_box_diagonal(const std::vector<BezierPatch3>& nets);
  // The nets, and per patch the rational patch where it is one.
  using Kinds = std::pair<std::vector<BezierPatch3>, std::vector<std::optional<RationalBezierPatch>>>;
  static Kinds split_kinds(std::span<const AnyBezierPatch> patches);
  PatchSet(Kinds kinds, std::span<const KnownJoin> joins, double relative_tolerance);

  std::vector<BezierPatch3> nets_;
  // Per patch, the rational patch where it is one (empty: none is).
  std::vector<std::optional<RationalBezierPatch>> rational_;
  std::size_t rational_count_ = 0;
  double size_ = 0.0;
  double tolerance_ = 0.0;
  std::vector<SharedEdge> shared_;
  std::vector<TJunction> t_junctions_;
  std::vector<EdgeRef> collapsed_;
  std::vector<EdgeRef> open_;
  std::vector<BoundaryLoop> loops_;
  std::vector<TouchingPoint> touching_;
};

/// Everything a PatchSet knows, in one value that prints as text and as JSON.
struct PatchSetReport {
  std::size_t patches;
  std::size_t shared_edges;
  std::size_t open_edges;
  std::size_t collapsed_edges;
  std::size_t boundary_loops;
  std::size_t touching_points;
  std::size_t t_junctions;
  /// Every shared edge (and T-junction part) walked in opposite directions by its patches.
  bool consistently_oriented;
  /// No open edge.
  bool closed;
  /// Lowest C^k over the shared edges (-1 if there is a gap; -1 also if there is no shared edge).
  int min_ck;
  /// Number of shared edges that are G^1.
  std::size_t g1_edges;
  double tolerance;
  const PatchSet* set;
  /// How many of the patches are rational.
  std::size_t rational_patches = 0;
};

/// Patches joined by shared edges and T-junctions, one connected part of a set.
struct Shell {
  /// The patches, in increasing order.
  std::vector<std::uint32_t> patches;
  /// No open edge.
  bool closed;
  /// Every shared edge and T-junction part in it walked in opposite directions.
  bool consistently_oriented;
};

/// The shells of a set: its edge-connected parts (touching points and collapsed edges do not
/// join patches), in the order of their smallest patch.
std::vector<Shell> shells(const PatchSet& set);

/// The tight box of the set's surface, every patch of its kind (surfaces/patch_bounding_box.h),
/// each face within `tolerance` of the surface's extreme. \throws InvalidInput as bounding_box.
Eigen::AlignedBox3d bounding_box(const PatchSet& set, double tolerance);

/// The report of a patch set (keeps a pointer to `set` for the per-element listing).
PatchSetReport report(const PatchSet& set);
/// Human-readable report with every shared, open and collapsed edge, loop and touching point.
std::ostream& operator<<(std::ostream& out, const PatchSetReport& report);
/// The report as JSON (keys as in PatchSetReport, plus arrays of the elements).
std::string to_json(const PatchSetReport& report);

/// Readable edge name: "v0", "u1", "v1", "u0".
const char* edge_name(PatchEdge edge);

}  // namespace patchwork
