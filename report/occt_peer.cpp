#include "report/occt_peer.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BezierSurface.hxx>
#include <IMeshData_Status.hxx>
#include <Poly_Triangulation.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"

namespace patchwork::performance {
namespace {

void check_arguments(std::span<const BezierPatch3> patches, double linear_deflection, double angular_deflection,
                     int repeats) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(linear_deflection) || !positive(angular_deflection)) {
    throw InvalidInput(patchwork::detail::message("occt_tessellate: deflections must be positive and finite (linear ",
                                                  linear_deflection, ", angular ", angular_deflection, ")"));
  }
  if (repeats < 1) throw InvalidInput(patchwork::detail::message("occt_tessellate: repeats ", repeats, " < 1"));
  const int max_degree = Geom_BezierSurface::MaxDegree();
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const int n = patches[k].degree_u();
    const int m = patches[k].degree_v();
    if (n < 1 || m < 1 || n > max_degree || m > max_degree) {
      throw InvalidInput(patchwork::detail::message("occt_tessellate: patch ", k, " has degrees (", n, ", ", m,
                                                    "), Open CASCADE takes 1..", max_degree));
    }
  }
}

// Pole (i+1, j+1) = P_ij: Geom_BezierSurface's first pole index runs along U, so (U, V) = (u, v).
TopoDS_Face make_face(const BezierPatch3& patch) {
  TColgp_Array2OfPnt poles(1, patch.degree_u() + 1, 1, patch.degree_v() + 1);
  for (int j = 0; j <= patch.degree_v(); ++j) {
    for (int i = 0; i <= patch.degree_u(); ++i) {
      const Vec3& P = patch.control_point(i, j);
      poles.SetValue(i + 1, j + 1, gp_Pnt(P.x(), P.y(), P.z()));
    }
  }
  // TolDegen: boundary edges shorter than this (the teapot's collapsed edges) become degenerate.
  BRepBuilderAPI_MakeFace maker(new Geom_BezierSurface(poles), Precision::Confusion());
  if (!maker.IsDone()) throw NumericalError("occt_tessellate: BRepBuilderAPI_MakeFace failed");
  return maker.Face();
}

// The faces in patch order, unsewn.
TopoDS_Compound make_faces(std::span<const BezierPatch3> patches) {
  TopoDS_Compound compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  for (const BezierPatch3& patch : patches) builder.Add(compound, make_face(patch));
  return compound;
}

void mesh(const TopoDS_Shape& shape, double linear_deflection, double angular_deflection) {
  const BRepMesh_IncrementalMesh mesher(shape, linear_deflection, /*isRelative=*/false, angular_deflection,
                                        /*isInParallel=*/false);
  if (!mesher.IsDone() || (mesher.GetStatusFlags() & IMeshData_Failure) != 0) {
    throw NumericalError(patchwork::detail::message("occt_tessellate: BRepMesh_IncrementalMesh failed (status flags ",
                                                    mesher.GetStatusFlags(), ")"));
  }
}

// Every face's triangulation, located, nodes appended without welding, wound along F_u x F_v.
detail::OcctParametricMesh collect(const TopoDS_Compound& compound) {
  detail::OcctParametricMesh result;
  std::size_t k = 0;
  for (TopoDS_Iterator it(compound); it.More(); it.Next(), ++k) {
    const TopoDS_Face& face = TopoDS::Face(it.Value());
    TopLoc_Location location;
    const Handle(Poly_Triangulation)& triangulation = BRep_Tool::Triangulation(face, location);
    if (triangulation.IsNull() || triangulation->NbTriangles() == 0) {
      throw NumericalError(
          patchwork::detail::message("occt_tessellate: Open CASCADE left patch ", k, " without a triangulation"));
    }
    const gp_Trsf transformation = location.Transformation();
    const auto base = static_cast<std::uint32_t>(result.mesh.positions.size());
    result.first_vertex.push_back(base);
    for (int i = 1; i <= triangulation->NbNodes(); ++i) {
      const gp_Pnt p = triangulation->Node(i).Transformed(transformation);
      result.mesh.positions.emplace_back(p.X(), p.Y(), p.Z());
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const gp_Pnt2d uv = triangulation->HasUVNodes() ? triangulation->UVNode(i) : gp_Pnt2d(nan, nan);
      result.uv.emplace_back(uv.X(), uv.Y());
    }
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
      int a = 0, b = 0, c = 0;
      triangulation->Triangle(t).Get(a, b, c);
      if (reversed) std::swap(b, c);
      for (const int node : {a, b, c}) result.mesh.indices.push_back(base + static_cast<std::uint32_t>(node - 1));
    }
  }
  result.first_vertex.push_back(result.mesh.positions.size());
  return result;
}

// Runs an OCCT computation, turning its exceptions into NumericalError.
template <class F>
auto guarded(F&& f) {
  try {
    return f();
  } catch (const Standard_Failure& failure) {
    throw NumericalError(patchwork::detail::message("occt_tessellate: Open CASCADE: ", failure.GetMessageString()));
  }
}

}  // namespace

std::string occt_version() { return OCC_VERSION_COMPLETE; }

OcctRun occt_tessellate(std::span<const BezierPatch3> patches, double linear_deflection, double angular_deflection,
                        int repeats) {
  check_arguments(patches, linear_deflection, angular_deflection, repeats);
  return guarded([&] {
    std::vector<double> seconds;
    TopoDS_Compound compound;
    for (int r = 0; r < repeats; ++r) {
      compound = make_faces(patches);  // fresh faces: nothing meshed is left to reuse
      const auto start = std::chrono::steady_clock::now();
      mesh(compound, linear_deflection, angular_deflection);
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    const std::size_t half = seconds.size() / 2;
    const double median = seconds.size() % 2 == 1 ? seconds[half] : 0.5 * (seconds[half - 1] + seconds[half]);
    return OcctRun{collect(compound).mesh, median, seconds.front(), repeats};
  });
}

namespace detail {

OcctParametricMesh occt_parametric_mesh(std::span<const BezierPatch3> patches, double linear_deflection,
                                        double angular_deflection) {
  check_arguments(patches, linear_deflection, angular_deflection, 1);
  return guarded([&] {
    const TopoDS_Compound compound = make_faces(patches);
    mesh(compound, linear_deflection, angular_deflection);
    return collect(compound);
  });
}

}  // namespace detail
}  // namespace patchwork::performance
