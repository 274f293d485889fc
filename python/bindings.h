#pragma once
// The parts of the module _patchwork, one function a part (python/module.cpp calls them in
// dependency order: a part may use the classes of the parts before it).

#include <pybind11/pybind11.h>

namespace patchwork::python {

/// patchwork.Error and its subclasses, and the translation of the C++ exception family.
void bind_errors(pybind11::module_& m);
/// Bezier, rational Bezier and NURBS curves in 2D and 3D.
void bind_curves(pybind11::module_& m);
/// Patches, NURBS surfaces, patch sets and reading files of patches.
void bind_surfaces(pybind11::module_& m);
/// Polygon meshes: files, topology, orientation, normals; subdivision.
void bind_meshes(pybind11::module_& m);
/// The tessellator, prepared surfaces and glTF writing.
void bind_tessellation(pybind11::module_& m);
/// Closest points, ray casting and intersections.
void bind_queries(pybind11::module_& m);

}  // namespace patchwork::python
