// libFuzzer target: the free-form OBJ reader on arbitrary bytes. A document that parses must pass
// validate() record by record, give Bezier records knot vectors with as many control points, and
// come back from the writer equal bit for bit (the writer's text reads back to itself).

#include <bit>
#include <cstdint>
#include <string>

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
  });
  return 0;
}
