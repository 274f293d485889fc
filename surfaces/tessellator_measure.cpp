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
//     triangle) always. (The inner cells take (u, v) on the sixths of a cell, as the fine grids
//     of the first meter did: the same points but for rounding.)
//   - the centroid and the three inner points belong to one triangle each.
//
// Cost model. A pattern of T triangles has about T/2 points and 3T/2 edges, so a piece costs
// about 4 + 1.5 = 5.5 evaluations a triangle, plus one per welded boundary point (10 before);
// an inner cell (two triangles) takes 11 (42 before, with normals). An evaluation is a position
// only (evaluate_points: no derivatives, no normals), vectorised across points, in batches of 256
// samples per piece with no allocation. The inner cells go a row of samples at a time (all on one
// v), and where rows are long (16 cells or more) each row is one batch, for which
// evaluate_points contracts the net in v once: a sample then costs the Bernstein values of u and
// n + 1 terms. Besides S, a sample costs its L (three weighted corners) and a squared distance.

#include "surfaces/tessellator_stages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/parallel.h"

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

  void add(double u, double v, const Vec3& linear) {
    us_[count_] = u;
    vs_[count_] = v;
    linear_[count_] = linear;
    if (++count_ == capacity) evaluate();
  }

  double largest() {
    evaluate();
    return std::sqrt(largest_);
  }

  // Evaluates the samples waiting (a row of samples on one v goes to evaluate_points' row loop).
  void evaluate() {
    if (count_ == 0) return;
    if (pieces_.evaluate_points) {
      pieces_.evaluate_points(p_, {us_.data(), count_}, {vs_.data(), count_}, {surface_.data(), count_});
    } else {
      for (std::size_t k = 0; k < count_; ++k) surface_[k] = pieces_.evaluate(p_, us_[k], vs_[k]);
    }
    for (std::size_t k = 0; k < count_; ++k) largest_ = std::max(largest_, (surface_[k] - linear_[k]).squaredNorm());
    count_ = 0;
  }

 private:
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
    batch.add(s.x(), s.y(), linear);
  }
}

// The samples of an inner cell row by row: at sixths (a, b) of the cell, in its upper triangle
// or its lower one, sample k of measure_sample_weights there. They are what sample_triangle takes
// from the cell's two triangles: every inner point and centroid, the lower triangle's bottom and
// right midpoints and the upper's diagonal one (the top and left midpoints are the next cells',
// or boundary triangles').
//   cell (i, j):  (i, j+1) ---- (i+1, j+1)     lower triangle (i, j), (i+1, j), (i+1, j+1)
//                    |  upper  /  |             upper triangle (i, j), (i+1, j+1), (i, j+1)
//                    |      /     |             the sample of weights w lies at
//                 (i, j) ---- (i+1, j)            lower: (6 (w1 + w2), 6 w2), upper: (6 w1, 6 (w1 + w2))
struct CellSample {
  std::size_t a;
  bool upper;
  std::size_t k;
};
// clang-format off
constexpr std::array<CellSample, 11> cell_samples = {{
    {3, false, 3},                 // b = 0: the bottom midpoint
    {2, false, 7}, {5, false, 8},  // b = 1
    {1, true, 7},  {4, false, 6},  // b = 2
    {3, true, 3},  {6, false, 4},  // b = 3: the diagonal and right midpoints
    {2, true, 6},  {5, false, 9},  // b = 4
    {1, true, 9},  {4, true, 8}}}; // b = 5
// clang-format on
// Row b of the cell is cell_samples[cell_row_start[b] .. cell_row_start[b + 1]).
constexpr std::array<std::size_t, 7> cell_row_start = {0, 1, 3, 5, 7, 9, 11};

// A row of inner cells: the u of their sixths (us[6 i + a] for cell i), the interior points and
// the first cell's corner (i, j) among them, the points of a row, and the cells in the row.
struct CellRow {
  const double* us;
  const Vec3* interior;
  std::uint32_t first;
  std::uint32_t row;
  std::uint32_t cells;
};

