#pragma once
// numpy in and out, as docs/python.md pins it:
//   - inputs of any dtype and memory order are converted once to C-ordered float64 (forcecast);
//     a wrong shape is an InvalidInput (a ValueError in Python) naming the argument and the shape
//     it must have;
//   - outputs that a result object owns (a tessellation's arrays, a mesh's positions) are views
//     without a copy, whose `base` is that object, so the arrays keep it alive;
//   - outputs computed for the call (evaluated points) are written into a vector that is then
//     moved into a capsule: the array owns it, nothing is copied;
//   - evaluation over parameter arrays runs without the GIL.

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/errors.h"
#include "core/types.h"

namespace patchwork::python {

namespace py = pybind11;

/// float64 in C order, converted once from whatever the caller passed.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
/// uint32 in C order.
using IndexArray = py::array_t<std::uint32_t, py::array::c_style>;

/// "(n, 3)" and the like, for messages.
inline std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k) {
    if (k > 0) text += ", ";
    text += std::to_string(array.shape(k));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

/// Checks that `array` has `ndim` dimensions and, where `shape` gives one >= 0, that extent.
/// \throws InvalidInput naming `name`, the shape wanted (`wanted`, e.g. "(n, 3)") and the shape given.
inline void require_shape(const py::array& array, const char* name, std::initializer_list<py::ssize_t> shape,
                          const char* wanted) {
  bool ok = array.ndim() == static_cast<py::ssize_t>(shape.size());
  py::ssize_t k = 0;
  for (const py::ssize_t extent : shape) {
    if (ok && extent >= 0 && array.shape(k) != extent) ok = false;
    ++k;
  }
  if (!ok) throw InvalidInput(detail::message(name, ": expected an array of shape ", wanted, ", got ", shape_text(array)));
}

/// The rows of an (n, Dim) array as points. \throws InvalidInput naming `name` for another shape.
template <int Dim>
std::vector<Point<Dim>> points_from(const DoubleArray& array, const char* name) {
  require_shape(array, name, {-1, Dim}, Dim == 2 ? "(n, 2)" : Dim == 3 ? "(n, 3)" : "(n, 4)");
  std::vector<Point<Dim>> points(static_cast<std::size_t>(array.shape(0)));
  const double* data = array.data();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int d = 0; d < Dim; ++d) points[i][d] = data[i * Dim + static_cast<std::size_t>(d)];
  }
  return points;
}

/// A 1-D array's values. \throws InvalidInput naming `name` for another shape.
inline std::vector<double> values_from(const DoubleArray& array, const char* name) {
  require_shape(array, name, {-1}, "(n,)");
  return {array.data(), array.data() + array.shape(0)};
}

/// One point from a sequence of Dim numbers. \throws InvalidInput naming `name` otherwise.
template <int Dim>
Point<Dim> point_from(const DoubleArray& array, const char* name) {
  require_shape(array, name, {Dim}, Dim == 2 ? "(2,)" : "(3,)");
  return Eigen::Map<const Point<Dim>>(array.data());
}

/// Indices from any integer array or sequence (not floats, which would be truncated), each in
/// [0, 2^32): converted once to C-ordered uint32.
/// \throws InvalidInput naming `name` for another dtype or a value out of range (never wrapped).
inline IndexArray indices_from(const py::handle& object, const char* name) {
  const py::array array = py::module_::import("numpy").attr("asarray")(object);
  const char kind = array.dtype().kind();
  if (array.size() > 0 && kind != 'i' && kind != 'u') {
    throw InvalidInput(detail::message(name, ": expected integer indices, got an array of dtype ",
                                       py::str(array.dtype()).cast<std::string>()));
  }
  if (array.size() > 0) {
    // Compared as Python integers: exact for every integer dtype.
    const py::int_ low = array.attr("min")();
    const py::int_ high = array.attr("max")();
    if (low < py::int_(0) || high > py::int_(0xffffffffu)) {
      const py::int_ bad = low < py::int_(0) ? low : high;
      throw InvalidInput(detail::message(name, ": index ", std::string(py::str(py::handle(bad))), " is not in [0, 2^32)"));
    }
  }
  return IndexArray(array.attr("astype")("uint32", py::arg("order") = "C"));
}

