#include "surfaces/patch_transform.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/errors.h"
#include "curves/curve_transform.h"

namespace patchwork {
namespace {

// The determinant of the map's linear part; InvalidInput (naming the function) where it is not
// finite or zero.
template <class Matrix>
double checked_determinant(const char* function, const Matrix& linear) {
  detail::check_finite_map(function, linear);
  const double det = linear.determinant();
  if (det == 0.0) throw InvalidInput(detail::message(function, ": the map is singular (det = 0)"));
  return det;
}

double checked_determinant(const char* function, const Eigen::Affine3d& map) {
  detail::check_finite_map(function, map.matrix());
  return checked_determinant(function, Eigen::Matrix3d(map.linear()));
}

// The homogeneous net of a NURBS surface mapped by M, back as points and weights.
NurbsSurface from_homogeneous(const NurbsSurface& surface, const std::vector<Vec4>& H) {
  std::vector<Vec3> points(H.size());
  std::vector<double> weights(H.size());
  for (std::size_t k = 0; k < H.size(); ++k) {
    points[k] = H[k].head<3>() / H[k][3];
    weights[k] = H[k][3];
  }
  return NurbsSurface(surface.knots_u(), surface.knots_v(), points, weights);
}

// The net with i -> n - i in every row (u reversed), u fastest with rows of n + 1 points.
template <class Point>
std::vector<Point> reversed_rows(const std::vector<Point>& net, int n) {
  std::vector<Point> result(net.size());
  const std::size_t row = static_cast<std::size_t>(n) + 1;
  for (std::size_t k = 0; k < net.size(); ++k) result[k] = net[(k / row) * row + (row - 1 - k % row)];
  return result;
}

}  // namespace

BezierPatch3 transform(const BezierPatch3& patch, const Eigen::Affine3d& map) {
  checked_determinant("transform", map);
  return BezierPatch3(patch.degree_u(), patch.degree_v(),
                      detail::affine_points<3>("transform", patch.control_points(), map, patch.degree_u() + 1));
}

RationalBezierPatch transform(const RationalBezierPatch& patch, const Eigen::Affine3d& map) {
  checked_determinant("transform", map);
  const BezierPatch4& H = patch.homogeneous();
  // The last row of [A b; 0 1] is (0, 0, 0, 1): the weights come out exactly as they were.
  return RationalBezierPatch(BezierPatch4(
      H.degree_u(), H.degree_v(),
      detail::projective_points<3>("transform", H.control_points(), projective_matrix<3>(map), H.degree_u() + 1)));
}

NurbsSurface transform(const NurbsSurface& surface, const Eigen::Affine3d& map) {
  checked_determinant("transform", map);
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (int j = 0; j < surface.count_v(); ++j) {
    for (int i = 0; i < surface.count_u(); ++i) {
      points.push_back(surface.control_point(i, j));
      weights.push_back(surface.weight(i, j));
    }
  }
  return NurbsSurface(surface.knots_u(), surface.knots_v(),
                      detail::affine_points<3>("transform", points, map, surface.count_u()), weights);
}

RationalBezierPatch projective_transform(const RationalBezierPatch& patch, const Eigen::Matrix4d& map) {
  checked_determinant("projective_transform", map);
  const BezierPatch4& H = patch.homogeneous();
  return RationalBezierPatch(
      BezierPatch4(H.degree_u(), H.degree_v(),
                   detail::projective_points<3>("projective_transform", H.control_points(), map, H.degree_u() + 1)));
}

RationalBezierPatch projective_transform(const BezierPatch3& patch, const Eigen::Matrix4d& map) {
  return projective_transform(as_rational(patch), map);
}

NurbsSurface projective_transform(const NurbsSurface& surface, const Eigen::Matrix4d& map) {
  checked_determinant("projective_transform", map);
  return from_homogeneous(
      surface, detail::projective_points<3>("projective_transform", surface.homogeneous(), map, surface.count_u()));
}

BezierPatch3 reverse_u(const BezierPatch3& patch) {
  return BezierPatch3(patch.degree_u(), patch.degree_v(), reversed_rows(patch.control_points(), patch.degree_u()));
}

RationalBezierPatch reverse_u(const RationalBezierPatch& patch) {
  const BezierPatch4& H = patch.homogeneous();
  return RationalBezierPatch(BezierPatch4(H.degree_u(), H.degree_v(), reversed_rows(H.control_points(), H.degree_u())));
}

namespace {

// The edge's name and direction once u is reversed: u0 and u1 exchange, v0 and v1 run the
// other way (returned as true).
std::pair<PatchEdge, bool> edge_after_reversal(PatchEdge edge) {
  switch (edge) {
    case PatchEdge::u0:
      return {PatchEdge::u1, false};
    case PatchEdge::u1:
      return {PatchEdge::u0, false};
    case PatchEdge::v0:
      return {PatchEdge::v0, true};
    case PatchEdge::v1:
      return {PatchEdge::v1, true};
  }
  return {edge, false};
}

// The set of the mapped patches (`map_patch` of each, u reversed when asked), its shared edges
// passed on as known joins.
template <class MapPatch>
TransformedPatchSet transform_set(const PatchSet& set, double det, TransformOrientation orientation,
                                  MapPatch map_patch) {
  const bool reversed = det < 0.0;
  const bool reverse = reversed && orientation == TransformOrientation::keep;
  std::vector<AnyBezierPatch> patches;
  patches.reserve(set.count());
  for (std::uint32_t p = 0; p < set.count(); ++p) {
    AnyBezierPatch mapped = map_patch(set.patch(p), p);
    if (reverse) mapped = std::visit([](const auto& patch) { return AnyBezierPatch(reverse_u(patch)); }, mapped);
    patches.push_back(std::move(mapped));
  }
  std::vector<KnownJoin> joins;
  joins.reserve(set.shared_edges().size());
  for (const SharedEdge& shared : set.shared_edges()) {
    KnownJoin join{shared.first, shared.second, shared.reversed, shared.continuity.ck};
    if (reverse) {
      const auto [first, first_flips] = edge_after_reversal(shared.first.edge);
      const auto [second, second_flips] = edge_after_reversal(shared.second.edge);
      join.first.edge = first;
      join.second.edge = second;
      join.reversed = shared.reversed != (first_flips != second_flips);
    }
    joins.push_back(join);
  }
  const double relative_tolerance = set.size() > 0.0 ? set.tolerance() / set.size() : 1e-9;
  return {PatchSet(patches, joins, relative_tolerance), reversed, reverse};
}

}  // namespace

TransformedPatchSet transform(const PatchSet& set, const Eigen::Affine3d& map, TransformOrientation orientation) {
  const double det = checked_determinant("transform", map);
  return transform_set(set, det, orientation, [&](const AnyBezierPatch& patch, std::uint32_t) {
    return std::visit([&](const auto& kind) { return AnyBezierPatch(transform(kind, map)); }, patch);
  });
}

TransformedPatchSet projective_transform(const PatchSet& set, const Eigen::Matrix4d& map,
                                         TransformOrientation orientation) {
  const double det = checked_determinant("projective_transform", map);
  return transform_set(set, det, orientation, [&](const AnyBezierPatch& patch, std::uint32_t p) {
    try {
      return std::visit([&](const auto& kind) { return AnyBezierPatch(projective_transform(kind, map)); }, patch);
    } catch (const InvalidInput& error) {
      // "projective_transform: control point ..." becomes "projective_transform: patch p, control point ...".
      const std::string what = error.what();
      const std::string prefix = "projective_transform: ";
      throw InvalidInput(
          detail::message(prefix, "patch ", p, ", ", what.substr(what.rfind(prefix, 0) == 0 ? prefix.size() : 0)));
    }
  });
}

}  // namespace patchwork
