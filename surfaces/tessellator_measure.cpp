// The tessellator's measured error e_par: |S(u,v) - L(u,v)| at the ten barycentric samples of
// every triangle (measure_sample_weights: the corners, the edge midpoints, the centroid and three
// inner points), S the piece's surface, L the linear interpolant of the mesh positions.
//
// What is evaluated. The samples of neighbouring triangles coincide, and a coinciding sample
// has one value, so each is evaluated once:
//   - corner k of a triangle is (u_k, v_k) with L = the mesh position exactly (weights 1, 0, 0).
//     Where that position is the piece's own surface point, |S - L| is zero but for the rounding
//     of two evaluations of the same point, and the corner is skipped: every interior point
//     (write_patch evaluates it on this piece at out.uv(k)) and every boundary point this piece
//     owns (out.owner: the welded position is the one evaluate_sides computed on this piece at
//     pattern.points[k].uv). The others are evaluated once per point: boundary points that
//     take another piece's position (shared edges, T-junctions, where welding may have moved
//     them by the weld gap) and the points of collapsed edges. Every boundary point is a corner
//     of some triangle of the pattern (it triangulates the unit square with these points).
//   - the midpoint of an edge: its (u, v) and L are 0.5 a + 0.5 b of the edge's ends, the same
//     bits from either triangle. Triangles are counter-clockwise in (u, v), so an edge inside the
//     square is walked a -> b by one triangle and b -> a by the other: it is sampled by the one
//     that walks it from the lower pattern index to the higher (inner cells and boundary
//     triangles number their points alike), and an edge on the square's sides (no other
//     triangle) always.
//   - the centroid and the three inner points belong to one triangle each.
//
// Cost model. A pattern of T triangles has about T/2 points and 3T/2 edges, so a piece costs
// about 4 + 1.5 = 5.5 evaluations a triangle, plus one per welded boundary point (10 a triangle
// before); an inner cell (two triangles) takes 11. An evaluation is a position only
// (evaluate_points: Bernstein values of u and v and the tensor sum, vectorised across points, no
// derivatives or normals), in batches of 256 samples per piece with no allocation; the rest is
// L (three weighted corners) and a squared distance per sample. At large rates the meter costs
// about 5.5 point evaluations a triangle against the tessellation's half a point with its
// normal.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"
#include "surfaces/tessellator_stages.h"

namespace patchwork::detail {
namespace {

constexpr const auto& samples = measure_sample_weights;

// Samples of one piece waiting for S: their (u, v) and L, evaluated a batch at a time. Keeps the
// largest |S - L|^2; its square root is the largest |S - L| bit for bit (Eigen's norm is the
// square root of squaredNorm, and sqrt is monotone). A NaN distance is passed over, as
// std::max(error, distance) did.
class SampleBatch {
 public:
  SampleBatch(const SurfacePieces& pieces, std::uint32_t p) : pieces_(pieces), p_(p) {}

  void add(const Vec2& uv, const Vec3& linear) {
    us_[count_] = uv.x();
    vs_[count_] = uv.y();
    linear_[count_] = linear;
    if (++count_ == capacity) flush();
  }

  double largest() {
    flush();
    return std::sqrt(largest_);
  }

 private:
  void flush() {
    if (count_ == 0) return;
    if (pieces_.evaluate_points) {
      pieces_.evaluate_points(p_, {us_.data(), count_}, {vs_.data(), count_}, {surface_.data(), count_});
    } else {
      for (std::size_t k = 0; k < count_; ++k) surface_[k] = pieces_.evaluate(p_, us_[k], vs_[k]);
    }
    for (std::size_t k = 0; k < count_; ++k) largest_ = std::max(largest_, (surface_[k] - linear_[k]).squaredNorm());
    count_ = 0;
  }

