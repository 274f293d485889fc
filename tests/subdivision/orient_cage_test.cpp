// orient_cage(): closed cages from the wild with faces wound the wrong way (a torus, a sphere
// from the cube) come back consistent, with the faces it flipped named, and subdivide exactly as
// the consistent cage does; the library refuses the inconsistent cage until it is oriented.

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "core/errors.h"
#include "meshes/topology.h"
#include "subdivision/orient_cage.h"
#include "subdivision/refine.h"
#include "tests/meshes/face_lists.h"
#include "tests/meshes/mesh_generators.h"

namespace patchwork {
namespace {

// The unit cube with outward faces: a sphere as a cage.
FaceVertexMesh outward_cube() {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  return testing::make_mesh(points,
                            {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
}

std::vector<FaceId> faces_where(const std::vector<bool>& flag, bool value) {
  std::vector<FaceId> faces;
  for (std::uint32_t f = 0; f < flag.size(); ++f) {
    if (flag[f] == value) faces.push_back(FaceId{f});
  }
  return faces;
}

RC_GTEST_PROP(OrientCage, RandomlyFlippedClosedCagesSubdivideAsTheConsistentOne, ()) {
  testing::Random random(*rc::gen::arbitrary<std::uint64_t>());
  // A torus of 3..7 x 3..7 quads, a triangulated torus, or the cube (a sphere).
  FaceVertexMesh consistent = outward_cube();
  const auto kind = random.below(3);
  if (kind != 0) consistent = testing::torus(3 + random.below(5), 3 + random.below(5)).mesh;
  if (kind == 2)
    consistent = testing::triangulated(testing::torus(3 + random.below(3), 3 + random.below(3)), random).mesh;
  const std::size_t faces = consistent.face_count();
  // Any number of faces flipped, each with a probability of its own.
  const double p = random.uniform(0.0, 1.0);
  std::vector<bool> flip(faces);
  for (std::size_t f = 0; f < faces; ++f) flip[f] = random.uniform(0.0, 1.0) < p;
  const std::size_t flipped_count = static_cast<std::size_t>(std::count(flip.begin(), flip.end(), true));
  RC_PRE(2 * flipped_count != faces);  // a tie keeps face 0's orientation: checked below
  SubdivisionCage cage;
  cage.mesh = testing::flip_faces(consistent, flip);
  // A face-varying channel with a value per corner of the consistent cage, its indices flipped
  // with their faces (as a file from the wild has them): index c at a corner means "this corner is
  // corner c of the consistent cage".
  std::vector<std::uint32_t> corner_ids(consistent.face_indices().size());
  for (std::uint32_t c = 0; c < corner_ids.size(); ++c) corner_ids[c] = c;
  const auto flipped_ids = [&](const std::vector<bool>& which) {
    return testing::flip_faces(FaceVertexMesh(Positions::Zero(static_cast<Eigen::Index>(corner_ids.size()), 3),
                                              consistent.face_sizes(), corner_ids),
                               which)
        .face_indices();
  };
  FaceVaryingData uv;
  uv.values = Eigen::MatrixXd::Random(static_cast<Eigen::Index>(corner_ids.size()), 2);
  uv.indices = flipped_ids(flip);
  cage.face_varying = uv;

  const CageOrientation oriented = orient_cage(cage);
  // The fewest faces flip: the ones flipped here when they are fewer than half, else the others,
  // and the result is the consistent cage, or the consistent cage with every face reversed.
  const bool minority = 2 * flipped_count < faces;
  RC_ASSERT(oriented.flipped == faces_where(flip, minority));
  RC_ASSERT(oriented.non_orientable_components == 0u);
  RC_ASSERT(oriented.seam_edges == 0u);
  const FaceVertexMesh expected =
      minority ? consistent : testing::flip_faces(consistent, std::vector<bool>(faces, true));
  RC_ASSERT(oriented.cage.mesh.face_indices() == expected.face_indices());
  RC_ASSERT(oriented.cage.mesh.face_sizes() == expected.face_sizes());
  RC_ASSERT(analyze(oriented.cage.mesh).orientable);
  // Each corner keeps its face-varying value: the indices moved with their corners.
  RC_ASSERT(oriented.cage.face_varying->indices ==
            (minority ? corner_ids : flipped_ids(std::vector<bool>(faces, true))));
  for (std::size_t c = 0; c < corner_ids.size(); ++c) {
    RC_ASSERT(oriented.cage.mesh.face_indices()[c] ==
              consistent.face_indices()[oriented.cage.face_varying->indices[c]]);
  }

  // Subdivided, it is the consistent cage subdivided: the same points and the same report.
  const int levels = 1 + static_cast<int>(random.below(2));
  SubdivisionCage reference;
  reference.mesh = expected;
  const UniformRefinement mine = refine_uniform(oriented.cage, levels);
  const UniformRefinement theirs = refine_uniform(reference, levels);
  RC_ASSERT(mine.cage.mesh.face_indices() == theirs.cage.mesh.face_indices());
  RC_ASSERT(mine.cage.mesh.positions().rows() == theirs.cage.mesh.positions().rows());
  RC_ASSERT((mine.cage.mesh.positions() - theirs.cage.mesh.positions()).cwiseAbs().maxCoeff() <= 1e-12);
  RC_ASSERT(to_json(mine.topology) == to_json(theirs.topology));
  RC_ASSERT(to_json(mine.topology) == to_json(analyze(mine.cage.mesh)));
  // Orienting again flips nothing; the unoriented cage is refused, naming two faces.
  RC_ASSERT(orient_cage(oriented.cage).flipped.empty());
  if (flipped_count != 0 && flipped_count != faces) {
    const std::string message = testing::error_message<TopologyError>([&] { refine_uniform(cage, 1); });
    RC_ASSERT(message.find("in the same direction (orient_cage() the cage first)") != std::string::npos);
  }
}

TEST(OrientCage, ATieKeepsTheFirstFacesOrientation) {
  // Three of the cube's six faces flipped: either choice flips three, the first face decides.
  std::vector<bool> flip = {true, false, true, false, true, false};
  SubdivisionCage cage;
  cage.mesh = testing::flip_faces(outward_cube(), flip);
  const CageOrientation oriented = orient_cage(cage);
  EXPECT_EQ(oriented.flipped, (std::vector<FaceId>{FaceId{1}, FaceId{3}, FaceId{5}}));
  EXPECT_EQ(oriented.cage.mesh.face_indices(),
            testing::flip_faces(outward_cube(), std::vector<bool>(6, true)).face_indices());
}

TEST(OrientCage, NonOrientableComponentsKeepTheirWindingAndCountTheirSeams) {
  // A Moebius band of 2 x 8 quads: glued at column 0 with a twist, the 2 edges of that column
  // are walked the same way by both their faces; an oriented cube beside it.
  const testing::KnownSurface band = testing::mobius_band(2, 8);
  const testing::KnownSurface both =
      testing::disjoint_union(band, testing::KnownSurface{"cube", outward_cube(), 2, 0, 1, true, 0, std::nullopt});
  SubdivisionCage cage;
  cage.mesh = both.mesh;
  const CageOrientation oriented = orient_cage(cage);
  EXPECT_TRUE(oriented.flipped.empty());
  EXPECT_EQ(oriented.non_orientable_components, 1u);
  EXPECT_EQ(oriented.seam_edges, 2u);
  EXPECT_EQ(oriented.cage.mesh.face_indices(), both.mesh.face_indices());
}

}  // namespace
}  // namespace patchwork
