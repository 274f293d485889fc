// libFuzzer target: the free-form OBJ reader on arbitrary bytes. A document that parses must pass
// validate() record by record, give Bezier records knot vectors with as many control points, and
// come back from the writer equal bit for bit (the writer's text reads back to itself); its
// surfaces become a patch set (io/freeform_surfaces.h: knot insertion for the ranges, Bezier
// extraction, the known joins), one patch per span of each range, every corner the surface's
// point there.

#include <bit>
#include <cstdint>
#include <string>

#include "io/freeform_surfaces.h"
#include "io/obj_freeform.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

namespace {

bool same_bits(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) return false;
  }
  return true;
}

// The knot vector of a direction has the control points its basis implies.
bool knots_agree(FreeformBasis basis, int degree, const std::vector<double>& parameters) {
  return control_point_count(FreeformBasis::bspline, degree, bspline_knots(basis, degree, parameters)) ==
         control_point_count(basis, degree, parameters);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_documented_errors_only([&] {
    const FreeformDocument document = parse_obj_freeform(fuzz::as_text(data, size), "fuzz.obj");
    for (const FreeformSurface& surface : document.surfaces) {
      validate(surface);
      PATCHWORK_FUZZ_CHECK(knots_agree(surface.basis, surface.degree_u, surface.parameters_u));
      PATCHWORK_FUZZ_CHECK(knots_agree(surface.basis, surface.degree_v, surface.parameters_v));
      const auto [count_u, count_v] = control_point_counts(surface);
      PATCHWORK_FUZZ_CHECK(count_u * count_v == static_cast<std::int64_t>(surface.points.size()));
    }
    for (const FreeformCurve& curve : document.curves) {
      validate(curve);
      PATCHWORK_FUZZ_CHECK(knots_agree(curve.basis, curve.degree, curve.parameters));
    }
    const std::string text = format_obj_freeform(document);
    const FreeformDocument back = parse_obj_freeform(text, "back.obj");
    PATCHWORK_FUZZ_CHECK(format_obj_freeform(back) == text);
    PATCHWORK_FUZZ_CHECK(back.surfaces.size() == document.surfaces.size());
    PATCHWORK_FUZZ_CHECK(back.curves.size() == document.curves.size());
    for (std::size_t k = 0; k < back.surfaces.size(); ++k) {
      const FreeformSurface& a = document.surfaces[k];
      const FreeformSurface& b = back.surfaces[k];
      PATCHWORK_FUZZ_CHECK(a.name == b.name && same_bits(a.parameters_u, b.parameters_u) &&
                           same_bits(a.parameters_v, b.parameters_v) && same_bits(a.weights, b.weights) &&
                           a.points == b.points);
    }
    for (std::size_t k = 0; k < back.curves.size(); ++k) {
      const FreeformCurve& a = document.curves[k];
      const FreeformCurve& b = back.curves[k];
      PATCHWORK_FUZZ_CHECK(a.name == b.name && same_bits(a.parameters, b.parameters) &&
                           same_bits(a.weights, b.weights) && a.points == b.points);
    }
    if (document.surfaces.empty()) return;
    std::size_t spans = 0;
    for (const FreeformSurface& surface : document.surfaces) {
      const NurbsSurface nurbs = nurbs_surface(surface);
      const NurbsBezierPatches pieces = freeform_bezier_patches(surface);
      PATCHWORK_FUZZ_CHECK(pieces.patches.size() == static_cast<std::size_t>(pieces.spans_u * pieces.spans_v));
      PATCHWORK_FUZZ_CHECK(pieces.breaks_u.front() == surface.u0 && pieces.breaks_u.back() == surface.u1);
      PATCHWORK_FUZZ_CHECK(pieces.breaks_v.front() == surface.v0 && pieces.breaks_v.back() == surface.v1);
      // The first patch's corner (0, 0) is the surface at (u0, v0), to rounding of the net's size.
      const AnyBezierPatch& first = pieces.patches.front();
      const Vec3 corner = std::holds_alternative<BezierPatch3>(first) ? std::get<BezierPatch3>(first).evaluate(0, 0)
                                                                      : std::get<RationalBezierPatch>(first).evaluate(0, 0);
      const Vec3 exact = nurbs.evaluate(surface.u0, surface.v0);
      double scale = 1.0;
      for (const Vec3& p : surface.points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
      if (corner.allFinite() && exact.allFinite()) PATCHWORK_FUZZ_CHECK((corner - exact).norm() <= 1e-6 * scale);
      spans += pieces.patches.size();
    }
    PATCHWORK_FUZZ_CHECK(freeform_patch_set(document).count() == spans);
  });
  return 0;
}
