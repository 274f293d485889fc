// libFuzzer target: subdivision cages from arbitrary bytes (up to 10 vertices and 12 faces,
// creases, corners and holes with any sharpness, every scheme and boundary rule) through
// validation, one or two levels of uniform refinement and the limit surface. Whatever
// validate_cage() lets through must not crash OpenSubdiv, and the refined report must be the
// refined mesh's.

#include <cstdio>
#include <limits>
#include <string>

#include "meshes/topology.h"
#include "subdivision/limit_surface.h"
#include "subdivision/refine.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader bytes(data, size);
  SubdivisionCage cage;
  cage.options.scheme = static_cast<SubdivisionScheme>(bytes.below(3));
  cage.options.boundary = static_cast<BoundaryInterpolation>(bytes.below(3));
  // 3 to 10 vertices, 1 to 12 faces of 3 to 5 corners, indices in range.
  const fuzz::FaceListBytes list = fuzz::face_list(bytes, 3, 8, 1, 12, 3, 3, 0);
  const auto vertices = static_cast<std::uint32_t>(list.positions.rows());
  const auto faces = static_cast<std::uint32_t>(list.sizes.size());
  const auto sharpness = [&] {
    const std::uint32_t s = bytes.below(8);
    return s == 7 ? std::numeric_limits<double>::infinity() : s == 6 ? -1.0 : s * 0.75;
  };
  for (std::uint32_t k = bytes.below(4); k > 0; --k)
    cage.creases.push_back({bytes.below(vertices), bytes.below(vertices), sharpness()});
  for (std::uint32_t k = bytes.below(3); k > 0; --k) cage.corners.push_back({bytes.below(vertices), sharpness()});
  for (std::uint32_t k = bytes.below(2); k > 0; --k) cage.holes.push_back(bytes.below(faces));
  const int levels = 1 + static_cast<int>(bytes.below(2));
  fuzz::expect_documented_errors_only([&] {
    cage.mesh = FaceVertexMesh(list.positions, list.sizes, list.indices);
    const UniformRefinement refined = refine_uniform(cage, levels);
    refined.cage.mesh.validate();
    if (refined.cage.holes.empty()) {
      const std::string derived = to_json(refined.topology);
      const std::string analysed = to_json(analyze(refined.cage.mesh));
      if (derived != analysed) {
        std::fprintf(stderr, "derived  %s\nanalysed %s\n", derived.c_str(), analysed.c_str());
        std::fprintf(stderr, "cage: %zu vertices, %zu faces, scheme %d, boundary %d, levels %d\n",
                     cage.mesh.vertex_count(), cage.mesh.face_count(), static_cast<int>(cage.options.scheme),
                     static_cast<int>(cage.options.boundary), levels);
        for (std::size_t f = 0; f < cage.mesh.face_count(); ++f) {
          std::fprintf(stderr, " face");
          for (std::uint32_t v : cage.mesh.face(f)) std::fprintf(stderr, " %u", v);
          std::fprintf(stderr, "\n");
        }
      }
      PATCHWORK_FUZZ_CHECK(derived == analysed);
    }
    const LimitSurface surface(cage, 2);
    for (std::size_t f = 0; f < surface.face_count(); ++f) {
      if (!surface.has_surface(f)) continue;
      const LimitPoint point = surface.evaluate(f, 0.25, 0.25);
      PATCHWORK_FUZZ_CHECK(point.position.allFinite());
    }
  });
  return 0;
}