  static constexpr std::size_t capacity = 256;
  const SurfacePieces& pieces_;
  std::uint32_t p_;
  std::size_t count_ = 0;
  double largest_ = 0.0;
  std::array<double, capacity> us_;
  std::array<double, capacity> vs_;
  std::array<Vec3, capacity> linear_;
  std::array<Vec3, capacity> surface_;
};

// Both ends on one side of the unit square: the edge lies on it and belongs to one triangle.
bool on_side(const Vec2& a, const Vec2& b) {
  return (a.x() == b.x() && (a.x() == 0.0 || a.x() == 1.0)) || (a.y() == b.y() && (a.y() == 0.0 || a.y() == 1.0));
}

// Samples 3..9 of triangle t (pattern indices, counter-clockwise), its corners at `uv` with
// positions `x`; the corners are the caller's. Sample 3 + e is the midpoint of edge e, from
// corner e to corner (e + 1) mod 3, taken where the triangle owns the edge (see the file
// comment). (u, v) and L as the weights give them, summed corner by corner.
void sample_triangle(const Triangle& t, const std::array<Vec2, 3>& uv, const std::array<Vec3, 3>& x,
                     SampleBatch& batch) {
  for (std::size_t k = 3; k < samples.size(); ++k) {
    if (k < 6) {
      const std::size_t from = k - 3;
      const std::size_t to = (k - 2) % 3;
      if (!(t[from] < t[to] || on_side(uv[from], uv[to]))) continue;
    }
    Vec2 s = Vec2::Zero();
    Vec3 linear = Vec3::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
      s += samples[k][c] * uv[c];
      linear += samples[k][c] * x[c];
    }
    batch.add(s, linear);
  }
}

}  // namespace

double measured_piece_error(const SurfacePieces& pieces, std::uint32_t p, const PatchOutput& out,
                            std::span<const Vec3> welded_positions, std::span<const Vec3> interior) {
  SampleBatch batch(pieces, p);
  const std::uint32_t boundary = out.boundary_points();
  const auto position = [&](std::uint32_t k) -> const Vec3& {
    return k < boundary ? welded_positions[out.welded[k]] : interior[k - boundary];
  };
  // Corners: the boundary points whose position another piece (or a pole) gave.
  for (std::uint32_t k = 0; k < boundary; ++k) {
    if (!out.owner[k]) batch.add(out.pattern.points[k].uv, position(k));
  }
  for (const std::vector<Triangle>* triangles : {&out.kept, &out.dropped}) {
    for (const Triangle& t : *triangles) {
      sample_triangle(t, {out.uv(t[0]), out.uv(t[1]), out.uv(t[2])}, {position(t[0]), position(t[1]), position(t[2])},
                      batch);
    }
  }
  // The inner cells (make_pattern_boundary leaves them out), numbered as for_each_inner_triangle:
  //   cell (i, j):  (i, j+1) ---- (i+1, j+1)     lower triangle (i, j), (i+1, j), (i+1, j+1)
  //                    |  upper  /  |             upper triangle (i, j), (i+1, j+1), (i, j+1)
  //                    |      /     |             each samples its inner points and centroid;
  //                 (i, j) ---- (i+1, j)          the cell its bottom, right and diagonal midpoints
  const int nu = out.inner.u;
  const int nv = out.inner.v;
  if (nu > 2 && nv > 2) {
    const auto row = static_cast<std::uint32_t>(nu - 1);
    for (int j = 1; j + 1 < nv; ++j) {
      const double v0 = static_cast<double>(j) / nv;
      const double v1 = static_cast<double>(j + 1) / nv;
      double u0 = 1.0 / nu;
      for (int i = 1; i + 1 < nu; ++i) {
        const double u1 = static_cast<double>(i + 1) / nu;
        const std::uint32_t q = static_cast<std::uint32_t>(i - 1) + row * static_cast<std::uint32_t>(j - 1);
        const std::uint32_t a = boundary + q;
        const Vec2 uv00(u0, v0);
        const Vec2 uv11(u1, v1);
        sample_triangle({a, a + 1, a + row + 1}, {uv00, Vec2(u1, v0), uv11},
                        {interior[q], interior[q + 1], interior[q + row + 1]}, batch);
        sample_triangle({a, a + row + 1, a + row}, {uv00, uv11, Vec2(u0, v1)},
                        {interior[q], interior[q + row + 1], interior[q + row]}, batch);
        u0 = u1;
      }
    }
  }
  return batch.largest();
}

// e_par: |S(u,v) - L(u,v)| at the samples of every parameter triangle, L the linear
// interpolant of the mesh positions: the largest measured_piece_error, pieces in parallel.
double Tessellator::measure(const RenderMesh& mesh) const {
  std::vector<std::uint32_t> tessellated;
  for (std::uint32_t p = 0; p < count_; ++p) {
    if (!plans_[p].culled) tessellated.push_back(p);
  }
  std::vector<double> errors(tessellated.size(), 0.0);
  const std::span<const Vec3> positions(mesh.positions);
  parallel_for(tessellated.size(), options_.threads, [&](std::size_t q) {
    const std::uint32_t p = tessellated[q];
    const PatchOutput& out = (*outputs_)[p];
    errors[q] = measured_piece_error(pieces_, p, out, *welded_positions_,
                                     positions.subspan(out.first_vertex, out.interior_points()));
  });
  return errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end());
}

}  // namespace patchwork::detail
