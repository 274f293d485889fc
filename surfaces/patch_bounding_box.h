#pragma once
// Tight bounding boxes of patches by branch and bound. For each of the six directions the
// largest value of +-x_c over the surface lies between the best surface point found so far
// (corners of sub-patches are surface points) and the largest control-point value of the
// remaining sub-patches (convex hull property); sub-patches are split until the two are within
// the tolerance. The box returned always contains the surface (it is the upper bound).

#include <Eigen/Geometry>
#include <span>

#include "surfaces/bezier_patch.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// A box that contains F([0,1]^2) and whose every face is within `tolerance` of the surface's
/// extreme in that direction. \throws InvalidInput if tolerance is not positive.
Eigen::AlignedBox3d bounding_box(const BezierPatch3& patch, double tolerance);

/// The same for a rational patch (its points bound it: the weights are positive).
/// \throws InvalidInput if tolerance is not positive.
Eigen::AlignedBox3d bounding_box(const RationalBezierPatch& patch, double tolerance);

/// A box that contains the surface of every patch, each face within `tolerance` of the set's
/// extreme in that direction (patches that cannot reach past the others' corners are skipped).
/// \throws InvalidInput if tolerance is not positive. Empty box for no patches.
Eigen::AlignedBox3d bounding_box(std::span<const BezierPatch3> patches, double tolerance);

/// The box of the control points (contains the surface; not tight).
Eigen::AlignedBox3d control_box(const BezierPatch3& patch);

}  // namespace patchwork
