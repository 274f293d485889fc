// BezierPatch, RationalBezierPatch, NurbsSurface, PatchSet and files of patches in Python.
//
// Control nets are (n + 1, m + 1, 3) arrays with P_ij at [i, j] (i along u, j along v); weights
// are (n + 1, m + 1). patchwork stores P_ij at i + (n + 1) j, so a polynomial patch's net is a
// view with strides (24, 24 (n + 1), 8) bytes, not a copy.

#include <pybind11/operators.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <concepts>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "io/bpt.h"
#include "io/patch_file.h"
#include "python/bindings.h"
#include "python/arrays.h"
#include "surfaces/nurbs_shapes.h"
#include "surfaces/nurbs_surface.h"
#include "surfaces/surface_curvature.h"
#include "surfaces/surface_normal.h"

namespace patchwork::python {
namespace {

// The points of an (n + 1, m + 1, 3) array in patchwork's order (i + (n + 1) j), with n and m.
struct Net {
  int n;
  int m;
  std::vector<Vec3> points;
};

Net net_from(const DoubleArray& array) {
  require_shape(array, "control_points", {-1, -1, 3}, "(n + 1, m + 1, 3)");
  Net net{static_cast<int>(array.shape(0)) - 1, static_cast<int>(array.shape(1)) - 1, {}};
  const auto rows = static_cast<std::size_t>(net.n + 1);
  const auto columns = static_cast<std::size_t>(net.m + 1);
  net.points.resize(rows * columns);
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < columns; ++j) {
      const double* p = array.data() + 3 * (i * columns + j);
      net.points[i + rows * j] = Vec3(p[0], p[1], p[2]);
    }
  }
  return net;
}

// The weights of an (n + 1, m + 1) array in patchwork's order.
std::vector<double> weights_from(const DoubleArray& array, int n, int m) {
  require_shape(array, "weights", {n + 1, m + 1}, "(n + 1, m + 1), as control_points");
  std::vector<double> weights(static_cast<std::size_t>((n + 1) * (m + 1)));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= m; ++j) weights[static_cast<std::size_t>(i + (n + 1) * j)] = array.data()[i * (m + 1) + j];
  }
  return weights;
}

// An (n + 1, m + 1, 3) array of f(i, j) (a copy), and the (n + 1, m + 1) array of g(i, j).
template <class F>
py::array_t<double> grid_of_points(int rows, int columns, F&& f) {
  std::vector<double> flat;
  flat.reserve(static_cast<std::size_t>(rows * columns * 3));
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      const Vec3 p = f(i, j);
      flat.insert(flat.end(), p.data(), p.data() + 3);
    }
  }
  return owning(std::move(flat), {rows, columns, 3});
}
template <class G>
py::array_t<double> grid_of_values(int rows, int columns, G&& g) {
  std::vector<double> flat;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) flat.push_back(g(i, j));
  }
  return owning(std::move(flat), {rows, columns});
}

// The derivative d^(ku+kv) F / du^ku dv^kv of any surface kind.
// Orders up to this many (ku + kv): the derivatives' table grows as the order squared.
constexpr int max_derivative_order = 64;

template <class Surface>
Vec3 mixed_derivative(const Surface& surface, double u, double v, int ku, int kv) {
  return partial_derivatives(surface, u, v, ku + kv).at(ku, kv);
}

// \throws InvalidInput unless 0 <= ku, kv and ku + kv <= max_derivative_order.
void check_orders(int ku, int kv) {
  if (ku < 0 || kv < 0 || ku > max_derivative_order - kv) {
    throw InvalidInput(detail::message("derivative: ku and kv must be >= 0 with ku + kv <= ", max_derivative_order,
                                       ", got ", ku, " and ", kv));
  }
}

