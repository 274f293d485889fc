#pragma once
// Affine and projective maps of curves, exact on the control points.
//
// Affine maps x -> A x + b (A the linear part, b the translation) commute with the Bernstein
// and B-spline combinations, whose coefficients sum to one, so the image of a curve is the
// curve of the mapped control points:
//
//   C'(t) = sum_i B_i(t) (A P_i + b) = A C(t) + b.
//
// A rational curve is mapped on its homogeneous points h_i = (w_i P_i, w_i) by the matrix
//
//   M = [ A  b ]          h'_i = M h_i = (w_i (A P_i + b), w_i),
//       [ 0  1 ]
//
// so its weights are unchanged and P'_i = A P_i + b (to one rounding of the division by w_i).
//
// A projective map is any invertible (Dim+1) x (Dim+1) matrix M acting on homogeneous points,
// x -> (M (x, 1))_head / (M (x, 1))_last. It maps a rational curve H(t) = sum_i B_i(t) h_i to
// the rational curve with homogeneous points M h_i, whose weights are the last row of M times h_i:
//
//   - every new weight > 0: that is the mapped curve;
//   - every new weight < 0: the negated points -M h_i are the same curve (C = H / w does not
//     change when H and w change sign together), with positive weights;
//   - otherwise (a zero weight, or both signs): the weight function w(t) of the image may vanish,
//     where the image passes through the plane at infinity; the curve has no representation
//     with positive weights and InvalidInput names the first control point whose weight is zero
//     or has the other sign than control point 0's.
//
// A polynomial curve is the rational curve with all weights 1, so its projective image is a
// rational curve. Projective maps keep conics conics: a circle_arc maps to an exact conic arc.
// Parameters, intervals and knot vectors are unchanged.

#include <Eigen/Geometry>

#include "core/errors.h"
#include "curves/bezier_curve.h"
#include "curves/bspline_curve.h"
#include "curves/rational_bezier_curve.h"

namespace patchwork {

/// The affine map x -> A x + b of Dim-space (convert an Isometry with AffineMap<Dim>(motion)).
template <int Dim>
using AffineMap = Eigen::Transform<double, Dim, Eigen::Affine>;

/// A projective map of Dim-space as a matrix on homogeneous points (x, 1).
template <int Dim>
using ProjectiveMap = Eigen::Matrix<double, Dim + 1, Dim + 1>;

/// The image A C + b: control points A P_i + b, same interval.
/// \throws InvalidInput if an entry of the map is not finite or a mapped point overflows.
template <int Dim>
BezierCurve<Dim> transform(const BezierCurve<Dim>& curve, const AffineMap<Dim>& map);

/// The image of a rational curve: homogeneous points (w_i (A P_i + b), w_i), weights unchanged.
/// \throws InvalidInput if an entry of the map is not finite or a mapped point overflows.
template <int Dim>
RationalBezierCurve<Dim> transform(const RationalBezierCurve<Dim>& curve, const AffineMap<Dim>& map);

/// The image of a B-spline curve: control points A P_i + b, same knots.
/// \throws InvalidInput if an entry of the map is not finite or a mapped point overflows.
template <int Dim>
BSplineCurve<Dim> transform(const BSplineCurve<Dim>& curve, const AffineMap<Dim>& map);

/// The image of a NURBS curve: homogeneous points (w_i (A P_i + b), w_i), same knots and weights.
/// \throws InvalidInput if an entry of the map is not finite or a mapped point overflows.
template <int Dim>
NurbsCurve<Dim> transform(const NurbsCurve<Dim>& curve, const AffineMap<Dim>& map);

/// The projective image of a rational curve: homogeneous points M h_i (negated if every new
/// weight is negative). \throws InvalidInput if an entry of M is not finite, M is singular, or
/// the new weights are not all of one sign (the file comment), naming the control point.
template <int Dim>
RationalBezierCurve<Dim> projective_transform(const RationalBezierCurve<Dim>& curve, const ProjectiveMap<Dim>& map);

/// The projective image of a polynomial curve (weights 1), a rational curve.
/// \throws InvalidInput as for a rational curve.
template <int Dim>
RationalBezierCurve<Dim> projective_transform(const BezierCurve<Dim>& curve, const ProjectiveMap<Dim>& map);

/// The projective image of a NURBS curve (same knots). \throws InvalidInput as for a rational curve.
template <int Dim>
NurbsCurve<Dim> projective_transform(const NurbsCurve<Dim>& curve, const ProjectiveMap<Dim>& map);

/// The projective image of a B-spline curve (weights 1), a NURBS curve.
/// \throws InvalidInput as for a rational curve.
template <int Dim>
NurbsCurve<Dim> projective_transform(const BSplineCurve<Dim>& curve, const ProjectiveMap<Dim>& map);

/// The (Dim+1) x (Dim+1) matrix [A b; 0 1] of an affine map.
template <int Dim>
ProjectiveMap<Dim> projective_matrix(const AffineMap<Dim>& map);

namespace detail {

/// Throws InvalidInput (naming `function`) unless every entry of the matrix is finite.
template <class Matrix>
void check_finite_map(const char* function, const Matrix& map) {
  if (!map.allFinite()) throw InvalidInput(message(function, ": the map has an entry that is not finite"));
}

/// A P + b for every point, in that order of operations (the affine image of control points).
/// \throws InvalidInput (naming `function` and the point, as projective_points does) if an image
///         is not finite.
template <int Dim>
std::vector<Point<Dim>> affine_points(const char* function, const std::vector<Point<Dim>>& points,
                                      const AffineMap<Dim>& map, int row_length = 0);

/// M h for every homogeneous point h, negated when every new weight is negative.
/// \throws InvalidInput (naming `function` and the control point) if the new weights are not all
///         of one sign, or an image is not finite. With row_length > 0 the points are a net listed
///         u fastest, and the control point is named (i, j) = (k % row_length, k / row_length).
template <int Dim>
std::vector<Point<Dim + 1>> projective_points(const char* function, const std::vector<Point<Dim + 1>>& points,
                                              const ProjectiveMap<Dim>& map, int row_length = 0);

/// The homogeneous points (P, 1) of polynomial control points.
template <int Dim>
std::vector<Point<Dim + 1>> unit_weight_points(const std::vector<Point<Dim>>& points);

}  // namespace detail
}  // namespace patchwork
