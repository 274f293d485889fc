// The tessellator's measured error e_par: |S(u,v) - L(u,v)| at ten barycentric samples of every
// triangle, the inner cells evaluated as fine grids.

#include "surfaces/tessellator_stages.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace patchwork::detail {

// The sampled error over the inner cells of patch p (make_pattern_boundary leaves them out).
// Their samples fall on a grid of sixths of a cell (every sample weight is a multiple of 1/6),
// so each row of cells is evaluated as one grid, 7 fine rows by 6 fine columns a cell, with
// the grid kernel instead of point by point (ten times faster at large rates).
//   cell (i, j):  (i, j+1) ---- (i+1, j+1)     lower triangle (i, j), (i+1, j), (i+1, j+1)
//                    |  upper  /  |             upper triangle (i, j), (i+1, j+1), (i, j+1)
//                    |      /     |             sample (a, b) in sixths of the cell
//                 (i, j) ---- (i+1, j)
template <class Position>
double Tessellator::inner_cells_error(std::uint32_t p, const PatchOutput& out, const Position& position) const {
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
double Tessellator::measure(const RenderMesh& mesh) const {
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

}  // namespace patchwork::detail
