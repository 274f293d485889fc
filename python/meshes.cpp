// Mesh (FaceVertexMesh), RenderMesh, mesh files, topology, orientation, normals and subdivision
// in Python.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>
#include <utility>
#include <vector>

#include "io/gltf.h"
#include "io/polygon_mesh_file.h"
#include "meshes/normals.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"
#include "python/bindings.h"
#include "python/render_arrays.h"
#include "subdivision/limit_surface.h"
#include "subdivision/refine.h"

namespace patchwork::python {
namespace {

// A mesh from positions and faces: an (m, k) integer array of k-gons, or a list of index lists.
FaceVertexMesh mesh_from(const DoubleArray& positions, const py::object& faces) {
  require_shape(positions, "positions", {-1, 3}, "(n, 3)");
  Positions p(positions.shape(0), 3);
  std::copy_n(positions.data(), positions.size(), p.data());
  if (py::isinstance<py::array>(faces)) {
    const IndexArray uniform = indices_from(faces, "faces");
    require_shape(uniform, "faces", {-1, -1}, "(m, k) or a list of index lists");
    return FaceVertexMesh::uniform(std::move(p), static_cast<std::uint32_t>(uniform.shape(1)),
                                   {uniform.data(), uniform.data() + uniform.size()});
  }
  if (!py::isinstance<py::sequence>(faces) || py::isinstance<py::str>(faces)) {
    throw InvalidInput("faces: expected an (m, k) integer array or a list of index lists");
  }
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  for (const py::handle face : faces) {
    const std::string name = detail::message("faces[", sizes.size(), "]");
    const IndexArray corners = indices_from(face, name.c_str());
    require_shape(corners, name.c_str(), {-1}, "(k,)");
    sizes.push_back(static_cast<std::uint32_t>(corners.size()));
    indices.insert(indices.end(), corners.data(), corners.data() + corners.size());
  }
  return FaceVertexMesh(std::move(p), std::move(sizes), std::move(indices));
}

SubdivisionScheme scheme_named(const std::string& name) { return parse_scheme(name); }

// The cage of a mesh for `scheme`, the rest as OpenSubdiv's defaults (docs/subdivision.md).
SubdivisionCage cage_of(const FaceVertexMesh& mesh, const std::string& scheme) {
  SubdivisionCage cage;
  cage.mesh = mesh;
  cage.options.scheme = scheme_named(scheme);
  return cage;
}

NormalWeighting weighting_named(const std::string& name) {
  if (name == "angle") return NormalWeighting::angle;
  if (name == "area") return NormalWeighting::area;
  if (name == "uniform") return NormalWeighting::uniform;
  throw InvalidInput(detail::message("weighting: expected 'angle', 'area' or 'uniform', got '", name, "'"));
}

// Per-face ids as a uint32 array.
py::array_t<std::uint32_t> face_ids(const std::vector<FaceId>& ids) {
  std::vector<std::uint32_t> values;
  values.reserve(ids.size());
  for (const FaceId id : ids) values.push_back(id.value);
  const py::ssize_t n = static_cast<py::ssize_t>(values.size());
  return owning(std::move(values), {n});
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

}  // namespace

void bind_meshes(py::module_& m) {
  py::class_<FaceVertexMesh>(m, "Mesh", "A polygon mesh: positions and faces (index lists).")
      .def(py::init(&mesh_from), py::arg("positions"), py::arg("faces"),
           "From an (n, 3) array of positions and the faces: an (m, k) array of k-gons or a list of index lists.")
      .def_property_readonly(
          "positions",
          [](py::object self) {
            const auto& mesh = self.cast<const FaceVertexMesh&>();
            return read_only(view<double, 3>(mesh.positions().data(), mesh.vertex_count(), 3 * sizeof(double), self));
          },
          "The positions, a read-only (n, 3) view (no copy).")
      .def_property_readonly(
          "face_sizes",
          [](py::object self) { return read_only(view(self.cast<const FaceVertexMesh&>().face_sizes(), self)); },
          "The number of corners of every face, a read-only (m,) uint32 view.")
      .def_property_readonly(
          "face_indices",
          [](py::object self) { return read_only(view(self.cast<const FaceVertexMesh&>().face_indices(), self)); },
          "Every face's vertex indices, face after face, a read-only uint32 view.")
      .def_property_readonly("vertex_count", &FaceVertexMesh::vertex_count, "The number of vertices.")
      .def_property_readonly("face_count", &FaceVertexMesh::face_count, "The number of faces.")
      .def("__repr__", [](const FaceVertexMesh& mesh) {
        return detail::message("Mesh(", mesh.vertex_count(), " vertices, ", mesh.face_count(), " faces)");
      });

  py::class_<RenderMesh> render(m, "RenderMesh", "Triangles with per-vertex attributes, as glTF holds them.");
  bind_render_arrays(render, [](const RenderMesh& mesh) -> const RenderMesh& { return mesh; });
  render.def("welded", &welded_faces, "The triangles over the welded positions, as a Mesh.");

  m.def("read_mesh", &read_polygon_mesh, py::arg("path"), py::call_guard<py::gil_scoped_release>(),
        "A polygon mesh from .obj, .off, .ply, or the welded triangles of .glb/.gltf (IoError, ParseError).");
  m.def("write_mesh", &write_polygon_mesh, py::arg("path"), py::arg("mesh"), py::call_guard<py::gil_scoped_release>(),
        "Writes a polygon mesh as .obj, .off, .ply (as it is) or .glb/.gltf (triangulated, normals), atomically.");
  m.def(
      "read_gltf", [](const std::filesystem::path& path, bool z_up) { return read_gltf(path, z_up); }, py::arg("path"),
      py::arg("z_up") = true, py::call_guard<py::gil_scoped_release>(),
      "The render mesh of a .glb/.gltf file (z_up: convert glTF's +Y up to patchwork's +Z up).");

  m.def(
      "topology", [](const FaceVertexMesh& mesh) { return json_loads(to_json(analyze(mesh))); }, py::arg("mesh"),
      "The topology report (Euler characteristic, genus, boundary loops, manifoldness, orientability, "
      "components) as a dict, the keys of `patchwork info --json`.");
  m.def(
      "orient",
      [](const FaceVertexMesh& mesh, bool outward) {
        Orientation o = outward ? orient_outward(mesh) : orient(mesh);
        return py::make_tuple(std::move(o.mesh), face_ids(o.flipped));
      },
      py::arg("mesh"), py::arg("outward") = false,
      "Consistently oriented faces and the faces flipped: (Mesh, uint32 array); outward: closed components "
      "with positive volume.");
  m.def("signed_volume", &signed_volume, py::arg("mesh"), "The signed volume the faces enclose.");
  m.def(
      "face_normals",
      [](const FaceVertexMesh& mesh) {
        std::vector<Vec3> normals = face_normals(mesh);
        const py::ssize_t n = static_cast<py::ssize_t>(normals.size());
        return owning(flatten(normals), {n, 3});
      },
      py::arg("mesh"), "The unit normal of every face (Newell's method), an (m, 3) array.");
  m.def(
      "vertex_normals",
      [](const FaceVertexMesh& mesh, const std::string& weighting) {
        std::vector<Vec3> normals = vertex_normals(mesh, weighting_named(weighting));
        const py::ssize_t n = static_cast<py::ssize_t>(normals.size());
        return owning(flatten(normals), {n, 3});
      },
      py::arg("mesh"), py::arg("weighting") = "angle",
      "One unit normal per vertex ('angle', 'area' or 'uniform' weighted), an (n, 3) array.");

  m.def(
      "subdivide",
      [](const FaceVertexMesh& mesh, int levels, const std::string& scheme) {
        const SubdivisionCage cage = cage_of(mesh, scheme);
        py::gil_scoped_release release;
        return surface_faces(refine_uniform(cage, levels).cage);
      },
      py::arg("mesh"), py::arg("levels") = 1, py::arg("scheme") = "catmull-clark",
      "Uniform subdivision (OpenSubdiv): 'catmull-clark', 'loop' or 'bilinear'.");

  py::class_<LimitSurface>(m, "LimitSurface", "The limit surface of a subdivision cage (OpenSubdiv's patch table).")
      .def(py::init([](const FaceVertexMesh& mesh, const std::string& scheme, int isolation_level) {
             const SubdivisionCage cage = cage_of(mesh, scheme);
             py::gil_scoped_release release;
             return LimitSurface(cage, isolation_level);
           }),
           py::arg("mesh"), py::arg("scheme") = "catmull-clark", py::arg("isolation_level") = default_isolation_level,
           "Adaptively refines the cage to `isolation_level` around its irregular features.")
      .def_property_readonly("face_count", &LimitSurface::face_count, "The number of base faces (parameter domains).")
      .def(
          "evaluate",
          [](const LimitSurface& s, const py::object& face_objects, const DoubleArray& u, const DoubleArray& v) {
            const IndexArray faces = indices_from(face_objects, "faces");
            if (shape_of(faces) != shape_of(u) || shape_of(u) != shape_of(v)) {
              throw InvalidInput(detail::message("faces, u, v: expected arrays of one shape, got ", shape_text(faces),
                                                 ", ", shape_text(u), ", ", shape_text(v)));
            }
            const std::uint32_t* f = faces.data();
            const double* uu = u.data();
            std::size_t k = 0;
            // map_parameters walks v in order; the face and u of the same element go beside it.
            return map_parameters<3>(v, [&](double vv) {
              const Vec3 p = s.position(f[k], uu[k], vv);
              ++k;
              return p;
            });
          },
          py::arg("faces"), py::arg("u"), py::arg("v"),
          "Limit positions at (face, u, v) for arrays of one shape: shape u.shape + (3,).")
      .def(
          "patch_set", [](const LimitSurface& s) { return to_patch_set(s); },
          "The Bezier patches of the limit surface as a PatchSet (Catmull-Clark and bilinear).");
}

}  // namespace patchwork::python
