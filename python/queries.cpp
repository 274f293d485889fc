// Closest points, ray casting, curve-curve and curve-surface intersections, self-intersections and
// plane sections in Python (queries/, docs/queries.md): every answer with its certified bound.

#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "curves/bspline_conversion.h"
#include "python/bindings.h"
#include "python/curve_types.h"
#include "queries/closest_point.h"
#include "queries/curve_intersection.h"
#include "queries/curve_surface_intersection.h"
#include "queries/patch_bvh.h"
#include "queries/plane_section.h"
#include "queries/ray_cast.h"
#include "queries/self_intersection.h"
#include "queries/spline_intersection.h"

namespace patchwork::python {
namespace {

// A curve's closest point in either dimension (the point as an array).
struct CurveFoot {
  double distance;
  double lower_bound;
  py::array_t<double> point;
  double t;
  bool attained_more_than_once;
  std::int64_t pieces;
};

template <int Dim>
CurveFoot curve_foot(const CurveClosestPoint<Dim>& c) {
  return {c.distance, c.lower_bound, point_array<Dim>(c.point), c.t, c.attained_more_than_once, c.pieces};
}

// An intersection point of two curves in either dimension.
struct CurvePoint {
  double t;
  double s;
  py::array_t<double> point;
  double t_bound;
  double s_bound;
  double distance;
  bool tangential;
};

struct CurveCommon {
  std::vector<CurvePoint> points;
  std::vector<CurveOverlap> overlaps;
  double eps;
};

template <int Dim>
CurveCommon curve_common(const CurveIntersections<Dim>& x) {
  CurveCommon common{{}, x.overlaps, x.eps};
  for (const auto& p : x.points) {
    common.points.push_back({p.t, p.s, point_array<Dim>(p.point), p.t_bound, p.s_bound, p.distance, p.tangential});
  }
  return common;
}

ClosestPointOptions closest_options(double relative_gap, std::int64_t max_pieces) {
  ClosestPointOptions options;
  options.relative_gap = relative_gap;
  options.max_pieces = max_pieces;
  return options;
}

// Registers closest_point(target, point, ...) for a surface kind.
template <class Target>
void def_surface_closest(py::module_& m) {
  m.def(
      "closest_point",
      [](const Target& target, const DoubleArray& point, double relative_gap, std::int64_t max_pieces) {
        const Vec3 q = point_from<3>(point, "point");
        py::gil_scoped_release release;
        return closest_point(target, q, closest_options(relative_gap, max_pieces));
      },
      py::arg("target"), py::arg("point"), py::kw_only(), py::arg("relative_gap") = ClosestPointOptions{}.relative_gap,
      py::arg("max_pieces") = ClosestPointOptions{}.max_pieces,
      "The globally closest point of the surface, with a certified interval [lower_bound, distance].");
}

// Registers closest_point(curve, point, ...) for a curve kind.
template <class Any>
void def_curve_closest(py::module_& m) {
  m.def(
      "closest_point",
      [](const Any& curve, const DoubleArray& point, double relative_gap, std::int64_t max_pieces) {
        const ClosestPointOptions options = closest_options(relative_gap, max_pieces);
        return std::visit(
            [&](const auto& c) {
              constexpr int dim = dimension_of<std::decay_t<decltype(c)>>;
              const Point<dim> q = point_from<dim>(point, "point");
              CurveClosestPoint<dim> foot;
              {
                py::gil_scoped_release release;
                foot = closest_point(c, q, options);
              }
              return curve_foot(foot);
            },
            curve.curve);
      },
      py::arg("target"), py::arg("point"), py::kw_only(), py::arg("relative_gap") = ClosestPointOptions{}.relative_gap,
      py::arg("max_pieces") = ClosestPointOptions{}.max_pieces,
      "The globally closest point of the curve, with a certified interval [lower_bound, distance].");
}

// The tolerance of a 3D intersection, required there and refused in 2D (where the answer is exact
// to rounding). \throws InvalidInput naming it.
double tolerance_for(int dimension, const std::optional<double>& tolerance) {
  if (dimension == 3 && !tolerance) throw InvalidInput("tolerance: space curves meet within a tolerance; give one");
  if (dimension == 2 && tolerance) throw InvalidInput("tolerance: planar intersections take none (they are certified to rounding)");
  return tolerance.value_or(0.0);
}

// The intersections of two curves of one kind (Bezier, rational or NURBS).
template <class Any>
CurveCommon intersect_same_kind(const Any& first, const Any& second, const std::optional<double>& tolerance) {
  const double tol = tolerance_for(first.dimension(), tolerance);
  return visit_same_dimension(first, second, [&](const auto& a, const auto& b) {
    constexpr int dim = dimension_of<std::decay_t<decltype(a)>>;
    // The search without the GIL; its answer becomes Python objects with it.
    const CurveIntersections<dim> x = [&] {
      py::gil_scoped_release release;
      if constexpr (dim == 2) {
        return intersect_curves(a, b);
      } else {
        return intersect_curves(a, b, tol);
      }
    }();
    return curve_common(x);
  });
}

template <class Any>
CurveCommon self_intersect(const Any& curve, const std::optional<double>& tolerance) {
  const double tol = tolerance_for(curve.dimension(), tolerance);
  return std::visit(
      [&](const auto& c) {
        constexpr int dim = dimension_of<std::decay_t<decltype(c)>>;
        const CurveIntersections<dim> x = [&] {
          py::gil_scoped_release release;
          if constexpr (dim == 2) {
            return self_intersections(c);
          } else {
            return self_intersections(c, tol);
          }
        }();
        return curve_common(x);
      },
      curve.curve);
}

// A 3D curve of any kind as the rational Bezier pieces the curve-surface search takes.
template <class Any>
std::vector<RationalBezierCurve3> space_pieces(const Any& curve) {
  if (curve.dimension() != 3) throw InvalidInput("curve: intersecting with a surface needs a space curve (n, 3)");
  const auto& c = std::get<1>(curve.curve);
  using Curve = std::decay_t<decltype(c)>;
  if constexpr (std::is_same_v<Curve, BezierCurve3>) {
    return {as_rational(c)};
  } else if constexpr (std::is_same_v<Curve, RationalBezierCurve3>) {
    return {c};
  } else {
    return bezier_pieces(c);
  }
}

// Registers intersect_curve_surface(curve, patch_set) for a curve kind.
template <class Any>
void def_curve_surface(py::module_& m) {
  m.def(
      "intersect_curve_surface",
      [](const Any& curve, const PatchSet& set) {
        const std::vector<RationalBezierCurve3> pieces = space_pieces(curve);
        py::gil_scoped_release release;
        return detail::intersect_pieces_with_set(pieces, set);
      },
      py::arg("curve"), py::arg("patch_set"),
      "Every point where a space curve meets the patch set, certified (tangential contacts flagged). For a "
      "NURBS curve, t is the parameter of its Bezier piece's span.");
}

}  // namespace

void bind_queries(py::module_& m) {
  py::class_<SurfaceClosestPoint>(m, "SurfaceClosestPoint", "The closest point of a surface, certified.")
      .def_readonly("distance", &SurfaceClosestPoint::distance, "|F(u, v) - q| at the foot (the interval's upper end).")
      .def_readonly("lower_bound", &SurfaceClosestPoint::lower_bound, "No point of the surface is nearer.")
      .def_property_readonly(
          "point", [](const SurfaceClosestPoint& c) { return point_array<3>(c.point); }, "The foot point F(u, v).")
      .def_readonly("patch", &SurfaceClosestPoint::patch, "The foot's patch.")
      .def_readonly("u", &SurfaceClosestPoint::u, "The foot's u.")
      .def_readonly("v", &SurfaceClosestPoint::v, "The foot's v.")
      .def_readonly("attained_more_than_once", &SurfaceClosestPoint::attained_more_than_once,
                    "Another foot, apart from this one, is as near within the interval.")
      .def_readonly("pieces", &SurfaceClosestPoint::pieces, "Pieces examined.")
      .def("__repr__", [](const SurfaceClosestPoint& c) {
        return detail::message("SurfaceClosestPoint(distance=", c.distance, ", patch=", c.patch, ", u=", c.u, ", v=", c.v, ")");
      });
  py::class_<CurveFoot>(m, "CurveClosestPoint", "The closest point of a curve, certified.")
      .def_readonly("distance", &CurveFoot::distance, "|C(t) - q| at the foot (the interval's upper end).")
      .def_readonly("lower_bound", &CurveFoot::lower_bound, "No point of the curve is nearer.")
      .def_property_readonly(
          "point", [](const CurveFoot& c) { return py::array_t<double>(c.point.attr("copy")()); }, "The foot point C(t).")
      .def_readonly("t", &CurveFoot::t, "The foot's parameter.")
      .def_readonly("attained_more_than_once", &CurveFoot::attained_more_than_once,
                    "Another foot, apart from this one, is as near within the interval.")
      .def_readonly("pieces", &CurveFoot::pieces, "Pieces examined.");

  py::class_<PatchBvh>(m, "PatchBvh", "A bounding-volume hierarchy over a patch set's pieces, for many queries.")
      .def(py::init([](const PatchSet& set, int pieces_per_side) {
             py::gil_scoped_release release;
             return PatchBvh(set, pieces_per_side);
           }),
           py::arg("patch_set"), py::arg("pieces_per_side") = 0, py::keep_alive<1, 2>(),
           "The hierarchy of `patch_set` (kept alive as long as this object); pieces_per_side 0 picks by size.");

  def_surface_closest<PatchBvh>(m);
  def_surface_closest<PatchSet>(m);
  def_surface_closest<BezierPatch3>(m);
  def_surface_closest<RationalBezierPatch>(m);
  def_curve_closest<AnyBezierCurve>(m);
  def_curve_closest<AnyRationalCurve>(m);
  def_curve_closest<AnyNurbsCurve>(m);

  m.def(
      "closest_points",
      [](const PatchBvh& bvh, const DoubleArray& points, double relative_gap, std::int64_t max_pieces) {
        const std::vector<Vec3> queries = points_from<3>(points, "points");
        const ClosestPointOptions options = closest_options(relative_gap, max_pieces);
        const std::size_t n = queries.size();
        std::vector<double> distance(n), lower(n), u(n), v(n), foot(3 * n);
        std::vector<std::uint32_t> patch(n);
        std::vector<std::uint8_t> twice(n);
        {
          py::gil_scoped_release release;
          for (std::size_t k = 0; k < n; ++k) {
            const SurfaceClosestPoint c = closest_point(bvh, queries[k], options);
            distance[k] = c.distance;
            lower[k] = c.lower_bound;
            u[k] = c.u;
            v[k] = c.v;
            patch[k] = c.patch;
            twice[k] = c.attained_more_than_once ? 1 : 0;
            std::copy_n(c.point.data(), 3, foot.data() + 3 * k);
          }
        }
        const py::ssize_t count = static_cast<py::ssize_t>(n);
        py::dict result;
        result["distance"] = owning(std::move(distance), {count});
        result["lower_bound"] = owning(std::move(lower), {count});
        result["point"] = owning(std::move(foot), {count, 3});
        result["patch"] = owning(std::move(patch), {count});
        result["u"] = owning(std::move(u), {count});
        result["v"] = owning(std::move(v), {count});
        result["attained_more_than_once"] =
            owning(std::move(twice), {count}).attr("astype")(py::module_::import("numpy").attr("bool_"));
        return result;
      },
      py::arg("bvh"), py::arg("points"), py::kw_only(), py::arg("relative_gap") = ClosestPointOptions{}.relative_gap,
      py::arg("max_pieces") = ClosestPointOptions{}.max_pieces,
      "closest_point for every row of an (n, 3) array, without the GIL: a dict of arrays distance, "
      "lower_bound, point (n, 3), patch, u, v, attained_more_than_once.");

  py::class_<RayHit>(m, "RayHit", "Where a ray meets a patch set.")
      .def_readonly("t", &RayHit::t, "The ray parameter: origin + t direction.")
      .def_readonly("patch", &RayHit::patch, "The patch hit.")
      .def_readonly("u", &RayHit::u, "The hit's u.")
      .def_readonly("v", &RayHit::v, "The hit's v.")
      .def_property_readonly("point", [](const RayHit& h) { return point_array<3>(h.point); }, "F(u, v).")
      .def_property_readonly(
          "normal", [](const RayHit& h) { return point_array<3>(h.normal); }, "The exact unit normal at the hit.")
      .def_readonly("grazing", &RayHit::grazing, "The ray touches the surface there (tangent) rather than crossing.")
      .def("__repr__", [](const RayHit& h) {
        return detail::message("RayHit(t=", h.t, ", patch=", h.patch, ", u=", h.u, ", v=", h.v, ")");
      });
  const auto ray = [](const auto& target, const DoubleArray& origin, const DoubleArray& direction, double t_min,
                      double t_max) {
    const Vec3 o = point_from<3>(origin, "origin");
    const Vec3 d = point_from<3>(direction, "direction");
    py::gil_scoped_release release;
    return ray_cast(target, o, d, RayOptions{t_min, t_max}).hits;
  };
  constexpr double infinity = std::numeric_limits<double>::infinity();
  m.def(
      "ray_cast",
      [ray](const PatchBvh& bvh, const DoubleArray& o, const DoubleArray& d, double t_min, double t_max) {
        return ray(bvh, o, d, t_min, t_max);
      },
      py::arg("target"), py::arg("origin"), py::arg("direction"), py::kw_only(), py::arg("t_min") = 0.0,
      py::arg("t_max") = infinity, "Every hit of the ray in [t_min, t_max], in order of t, none missed or doubled.");
  m.def(
      "ray_cast",
      [ray](const PatchSet& set, const DoubleArray& o, const DoubleArray& d, double t_min, double t_max) {
        return ray(set, o, d, t_min, t_max);
      },
      py::arg("target"), py::arg("origin"), py::arg("direction"), py::kw_only(), py::arg("t_min") = 0.0,
      py::arg("t_max") = infinity, "As above, building the hierarchy for this one ray.");

  py::class_<CurvePoint>(m, "CurveIntersection", "An isolated point two curves share.")
      .def_readonly("t", &CurvePoint::t, "The first curve's parameter.")
      .def_readonly("s", &CurvePoint::s, "The second curve's parameter.")
      .def_property_readonly(
          "point", [](const CurvePoint& c) { return py::array_t<double>(c.point.attr("copy")()); }, "The point.")
      .def_readonly("t_bound", &CurvePoint::t_bound, "The true t is within t_bound of t.")
      .def_readonly("s_bound", &CurvePoint::s_bound, "The true s is within s_bound of s.")
      .def_readonly("distance", &CurvePoint::distance, "|first(t) - second(s)|.")
      .def_readonly("tangential", &CurvePoint::tangential, "The curves touch rather than cross.");
  py::class_<CurveOverlap>(m, "CurveOverlap", "A parameter interval on which two curves coincide.")
      .def_readonly("t0", &CurveOverlap::t0, "Start on the first curve.")
      .def_readonly("t1", &CurveOverlap::t1, "End on the first curve.")
      .def_readonly("s0", &CurveOverlap::s0, "The second curve's parameter matching t0.")
      .def_readonly("s1", &CurveOverlap::s1, "The second curve's parameter matching t1.");
  py::class_<CurveCommon>(m, "CurveIntersections", "Everything two curves (or a curve with itself) have in common.")
      .def_readonly("points", &CurveCommon::points, "Isolated points, ordered by t.")
      .def_readonly("overlaps", &CurveCommon::overlaps, "Overlap intervals, ordered by t0.")
      .def_readonly("eps", &CurveCommon::eps, "The rounding level used.");

  const char* intersect_doc =
      "The intersections of two curves of one kind and dimension; planar ones certified to rounding (no "
      "tolerance), space curves within `tolerance`.";
  m.def("intersect_curves", &intersect_same_kind<AnyBezierCurve>, py::arg("first"), py::arg("second"),
        py::arg("tolerance") = py::none(), intersect_doc);
  m.def("intersect_curves", &intersect_same_kind<AnyRationalCurve>, py::arg("first"), py::arg("second"),
        py::arg("tolerance") = py::none(), intersect_doc);
  m.def("intersect_curves", &intersect_same_kind<AnyNurbsCurve>, py::arg("first"), py::arg("second"),
        py::arg("tolerance") = py::none(), intersect_doc);
  const char* self_doc = "Where a curve crosses or touches itself (t < s), and where it retraces itself.";
  m.def("self_intersections", &self_intersect<AnyBezierCurve>, py::arg("curve"), py::arg("tolerance") = py::none(), self_doc);
  m.def("self_intersections", &self_intersect<AnyRationalCurve>, py::arg("curve"), py::arg("tolerance") = py::none(), self_doc);
  m.def("self_intersections", &self_intersect<AnyNurbsCurve>, py::arg("curve"), py::arg("tolerance") = py::none(), self_doc);

  py::class_<CurveSurfaceHit>(m, "CurveSurfaceHit", "Where a curve meets a surface.")
      .def_readonly("t", &CurveSurfaceHit::t, "The curve's parameter.")
      .def_readonly("patch", &CurveSurfaceHit::patch, "The patch.")
      .def_readonly("u", &CurveSurfaceHit::u, "The patch's u.")
      .def_readonly("v", &CurveSurfaceHit::v, "The patch's v.")
      .def_property_readonly("point", [](const CurveSurfaceHit& h) { return point_array<3>(h.point); }, "The point.")
      .def_readonly("distance", &CurveSurfaceHit::distance, "|C(t) - F(u, v)|.")
      .def_readonly("tangential", &CurveSurfaceHit::tangential, "The curve touches the surface rather than crossing.");
  py::class_<CurveSurfaceHits>(m, "CurveSurfaceHits", "Every point a curve shares with a surface.")
      .def_readonly("hits", &CurveSurfaceHits::hits, "The hits, ordered by t.")
      .def_readonly("eps", &CurveSurfaceHits::eps, "The rounding level used.");
  def_curve_surface<AnyBezierCurve>(m);
  def_curve_surface<AnyRationalCurve>(m);
  def_curve_surface<AnyNurbsCurve>(m);

  py::class_<SectionPolyline>(m, "SectionPolyline", "One polyline of a plane section.")
      .def_property_readonly(
          "points",
          [](const SectionPolyline& p) {
            std::vector<double> flat;
            for (const SectionVertex& x : p.vertices) flat.insert(flat.end(), x.point.data(), x.point.data() + 3);
            const py::ssize_t n = static_cast<py::ssize_t>(p.vertices.size());
            return owning(std::move(flat), {n, 3});
          },
          "The vertices, an (n, 3) array.")
      .def_property_readonly(
          "patches",
          [](const SectionPolyline& p) {
            std::vector<std::uint32_t> patches;
            for (const SectionVertex& x : p.vertices) patches.push_back(x.patch);
            const py::ssize_t n = static_cast<py::ssize_t>(patches.size());
            return owning(std::move(patches), {n});
          },
          "Each vertex's patch, an (n,) uint32 array.")
      .def_readonly("closed", &SectionPolyline::closed, "The polyline is a loop (its last vertex joins its first).");
  py::class_<PlaneSection>(m, "PlaneSection", "The section of a patch set by a plane, as polylines within a bound.")
      .def_readonly("polylines", &PlaneSection::polylines, "The polylines.")
      .def_readonly("patches_in_plane", &PlaneSection::patches_in_plane, "Patches lying in the plane.")
      .def_readonly("error_bound", &PlaneSection::error_bound, "Every polyline point is within this of the section.")
      .def_readonly("uncertified_pieces", &PlaneSection::uncertified_pieces, "Pieces whose bound could not be certified.");
  m.def(
      "plane_section",
      [](const PatchSet& set, const DoubleArray& point, const DoubleArray& normal, double tolerance) {
        const Vec3 p = point_from<3>(point, "point");
        const Vec3 n = point_from<3>(normal, "normal");
        py::gil_scoped_release release;
        return plane_section(set, p, n, tolerance);
      },
      py::arg("patch_set"), py::arg("point"), py::arg("normal"), py::arg("tolerance"),
      "The polylines where the plane through `point` with `normal` cuts the set, within `tolerance`.");
}

}  // namespace patchwork::python