/// Marks `array` read-only (a view of data whose invariants C++ checked once, on construction).
template <class Array>
Array read_only(Array array) {
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

/// A view of `rows` rows of `Cols` values of type T at `data` (row stride `row_bytes`), kept
/// alive by `owner` (the array's base). An empty view owns an empty array of that shape.
template <class T, py::ssize_t Cols>
py::array_t<T> view(const T* data, std::size_t rows, py::ssize_t row_bytes, py::handle owner) {
  // An empty view still has `owner` as its base; numpy needs some address for it.
  static const T nothing{};
  const py::ssize_t n = static_cast<py::ssize_t>(rows);
  return py::array_t<T>({n, Cols}, {row_bytes, static_cast<py::ssize_t>(sizeof(T))}, n == 0 ? &nothing : data, owner);
}

/// A 1-D view of `count` values at `data`, kept alive by `owner`.
template <class T>
py::array_t<T> view(const std::vector<T>& values, py::handle owner) {
  static const T nothing{};
  return py::array_t<T>({static_cast<py::ssize_t>(values.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                        values.empty() ? &nothing : values.data(), owner);
}

/// A view of fixed-size Eigen vectors (Vec2, Vec3, Vec4, Point<Dim>) as an (n, size) array.
template <class Vector>
py::array_t<double> rows_view(const std::vector<Vector>& rows, py::handle owner) {
  return view<double, Vector::RowsAtCompileTime>(rows.empty() ? nullptr : rows.front().data(), rows.size(),
                                                 static_cast<py::ssize_t>(sizeof(Vector)), owner);
}

/// An array that owns `values` (moved into a capsule, not copied), shaped `shape` (whose
/// product is the number of scalars).
template <class T>
py::array_t<T> owning(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(T);
  for (std::size_t k = shape.size(); k-- > 0;) {
    strides[k] = stride;
    stride *= shape[k];
  }
  return py::array_t<T>(shape, strides, owned->data(), free_when_done);
}

/// The scalars of packed fixed-size Eigen vectors, row after row (one pass, for owning()).
template <class Vector>
std::vector<double> flatten(const std::vector<Vector>& rows) {
  static_assert(sizeof(Vector) == sizeof(double) * Vector::RowsAtCompileTime, "rows must be packed");
  std::vector<double> flat(rows.size() * Vector::RowsAtCompileTime);
  if (!rows.empty()) std::copy_n(rows.front().data(), flat.size(), flat.data());
  return flat;
}

/// A point as a (Dim,) array.
template <int Dim>
py::array_t<double> point_array(const Point<Dim>& p) {
  return owning(std::vector<double>(p.data(), p.data() + Dim), {Dim});
}

/// The shape of a parameter array (() for a scalar), to shape results like their parameters.
inline std::vector<py::ssize_t> shape_of(const py::array& array) {
  return {array.shape(), array.shape() + array.ndim()};
}

/// f(t) for every t of `ts` (any shape, a scalar too), as an array of shape ts.shape + (Dim,),
/// computed without the GIL (f must not touch Python objects).
template <int Dim, class F>
py::array_t<double> map_parameters(const DoubleArray& ts, F&& f) {
  const std::size_t count = static_cast<std::size_t>(ts.size());
  std::vector<double> out(count * Dim);
  {
    py::gil_scoped_release release;
    const double* t = ts.data();
    for (std::size_t k = 0; k < count; ++k) Eigen::Map<Point<Dim>>(out.data() + k * Dim) = f(t[k]);
  }
  std::vector<py::ssize_t> shape = shape_of(ts);
  shape.push_back(Dim);
  return owning(std::move(out), std::move(shape));
}

/// f(u, v) for every pair of `us` and `vs` (the same shape, or one of them a scalar), as an
/// array of shape (that shape) + (Dim,), computed without the GIL.
/// \throws InvalidInput if the shapes differ and neither is a scalar.
template <int Dim, class F>
py::array_t<double> map_parameter_pairs(const DoubleArray& us, const DoubleArray& vs, F&& f) {
  const bool u_scalar = us.ndim() == 0;
  const bool v_scalar = vs.ndim() == 0;
  if (!u_scalar && !v_scalar && shape_of(us) != shape_of(vs)) {
    throw InvalidInput(detail::message("u and v: expected arrays of one shape (or a scalar), got ", shape_text(us),
                                       " and ", shape_text(vs)));
  }
  const DoubleArray& shaped = u_scalar ? vs : us;
  const std::size_t count = static_cast<std::size_t>(shaped.size());
  std::vector<double> out(count * Dim);
  {
    py::gil_scoped_release release;
    const double* u = us.data();
    const double* v = vs.data();
    for (std::size_t k = 0; k < count; ++k) {
      Eigen::Map<Point<Dim>>(out.data() + k * Dim) = f(u[u_scalar ? 0 : k], v[v_scalar ? 0 : k]);
    }
  }
  std::vector<py::ssize_t> shape = shape_of(shaped);
  shape.push_back(Dim);
  return owning(std::move(out), std::move(shape));
}

}  // namespace patchwork::python
