#include "bench/scene.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace patchwork::bench {

std::vector<BezierPatch3> rotated_copies(const std::vector<BezierPatch3>& patches, std::size_t copies) {
  Eigen::AlignedBox3d box;
  for (const BezierPatch3& patch : patches) {
    for (const Vec3& p : patch.control_points()) box.extend(p);
  }
  const Vec3 centre = box.center();
  const double spacing = 1.5 * box.diagonal().norm();
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(copies))));
  std::vector<BezierPatch3> scene;
  scene.reserve(patches.size() * copies);
  for (std::size_t k = 0; k < copies; ++k) {
    // One generator per copy: copy k is the same whatever the count.
    std::mt19937_64 random(k);
    std::normal_distribution<double> gaussian;
    Vec3 axis(gaussian(random), gaussian(random), gaussian(random));
    axis.normalize();
    const double angle = std::uniform_real_distribution<double>(0.0, 2.0 * 3.14159265358979323846)(random);
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const Vec3 offset(spacing * static_cast<double>(k % side), spacing * static_cast<double>(k / side), 0.0);
    for (const BezierPatch3& patch : patches) {
      std::vector<Vec3> points = patch.control_points();
      for (Vec3& p : points) p = rotation * (p - centre) + offset;
      scene.emplace_back(patch.degree_u(), patch.degree_v(), std::move(points));
    }
  }
  return scene;
}

}  // namespace patchwork::bench
