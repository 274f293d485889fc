#pragma once
// Tensor-product B-spline and NURBS surfaces (The NURBS Book, ch. 3-5):
//
//   S(u, v) = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij / sum_ij N_i,p(u) N_j,q(v) w_ij,
//
// knot vectors U (degree p, count_u control points along u) and V (degree q, count_v), the
// control points P_ij listed u fastest (index i + count_u j, the order of OBJ's `surf`), weights
// w_ij > 0 (all 1: a B-spline surface). It is stored as its homogeneous points (w P, w), and the
// derivatives follow from H = w S by Leibniz's rule as for RationalBezierPatch. The domain is
// [a_u, b_u] x [a_v, b_v], the valid ranges of U and V (curves/knot_vector.h: the right end
// belongs to the last non-empty span). Across a u-breakpoint of multiplicity m the surface is
// C^(p - m) (likewise in v).
//
// Bezier extraction refines every interior knot to multiplicity p (q) and cuts at the breakpoints,
// row by row and then column by column on the homogeneous points (the curves' bezier_pieces):
// patch (s, t) is S on [u_s, u_s+1] x [v_t, v_t+1], reparametrised to [0,1]^2, the same surface
// point for point. Neighbouring pieces share their edge rows exactly, and the continuity across
// each interior breakpoint is known from the knots.

#include <vector>

#include "curves/knot_vector.h"
#include "surfaces/bezier_patch.h"
#include "surfaces/patch_set.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

class NurbsSurface {
 public:
  /// Knots U and V, control points P_ij (u fastest) and weights (empty: all 1; all equal: stored
  /// as 1, the same surface).
  /// \throws InvalidInput if the counts do not match the knots (U.control_point_count() x
  ///         V.control_point_count()), a coordinate is not finite or a weight not positive and finite.
  NurbsSurface(KnotVector u, KnotVector v, const std::vector<Vec3>& points, const std::vector<double>& weights = {});

  /// The knots along u.
  const KnotVector& knots_u() const noexcept { return u_; }
  /// The knots along v.
  const KnotVector& knots_v() const noexcept { return v_; }
  /// The degree p along u.
  int degree_u() const noexcept { return u_.degree(); }
  /// The degree q along v.
  int degree_v() const noexcept { return v_.degree(); }
  /// Control points along u.
  int count_u() const noexcept { return u_.control_point_count(); }
  /// Control points along v.
  int count_v() const noexcept { return v_.control_point_count(); }
  /// The homogeneous points (w P, w), u fastest.
  const std::vector<Vec4>& homogeneous() const noexcept { return homogeneous_; }
  /// P_ij. \pre 0 <= i < count_u(), 0 <= j < count_v().
  Vec3 control_point(int i, int j) const;
  /// w_ij.
  double weight(int i, int j) const { return at(i, j)[3]; }
  /// The weights are not all equal (else the surface is the B-spline of its control points).
  bool rational() const noexcept { return rational_; }

  /// S(u, v). \throws InvalidInput if (u, v) is not finite or outside the domain.
  Vec3 evaluate(double u, double v) const;
  Vec3 operator()(double u, double v) const { return evaluate(u, v); }

  /// The homogeneous point (w P, w)_ij.
  const Vec4& at(int i, int j) const { return homogeneous_[static_cast<std::size_t>(i + count_u() * j)]; }

  friend bool operator==(const NurbsSurface&, const NurbsSurface&) = default;

 private:
  KnotVector u_;
  KnotVector v_;
  std::vector<Vec4> homogeneous_;
  bool rational_ = false;
};

/// All partial derivatives of S with a + b <= order at (u, v) (one-sided from the span that
/// holds (u, v) at a breakpoint). \throws InvalidInput if order < 0 or (u, v) is outside the domain.
PartialDerivatives<3> partial_derivatives(const NurbsSurface& surface, double u, double v, int order);

/// The unit normal S_u x S_v / |S_u x S_v|, the limit normal where it vanishes (a NURBS sphere's
/// poles), as unit_normal of a patch; from the Bezier piece that holds (u, v).
/// Vanishing is judged against the size of the span's control points.
/// \throws InvalidInput outside the domain; NumericalError where the surface is degenerate
///         around (u, v).
Vec3 unit_normal(const NurbsSurface& surface, double u, double v);

/// The same surface with the knot u inserted `times` times into U (Boehm on every row of
/// homogeneous points). \throws InvalidInput as insert_knot of a curve.
NurbsSurface insert_knot_u(const NurbsSurface& surface, double u, int times = 1);
/// The same surface with the knot v inserted `times` times into V (on every column).
NurbsSurface insert_knot_v(const NurbsSurface& surface, double v, int times = 1);

/// The Bezier patches of a surface and what the knots say about them.
struct NurbsBezierPatches {
  /// Patch (s, t) at s + spans_u * t: a RationalBezierPatch, or a BezierPatch3 where the
  /// surface is not rational.
  std::vector<AnyBezierPatch> patches;
  int spans_u = 0;
  int spans_v = 0;
  /// The breakpoints along u (spans_u + 1 of them: a_u, the interior ones, b_u) and v.
  std::vector<double> breaks_u;
  std::vector<double> breaks_v;
  /// The continuity C^(p - m) across each interior u-breakpoint (spans_u - 1 of them), and v.
  std::vector<int> continuity_u;
  std::vector<int> continuity_v;
  /// The edges between neighbouring patches, with that continuity: (s, t) u1 against (s+1, t) u0,
  /// (s, t) v1 against (s, t+1) v0; an edge that collapses (a pole) is left out, as it joins nothing.
  std::vector<KnownJoin> joins;
};

/// The Bezier extraction of the file comment.
NurbsBezierPatches bezier_patches(const NurbsSurface& surface);

/// The Bezier patches of the surface over [u0, u1] x [v0, v1] only (OBJ's `surf` range): the
/// range's ends made breakpoints by knot insertion (to multiplicity p, q), the patches outside
/// left out. \throws InvalidInput unless a_u <= u0 < u1 <= b_u and a_v <= v0 < v1 <= b_v.
NurbsBezierPatches bezier_patches(const NurbsSurface& surface, double u0, double u1, double v0, double v1);

namespace detail {
struct DegeneracyThresholds;
/// surface_normal.h's degeneracy_thresholds of the control points P_ij and weights with
/// i0 <= i <= i1, j0 <= j <= j1 (a span's, or the whole net's).
DegeneracyThresholds degeneracy_thresholds(const NurbsSurface& surface, int i0, int i1, int j0, int j1);
}  // namespace detail

}  // namespace patchwork
