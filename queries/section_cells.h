#pragma once
// The cell search of plane_section (queries/plane_section.h), per patch: the scalar Bernstein
// patch of the signed distance, its crossings along iso-lines, and the subdivision of (u, v)
// cells into arcs, sides in the plane and tangent points. Internal to queries/.
//
// Iso-lines: `along_u` lines are v = const with parameter u, the others u = const with parameter
// v; a patch's edges are the lines v = 0 (edge v0), u = 1 (u1), v = 1 (v1) and u = 0 (u0), each with
// the parameter of boundary_curve(edge).

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "queries/plane_section.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork::detail {

/// A scalar Bernstein patch, c_ij at i + (n + 1) j.
struct ScalarNet {
  int n = 0;
  int m = 0;
  std::vector<double> c;
  double at(int i, int j) const { return c[static_cast<std::size_t>(i + (n + 1) * j)]; }
};

/// The roots of f along one iso-line, ascending, each with its node; `zero` when f vanishes
/// along the whole line (to rounding), which then has no isolated roots.
struct LineRoots {
  std::vector<double> t;
  std::vector<int> nodes;
  bool zero = false;
};

/// A piece of section curve from node a to node b through `inner`, within `bound` of the curve.
struct SectionPiece {
  int a;
  int b;
  std::vector<SectionVertex> inner;
  double bound;
};

/// A point where the plane may touch the surface, within `bound` of the touching section.
struct TangentCandidate {
  SectionVertex vertex;
  double bound;
};

/// What the search of one patch knows about one of its edges.
struct EdgeInfo {
  bool collapsed = false;
  /// The patch across the edge lies in the plane.
  bool neighbour_in_plane = false;
  /// The edge that stands for it (itself, or the first of its shared edge), and whether this
  /// edge's parameter runs against that one's.
  std::uint32_t canonical_patch = 0;
  PatchEdge canonical_edge = PatchEdge::v0;
  bool reversed = false;
};

/// Everything the section collects over the patches.
struct SectionState {
  double tolerance = 0.0;
  std::vector<SectionVertex> nodes;
  std::vector<SectionPiece> pieces;
  std::vector<TangentCandidate> tangent_candidates;
  /// Sides in the plane already reported: (canonical patch, along_u, coordinate, from, to).
  std::set<std::tuple<std::uint32_t, bool, double, double, double>> sides;
  /// Nodes found twice (a root at a cell corner, on both lines through it): each pair is one point.
  std::vector<std::pair<int, int>> same_nodes;
  std::size_t uncertified = 0;
  std::size_t cells = 0;
};

/// One patch of the section.
struct PatchSection {
  PatchSection(std::uint32_t index_, AnyBezierPatch patch_) : index(index_), patch(std::move(patch_)) {}
  std::uint32_t index;
  AnyBezierPatch patch;
  ScalarNet f;
  /// Coefficients of f at most this large are zero (rounding of their computation).
  double zero = 0.0;
  std::array<EdgeInfo, 4> edges;
  /// The roots along the four edges, set before the search (shared edges computed once).
  std::array<LineRoots, 4> edge_roots;
  /// The roots along interior lines: (along_u, coordinate).
  std::map<std::pair<bool, double>, LineRoots> lines;
};

/// The coefficients of f (or of the rational numerator g = w f) for the plane through p with unit
/// normal n.
ScalarNet signed_distance_net(const AnyBezierPatch& patch, const Vec3& p, const Vec3& n);

/// The coefficients, in the line's parameter, of f along the iso-line (along_u: v = at).
std::vector<double> iso_line(const ScalarNet& f, bool along_u, double at);

/// F(u, v) of a patch of either kind.
Vec3 evaluate_any(const AnyBezierPatch& patch, double u, double v);

/// The roots of f along an iso-line, their nodes appended to state.nodes (the patch's points).
LineRoots line_roots(const PatchSection& patch, bool along_u, double at, SectionState& state);

/// Subdivides the patch's domain, adding its pieces, nodes and tangent candidates to `state`.
void search_patch(PatchSection& patch, SectionState& state);

}  // namespace patchwork::detail
