#pragma once
// Scalar and vector aliases shared by every module.
//
// patchwork computes in double precision and keeps its points in Eigen's fixed-size vectors;
// there is no vector class of our own. `Point<D>` is a column vector of D doubles.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products and boxes on the point types

#include <cstdint>
#include <limits>

namespace patchwork {

using Scalar = double;

template <int Dim>
using Point = Eigen::Matrix<double, Dim, 1>;

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;

/// Half the machine epsilon, u = 2^-53: the relative error of one rounding of a double.
inline constexpr double unit_roundoff = std::numeric_limits<double>::epsilon() / 2;

/// Signed 64-bit count for topology formulas (chi = V - E + F may be negative).
using Count = std::int64_t;

}  // namespace patchwork
