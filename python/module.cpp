// The extension module _patchwork; python/patchwork/__init__.py re-exports it as `patchwork`.

#include "python/bindings.h"

PYBIND11_MODULE(_patchwork, m) {
  m.doc() = "patchwork: Bezier and NURBS curves and surfaces, meshes, guaranteed-error tessellation and "
            "certified queries (numpy in and out; docs/python.md)";
  patchwork::python::bind_errors(m);
  patchwork::python::bind_curves(m);
  patchwork::python::bind_surfaces(m);
  patchwork::python::bind_meshes(m);
  patchwork::python::bind_tessellation(m);
  patchwork::python::bind_queries(m);
}
