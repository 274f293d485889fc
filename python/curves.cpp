// BezierCurve, RationalBezierCurve, NurbsCurve and continuity checks in Python.

#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "curves/bspline_conversion.h"
#include "curves/continuity.h"
#include "curves/knot_insertion.h"
#include "curves/subdivision.h"
#include "python/bindings.h"
#include "python/curve_types.h"

namespace patchwork::python {
namespace {

// The control points of any curve kind as an (n, Dim) array (a copy: rational curves store
// homogeneous points, so there is no array of them to view).
template <class Curve>
py::array_t<double> control_points_of(const Curve& curve) {
  constexpr int dim = dimension_of<Curve>;
  std::vector<double> flat;
  if constexpr (requires { curve.control_points(); }) {
    for (const auto& p : curve.control_points()) flat.insert(flat.end(), p.data(), p.data() + dim);
  } else {
    const int count = static_cast<int>(curve.homogeneous().control_points().size());
    for (int i = 0; i < count; ++i) {
      const auto p = curve.control_point(i);
      flat.insert(flat.end(), p.data(), p.data() + dim);
    }
  }
  const py::ssize_t rows = static_cast<py::ssize_t>(flat.size() / dim);
  return owning(std::move(flat), {rows, dim});
}

// The weights of a rational curve.
template <class Curve>
py::array_t<double> weights_of(const Curve& curve) {
  std::vector<double> weights;
  const int count = static_cast<int>(curve.homogeneous().control_points().size());
  for (int i = 0; i < count; ++i) weights.push_back(curve.weight(i));
  const py::ssize_t n = static_cast<py::ssize_t>(weights.size());
  return owning(std::move(weights), {n});
}

// What every kind shares: dimension, degree, interval, control points, evaluation and
// derivatives over parameter arrays, equality.
template <class Any>
void bind_common(py::class_<Any>& c, const char* name) {
  const auto evaluate = [](const Any& a, const DoubleArray& t) {
    return std::visit(
        [&](const auto& k) {
          constexpr int dim = dimension_of<std::decay_t<decltype(k)>>;
          return map_parameters<dim>(t, [&](double s) { return k.evaluate(s); });
        },
        a.curve);
  };
  c.def_property_readonly("dimension", &Any::dimension, "2 for a planar curve, 3 for a space curve.")
      .def_property_readonly(
          "degree", [](const Any& a) { return std::visit([](const auto& k) { return k.degree(); }, a.curve); },
          "The polynomial degree.")
      .def_property_readonly(
          "interval",
          [](const Any& a) {
            return std::visit([](const auto& k) { return std::pair<double, double>(k.a(), k.b()); }, a.curve);
          },
          "The parameter interval (a, b).")
      .def_property_readonly(
          "control_points",
          [](const Any& a) { return std::visit([](const auto& k) { return control_points_of(k); }, a.curve); },
          "The control points, an (n + 1, dimension) array (a copy).")
      .def("evaluate", evaluate, py::arg("t"), "C(t) for a parameter or an array of them: shape t.shape + (dimension,).")
      .def("__call__", evaluate, py::arg("t"), "Same as evaluate(t).")
      .def(
          "derivative",
          [](const Any& a, const DoubleArray& t, int order) {
            return std::visit(
                [&](const auto& k) {
                  constexpr int dim = dimension_of<std::decay_t<decltype(k)>>;
                  return map_parameters<dim>(t, [&](double s) { return derivative(k, s, order); });
                },
                a.curve);
          },
          py::arg("t"), py::arg("order") = 1,
          "The order-th derivative C^(order)(t) for a parameter or an array: shape t.shape + (dimension,).")
      .def(py::self == py::self)
      .def("__repr__", [name](const Any& a) {
        return std::visit(
            [&](const auto& k) {
              return detail::message(name, "(degree ",
                                     k.degree(), ", dimension ", a.dimension(), ", interval [", k.a(), ", ", k.b(),
                                     "])");
            },
            a.curve);
      });
}

}  // namespace

void bind_curves(py::module_& m) {
  py::class_<AnyBezierCurve> bezier(m, "BezierCurve", "A polynomial Bezier curve in 2D or 3D on [a, b].");
  bezier.def(py::init([](const DoubleArray& points, double a, double b) {
               return make_curve<BezierCurve>(points, [&](auto p) {
                 return BezierCurve<point_dimension<typename decltype(p)::value_type>>(std::move(p), a, b);
               });
             }),
             py::arg("control_points"), py::arg("a") = 0.0, py::arg("b") = 1.0,
             "From control points, an (n + 1, 2) or (n + 1, 3) array, on [a, b].");
  bind_common(bezier, "BezierCurve");
  bezier
      .def(
          "split",
          [](const AnyBezierCurve& c, double t) {
            return std::visit(
                [&](const auto& k) {
                  auto [left, right] = split(k, t);
                  return std::pair<AnyBezierCurve, AnyBezierCurve>({std::move(left)}, {std::move(right)});
                },
                c.curve);
          },
          py::arg("t"), "The two curves on [a, t] and [t, b] (de Casteljau).")
      .def(
          "subcurve",
          [](const AnyBezierCurve& c, double t0, double t1) {
            return std::visit([&](const auto& k) { return AnyBezierCurve{subcurve(k, t0, t1)}; }, c.curve);
          },
          py::arg("t0"), py::arg("t1"), "The same curve restricted to [t0, t1], as a curve on [t0, t1].");

  py::class_<AnyRationalCurve> rational(m, "RationalBezierCurve",
                                        "A rational Bezier curve in 2D or 3D on [a, b] (positive weights).");
  rational.def(py::init([](const DoubleArray& points, const DoubleArray& weights, double a, double b) {
                 std::vector<double> w = values_from(weights, "weights");
                 return make_curve<RationalBezierCurve>(points, [&](auto p) {
                   return RationalBezierCurve<point_dimension<typename decltype(p)::value_type>>(std::move(p),
                                                                                              std::move(w), a, b);
                 });
               }),
               py::arg("control_points"), py::arg("weights"), py::arg("a") = 0.0, py::arg("b") = 1.0,
               "From control points ((n + 1, 2) or (n + 1, 3)) and n + 1 positive weights, on [a, b].");
  bind_common(rational, "RationalBezierCurve");
  rational
      .def_property_readonly(
          "weights", [](const AnyRationalCurve& c) { return std::visit([](const auto& k) { return weights_of(k); }, c.curve); },
          "The weights, an (n + 1,) array.")
      .def(
          "split",
          [](const AnyRationalCurve& c, double t) {
            return std::visit(
                [&](const auto& k) {
                  auto [left, right] = split(k, t);
                  return std::pair<AnyRationalCurve, AnyRationalCurve>({std::move(left)}, {std::move(right)});
                },
                c.curve);
          },
          py::arg("t"), "The two curves on [a, t] and [t, b] (de Casteljau on the homogeneous points).");

  py::class_<AnyNurbsCurve> nurbs(m, "NurbsCurve",
                                  "A B-spline or NURBS curve in 2D or 3D on the knot vector's valid range.");
  nurbs.def(py::init([](int degree, const DoubleArray& knots, const DoubleArray& points,
                        const std::optional<DoubleArray>& weights) {
              KnotVector knot_vector(degree, values_from(knots, "knots"));
              std::vector<double> w = weights ? values_from(*weights, "weights")
                                              : std::vector<double>(static_cast<std::size_t>(points.ndim() == 2 ? points.shape(0) : 0), 1.0);
              return make_curve<NurbsCurve>(points, [&](auto p) {
                return NurbsCurve<point_dimension<typename decltype(p)::value_type>>(knot_vector, std::move(p), std::move(w));
              });
            }),
            py::arg("degree"), py::arg("knots"), py::arg("control_points"), py::arg("weights") = py::none(),
            "From the degree p, the knots (n + p + 2 non-decreasing values), n + 1 control points "
            "((n + 1, 2) or (n + 1, 3)) and, for a NURBS curve, n + 1 positive weights (default: all 1).");
  bind_common(nurbs, "NurbsCurve");
  nurbs
      .def_property_readonly(
          "knots",
          [](const AnyNurbsCurve& c) {
            return std::visit(
                [](const auto& k) {
                  std::vector<double> knots = k.knot_vector().knots();
                  const py::ssize_t n = static_cast<py::ssize_t>(knots.size());
                  return owning(std::move(knots), {n});
                },
                c.curve);
          },
          "The knot vector (a copy).")
      .def_property_readonly(
          "weights", [](const AnyNurbsCurve& c) { return std::visit([](const auto& k) { return weights_of(k); }, c.curve); },
          "The weights (all 1 for a B-spline curve).")
      .def(
          "insert_knot",
          [](const AnyNurbsCurve& c, double u, int times) {
            return std::visit([&](const auto& k) { return AnyNurbsCurve{insert_knot(k, u, times)}; }, c.curve);
          },
          py::arg("u"), py::arg("times") = 1, "The same curve with the knot u inserted `times` more times (Boehm).")
      .def(
          "bezier_pieces",
          [](const AnyNurbsCurve& c) {
            return std::visit(
                [](const auto& k) {
                  std::vector<AnyRationalCurve> pieces;
                  for (auto& piece : bezier_pieces(k)) pieces.push_back({std::move(piece)});
                  return pieces;
                },
                c.curve);
          },
          "The rational Bezier curve of every knot span, in order (each on its span).");

  py::class_<Continuity>(m, "Continuity", "How two curves join.")
      .def_readonly("ck", &Continuity::ck, "The highest k <= max_order with a C^k join; -1 if the ends do not meet.")
      .def_readonly("g1", &Continuity::g1, "C^0 and equal unit tangent directions.")
      .def_readonly("gap", &Continuity::gap, "|first(b) - second(a)|.")
      .def("__repr__", [](const Continuity& c) {
        return detail::message("Continuity(ck=", c.ck, ", g1=", c.g1 ? "True" : "False", ", gap=", c.gap, ")");
      });
  m.def(
      "continuity",
      [](const AnyBezierCurve& first, const AnyBezierCurve& second, int max_order, double relative_tolerance) {
        return visit_same_dimension(first, second, [&](const auto& a, const auto& b) {
          return continuity(a, b, max_order, relative_tolerance);
        });
      },
      py::arg("first"), py::arg("second"), py::arg("max_order") = 2, py::arg("relative_tolerance") = 1e-10,
      "How `first` (at its end) joins `second` (at its start), up to C^max_order.");
}

}  // namespace patchwork::python