// Sample C of cell_samples in the cell whose corner (i, j) is interior point q: L, its
// triangle's corners weighted in the triangle's order, the weights known at compile time (a term
// of weight 0 adds nothing but the sign of a zero).
template <std::size_t C>
[[gnu::always_inline]] inline Vec3 cell_linear(const Vec3* interior, std::uint32_t q, std::uint32_t row) {
  constexpr CellSample sample = cell_samples[C];
  constexpr std::array<double, 3> w = samples[sample.k];
  // Lower triangle (i, j), (i+1, j), (i+1, j+1); upper (i, j), (i+1, j+1), (i, j+1).
  const std::array<std::uint32_t, 3> corner = sample.upper ? std::array<std::uint32_t, 3>{q, q + row + 1, q + row}
                                                           : std::array<std::uint32_t, 3>{q, q + 1, q + row + 1};
  Vec3 linear = Vec3::Zero();
  if constexpr (w[0] != 0.0) linear += w[0] * interior[corner[0]];
  if constexpr (w[1] != 0.0) linear += w[1] * interior[corner[1]];
  if constexpr (w[2] != 0.0) linear += w[2] * interior[corner[2]];
  return linear;
}

// Samples From + S... of every cell of a row of cells, at v.
template <std::size_t From, std::size_t... S>
void add_cell_samples(const CellRow& cells, double v, SampleBatch& batch, std::index_sequence<S...>) {
  for (std::uint32_t i = 0; i < cells.cells; ++i) {
    const std::uint32_t q = cells.first + i;
    (batch.add(cells.us[6 * i + cell_samples[From + S].a], v, cell_linear<From + S>(cells.interior, q, cells.row)),
     ...);
  }
}

// The samples of row B of every cell of a row of cells, at v.
template <std::size_t B>
void add_cell_row(const CellRow& cells, double v, SampleBatch& batch) {
  constexpr std::size_t from = cell_row_start[B];
  add_cell_samples<from>(cells, v, batch, std::make_index_sequence<cell_row_start[B + 1] - from>{});
}

constexpr std::array<void (*)(const CellRow&, double, SampleBatch&), 6> add_cell_rows = {
    add_cell_row<0>, add_cell_row<1>, add_cell_row<2>, add_cell_row<3>, add_cell_row<4>, add_cell_row<5>};

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
    if (!out.owner[k]) batch.add(out.pattern->points[k].uv.x(), out.pattern->points[k].uv.y(), position(k));
  }
  for (const std::span<const Triangle> triangles : {out.kept_triangles(), std::span<const Triangle>(out.dropped)}) {
    for (const Triangle& t : triangles) {
      sample_triangle(t, {out.uv(t[0]), out.uv(t[1]), out.uv(t[2])}, {position(t[0]), position(t[1]), position(t[2])},
                      batch);
    }
  }
  // The inner cells (make_pattern_boundary leaves them out), numbered as for_each_inner_triangle,
  // a row of samples at a time (cell_samples); (u, v) on the sixths of the cells.
  const int nu = out.inner.u;
  const int nv = out.inner.v;
  if (nu > 2 && nv > 2) {
    const auto cells = static_cast<std::uint32_t>(nu - 2);
    const std::uint32_t row = cells + 1;
    std::vector<double> us(6 * static_cast<std::size_t>(cells) + 1);
    for (std::size_t k = 0; k < us.size(); ++k) us[k] = (1.0 + static_cast<double>(k) / 6.0) / nu;
    // Long rows are evaluated a row at a time: the net is contracted in v once a row.
    const bool by_rows = cells >= 16;
    if (by_rows) batch.evaluate();
    for (int j = 1; j + 1 < nv; ++j) {
      const std::uint32_t first = row * static_cast<std::uint32_t>(j - 1);
      const CellRow cell_row{us.data(), interior.data(), first, row, cells};
      for (std::size_t b = 0; b < 6; ++b) {
        const double v = (j + static_cast<double>(b) / 6.0) / nv;
        add_cell_rows[b](cell_row, v, batch);
        if (by_rows) batch.evaluate();
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
