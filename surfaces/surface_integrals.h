#pragma once
// Surface area (seed Def 33: A = int int |F_u x F_v| du dv) and enclosed volume.
//
// Area: adaptive tensor Gauss-Legendre (8 x 8 nodes per cell): a cell is accepted when its rule
// and the sum over its four quarters differ by less than its share of the tolerance, and the
// differences add up to the error estimate.
// Volume of a closed, consistently and outward oriented patch set, by the divergence theorem
// with div(x) = 3:  V = (1/3) sum_patches int int F . (F_u x F_v) du dv. For polynomial patches
// the integrand is a polynomial of degree (3n-1, 3m-1), integrated exactly by ceil(3n/2) x
// ceil(3m/2) Gauss nodes; rational patches use the adaptive rule.

#include <functional>
#include <span>

#include "surfaces/bezier_patch.h"
#include "surfaces/rational_bezier_patch.h"

namespace patchwork {

/// A value and an estimate of |value - exact| (quadrature error; rounding not included).
struct SurfaceIntegral {
  double value;
  double error_estimate;
};

/// int over [0,1]^2 of f(u, v) du dv to absolute `tolerance`.
/// \throws InvalidInput if tolerance is not positive; NumericalError if 20 levels do not suffice.
SurfaceIntegral integrate_over_square(const std::function<double(double, double)>& f, double tolerance);

/// Area of the patch to absolute `tolerance`.
SurfaceIntegral area(const BezierPatch3& patch, double tolerance = 1e-10);
/// Area of the rational patch to absolute `tolerance`.
SurfaceIntegral area(const RationalBezierPatch& patch, double tolerance = 1e-10);

/// (1/3) int int F . (F_u x F_v): the patch's share of the volume, exact up to rounding.
double volume_contribution(const BezierPatch3& patch);
/// The rational patch's share of the volume, to absolute `tolerance`.
SurfaceIntegral volume_contribution(const RationalBezierPatch& patch, double tolerance = 1e-10);

/// Volume enclosed by closed, outward-oriented patches (negative if oriented inward). Whether
/// the set is closed is the caller's to check (PatchSet's report says so); for an open set the
/// number depends on the origin and means nothing.
double enclosed_volume(std::span<const BezierPatch3> patches);

}  // namespace patchwork
