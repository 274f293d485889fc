#include "surfaces/edge_continuity.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/errors.h"
#include "curves/continuity.h"
#include "surfaces/patch_edge_geometry.h"
#include "surfaces/surface_normal.h"

namespace patchwork {
namespace {

using detail::degree_across;
using detail::degree_along;
using detail::edge_parameter;
using detail::elevated_along;
using detail::walks_forward;

// The lowest C^k over the columns across the edge (each patch already elevated along it to the
// same degree): column i ends at the edge in `first` and starts there in `second`, and the join
// is C^k across the edge exactly when every column pair joins C^k (Bemerkung 18 per column).
template <int Dim>
int columns_ck(const BezierPatch<Dim>& first, PatchEdge first_edge, const BezierPatch<Dim>& second,
               PatchEdge second_edge, bool reversed, double relative_tolerance) {
  const int along = degree_along(first, first_edge);
  const int n1 = degree_across(first, first_edge);
  const int n2 = degree_across(second, second_edge);
  int ck = std::max(n1, n2);
  for (int i = 0; i <= along; ++i) {
    std::vector<Point<Dim>> column_first(static_cast<std::size_t>(n1) + 1);
    std::vector<Point<Dim>> column_second(static_cast<std::size_t>(n2) + 1);
    for (int l = 0; l <= n1; ++l) {
      column_first[static_cast<std::size_t>(n1 - l)] = row_from_edge(first, first_edge, l)[static_cast<std::size_t>(i)];
    }
    const int i2 = reversed ? along - i : i;
    for (int l = 0; l <= n2; ++l) {
      column_second[static_cast<std::size_t>(l)] = row_from_edge(second, second_edge, l)[static_cast<std::size_t>(i2)];
    }
    const Continuity c = continuity(BezierCurve<Dim>(column_first), BezierCurve<Dim>(column_second), std::max(n1, n2),
                                    relative_tolerance);
    ck = std::min(ck, c.ck);
  }
  return ck;
}

// The largest angle between the unit normals of the two sides at `samples` points along the
// edge; with the orientations opposite along the edge, normals agree.
double max_normal_angle(const std::function<Vec3(double, double)>& first_normal, PatchEdge first_edge,
                        const std::function<Vec3(double, double)>& second_normal, PatchEdge second_edge, bool reversed,
                        int samples) {
  const bool opposite_walks = walks_forward(first_edge) != (walks_forward(second_edge) != reversed);
  double angle = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double s = static_cast<double>(k) / (samples - 1);
    const Vec2 p1 = edge_parameter(first_edge, s);
    const Vec2 p2 = edge_parameter(second_edge, reversed ? 1.0 - s : s);
    const Vec3 n1 = first_normal(p1.x(), p1.y());
    Vec3 n2 = second_normal(p2.x(), p2.y());
    if (!opposite_walks) n2 = -n2;
    angle = std::max(angle, std::atan2(n1.cross(n2).norm(), n1.dot(n2)));
  }
  return angle;
}

constexpr double g1_angle = 1e-7;

}  // namespace

namespace detail {

EdgeAgreement edge_agreement(const std::vector<Vec4>& a, const std::vector<Vec4>& b, bool reversed) {
  EdgeAgreement result{0.0, 0.0, 0.0};
  double low = 0.0, high = 0.0, reach = 0.0;
  const Vec3 b0 = (reversed ? b.back() : b.front()).head<3>() / (reversed ? b.back() : b.front())[3];
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec4& q = b[reversed ? b.size() - 1 - i : i];
    const Vec3 pa = a[i].head<3>() / a[i][3];
    const Vec3 pb = q.head<3>() / q[3];
    result.points = std::max(result.points, (pa - pb).norm());
    reach = std::max(reach, (pb - b0).norm());
    const double ratio = q[3] / a[i][3];
    low = i == 0 ? ratio : std::min(low, ratio);
    high = i == 0 ? ratio : std::max(high, ratio);
  }
  result.weights = high / low - 1.0;
  result.gap = result.points + result.weights * reach;
  return result;
}

}  // namespace detail

