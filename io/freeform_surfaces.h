#pragma once
// OBJ free-form records (io/obj_freeform.h) as surfaces and back: a `surf` record is the NURBS
// surface of its knots (bspline_knots: a Bezier-basis record's breakpoints with multiplicity p),
// control points and weights; its range [u0, u1] x [v0, v1] selects the part that is used, cut
// out by knot insertion (bezier_patches(surface, range)). Several surfaces of a file are one
// patch set, joined where their edges meet (PatchSet finds the shared edges).

#include <string>
#include <vector>

#include "io/obj_freeform.h"
#include "surfaces/nurbs_surface.h"

namespace patchwork {

/// The NURBS surface of a record (over the whole domain of its parameters).
/// \throws InvalidInput if the record is not valid (validate(surface)).
NurbsSurface nurbs_surface(const FreeformSurface& surface);

/// The Bezier patches of a record over its range.
/// \throws InvalidInput if the record is not valid.
NurbsBezierPatches freeform_bezier_patches(const FreeformSurface& surface);

/// Every surface's Bezier patches over its range, in file order (a patch set's input).
/// \throws InvalidInput if the document has no surface or a record is not valid.
std::vector<AnyBezierPatch> freeform_patches(const FreeformDocument& document);

/// The patch set of a document: every surface's patches, joined inside each surface as its knots
/// say (KnownJoin) and across surfaces and closed seams where their edges meet.
/// \throws InvalidInput as freeform_patches.
PatchSet freeform_patch_set(const FreeformDocument& document, double relative_tolerance = 1e-9);

/// The record of a NURBS surface: basis bspline, rational when its weights differ, the range
/// its domain.
FreeformSurface freeform_surface(const NurbsSurface& surface, std::string name = {});

/// The record of a Bezier patch: basis bezier, one segment each way, parameters and range [0, 1].
FreeformSurface freeform_surface(const BezierPatch3& patch, std::string name = {});

}  // namespace patchwork
