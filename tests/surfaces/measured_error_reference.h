#pragma once
// The tessellator's measured error recomputed the straightforward way, the reference for
// surfaces/tessellator_measure.cpp: every one of the ten samples of every triangle of every
// piece's pattern (kept, dropped and the inner cells), S point by point from the piece's own
// evaluation at the sample's (u, v), L from the positions of the triangle's corners as the
// output mesh holds them (a dropped triangle's corners that no written triangle uses: the
// welded position of a boundary point, the piece's own point of an interior one).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "surfaces/tessellator.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork::testing {

/// The point of piece p at (u, v), evaluated the plain way (the patch's own evaluate).
using PiecePoint = std::function<Vec3(std::uint32_t p, double u, double v)>;

/// The meter and the reference on one run, per piece (0 for culled pieces).
struct MeasuredErrorComparison {
  /// Tessellation::measured_error of the run.
  double measured_error = 0.0;
  /// detail::measured_piece_error of each piece, on the positions of the output.
  std::vector<double> meter;
  /// The reference of each piece.
  std::vector<double> reference;
  /// The largest norm of a mesh position (the scale of rounding in S and L).
  double scale = 0.0;
  /// Some piece has interior points that no written triangle uses (their vertices were dropped).
  bool unused_interior = false;
  std::size_t triangles = 0;
};

/// `pieces` tessellated with `options` (not reordered, so the triangles stay where each piece
/// wrote them: its kept triangles, then its inner cells), the meter and the reference per piece.
inline MeasuredErrorComparison compare_measured_error(const SurfacePieces& pieces, TessellationOptions options,
                                                      const PiecePoint& own) {
  using detail::PatchOutput;
  using detail::Triangle;
  options.optimize = false;
  options.measure = true;
  Tessellation result;
  detail::Tessellator(pieces, options).run(result);  // keeps the scratch: every piece's pattern
  const detail::TessellatorScratch& scratch = result.scratch.get();
  const RenderMesh& mesh = result.mesh;
  MeasuredErrorComparison comparison;
  comparison.measured_error = result.measured_error;
  comparison.meter.assign(pieces.count, 0.0);
  comparison.reference.assign(pieces.count, 0.0);
  comparison.triangles = mesh.triangle_count();
  for (const Vec3& x : mesh.positions) comparison.scale = std::max(comparison.scale, x.norm());
  for (std::uint32_t p = 0; p < pieces.count; ++p) {
    const PatchOutput& out = scratch.outputs[p];
    if (out.boundary_points() == 0) continue;  // culled
    comparison.unused_interior = comparison.unused_interior || out.unused_interior;
    const auto boundary = static_cast<std::uint32_t>(out.boundary_points());
    const std::span<const Triangle> kept = out.kept_triangles();
    std::vector<Triangle> triangles(kept.begin(), kept.end());
    for_each_inner_triangle(out.inner, boundary, [&](const Triangle& t) { triangles.push_back(t); });
    std::map<std::uint32_t, Vec3> written;  // pattern point -> its position in the mesh
    for (std::size_t m = 0; m < triangles.size(); ++m) {
      for (std::size_t c = 0; c < 3; ++c) {
        written.emplace(triangles[m][c], mesh.positions[mesh.indices[3 * (out.first_triangle + m) + c]]);
      }
    }
    const auto position = [&](std::uint32_t k) -> Vec3 {
      if (const auto at = written.find(k); at != written.end()) return at->second;
      if (k < boundary) return scratch.welded_positions[out.welded[k]];
      const Vec2 uv = out.uv(k);
      return own(p, uv.x(), uv.y());
    };
    triangles.insert(triangles.end(), out.dropped.begin(), out.dropped.end());
    double error = 0.0;
    for (const Triangle& t : triangles) {
      for (const auto& w : measure_sample_weights) {
        Vec2 uv = Vec2::Zero();
        Vec3 linear = Vec3::Zero();
        for (std::size_t c = 0; c < 3; ++c) {
          uv += w[c] * out.uv(t[c]);
          linear += w[c] * position(t[c]);
        }
        error = std::max(error, (own(p, uv.x(), uv.y()) - linear).norm());
      }
    }
    comparison.reference[p] = error;
    std::vector<Vec3> interior(out.interior_points());
    for (std::size_t q = 0; q < interior.size(); ++q) interior[q] = position(boundary + static_cast<std::uint32_t>(q));
    comparison.meter[p] = detail::measured_piece_error(pieces, p, out, scratch.welded_positions, interior);
  }
  return comparison;
}

}  // namespace patchwork::testing
