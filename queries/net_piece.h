#pragma once
// Pieces of patches as control nets, the unit of every global search in queries/.
//
// A piece is the sub-patch of patch p over [u0, u1] x [v0, v1], reparametrised to [0,1]^2, kept
// as its homogeneous net (w P, w) (w = 1 on polynomial patches), P_ij at i + (n+1) j as in
// BezierPatch. Since the weights are positive, the piece lies in the convex hull of its points
// P_ij = (wP)_ij / w_ij, and every bound below rests on that:
//
//   control_box:      the axis-aligned box of the P_ij;
//   oriented bound:   the box of the P_ij in the frame (e1, e2, N) of the piece's corners,
//                     e1 along the u-edges, N normal to both edge directions: its extent along N
//                     shrinks like h^2 under halving (a smooth piece is nearly planar), so the
//                     distance from a point to it is a second-order lower bound on the distance
//                     to the surface.
//
// Halving is de Casteljau at 1/2 on the homogeneous net, exact but for rounding, which the
// bounds allow for through `rounding_margin` (first order in the unit roundoff, growing with the
// depth of halving).

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "core/types.h"
#include "surfaces/patch_set.h"

namespace patchwork::detail {

/// A sub-patch's homogeneous control net and where it lies in its patch.
struct NetPiece {
  std::uint32_t patch = 0;
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
  int n = 0;
  int m = 0;
  /// Halvings from the whole patch.
  int depth = 0;
  std::vector<Vec4> net;

  /// The point P_ij (dehomogenised).
  Vec3 point(int i, int j) const {
    const Vec4& h = net[static_cast<std::size_t>(i + (n + 1) * j)];
    return h.head<3>() / h[3];
  }
  /// The global parameters of the piece's local (s, t) in [0,1]^2.
  Vec2 global(double s, double t) const { return {u0 + s * (u1 - u0), v0 + t * (v1 - v0)}; }
};

/// The whole patch p of `set` as a piece.
NetPiece whole_piece(const PatchSet& set, std::uint32_t p);

/// The whole patch as a piece (polynomial: weights 1).
NetPiece whole_piece(const BezierPatch3& patch);
/// The whole rational patch as a piece.
NetPiece whole_piece(const RationalBezierPatch& patch);

/// The two halves of a piece along u (dir 0) or v (dir 1), low parameter first.
std::array<NetPiece, 2> halves(const NetPiece& piece, int dir);

/// The direction to halve a piece in for a search: the one whose control polygons are longer in
/// space (0: u, 1: v), so that wedges at collapsed edges are cut across, not along, the pole.
int longer_direction(const NetPiece& piece);

/// The piece split into k x k equal pieces (k >= 1), row by row in v.
std::vector<NetPiece> split_pieces(const NetPiece& piece, int k);

/// The box of the piece's control points, widened by its rounding margin (contains the piece).
Eigen::AlignedBox3d control_box(const NetPiece& piece);

/// A lower bound on the distance from q to every surface point of the piece: the distance to the
/// oriented box of its control points (see the file comment), less the rounding margin, >= 0.
double distance_lower_bound(const NetPiece& piece, const Vec3& q);

/// What rounding in halving and in the bounds' own arithmetic can move a control point by.
double rounding_margin(const NetPiece& piece);

}  // namespace patchwork::detail
