#pragma once
// patchwork's patches as Open CASCADE surfaces, for the report's OCCT code (report/occt_peer.cpp,
// report/queries_crosscheck.cpp): the only header outside those files that includes OCCT.
//
// A Bezier patch becomes a Geom_BezierSurface whose pole (i+1, j+1) is P_ij, so OCCT's (U, V) in
// [0,1]^2 is patchwork's (u, v) (surfaces/bezier_patch.h). A NurbsSurface becomes a
// Geom_BSplineSurface with the same degrees, poles, weights and knots (report/occt_peer.h).

#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>

#include "surfaces/bezier_patch.h"
#include "surfaces/nurbs_surface.h"

namespace patchwork::performance::detail {

/// The Geom_BezierSurface of a patch ((U, V) = (u, v)). \pre degrees within [1, 25].
Handle(Geom_BezierSurface) occt_bezier_surface(const BezierPatch3& patch);

/// The Geom_BSplineSurface of a NURBS surface (same parameters). \pre degrees within [1, 25].
Handle(Geom_BSplineSurface) occt_bspline_surface(const NurbsSurface& surface);

}  // namespace patchwork::performance::detail
