#include "io/freeform_surfaces.h"

#include "core/errors.h"

namespace patchwork {

NurbsSurface nurbs_surface(const FreeformSurface& surface) {
  validate(surface);
  return NurbsSurface(
      KnotVector(surface.degree_u, bspline_knots(surface.basis, surface.degree_u, surface.parameters_u)),
      KnotVector(surface.degree_v, bspline_knots(surface.basis, surface.degree_v, surface.parameters_v)),
      surface.points, surface.weights);
}

NurbsBezierPatches freeform_bezier_patches(const FreeformSurface& surface) {
  return bezier_patches(nurbs_surface(surface), surface.u0, surface.u1, surface.v0, surface.v1);
}

std::vector<AnyBezierPatch> freeform_patches(const FreeformDocument& document) {
  if (document.surfaces.empty()) throw InvalidInput("freeform_patches: the document has no surface");
  std::vector<AnyBezierPatch> patches;
  for (const FreeformSurface& surface : document.surfaces) {
    NurbsBezierPatches pieces = freeform_bezier_patches(surface);
    patches.insert(patches.end(), std::make_move_iterator(pieces.patches.begin()),
                   std::make_move_iterator(pieces.patches.end()));
  }
  return patches;
}

PatchSet freeform_patch_set(const FreeformDocument& document, double relative_tolerance) {
  if (document.surfaces.empty()) throw InvalidInput("freeform_patch_set: the document has no surface");
  std::vector<AnyBezierPatch> patches;
  std::vector<KnownJoin> joins;
  for (const FreeformSurface& surface : document.surfaces) {
    NurbsBezierPatches pieces = freeform_bezier_patches(surface);
    const auto first = static_cast<std::uint32_t>(patches.size());
    for (KnownJoin join : pieces.joins) {
      join.first.patch += first;
      join.second.patch += first;
      joins.push_back(join);
    }
    patches.insert(patches.end(), std::make_move_iterator(pieces.patches.begin()),
                   std::make_move_iterator(pieces.patches.end()));
  }
  return PatchSet(patches, joins, relative_tolerance);
}

FreeformSurface freeform_surface(const NurbsSurface& surface, std::string name) {
  FreeformSurface record;
  record.name = std::move(name);
  record.basis = FreeformBasis::bspline;
  record.rational = surface.rational();
  record.degree_u = surface.degree_u();
  record.degree_v = surface.degree_v();
  record.parameters_u = surface.knots_u().knots();
  record.parameters_v = surface.knots_v().knots();
  record.u0 = surface.knots_u().a();
  record.u1 = surface.knots_u().b();
  record.v0 = surface.knots_v().a();
  record.v1 = surface.knots_v().b();
  for (int j = 0; j < surface.count_v(); ++j) {
    for (int i = 0; i < surface.count_u(); ++i) {
      record.points.push_back(surface.control_point(i, j));
      record.weights.push_back(surface.rational() ? surface.weight(i, j) : 1.0);
    }
  }
  return record;
}

FreeformSurface freeform_surface(const BezierPatch3& patch, std::string name) {
  FreeformSurface record;
  record.name = std::move(name);
  record.basis = FreeformBasis::bezier;
  record.degree_u = patch.degree_u();
  record.degree_v = patch.degree_v();
  record.parameters_u = {0.0, 1.0};
  record.parameters_v = {0.0, 1.0};
  record.points = patch.control_points();  // the patch's order: P_ij at i + (n + 1) j, u fastest
  record.weights.assign(record.points.size(), 1.0);
  return record;
}

}  // namespace patchwork
