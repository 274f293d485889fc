// tessellate() over patch sets, prepared surfaces and subdivision limit surfaces, and
// tessellate_in_batches() over patch sets; Camera, Tessellation (its arrays as views),
// PreparedSurface and write_gltf in Python.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include "io/gltf.h"
#include "python/bindings.h"
#include "python/render_arrays.h"
#include "subdivision/limit_tessellator.h"
#include "surfaces/batched_tessellation.h"
#include "surfaces/prepared_surface.h"
#include "surfaces/tessellator.h"

namespace patchwork::python {
namespace {

BackFaceCulling culling_named(const std::string& name) {
  if (name == "automatic") return BackFaceCulling::automatic;
  if (name == "always") return BackFaceCulling::always;
  if (name == "never") return BackFaceCulling::never;
  throw InvalidInput(detail::message("back_face_culling: expected 'automatic', 'always' or 'never', got '", name, "'"));
}

UvMode uv_named(const std::string& name) {
  if (name == "none") return UvMode::none;
  if (name == "patch") return UvMode::patch;
  if (name == "atlas") return UvMode::atlas;
  throw InvalidInput(detail::message("uv: expected 'none', 'patch' or 'atlas', got '", name, "'"));
}

// The keyword arguments of tessellate(), in the order of its signature.
struct OptionArguments {
  std::optional<double> tolerance;
  std::optional<double> relative_tolerance;
  std::optional<int> segments;
  std::optional<Camera> camera;
  double pixel_tolerance;
  std::string back_face_culling;
  double crease_angle;
  std::string uv;
  bool tangents;
  int threads;
  bool measure;
  bool optimize;
  std::int64_t max_triangles;
  bool split_patches;
  std::optional<bool> streaming_stores;

