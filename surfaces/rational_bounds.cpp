#include "surfaces/rational_bounds.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <initializer_list>
#include <tuple>

#include "core/errors.h"
#include "surfaces/bernstein_product.h"

namespace patchwork {
namespace {

using detail::ScalarPatch;

// sum_k s_k a_k * b_k (products in the Bernstein basis, degrees elevated to match).
ScalarPatch combination(std::initializer_list<std::tuple<double, const ScalarPatch*, const ScalarPatch*>> terms) {
  ScalarPatch sum{0, 0, {}};
  for (const auto& [sign, a, b] : terms) detail::add(sum, detail::multiply(*a, *b), sign);
  return sum;
}

// Bounds of a homogeneous net (x, y, z, w), degrees (n, m), points at i + (n + 1) j: the
// numerators N = w^3 F_uu, w^3 F_uv, w^3 F_vv as Bernstein polynomials (per coordinate), their
// largest coefficient vector over the smallest coefficient of w^3 (rational_bounds.h).
SecondDerivativeBounds quotient_bounds(const std::vector<Vec4>& H, int n, int m) {
  Eigen::AlignedBox3d box;
  for (const Vec4& h : H) box.extend(Vec3(h.head<3>() / h[3]));
  // Moved to the box's centre: the numerators do not change (F_uu does not), their rounding does.
  const Vec3 centre = box.center();
  ScalarPatch w{n, m, {}};
  std::array<ScalarPatch, 3> g;
  for (int c = 0; c < 3; ++c) g[c] = {n, m, {}};
  for (const Vec4& h : H) {
    w.c.push_back(h[3]);
    for (int c = 0; c < 3; ++c) g[c].c.push_back(h[c] - centre[c] * h[3]);
  }
  using detail::derivative;
  const ScalarPatch wu = derivative(w, true), wv = derivative(w, false);
  const ScalarPatch wuu = derivative(wu, true), wuv = derivative(wu, false), wvv = derivative(wv, false);
  const ScalarPatch w2 = detail::multiply(w, w);
  const ScalarPatch w3 = detail::multiply(w2, w);
  const double w3_min = *std::min_element(w3.c.begin(), w3.c.end());
  std::array<ScalarPatch, 3> uu, uv, vv;
  for (int c = 0; c < 3; ++c) {
    const ScalarPatch gu = derivative(g[c], true), gv = derivative(g[c], false);
    const ScalarPatch guu = derivative(gu, true), guv = derivative(gu, false), gvv = derivative(gv, false);
    // w^2 F_u = g_u w - g w_u;  w^3 F_uu = w (g_uu w - g w_uu) - 2 w_u (g_u w - g w_u).
    const ScalarPatch first_u = combination({{1.0, &gu, &w}, {-1.0, &g[c], &wu}});
    const ScalarPatch first_v = combination({{1.0, &gv, &w}, {-1.0, &g[c], &wv}});
    const ScalarPatch second_uu = combination({{1.0, &guu, &w}, {-1.0, &g[c], &wuu}});
    const ScalarPatch second_vv = combination({{1.0, &gvv, &w}, {-1.0, &g[c], &wvv}});
    uu[c] = combination({{1.0, &w, &second_uu}, {-2.0, &wu, &first_u}});
    vv[c] = combination({{1.0, &w, &second_vv}, {-2.0, &wv, &first_v}});
    // w^3 F_uv = w (g_uv w + g_u w_v - g_v w_u - g w_uv) - 2 w_v (g_u w - g w_u).
    const ScalarPatch mixed =
        combination({{1.0, &guv, &w}, {1.0, &gu, &wv}, {-1.0, &gv, &wu}, {-1.0, &g[c], &wuv}});
    uv[c] = combination({{1.0, &w, &mixed}, {-2.0, &wv, &first_u}});
  }
  // |N| <= the largest coefficient vector (convex hull), w^3 >= its smallest coefficient.
  const auto largest = [](const std::array<ScalarPatch, 3>& N) {
    double result = 0.0;
    for (std::size_t k = 0; k < N[0].c.size(); ++k) result = std::max(result, Vec3(N[0].c[k], N[1].c[k], N[2].c[k]).norm());
    return result;
  };
  return {largest(uu) / w3_min, largest(uv) / w3_min, largest(vv) / w3_min};
}

}  // namespace

SecondDerivativeBounds second_derivative_bounds(const RationalBezierPatch& patch) {
  return quotient_bounds(patch.homogeneous().control_points(), patch.degree_u(), patch.degree_v());
}

std::vector<SecondDerivativeBounds> piece_second_derivative_bounds(const RationalBezierPatch& patch, int pieces) {
  if (pieces < 1 || pieces > 64) {
    throw InvalidInput(detail::message("second_derivative_bounds: ", pieces, " pieces is not in [1, 64]"));
  }
  std::vector<SecondDerivativeBounds> bounds;
  bounds.reserve(static_cast<std::size_t>(pieces) * static_cast<std::size_t>(pieces));
  const double size = 1.0 / pieces;
  for (int b = 0; b < pieces; ++b) {
    for (int a = 0; a < pieces; ++a) {
      if (pieces == 1) {
        bounds.push_back(second_derivative_bounds(patch));
        continue;
      }
      // The piece's net, then its bounds in the patch's parameters (a domain `pieces` times as
      // wide in its own).
      const BezierPatch4 piece = subpatch(patch.homogeneous(), a * size, (a + 1) * size, b * size, (b + 1) * size);
      const SecondDerivativeBounds own = quotient_bounds(piece.control_points(), patch.degree_u(), patch.degree_v());
      bounds.push_back(scaled_bounds(own, static_cast<double>(pieces)));
    }
  }
  return bounds;
}

SecondDerivativeBounds second_derivative_bounds(const RationalBezierPatch& patch, int pieces) {
  return merged_bounds(piece_second_derivative_bounds(patch, pieces));
}

}  // namespace patchwork