// What every surface kind shares: evaluation, derivatives, unit normals and curvature over
// parameter arrays.
template <class Surface>
void bind_surface_common(py::class_<Surface>& c) {
  const auto evaluate = [](const Surface& s, const DoubleArray& u, const DoubleArray& v) {
    return map_parameter_pairs<3>(u, v, [&](double a, double b) { return s.evaluate(a, b); });
  };
  c.def("evaluate", evaluate, py::arg("u"), py::arg("v"), "F(u, v) for parameters or arrays of them: shape u.shape + (3,).")
      .def("__call__", evaluate, py::arg("u"), py::arg("v"), "Same as evaluate(u, v).")
      .def(
          "derivative",
          [](const Surface& s, const DoubleArray& u, const DoubleArray& v, int ku, int kv) {
            check_orders(ku, kv);
            return map_parameter_pairs<3>(u, v, [&](double a, double b) { return mixed_derivative(s, a, b, ku, kv); });
          },
          py::arg("u"), py::arg("v"), py::arg("ku") = 1, py::arg("kv") = 0,
          "The partial derivative d^(ku+kv) F / du^ku dv^kv: shape u.shape + (3,).")
      .def(
          "normal",
          [](const Surface& s, const DoubleArray& u, const DoubleArray& v) {
            return map_parameter_pairs<3>(u, v, [&](double a, double b) { return unit_normal(s, a, b); });
          },
          py::arg("u"), py::arg("v"),
          "The exact unit normal (the limit normal where F_u x F_v vanishes, as at poles): shape u.shape + (3,).")
      .def(
          "curvature", [](const Surface& s, double u, double v) { return curvature(s, u, v); }, py::arg("u"),
          py::arg("v"), "Gaussian, mean and principal curvatures and directions at (u, v).");
  if constexpr (std::equality_comparable<Surface>) c.def(py::self == py::self);
}

}  // namespace

