#include "queries/net_piece.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/assert.h"

namespace patchwork::detail {
namespace {


// De Casteljau at s of `count` points at stride `stride` starting at `first`, writing the left
// piece's points to `left` and the right piece's to `right` (same stride).
void cut_line(const Vec4* first, std::size_t stride, int count, double s, Vec4* left, Vec4* right) {
  Vec4 work[32];
  PATCHWORK_ASSERT(count <= 32, "net_piece: degree above 31");
  for (int i = 0; i < count; ++i) work[i] = first[static_cast<std::size_t>(i) * stride];
  for (int r = 0; r < count; ++r) {
    left[static_cast<std::size_t>(r) * stride] = work[0];
    right[static_cast<std::size_t>(count - 1 - r) * stride] = work[count - 1 - r];
    for (int i = 0; i + 1 < count - r; ++i) work[i] = (1 - s) * work[i] + s * work[i + 1];
  }
}

// The piece cut at local parameter s along u (dir 0) or v (dir 1).
std::array<NetPiece, 2> cut(const NetPiece& piece, int dir, double s) {
  std::array<NetPiece, 2> out{piece, piece};
  const int rows = dir == 0 ? piece.m + 1 : piece.n + 1;
  const int count = dir == 0 ? piece.n + 1 : piece.m + 1;
  const std::size_t stride = dir == 0 ? 1 : static_cast<std::size_t>(piece.n + 1);
  const std::size_t row_step = dir == 0 ? static_cast<std::size_t>(piece.n + 1) : 1;
  for (int r = 0; r < rows; ++r) {
    const std::size_t start = static_cast<std::size_t>(r) * row_step;
    cut_line(piece.net.data() + start, stride, count, s, out[0].net.data() + start, out[1].net.data() + start);
  }
  for (NetPiece& half : out) ++half.depth;
  double& low_end = dir == 0 ? out[0].u1 : out[0].v1;
  double& high_start = dir == 0 ? out[1].u0 : out[1].v0;
  const double a = dir == 0 ? piece.u0 : piece.v0, b = dir == 0 ? piece.u1 : piece.v1;
  low_end = high_start = s == 0.5 ? 0.5 * (a + b) : a + s * (b - a);
  return out;
}

}  // namespace

std::array<NetPiece, 2> halves(const NetPiece& piece, int dir) { return cut(piece, dir, 0.5); }

int longer_direction(const NetPiece& piece) {
  // The points dehomogenised once (each is in two polygons); up to 32 x 32 on the stack.
  constexpr std::size_t most = 32 * 32;
  std::array<Vec3, most> stored;
  std::vector<Vec3> large;
  Vec3* points = piece.net.size() <= most ? stored.data() : (large.resize(piece.net.size()), large.data());
  for (std::size_t k = 0; k < piece.net.size(); ++k) points[k] = piece.net[k].head<3>() / piece.net[k][3];
  const auto at = [&](int i, int j) -> const Vec3& { return points[static_cast<std::size_t>(i + (piece.n + 1) * j)]; };
  double along_u = 0.0, along_v = 0.0;
  for (int j = 0; j <= piece.m; ++j) {
    double length = 0.0;
    for (int i = 0; i < piece.n; ++i) length += (at(i + 1, j) - at(i, j)).norm();
    along_u = std::max(along_u, length);
  }
  for (int i = 0; i <= piece.n; ++i) {
    double length = 0.0;
    for (int j = 0; j < piece.m; ++j) length += (at(i, j + 1) - at(i, j)).norm();
    along_v = std::max(along_v, length);
  }
  return along_u >= along_v ? 0 : 1;
}

NetPiece whole_piece(const BezierPatch3& patch) {
  NetPiece piece;
  piece.n = patch.degree_u();
  piece.m = patch.degree_v();
  piece.net.reserve(patch.control_points().size());
  for (const Vec3& p : patch.control_points()) piece.net.emplace_back(p.x(), p.y(), p.z(), 1.0);
  return piece;
}

NetPiece whole_piece(const RationalBezierPatch& patch) {
  NetPiece piece;
  piece.n = patch.degree_u();
  piece.m = patch.degree_v();
  piece.net = patch.homogeneous().control_points();
  return piece;
}

NetPiece whole_piece(const PatchSet& set, std::uint32_t p) {
  NetPiece piece = set.is_rational(p) ? whole_piece(*set.rational(p)) : whole_piece(set.control_nets()[p]);
  piece.patch = p;
  return piece;
}

std::vector<NetPiece> split_pieces(const NetPiece& piece, int k) {
  PATCHWORK_ASSERT(k >= 1, "split_pieces: k >= 1");
  // Columns by successive cuts at 1/k, 1/(k-1), ... of what remains (each piece the exact
  // sub-patch up to rounding), then each column the same way in v.
  const auto strips = [k](NetPiece rest, int dir) {
    std::vector<NetPiece> out;
    for (int c = 0; c + 1 < k; ++c) {
      auto [low, high] = cut(rest, dir, 1.0 / (k - c));
      out.push_back(std::move(low));
      rest = std::move(high);
    }
    out.push_back(std::move(rest));
    return out;
  };
  std::vector<NetPiece> pieces(static_cast<std::size_t>(k) * static_cast<std::size_t>(k));
  const std::vector<NetPiece> columns = strips(piece, 0);
  for (int c = 0; c < k; ++c) {
    std::vector<NetPiece> column = strips(columns[static_cast<std::size_t>(c)], 1);
    for (int r = 0; r < k; ++r) pieces[static_cast<std::size_t>(c + k * r)] = std::move(column[static_cast<std::size_t>(r)]);
  }
  // Each cut rounds once per level of de Casteljau, like a halving; the margin counts them.
  for (NetPiece& p : pieces) p.depth = piece.depth + 2 * k;
  return pieces;
}

namespace {

// The margin for control points whose largest coordinate (in absolute value) is `size`.
double margin_for(const NetPiece& piece, double size) {
  // Each halving adds at most (degree) roundings of a convex combination, each of relative size
  // u; the weights' division and the frame projections add a few more.
  return 8.0 * (piece.depth + 4) * (piece.n + piece.m + 2) * unit_roundoff * size;
}

}  // namespace

double rounding_margin(const NetPiece& piece) {
  double size = 0.0;
  for (int j = 0; j <= piece.m; ++j)
    for (int i = 0; i <= piece.n; ++i) size = std::max(size, piece.point(i, j).cwiseAbs().maxCoeff());
  return margin_for(piece, size);
}

Eigen::AlignedBox3d control_box(const NetPiece& piece) {
  // The box and the margin's size from one pass over the points.
  Eigen::AlignedBox3d box;
  for (int j = 0; j <= piece.m; ++j)
    for (int i = 0; i <= piece.n; ++i) box.extend(piece.point(i, j));
  const double margin = margin_for(piece, box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff());
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

double distance_lower_bound(const NetPiece& piece, const Vec3& q) {
  const Vec3 p00 = piece.point(0, 0), pn0 = piece.point(piece.n, 0);
  const Vec3 p0m = piece.point(0, piece.m), pnm = piece.point(piece.n, piece.m);
  Vec3 e1 = (pn0 - p00) + (pnm - p0m);
  Vec3 along_v = (p0m - p00) + (pnm - pn0);
  Vec3 normal = e1.cross(along_v);
  double distance_squared = 0.0;
  if (!(e1.squaredNorm() > 0.0) || !(normal.squaredNorm() > 1e-24 * e1.squaredNorm() * along_v.squaredNorm())) {
    // No frame from the corners (a collapsed edge or a curve-like piece): the axis box.
    Eigen::AlignedBox3d box;
    for (int j = 0; j <= piece.m; ++j)
      for (int i = 0; i <= piece.n; ++i) box.extend(piece.point(i, j));
    distance_squared = box.squaredExteriorDistance(q);
  } else {
    e1.normalize();
    normal.normalize();
    const Vec3 e2 = normal.cross(e1);
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (int j = 0; j <= piece.m; ++j) {
      for (int i = 0; i <= piece.n; ++i) {
        const Vec3 d = piece.point(i, j) - q;
        const Vec3 c(d.dot(e1), d.dot(e2), d.dot(normal));
        low = low.cwiseMin(c);
        high = high.cwiseMax(c);
      }
    }
    for (int c = 0; c < 3; ++c) {
      const double outside = std::max({low[c], -high[c], 0.0});
      distance_squared += outside * outside;
    }
  }
  return std::max(0.0, std::sqrt(distance_squared) - rounding_margin(piece));
}

}  // namespace patchwork::detail
