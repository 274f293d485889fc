// The vertex-cache and vertex-fetch order over several chunks of triangles (the order is found
// per chunk of 2^16 triangles, chunks in parallel): it keeps every triangle with its patch, does
// not depend on the threads, and reuses a result's storage from run to run.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "io/bpt.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator.h"
#include "tests/surfaces/tessellation_checks.h"

namespace patchwork {
namespace vertex_order_test {

const PatchSet& teapot() {
  static const PatchSet set(read_bpt(PATCHWORK_DATA_DIR "/teapot.bpt"));
  return set;
}

// A triangle as its corners' positions with its patch, rotated to start at the smallest corner
// (the vertex-cache order may rotate a triangle's corners, never flip it).
using KeyedTriangle = std::array<double, 10>;

std::vector<KeyedTriangle> keyed_triangles(const Tessellation& result) {
  const RenderMesh& mesh = result.mesh;
  std::vector<KeyedTriangle> keyed;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::array<Vec3, 3> corners;
    for (std::size_t k = 0; k < 3; ++k) corners[k] = mesh.positions[mesh.indices[3 * t + k]];
    const auto less = [](const Vec3& a, const Vec3& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    const auto first = static_cast<std::size_t>(std::min_element(corners.begin(), corners.end(), less) - corners.begin());
    KeyedTriangle key{};
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t c = 0; c < 3; ++c) key[3 * k + c] = corners[(first + k) % 3][static_cast<Eigen::Index>(c)];
    }
    key[9] = result.triangle_patches[t];
    keyed.push_back(key);
  }
  std::sort(keyed.begin(), keyed.end());
  return keyed;
}

// 48 x 48 per patch: 147,072 triangles, three chunks.
TessellationOptions uniform48(bool optimize, int threads) {
  TessellationOptions options;
  options.segments = 48;
  options.optimize = optimize;
  options.threads = threads;
  return options;
}

TEST(TessellatorVertexOrder, ChunksKeepEveryTriangleWithItsPatch) {
  const Tessellation plain = tessellate(teapot(), uniform48(false, 1));
  const Tessellation ordered = tessellate(teapot(), uniform48(true, 1));
  ASSERT_GT(ordered.mesh.triangle_count(), std::size_t{2} << 16) << "more than two chunks";
  EXPECT_EQ(keyed_triangles(ordered), keyed_triangles(plain));
  // Each vertex is its triangle's patch at its UV (patch parameters).
  const RenderMesh& mesh = ordered.mesh;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const BezierPatch3& patch = teapot().patches()[ordered.triangle_patches[t]];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      ASSERT_LT((patch.evaluate(mesh.uvs[v].x(), mesh.uvs[v].y()) - mesh.positions[v]).norm(), 1e-12)
          << "triangle " << t;
    }
  }
  // Vertices in order of first use: the first use of vertex v comes after that of v - 1.
  std::vector<std::size_t> first_use(mesh.vertex_count(), mesh.indices.size());
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) first_use[mesh.indices[k]] = std::min(first_use[mesh.indices[k]], k);
  EXPECT_TRUE(std::is_sorted(first_use.begin(), first_use.end()));
  EXPECT_EQ(first_use.back() < mesh.indices.size(), true) << "every vertex used";
}

TEST(TessellatorVertexOrder, ChunkedOrderDoesNotDependOnTheThreadsAndReusesTheResult) {
  const Tessellation one = tessellate(teapot(), uniform48(true, 1));
  testing::expect_identical_tessellations(one, tessellate(teapot(), uniform48(true, 3)));
  // Reused through a smaller and a larger run, on two threads, from a prepared surface.
  const PreparedSurface prepared(teapot());
  Tessellation reused;
  TessellationOptions coarse;
  coarse.relative_tolerance = 1e-2;
  coarse.threads = 2;
  for (const TessellationOptions& options : {uniform48(true, 2), coarse, uniform48(true, 2)}) {
    tessellate(prepared, options, reused);
    testing::expect_identical_tessellations(reused, tessellate(teapot(), options));
  }
  testing::expect_identical_tessellations(one, reused);
}

}  // namespace vertex_order_test
}  // namespace patchwork
