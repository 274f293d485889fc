#include "curves/bspline_measures.h"

#include "core/errors.h"
#include "curves/bspline_conversion.h"
#include "curves/dimensions.h"

namespace patchwork {
namespace {

template <class Pieces>
ArcLength sum_of_lengths(const Pieces& pieces, double tolerance) {
  if (!(tolerance > 0.0)) throw InvalidInput(detail::message("arc_length: tolerance ", tolerance, " is not positive"));
  ArcLength total{0.0, 0.0};
  for (const auto& piece : pieces) {
    const ArcLength part = arc_length(piece, tolerance / static_cast<double>(pieces.size()));
    total.length += part.length;
    total.error_estimate += part.error_estimate;
  }
  return total;
}

template <int Dim, class Pieces>
Box<Dim> union_of_boxes(const Pieces& pieces) {
  Box<Dim> box = bounding_box(pieces.front());
  for (const auto& piece : pieces) box.extend(bounding_box(piece));
  return box;
}

}  // namespace

template <int Dim>
ArcLength arc_length(const BSplineCurve<Dim>& curve, double tolerance) {
  return sum_of_lengths(bezier_pieces(curve), tolerance);
}

template <int Dim>
ArcLength arc_length(const NurbsCurve<Dim>& curve, double tolerance) {
  return sum_of_lengths(bezier_pieces(curve), tolerance);
}

template <int Dim>
Box<Dim> bounding_box(const BSplineCurve<Dim>& curve) {
  return union_of_boxes<Dim>(bezier_pieces(curve));
}

template <int Dim>
Box<Dim> bounding_box(const NurbsCurve<Dim>& curve) {
  return union_of_boxes<Dim>(bezier_pieces(curve));
}

template <int Dim>
Box<Dim> control_box(const BSplineCurve<Dim>& curve) {
  Box<Dim> box(curve.control_points().front());
  for (const auto& p : curve.control_points()) box.extend(p);
  return box;
}

template <int Dim>
Box<Dim> control_box(const NurbsCurve<Dim>& curve) {
  Box<Dim> box(curve.control_point(0));
  for (int i = 0; i < curve.control_point_count(); ++i) box.extend(curve.control_point(i));
  return box;
}

#define PATCHWORK_INSTANTIATE(D)                                 \
  template ArcLength arc_length(const BSplineCurve<D>&, double); \
  template Box<D> bounding_box(const BSplineCurve<D>&);          \
  template Box<D> control_box(const BSplineCurve<D>&);
PATCHWORK_FOR_EACH_CURVE_DIM(PATCHWORK_INSTANTIATE)
#undef PATCHWORK_INSTANTIATE

#define PATCHWORK_INSTANTIATE(D)                               \
  template ArcLength arc_length(const NurbsCurve<D>&, double); \
  template Box<D> bounding_box(const NurbsCurve<D>&);          \
  template Box<D> control_box(const NurbsCurve<D>&);
PATCHWORK_INSTANTIATE(2)
PATCHWORK_INSTANTIATE(3)
#undef PATCHWORK_INSTANTIATE

}  // namespace patchwork