  TessellationOptions options() const {
    TessellationOptions o;
    o.tolerance = tolerance;
    o.relative_tolerance = relative_tolerance;
    o.segments = segments;
    o.camera = camera;
    o.pixel_tolerance = pixel_tolerance;
    o.back_face_culling = culling_named(back_face_culling);
    o.crease_angle = crease_angle;
    o.uv = uv_named(uv);
    o.tangents = tangents;
    o.threads = threads;
    o.measure = measure;
    o.optimize = optimize;
    o.max_triangles = max_triangles;
    o.split_patches = split_patches;
    o.streaming_stores = streaming_stores;
    return o;
  }
};

// Registers `name`(surface, *, options..., extra...) for one kind of surface; `run`(surface,
// options, extra...) tessellates it (without the GIL). `extra_args` name the Extra parameters,
// keyword-only after the options.
template <class Surface, class... Extra, class Run, class... ExtraArgs>
void def_tessellate(py::module_& m, const char* name, const char* doc, Run run, ExtraArgs... extra_args) {
  static_assert(sizeof...(Extra) == sizeof...(ExtraArgs), "one py::arg per extra parameter");
  const TessellationOptions defaults;
  m.def(
      name,
      [run](const Surface& surface, std::optional<double> tolerance, std::optional<double> relative_tolerance,
            std::optional<int> segments, std::optional<Camera> camera, double pixel_tolerance,
            std::string back_face_culling, double crease_angle, std::string uv, bool tangents, int threads,
            bool measure, bool optimize, std::int64_t max_triangles, bool split_patches,
            std::optional<bool> streaming_stores, Extra... extra) {
        const TessellationOptions options =
            OptionArguments{tolerance,    relative_tolerance, segments,     camera,           pixel_tolerance,
                            std::move(back_face_culling), crease_angle, std::move(uv), tangents, threads,
                            measure,      optimize,           max_triangles, split_patches,  streaming_stores}
                .options();
        py::gil_scoped_release release;
        return run(surface, options, extra...);
      },
      py::arg("surface"), py::kw_only(), py::arg("tolerance") = py::none(), py::arg("relative_tolerance") = py::none(),
      py::arg("segments") = py::none(), py::arg("camera") = py::none(),
      py::arg("pixel_tolerance") = defaults.pixel_tolerance, py::arg("back_face_culling") = "automatic",
      py::arg("crease_angle") = defaults.crease_angle, py::arg("uv") = "patch", py::arg("tangents") = defaults.tangents,
      py::arg("threads") = defaults.threads, py::arg("measure") = defaults.measure,
      py::arg("optimize") = defaults.optimize, py::arg("max_triangles") = defaults.max_triangles,
      py::arg("split_patches") = defaults.split_patches, py::arg("streaming_stores") = py::none(), extra_args..., doc);
}

constexpr const char* tessellate_doc =
    "A triangle mesh within a guaranteed error of the surface. Exactly one of tolerance (model units), "
    "relative_tolerance (of the tight box diagonal), segments (uniform N x N per patch) and camera (with "
    "pixel_tolerance). The GIL is released while it runs.";

}  // namespace

void bind_tessellation(py::module_& m) {
  py::class_<Camera>(m, "Camera", "A pinhole camera for view-dependent tolerance and culling.")
      .def(py::init([](const DoubleArray& eye, const DoubleArray& target, const DoubleArray& up, double fov_degrees,
                       int width, int height) {
             Camera camera{point_from<3>(eye, "eye"), point_from<3>(target, "target"), point_from<3>(up, "up"),
                           fov_degrees, width, height};
             validate(camera);
             return camera;
           }),
           py::arg("eye"), py::arg("target"), py::arg("up") = std::vector<double>{0.0, 0.0, 1.0},
           py::arg("fov_degrees") = 45.0, py::arg("width") = 1920, py::arg("height") = 1080,
           "Looks from eye at target; up is the world's up (Z for patchwork); fov is vertical, in degrees.")
      .def_property_readonly("eye", [](const Camera& c) { return point_array<3>(c.eye); }, "The eye point.")
      .def_property_readonly("target", [](const Camera& c) { return point_array<3>(c.target); }, "The target point.")
      .def_property_readonly("up", [](const Camera& c) { return point_array<3>(c.up); }, "The up direction.")
      .def_readonly("fov_degrees", &Camera::fov_degrees, "Vertical field of view, degrees.")
      .def_readonly("width", &Camera::width, "Image width, pixels.")
      .def_readonly("height", &Camera::height, "Image height, pixels.");

  py::class_<Tessellation> t(m, "Tessellation", "A tessellation: the render mesh's arrays and the error bounds.");
  bind_render_arrays(t, [](const Tessellation& s) -> const RenderMesh& { return s.mesh; });
  t.def_property_readonly(
       "triangle_patches", [](py::object self) { return view(self.cast<const Tessellation&>().triangle_patches, self); },
       "The patch (for a limit surface: the base face) of every triangle, an (m,) uint32 view.")
      .def_readonly("tolerance", &Tessellation::tolerance, "The absolute tolerance used (camera: the largest).")
      .def_readonly("error_bound", &Tessellation::error_bound, "The guaranteed bound on |S - L| over every triangle.")
      .def_readonly("weld_gap", &Tessellation::weld_gap, "How far welding moved a boundary point (part of error_bound).")
      .def_readonly("measured_error", &Tessellation::measured_error, "The sampled |S - L| (0 if not measured).")
      .def_readonly("tessellation_seconds", &Tessellation::tessellation_seconds, "Wall-clock seconds, measuring excluded.")
      .def_readonly("measure_seconds", &Tessellation::measure_seconds, "Wall-clock seconds of the measurement.")
      .def_readonly("culled_patches", &Tessellation::culled_patches, "Patches left out by frustum or back-face culling.")
      .def_readonly("culled_triangles", &Tessellation::culled_triangles, "Triangles those patches would have had.")
      .def_readonly("welded_vertices", &Tessellation::welded_vertices, "Distinct welded points.")
      .def(
          "render_mesh", [](const Tessellation& s) { return s.mesh; }, "A copy of the mesh as a RenderMesh.")
      .def("__repr__", [](const Tessellation& s) {
        return detail::message("Tessellation(", s.mesh.triangle_count(), " triangles, ", s.mesh.vertex_count(),
                               " vertices, error_bound ", s.error_bound, ", measured_error ", s.measured_error, ")");
      });

  py::class_<PreparedSurface>(m, "PreparedSurface",
                              "A patch set prepared for tessellating again and again (per frame, per tolerance).")
      .def(py::init([](const PatchSet& set) {
             py::gil_scoped_release release;
             return PreparedSurface(set);
           }),
           py::arg("patch_set"), py::keep_alive<1, 2>(),
           "Prepares `patch_set` once (bounds, pieces); it is kept alive as long as this object.")
      .def_property_readonly(
          "patch_set", [](const PreparedSurface& p) -> const PatchSet& { return p.set(); },
          py::return_value_policy::reference_internal, "The patch set prepared.");

  def_tessellate<PatchSet>(m, "tessellate", tessellate_doc,
                           [](const PatchSet& set, const TessellationOptions& o) { return tessellate(set, o); });
  def_tessellate<PreparedSurface>(m, "tessellate", tessellate_doc,
                                  [](const PreparedSurface& prepared, const TessellationOptions& o) {
                                    return tessellate(prepared, o);
                                  });
  def_tessellate<LimitSurface>(m, "tessellate", tessellate_doc,
                               [](const LimitSurface& surface, const TessellationOptions& o) {
                                 return tessellate_limit(surface, o);
                               });
  def_tessellate<PatchSet, std::size_t>(
      m, "tessellate_in_batches",
      "tessellate(patch_set, ...) a batch of whole shells (at least batch_patches patches) at a time into one "
      "mesh: one batch's working memory instead of the whole set's, every guarantee kept; each batch chooses its "
      "own split and vertex order. A camera, atlas UVs or a single batch give exactly tessellate(). The GIL is "
      "released while it runs.",
      [](const PatchSet& set, const TessellationOptions& o, std::size_t batch_patches) {
        return tessellate_in_batches(set, o, batch_patches);
      },
      py::arg("batch_patches") = default_batch_patches);

  const auto write = [](const std::filesystem::path& path, const RenderMesh& mesh, bool z_up, std::optional<bool> double_sided,
                        const std::string& name) {
    const GltfOptions options{z_up, double_sided, name};
    py::gil_scoped_release release;
    return write_gltf(path, mesh, options);
  };
  m.def(
      "write_gltf",
      [write](const std::filesystem::path& path, const Tessellation& t, bool z_up, std::optional<bool> double_sided,
              const std::string& name) { return write(path, t.mesh, z_up, double_sided, name); },
      py::arg("path"), py::arg("mesh"), py::kw_only(), py::arg("z_up") = true, py::arg("double_sided") = py::none(),
      py::arg("name") = "patchwork",
      "Writes a .glb or .gltf file atomically; returns the bound on how far the file's float positions are "
      "from the mesh's.");
  m.def("write_gltf", write, py::arg("path"), py::arg("mesh"), py::kw_only(), py::arg("z_up") = true,
        py::arg("double_sided") = py::none(), py::arg("name") = "patchwork",
        "Writes a render mesh as a .glb or .gltf file atomically; returns the position rounding bound.");
}

}  // namespace patchwork::python