EdgeContinuity edge_continuity(const BezierPatch3& first_patch, PatchEdge first_edge, const BezierPatch3& second_patch,
                               PatchEdge second_edge, bool reversed, double relative_tolerance) {
  const int along = std::max(degree_along(first_patch, first_edge), degree_along(second_patch, second_edge));
  const BezierPatch3 first = elevated_along(first_patch, first_edge, along);
  const BezierPatch3 second = elevated_along(second_patch, second_edge, along);
  EdgeContinuity result{
      detail::max_distance(row_from_edge(first, first_edge, 0), row_from_edge(second, second_edge, 0), reversed),
      columns_ck(first, first_edge, second, second_edge, reversed, relative_tolerance), false, 0.0};
  // G^1 from sampled normals (each patch's degeneracy thresholds found once for its samples).
  const detail::DegeneracyThresholds first_thresholds = detail::degeneracy_thresholds(first);
  const detail::DegeneracyThresholds second_thresholds = detail::degeneracy_thresholds(second);
  result.max_normal_angle = max_normal_angle(
      [&](double u, double v) { return detail::unit_normal(first, u, v, first_thresholds); }, first_edge,
      [&](double u, double v) { return detail::unit_normal(second, u, v, second_thresholds); }, second_edge, reversed,
      4 * std::max(first.degree_u(), first.degree_v()) + 1);
  result.g1 = result.ck >= 0 && result.max_normal_angle <= g1_angle;
  return result;
}

EdgeContinuity edge_continuity(const AnyBezierPatch& first_patch, PatchEdge first_edge,
                               const AnyBezierPatch& second_patch, PatchEdge second_edge, bool reversed,
                               double relative_tolerance) {
  const auto* first_polynomial = std::get_if<BezierPatch3>(&first_patch);
  const auto* second_polynomial = std::get_if<BezierPatch3>(&second_patch);
  if (first_polynomial != nullptr && second_polynomial != nullptr) {
    return edge_continuity(*first_polynomial, first_edge, *second_polynomial, second_edge, reversed,
                           relative_tolerance);
  }
  const auto rational = [](const AnyBezierPatch& patch) {
    const auto* p = std::get_if<BezierPatch3>(&patch);
    return p != nullptr ? as_rational(*p) : std::get<RationalBezierPatch>(patch);
  };
  const RationalBezierPatch first_rational = rational(first_patch);
  const RationalBezierPatch second_rational = rational(second_patch);
  const int along = std::max(degree_along(first_rational.homogeneous(), first_edge),
                             degree_along(second_rational.homogeneous(), second_edge));
  const BezierPatch4 first = elevated_along(first_rational.homogeneous(), first_edge, along);
  BezierPatch4 second = elevated_along(second_rational.homogeneous(), second_edge, along);
  const std::vector<Vec4> first_row = row_from_edge(first, first_edge, 0);
  const std::vector<Vec4> second_row = row_from_edge(second, second_edge, 0);
  const detail::EdgeAgreement agreement = detail::edge_agreement(first_row, second_row, reversed);
  // Scaled so that the homogeneous rows agree at the edge's start (the surface is unchanged).
  const double scale = first_row.front()[3] / (reversed ? second_row.back() : second_row.front())[3];
  std::vector<Vec4> scaled = second.control_points();
  for (Vec4& h : scaled) h *= scale;
  second = BezierPatch4(second.degree_u(), second.degree_v(), std::move(scaled));
  EdgeContinuity result{agreement.gap, columns_ck(first, first_edge, second, second_edge, reversed, relative_tolerance),
                        false, 0.0};
  result.max_normal_angle =
      max_normal_angle([&](double u, double v) { return unit_normal(first_rational, u, v); }, first_edge,
                       [&](double u, double v) { return unit_normal(second_rational, u, v); }, second_edge, reversed,
                       4 * std::max(first.degree_u(), first.degree_v()) + 1);
  result.g1 = result.ck >= 0 && result.max_normal_angle <= g1_angle;
  return result;
}

std::vector<std::vector<Vec3>> continue_across(const BezierPatch3& patch, PatchEdge edge, int k,
                                               int degree_across_new) {
  if (k < 0 || k > degree_across_new) {
    throw InvalidInput(detail::message("continue_across: order k = ", k, " not in [0, ", degree_across_new, "]"));
  }
  const int along = degree_along(patch, edge);
  const int across = degree_across(patch, edge);
  std::vector<std::vector<Vec3>> rows(static_cast<std::size_t>(k) + 1,
                                      std::vector<Vec3>(static_cast<std::size_t>(along) + 1));
  for (int i = 0; i <= along; ++i) {
    std::vector<Vec3> column(static_cast<std::size_t>(across) + 1);
    for (int l = 0; l <= across; ++l)
      column[static_cast<std::size_t>(across - l)] = row_from_edge(patch, edge, l)[static_cast<std::size_t>(i)];
    const std::vector<Vec3> next = continue_ck(BezierCurve3(std::move(column)), k, degree_across_new, 1.0);
    for (int j = 0; j <= k; ++j)
      rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = next[static_cast<std::size_t>(j)];
  }
  return rows;
}

}  // namespace patchwork
