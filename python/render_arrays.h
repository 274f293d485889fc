#pragma once
// The arrays of a render mesh as numpy views, for RenderMesh and Tessellation alike: positions,
// normals (n, 3), uvs (n, 2), tangents (n, 4) float64; indices (m, 3) and position_ids (n,)
// uint32; each a view of the object's own storage, with the object as its base. An attribute
// the mesh does not have is an empty array of its shape ((0, 3), ...).

#include "meshes/render_mesh.h"
#include "python/arrays.h"

namespace patchwork::python {

/// Adds the array properties to `c`, whose objects hold a RenderMesh that `mesh_of` returns.
template <class Holder, class MeshOf>
void bind_render_arrays(py::class_<Holder>& c, MeshOf mesh_of) {
  c.def_property_readonly(
       "positions", [mesh_of](py::object self) { return rows_view(mesh_of(self.cast<const Holder&>()).positions, self); },
       "Vertex positions, an (n, 3) float64 view.")
      .def_property_readonly(
          "normals", [mesh_of](py::object self) { return rows_view(mesh_of(self.cast<const Holder&>()).normals, self); },
          "Unit vertex normals, an (n, 3) float64 view ((0, 3) if none).")
      .def_property_readonly(
          "uvs", [mesh_of](py::object self) { return rows_view(mesh_of(self.cast<const Holder&>()).uvs, self); },
          "Texture coordinates, an (n, 2) float64 view ((0, 2) if none).")
      .def_property_readonly(
          "tangents", [mesh_of](py::object self) { return rows_view(mesh_of(self.cast<const Holder&>()).tangents, self); },
          "Unit tangents with handedness w = +-1, an (n, 4) float64 view ((0, 4) if none).")
      .def_property_readonly(
          "indices",
          [mesh_of](py::object self) {
            const RenderMesh& mesh = mesh_of(self.cast<const Holder&>());
            return view<std::uint32_t, 3>(mesh.indices.data(), mesh.triangle_count(), 3 * sizeof(std::uint32_t), self);
          },
          "Triangles, an (m, 3) uint32 view, counter-clockwise seen from the normals' side.")
      .def_property_readonly(
          "position_ids",
          [mesh_of](py::object self) { return view(mesh_of(self.cast<const Holder&>()).position_ids, self); },
          "Per vertex, its welded point: vertices with one id share the position.")
      .def_property_readonly(
          "vertex_count", [mesh_of](const Holder& h) { return mesh_of(h).vertex_count(); }, "The number of vertices.")
      .def_property_readonly(
          "triangle_count", [mesh_of](const Holder& h) { return mesh_of(h).triangle_count(); },
          "The number of triangles.");
}

}  // namespace patchwork::python
