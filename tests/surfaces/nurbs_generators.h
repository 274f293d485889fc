#pragma once
// RapidCheck generators of NURBS surfaces, on the knot vectors of tests/curves/bspline_generators.h.

#include <rapidcheck.h>

#include <vector>

#include "surfaces/nurbs_surface.h"
#include "tests/curves/bspline_generators.h"

namespace patchwork::nurbs_gen {

/// A random NURBS surface: degrees 1..3, random knot vectors (clamped or, unless clamped_only,
/// not; interior knots repeated up to the degree), coordinates in [-10, 10], weights in [1/4, 4]
/// (or all 1).
inline rc::Gen<NurbsSurface> nurbs_surface(bool rational, bool clamped_only = false) {
  return rc::gen::exec([rational, clamped_only] {
    const KnotVector U = *bspline_gen::knot_vector(1, 3, 3, 0, clamped_only);
    const KnotVector V = *bspline_gen::knot_vector(1, 3, 3, 0, clamped_only);
    const int count = U.control_point_count() * V.control_point_count();
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int k = 0; k < count; ++k) {
      points.emplace_back(*rc::gen::inRange(-80, 81) / 8.0, *rc::gen::inRange(-80, 81) / 8.0,
                          *rc::gen::inRange(-80, 81) / 8.0);
      weights.push_back(rational ? *rc::gen::inRange(2, 33) / 8.0 : 1.0);
    }
    return NurbsSurface(U, V, points, weights);
  });
}

}  // namespace patchwork::nurbs_gen
