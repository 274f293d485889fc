#include "report/occt_peer.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <IMeshData_Status.hxx>
#include <Poly_Triangulation.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
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
#include "report/occt_geometry.h"

namespace patchwork::performance {
namespace {

void check_meshing_arguments(double linear_deflection, double angular_deflection, int repeats) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(linear_deflection) || !positive(angular_deflection)) {
    throw InvalidInput(patchwork::detail::message("occt_tessellate: deflections must be positive and finite (linear ",
                                                  linear_deflection, ", angular ", angular_deflection, ")"));
  }
  if (repeats < 1) throw InvalidInput(patchwork::detail::message("occt_tessellate: repeats ", repeats, " < 1"));
}

void check_arguments(std::span<const BezierPatch3> patches, double linear_deflection, double angular_deflection,
                     int repeats) {
  check_meshing_arguments(linear_deflection, angular_deflection, repeats);
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

// The face on a whole surface, trimmed by its natural bounds.
TopoDS_Face make_face(const Handle(Geom_Surface) & surface) {
  // TolDegen: boundary edges shorter than this (the teapot's collapsed edges, a sphere's poles)
  // become degenerate.
  BRepBuilderAPI_MakeFace maker(surface, Precision::Confusion());
  if (!maker.IsDone()) throw NumericalError("occt_tessellate: BRepBuilderAPI_MakeFace failed");
  return maker.Face();
}

TopoDS_Face make_face(const BezierPatch3& patch) { return make_face(detail::occt_bezier_surface(patch)); }

void check_degrees(const char* function, const NurbsSurface& surface) {
  const int max_degree = Geom_BSplineSurface::MaxDegree();
  const int p = surface.degree_u();
  const int q = surface.degree_v();
  if (p < 1 || q < 1 || p > max_degree || q > max_degree) {
    throw InvalidInput(
        patchwork::detail::message(function, ": degrees (", p, ", ", q, "), Open CASCADE takes 1..", max_degree));
  }
}

// The knots as OCCT wants them: distinct values and their multiplicities, 1-based.
std::pair<TColStd_Array1OfReal, TColStd_Array1OfInteger> distinct_knots(const KnotVector& knots) {
  std::vector<double> values;
  std::vector<int> multiplicities;
  for (const double knot : knots.knots()) {
    if (!values.empty() && knot == values.back()) {
      ++multiplicities.back();
    } else {
      values.push_back(knot);
      multiplicities.push_back(1);
    }
  }
  const int n = static_cast<int>(values.size());
  std::pair<TColStd_Array1OfReal, TColStd_Array1OfInteger> result{TColStd_Array1OfReal(1, n),
                                                                  TColStd_Array1OfInteger(1, n)};
  for (int k = 0; k < n; ++k) {
    result.first.SetValue(k + 1, values[static_cast<std::size_t>(k)]);
    result.second.SetValue(k + 1, multiplicities[static_cast<std::size_t>(k)]);
  }
  return result;
}

// The faces in order, unsewn.
TopoDS_Compound make_compound(const std::vector<TopoDS_Face>& faces) {
  TopoDS_Compound compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  for (const TopoDS_Face& face : faces) builder.Add(compound, face);
  return compound;
}

TopoDS_Compound make_faces(std::span<const BezierPatch3> patches) {
  std::vector<TopoDS_Face> faces;
  for (const BezierPatch3& patch : patches) faces.push_back(make_face(patch));
  return make_compound(faces);
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
auto guarded(const char* function, F&& f) {
  try {
    return f();
  } catch (const Standard_Failure& failure) {
    throw NumericalError(patchwork::detail::message(function, ": Open CASCADE: ", failure.GetMessageString()));
  }
}

// Meshes the compound `make_compound()` builds `repeats` times, each time fresh (nothing meshed
// is left to reuse), timing only the meshing.
template <class MakeCompound>
OcctRun timed_mesh(const MakeCompound& make_compound, double linear_deflection, double angular_deflection,
                   int repeats) {
  return guarded("occt_tessellate", [&] {
    std::vector<double> seconds;
    TopoDS_Compound compound;
    for (int r = 0; r < repeats; ++r) {
      compound = make_compound();
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

}  // namespace

std::string occt_version() { return OCC_VERSION_COMPLETE; }

OcctRun occt_tessellate(std::span<const BezierPatch3> patches, double linear_deflection, double angular_deflection,
                        int repeats) {
  check_arguments(patches, linear_deflection, angular_deflection, repeats);
  return timed_mesh([&] { return make_faces(patches); }, linear_deflection, angular_deflection, repeats);
}

OcctRun timed_enough(const std::function<OcctRun(int repeats)>& tessellate, int repeats) {
  OcctRun run = tessellate(1);
  if (run.seconds_median < 1.0 && repeats > 1) run = tessellate(repeats);
  return run;
}

OcctRun occt_tessellate(const NurbsSurface& surface, double linear_deflection, double angular_deflection, int repeats) {
  check_meshing_arguments(linear_deflection, angular_deflection, repeats);
  check_degrees("occt_tessellate", surface);
  return timed_mesh([&] { return make_compound({make_face(detail::occt_bspline_surface(surface))}); },
                    linear_deflection, angular_deflection, repeats);
}

std::vector<SurfaceJet> occt_evaluate(const NurbsSurface& surface, std::span<const Vec2> parameters) {
  check_degrees("occt_evaluate", surface);
  const KnotVector& U = surface.knots_u();
  const KnotVector& V = surface.knots_v();
  for (const Vec2& uv : parameters) {
    if (!(uv.x() >= U.a() && uv.x() <= U.b() && uv.y() >= V.a() && uv.y() <= V.b())) {
      throw InvalidInput(patchwork::detail::message("occt_evaluate: (", uv.x(), ", ", uv.y(), ") outside [", U.a(),
                                                    ", ", U.b(), "] x [", V.a(), ", ", V.b(), "]"));
    }
  }
  return guarded("occt_evaluate", [&] {
    const Handle(Geom_BSplineSurface) bspline = detail::occt_bspline_surface(surface);
    std::vector<SurfaceJet> jets;
    jets.reserve(parameters.size());
    for (const Vec2& uv : parameters) {
      gp_Pnt point;
      bspline->D0(uv.x(), uv.y(), point);
      gp_Pnt ignored;
      gp_Vec du, dv;
      bspline->D1(uv.x(), uv.y(), ignored, du, dv);
      jets.push_back(
          {Vec3(point.X(), point.Y(), point.Z()), Vec3(du.X(), du.Y(), du.Z()), Vec3(dv.X(), dv.Y(), dv.Z())});
    }
    return jets;
  });
}

namespace detail {

// Pole (i+1, j+1) = P_ij: Geom_BezierSurface's first pole index runs along U, so (U, V) = (u, v).
Handle(Geom_BezierSurface) occt_bezier_surface(const BezierPatch3& patch) {
  TColgp_Array2OfPnt poles(1, patch.degree_u() + 1, 1, patch.degree_v() + 1);
  for (int j = 0; j <= patch.degree_v(); ++j) {
    for (int i = 0; i <= patch.degree_u(); ++i) {
      const Vec3& P = patch.control_point(i, j);
      poles.SetValue(i + 1, j + 1, gp_Pnt(P.x(), P.y(), P.z()));
    }
  }
  return new Geom_BezierSurface(poles);
}

// Pole (i+1, j+1) = P_ij with weight w_ij (see the header's file comment).
Handle(Geom_BSplineSurface) occt_bspline_surface(const NurbsSurface& surface) {
  TColgp_Array2OfPnt poles(1, surface.count_u(), 1, surface.count_v());
  TColStd_Array2OfReal weights(1, surface.count_u(), 1, surface.count_v());
  for (int j = 0; j < surface.count_v(); ++j) {
    for (int i = 0; i < surface.count_u(); ++i) {
      const Vec3 P = surface.control_point(i, j);
      poles.SetValue(i + 1, j + 1, gp_Pnt(P.x(), P.y(), P.z()));
      weights.SetValue(i + 1, j + 1, surface.weight(i, j));
    }
  }
  const auto [u_knots, u_multiplicities] = distinct_knots(surface.knots_u());
  const auto [v_knots, v_multiplicities] = distinct_knots(surface.knots_v());
  return new Geom_BSplineSurface(poles, weights, u_knots, v_knots, u_multiplicities, v_multiplicities,
                                 surface.degree_u(), surface.degree_v());
}

OcctParametricMesh occt_parametric_mesh(std::span<const BezierPatch3> patches, double linear_deflection,
                                        double angular_deflection) {
  check_arguments(patches, linear_deflection, angular_deflection, 1);
  return guarded("occt_tessellate", [&] {
    const TopoDS_Compound compound = make_faces(patches);
    mesh(compound, linear_deflection, angular_deflection);
    return collect(compound);
  });
}

}  // namespace detail
}  // namespace patchwork::performance