void bind_surfaces(py::module_& m) {
  // Registered before the functions that return it, so that their signatures name it.
  py::class_<PatchSet> patch_set(m, "PatchSet", "Bezier patches (polynomial and rational) and their adjacency.");
  py::class_<SurfaceCurvature>(m, "SurfaceCurvature", "Curvature of a surface at a point.")
      .def_readonly("defined", &SurfaceCurvature::defined, "False where F_u x F_v vanishes away from a pole.")
      .def_readonly("gaussian", &SurfaceCurvature::gaussian, "Gaussian curvature K = k1 k2.")
      .def_readonly("mean", &SurfaceCurvature::mean, "Mean curvature H = (k1 + k2) / 2.")
      .def_readonly("k1", &SurfaceCurvature::k1, "Larger principal curvature.")
      .def_readonly("k2", &SurfaceCurvature::k2, "Smaller principal curvature.")
      .def_property_readonly(
          "d1", [](const SurfaceCurvature& c) { return point_array<3>(c.d1); }, "Unit principal direction of k1.")
      .def_property_readonly(
          "d2", [](const SurfaceCurvature& c) { return point_array<3>(c.d2); }, "Unit principal direction of k2.")
      .def_property_readonly(
          "normal", [](const SurfaceCurvature& c) { return point_array<3>(c.normal); }, "The unit normal.")
      .def_readonly("umbilic", &SurfaceCurvature::umbilic, "k1 = k2 (any orthonormal directions).")
      .def_readonly("at_pole", &SurfaceCurvature::at_pole, "Computed at a pole from the curves through it.");

  py::class_<BezierPatch3> patch(m, "BezierPatch", "A polynomial tensor-product Bezier patch over [0, 1]^2.");
  patch
      .def(py::init([](const DoubleArray& points) {
             Net net = net_from(points);
             return BezierPatch3(net.n, net.m, std::move(net.points));
           }),
           py::arg("control_points"), "From an (n + 1, m + 1, 3) array of control points, P_ij at [i, j].")
      .def_property_readonly(
          "degree", [](const BezierPatch3& p) { return std::pair<int, int>(p.degree_u(), p.degree_v()); },
          "The degrees (n, m).")
      .def_property_readonly(
          "control_points",
          [](py::object self) {
            const auto& p = self.cast<const BezierPatch3&>();
            const py::ssize_t rows = p.degree_u() + 1;
            const py::ssize_t columns = p.degree_v() + 1;
            constexpr py::ssize_t point = sizeof(Vec3);
            return read_only(py::array_t<double>({rows, columns, py::ssize_t{3}}, {point, point * rows, py::ssize_t{8}},
                                                 p.control_points().front().data(), self));
          },
          "The control net, a read-only (n + 1, m + 1, 3) view (no copy), P_ij at [i, j].")
      .def(
          "split_u", [](const BezierPatch3& p, double u) { return split_u(p, u); }, py::arg("u"),
          "The two patches over [0, u] and [u, 1] in u, each reparametrised to [0, 1].")
      .def(
          "split_v", [](const BezierPatch3& p, double v) { return split_v(p, v); }, py::arg("v"),
          "The two patches over [0, v] and [v, 1] in v.")
      .def(
          "subpatch",
          [](const BezierPatch3& p, double u0, double u1, double v0, double v1) { return subpatch(p, u0, u1, v0, v1); },
          py::arg("u0"), py::arg("u1"), py::arg("v0"), py::arg("v1"),
          "The patch over [u0, u1] x [v0, v1], reparametrised to [0, 1]^2.")
      .def("__repr__", [](const BezierPatch3& p) {
        return detail::message("BezierPatch(degree (", p.degree_u(), ", ", p.degree_v(), "))");
      });
  bind_surface_common(patch);

  py::class_<RationalBezierPatch> rational(m, "RationalBezierPatch",
                                           "A rational tensor-product Bezier patch over [0, 1]^2 (positive weights).");
  rational
      .def(py::init([](const DoubleArray& points, const DoubleArray& weights) {
             const Net net = net_from(points);
             return RationalBezierPatch(net.n, net.m, net.points, weights_from(weights, net.n, net.m));
           }),
           py::arg("control_points"), py::arg("weights"),
           "From an (n + 1, m + 1, 3) array of control points and an (n + 1, m + 1) array of weights.")
      .def_property_readonly(
          "degree", [](const RationalBezierPatch& p) { return std::pair<int, int>(p.degree_u(), p.degree_v()); },
          "The degrees (n, m).")
      .def_property_readonly(
          "control_points",
          [](const RationalBezierPatch& p) {
            return grid_of_points(p.degree_u() + 1, p.degree_v() + 1, [&](int i, int j) { return p.control_point(i, j); });
          },
          "The control points, an (n + 1, m + 1, 3) array (a copy).")
      .def_property_readonly(
          "weights",
          [](const RationalBezierPatch& p) {
            return grid_of_values(p.degree_u() + 1, p.degree_v() + 1, [&](int i, int j) { return p.weight(i, j); });
          },
          "The weights, an (n + 1, m + 1) array (a copy).")
      .def(
          "split_u", [](const RationalBezierPatch& p, double u) { return split_u(p, u); }, py::arg("u"),
          "The two patches over [0, u] and [u, 1] in u.")
      .def(
          "split_v", [](const RationalBezierPatch& p, double v) { return split_v(p, v); }, py::arg("v"),
          "The two patches over [0, v] and [v, 1] in v.")
      .def_static(
          "sphere_octant", [](const DoubleArray& center, double radius) { return sphere_octant(point_from<3>(center, "center"), radius); },
          py::arg("center"), py::arg("radius"), "One eighth of a sphere, exactly (biquadratic).")
      .def("__repr__", [](const RationalBezierPatch& p) {
        return detail::message("RationalBezierPatch(degree (", p.degree_u(), ", ", p.degree_v(), "))");
      });
  bind_surface_common(rational);

  py::class_<NurbsSurface> nurbs(m, "NurbsSurface", "A B-spline or NURBS surface over its knot vectors' ranges.");
  nurbs
      .def(py::init([](int degree_u, int degree_v, const DoubleArray& knots_u, const DoubleArray& knots_v,
                       const DoubleArray& points, const std::optional<DoubleArray>& weights) {
             const Net net = net_from(points);
             return NurbsSurface(KnotVector(degree_u, values_from(knots_u, "knots_u")),
                                 KnotVector(degree_v, values_from(knots_v, "knots_v")), net.points,
                                 weights ? weights_from(*weights, net.n, net.m) : std::vector<double>{});
           }),
           py::arg("degree_u"), py::arg("degree_v"), py::arg("knots_u"), py::arg("knots_v"), py::arg("control_points"),
           py::arg("weights") = py::none(),
           "From degrees, knot vectors, a (count_u, count_v, 3) control net and, for NURBS, (count_u, count_v) weights.")
      .def_property_readonly(
          "degree", [](const NurbsSurface& s) { return std::pair<int, int>(s.degree_u(), s.degree_v()); },
          "The degrees (p, q).")
      .def_property_readonly("rational", &NurbsSurface::rational, "Whether the weights are not all equal.")
      .def_property_readonly(
          "control_points",
          [](const NurbsSurface& s) {
            return grid_of_points(s.count_u(), s.count_v(), [&](int i, int j) { return s.control_point(i, j); });
          },
          "The control points, a (count_u, count_v, 3) array (a copy).")
      .def_property_readonly(
          "weights",
          [](const NurbsSurface& s) {
            return grid_of_values(s.count_u(), s.count_v(), [&](int i, int j) { return s.weight(i, j); });
          },
          "The weights, a (count_u, count_v) array (a copy).")
      .def(
          "patch_set",
          [](const NurbsSurface& s, double relative_tolerance) {
            const NurbsBezierPatches pieces = bezier_patches(s);
            return PatchSet(pieces.patches, pieces.joins, relative_tolerance);
          },
          py::arg("relative_tolerance") = 1e-9,
          "Its Bezier patches (one a knot span pair) as a patch set, joined along the knot lines.")
      .def_static(
          "sphere", [](const DoubleArray& c, double r) { return nurbs_sphere(point_from<3>(c, "center"), r); },
          py::arg("center"), py::arg("radius"), "The exact sphere (rational biquadratic).")
      .def_static(
          "torus",
          [](const DoubleArray& c, double major, double minor) { return nurbs_torus(point_from<3>(c, "center"), major, minor); },
          py::arg("center"), py::arg("major"), py::arg("minor"), "The exact torus around the z axis.")
      .def_static(
          "cylinder",
          [](const DoubleArray& c, double r, double h) { return nurbs_cylinder(point_from<3>(c, "center"), r, h); },
          py::arg("center"), py::arg("radius"), py::arg("height"), "The exact cylinder along z.")
      .def("__repr__", [](const NurbsSurface& s) {
        return detail::message("NurbsSurface(degree (", s.degree_u(), ", ", s.degree_v(), "), ", s.count_u(), " x ",
                               s.count_v(), " control points)");
      });
  bind_surface_common(nurbs);

  patch_set
      .def(py::init([](const py::sequence& patches, double relative_tolerance) {
             std::vector<AnyBezierPatch> any;
             for (const py::handle p : patches) {
               if (py::isinstance<BezierPatch3>(p)) {
                 any.emplace_back(p.cast<const BezierPatch3&>());
               } else if (py::isinstance<RationalBezierPatch>(p)) {
                 any.emplace_back(p.cast<const RationalBezierPatch&>());
               } else {
                 throw InvalidInput(detail::message("patches: item ", any.size(),
                                                    " is not a BezierPatch or RationalBezierPatch"));
               }
             }
             py::gil_scoped_release release;
             return PatchSet(any, relative_tolerance);
           }),
           py::arg("patches"), py::arg("relative_tolerance") = 1e-9,
           "From a list of BezierPatch and RationalBezierPatch; edges are joined where their control points "
           "agree within relative_tolerance times the box diagonal.")
      .def("__len__", &PatchSet::count, "The number of patches.")
      .def(
          "__getitem__",
          [](const PatchSet& s, std::int64_t i) {
            const auto count = static_cast<std::int64_t>(s.count());
            if (i < 0) i += count;
            if (i < 0 || i >= count) throw py::index_error(detail::message("patch index out of range (", count, " patches)"));
            return s.patch(static_cast<std::uint32_t>(i));
          },
          py::arg("index"), "Patch `index`, a BezierPatch or a RationalBezierPatch.")
      .def_property_readonly("rational_count", &PatchSet::rational_count, "How many patches are rational.")
      .def_property_readonly("tolerance", &PatchSet::tolerance, "The absolute tolerance of the edge comparisons.")
      .def_property_readonly("size", &PatchSet::size, "The diagonal of the box of all control points.")
      .def(
          "bounding_box",
          [](const PatchSet& s, double tolerance) {
            const Eigen::AlignedBox3d box = bounding_box(s, tolerance);
            return std::pair(point_array<3>(box.min()), point_array<3>(box.max()));
          },
          py::arg("tolerance"), "The tight box (min, max) of the surface, each face within `tolerance` of it.")
      .def(
          "report",
          [](const PatchSet& s) { return py::module_::import("json").attr("loads")(to_json(report(s))); },
          "The patch-set report (shared, open and collapsed edges, loops, touching points, continuity, "
          "orientation) as a dict, the keys of `patchwork patches --json`.")
      .def("__repr__", [](const PatchSet& s) {
        return detail::message("PatchSet(", s.count(), " patches, ", s.rational_count(), " rational)");
      });

  m.def(
      "read_bpt", [](const std::filesystem::path& path) { return PatchSet(read_bpt(path)); }, py::arg("path"),
      py::call_guard<py::gil_scoped_release>(), "The patch set of a BPT file (IoError, ParseError naming the file).");
  m.def(
      "read_patches", [](const std::filesystem::path& path) { return read_patch_set(path); }, py::arg("path"),
      py::call_guard<py::gil_scoped_release>(),
      "The patch set of a .bpt file or of a free-form .obj file (its NURBS and Bezier surfaces, joined).");
  m.def(
      "write_bpt",
      [](const std::filesystem::path& path, const PatchSet& s) {
        const auto& patches = s.patches();
        py::gil_scoped_release release;
        write_bpt(path, patches);
      },
      py::arg("path"), py::arg("patch_set"),
      "Writes a set of polynomial patches as a BPT file, atomically (InvalidInput if one is rational).");
}

}  // namespace patchwork::python
