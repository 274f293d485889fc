#include "subdivision/refine.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include "core/errors.h"
#include "meshes/orientation.h"
#include "subdivision/osd_refiner.h"

namespace patchwork {

namespace osd = OpenSubdiv;

namespace detail {

namespace {

// OpenSubdiv reports through a global callback and then returns null; the message is kept
// here and thrown by the caller, so no exception passes through OpenSubdiv's frames.
thread_local std::string osd_error;

void record_error(osd::Far::ErrorType, const char* message) { osd_error = message; }
void ignore_warning(const char*) {}

float osd_sharpness(double sharpness) {
  return sharpness >= infinitely_sharp ? osd::Sdc::Crease::SHARPNESS_INFINITE : static_cast<float>(sharpness);
}

osd::Sdc::SchemeType osd_scheme(SubdivisionScheme scheme) {
  switch (scheme) {
    case SubdivisionScheme::catmull_clark: return osd::Sdc::SCHEME_CATMARK;
    case SubdivisionScheme::loop: return osd::Sdc::SCHEME_LOOP;
    case SubdivisionScheme::bilinear: return osd::Sdc::SCHEME_BILINEAR;
  }
  return osd::Sdc::SCHEME_CATMARK;
}

osd::Sdc::Options osd_options(const SubdivisionOptions& options) {
  osd::Sdc::Options result;
  switch (options.boundary) {
    case BoundaryInterpolation::none: result.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_NONE); break;
    case BoundaryInterpolation::edges:
      result.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
      break;
    case BoundaryInterpolation::edges_and_corners:
      result.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
      break;
  }
  using F = osd::Sdc::Options;
  static constexpr F::FVarLinearInterpolation fvar[] = {F::FVAR_LINEAR_NONE,          F::FVAR_LINEAR_CORNERS_ONLY,
                                                        F::FVAR_LINEAR_CORNERS_PLUS1, F::FVAR_LINEAR_CORNERS_PLUS2,
                                                        F::FVAR_LINEAR_BOUNDARIES,    F::FVAR_LINEAR_ALL};
  result.SetFVarLinearInterpolation(fvar[static_cast<int>(options.face_varying)]);
  return result;
}

}  // namespace

std::unique_ptr<osd::Far::TopologyRefiner> make_refiner(const SubdivisionCage& cage) {
  validate_cage(cage);
  const FaceVertexMesh& mesh = cage.mesh;
  std::vector<int> sizes(mesh.face_sizes().begin(), mesh.face_sizes().end());
  std::vector<osd::Far::Index> indices(mesh.face_indices().begin(), mesh.face_indices().end());
  std::vector<osd::Far::Index> crease_pairs;
  std::vector<float> crease_weights;
  for (const Crease& crease : cage.creases) {
    crease_pairs.push_back(static_cast<osd::Far::Index>(crease.a));
    crease_pairs.push_back(static_cast<osd::Far::Index>(crease.b));
    crease_weights.push_back(osd_sharpness(crease.sharpness));
  }
  std::vector<osd::Far::Index> corner_vertices;
  std::vector<float> corner_weights;
  for (const Corner& corner : cage.corners) {
    corner_vertices.push_back(static_cast<osd::Far::Index>(corner.vertex));
    corner_weights.push_back(osd_sharpness(corner.sharpness));
  }
  std::vector<osd::Far::Index> holes(cage.holes.begin(), cage.holes.end());
  std::vector<osd::Far::Index> fvar_indices;

  osd::Far::TopologyDescriptor descriptor;
  descriptor.numVertices = static_cast<int>(mesh.vertex_count());
  descriptor.numFaces = static_cast<int>(mesh.face_count());
  descriptor.numVertsPerFace = sizes.data();
  descriptor.vertIndicesPerFace = indices.data();
  descriptor.numCreases = static_cast<int>(cage.creases.size());
  descriptor.creaseVertexIndexPairs = crease_pairs.data();
  descriptor.creaseWeights = crease_weights.data();
  descriptor.numCorners = static_cast<int>(cage.corners.size());
  descriptor.cornerVertexIndices = corner_vertices.data();
  descriptor.cornerWeights = corner_weights.data();
  descriptor.numHoles = static_cast<int>(holes.size());
  descriptor.holeIndices = holes.data();
  osd::Far::TopologyDescriptor::FVarChannel channel;
  if (cage.face_varying) {
    fvar_indices.assign(cage.face_varying->indices.begin(), cage.face_varying->indices.end());
    channel.numValues = static_cast<int>(cage.face_varying->values.rows());
    channel.valueIndices = fvar_indices.data();
    descriptor.numFVarChannels = 1;
    descriptor.fvarChannels = &channel;
  }

  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  osd::Far::SetErrorCallback(record_error);
  osd::Far::SetWarningCallback(ignore_warning);
  osd_error.clear();
  std::unique_ptr<osd::Far::TopologyRefiner> refiner(
      Factory::Create(descriptor, Factory::Options(osd_scheme(cage.options.scheme), osd_options(cage.options))));
  if (!refiner) {
    throw TopologyError("OpenSubdiv rejected the cage: " + (osd_error.empty() ? std::string("no reason given") : osd_error));
  }
  return refiner;
}

}  // namespace detail

std::int64_t refined_face_count(const FaceVertexMesh& mesh, SubdivisionScheme scheme, int levels) {
  if (levels <= 0) return static_cast<std::int64_t>(mesh.face_count());
  // Loop splits each triangle in four; the quad schemes make one quad per face corner first.
  std::int64_t faces = scheme == SubdivisionScheme::loop ? 4 * static_cast<std::int64_t>(mesh.face_count())
                                                         : static_cast<std::int64_t>(mesh.face_indices().size());
  for (int level = 2; level <= levels && faces <= max_refined_faces; ++level) faces *= 4;
  return faces;
}

TopologyReport refined_topology(const FaceVertexMesh& cage, const TopologyReport& report, SubdivisionScheme scheme,
                                int levels) {
  if (!report.manifold || report.isolated_vertices != 0 || !report.orientable) {
    throw InvalidInput("refined_topology: the cage must be an orientable manifold without isolated vertices");
  }
  std::vector<Count> corners(report.per_component.size(), 0);
  const std::vector<std::uint32_t> component = face_components(cage);
  for (std::size_t f = 0; f < cage.face_count(); ++f) corners[component[f]] += cage.face_sizes()[f];
  TopologyReport refined = report;
  refined.vertices = refined.edges = refined.faces = 0;
  for (std::size_t c = 0; c < refined.per_component.size(); ++c) {
    ComponentTopology& part = refined.per_component[c];
    Count v = part.vertices;
    Count e = part.edges;
    Count f = part.faces;
    Count k = corners[c];
    for (int level = 1; level <= levels; ++level) {
      if (scheme == SubdivisionScheme::loop) {
        // A vertex per vertex and per edge; each edge splits in two and each triangle adds three.
        const Count next_v = v + e, next_e = 2 * e + 3 * f, next_f = 4 * f;
        v = next_v, e = next_e, f = next_f;
      } else {
        // A vertex per vertex, edge and face; each edge splits in two and each face corner adds
        // an edge to the face point and a quad.
        const Count next_v = v + e + f, next_e = 2 * e + k, next_f = k;
        v = next_v, e = next_e, f = next_f;
        k = 4 * f;
      }
    }
    part.vertices = v;
    part.edges = e;
    part.faces = f;
    refined.vertices += v;
    refined.edges += e;
    refined.faces += f;
  }
  refined.boundary_edges = report.boundary_edges << levels;
  return refined;
}

FaceVertexMesh surface_faces(const SubdivisionCage& cage) {
  if (cage.holes.empty()) return cage.mesh;
  std::vector<bool> hole(cage.mesh.face_count(), false);
  for (auto f : cage.holes) hole.at(f) = true;
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  for (std::size_t f = 0; f < cage.mesh.face_count(); ++f) {
    if (hole[f]) continue;
    const auto face = cage.mesh.face(f);
    sizes.push_back(static_cast<std::uint32_t>(face.size()));
    indices.insert(indices.end(), face.begin(), face.end());
  }
  return FaceVertexMesh(cage.mesh.positions(), std::move(sizes), std::move(indices));
}

UniformRefinement refine_uniform(const SubdivisionCage& cage, int levels) {
  if (levels < 0 || levels > max_refinement_levels) {
    throw InvalidInput(detail::message("refine_uniform: levels must be in 0..", max_refinement_levels, ", not ",
                                       levels));
  }
  const std::int64_t faces = refined_face_count(cage.mesh, cage.options.scheme, levels);
  if (faces > max_refined_faces) {
    throw InvalidInput(detail::message("refine_uniform: ", levels, " levels would make more than ", max_refined_faces,
                                       " faces (", cage.mesh.face_count(), " faces in the cage)"));
  }
  auto refiner = detail::make_refiner(cage);
  if (levels == 0) {
    UniformRefinement result{cage, cage.holes.empty() ? analyze(cage.mesh) : analyze(surface_faces(cage)), 0};
    return result;
  }
  const bool tagged = !cage.creases.empty() || !cage.corners.empty();
  osd::Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = tagged;  // the last level's edges, only to read its creases
  refiner->RefineUniform(uniform);

  // Positions and vertex data, level by level, in rows of [x y z data...]. The buffers are not
  // zeroed: interpolation writes every row (fresh pages were a third of the time at 2.5M faces).
  const int columns = 3 + static_cast<int>(cage.vertex_data.cols());
  const detail::PrimvarRefiner primvars(*refiner);
  const auto interpolate = [&](int level, double* from, double* to, int width, bool face_varying) {
    if (width == 3 && !face_varying) {
      const detail::FixedRows<3> source{from};
      detail::FixedRows<3> target{to};
      primvars.Interpolate(level, source, target);
    } else {
      const detail::PrimvarRows source{from, width};
      detail::PrimvarRows target{to, width};
      if (face_varying) {
        primvars.InterpolateFaceVarying(level, source, target, 0);
      } else {
        primvars.Interpolate(level, source, target);
      }
    }
  };
  const auto rows = [](std::size_t count, int width) {
    return std::make_unique_for_overwrite<double[]>(count * static_cast<std::size_t>(width));
  };
  auto source = rows(cage.mesh.vertex_count(), columns);
  for (std::size_t v = 0; v < cage.mesh.vertex_count(); ++v) {
    for (int k = 0; k < 3; ++k) source[v * columns + k] = cage.mesh.positions()(static_cast<Eigen::Index>(v), k);
    for (int k = 3; k < columns; ++k) source[v * columns + k] = cage.vertex_data(static_cast<Eigen::Index>(v), k - 3);
  }
  const int fvar_columns = cage.face_varying ? static_cast<int>(cage.face_varying->values.cols()) : 0;
  std::unique_ptr<double[]> fvar_source;
  if (cage.face_varying) {
    const auto& values = cage.face_varying->values;
    fvar_source = rows(static_cast<std::size_t>(values.rows()), fvar_columns);
    for (Eigen::Index r = 0; r < values.rows(); ++r) {
      for (int k = 0; k < fvar_columns; ++k) fvar_source[static_cast<std::size_t>(r) * fvar_columns + k] = values(r, k);
    }
  }
  const auto& last = refiner->GetLevel(levels);
  const auto vertex_count = static_cast<Eigen::Index>(last.GetNumVertices());
  // Positions alone: the last level is interpolated straight into the result's rows.
  Positions positions(vertex_count, 3);
  for (int level = 1; level <= levels; ++level) {
    const auto& refined = refiner->GetLevel(level);
    if (level == levels && columns == 3) {
      interpolate(level, source.get(), positions.data(), 3, false);
    } else {
      auto target = rows(static_cast<std::size_t>(refined.GetNumVertices()), columns);
      interpolate(level, source.get(), target.get(), columns, false);
      source = std::move(target);
    }
    if (cage.face_varying) {
      auto fvar_target = rows(static_cast<std::size_t>(refined.GetNumFVarValues(0)), fvar_columns);
      interpolate(level, fvar_source.get(), fvar_target.get(), fvar_columns, true);
      fvar_source = std::move(fvar_target);
    }
  }

  SubdivisionCage result;
  result.options = cage.options;
  result.vertex_data.resize(vertex_count, columns - 3);
  if (columns > 3) {
    for (Eigen::Index v = 0; v < vertex_count; ++v) {
      for (int k = 0; k < 3; ++k) positions(v, k) = source[static_cast<std::size_t>(v) * columns + k];
      for (int k = 3; k < columns; ++k) result.vertex_data(v, k - 3) = source[static_cast<std::size_t>(v) * columns + k];
    }
  }
  std::vector<std::uint32_t> sizes(static_cast<std::size_t>(last.GetNumFaces()));
  std::vector<std::uint32_t> indices;
  indices.reserve(last.GetNumFaceVertices());
  std::vector<std::uint32_t> fvar_indices;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto face = last.GetFaceVertices(f);
    sizes[static_cast<std::size_t>(f)] = static_cast<std::uint32_t>(face.size());
    for (int k = 0; k < face.size(); ++k) indices.push_back(static_cast<std::uint32_t>(face[k]));
    if (cage.face_varying) {
      const auto values = last.GetFaceFVarValues(f, 0);
      for (int k = 0; k < values.size(); ++k) fvar_indices.push_back(static_cast<std::uint32_t>(values[k]));
    }
    if (last.IsFaceHole(f)) result.holes.push_back(static_cast<std::uint32_t>(f));
  }
  result.mesh = FaceVertexMesh(std::move(positions), std::move(sizes), std::move(indices));
  if (cage.face_varying) {
    FaceVaryingData data;
    data.values.resize(last.GetNumFVarValues(0), fvar_columns);
    for (Eigen::Index r = 0; r < data.values.rows(); ++r) {
      for (int k = 0; k < fvar_columns; ++k) data.values(r, k) = fvar_source[static_cast<std::size_t>(r) * fvar_columns + k];
    }
    data.indices = std::move(fvar_indices);
    result.face_varying = std::move(data);
  }
  // Tags as they stand at this level (none can appear without any in the cage). Boundary edges
  // are sharp by the boundary rule, not by a tag.
  for (int e = 0; tagged && e < last.GetNumEdges(); ++e) {
    const float sharpness = last.GetEdgeSharpness(e);
    if (sharpness > 0.0f && !last.IsEdgeBoundary(e)) {
      const auto ends = last.GetEdgeVertices(e);
      result.creases.push_back({static_cast<std::uint32_t>(ends[0]), static_cast<std::uint32_t>(ends[1]),
                                sharpness >= osd::Sdc::Crease::SHARPNESS_INFINITE ? infinitely_sharp : sharpness});
    }
  }
  for (int v = 0; tagged && v < last.GetNumVertices(); ++v) {
    const float sharpness = last.GetVertexSharpness(v);
    if (sharpness > 0.0f) {
      result.corners.push_back({static_cast<std::uint32_t>(v),
                                sharpness >= osd::Sdc::Crease::SHARPNESS_INFINITE ? infinitely_sharp : sharpness});
    }
  }
  UniformRefinement refinement{std::move(result), {}, levels};
  // Without holes the report follows from the cage's (validated manifold) by the closed forms;
  // the tests check it against analyze() of the refined mesh. A non-orientable cage gets
  // analyze(): its proving cycle is one of the refined faces.
  const TopologyReport cage_report = analyze(cage.mesh);
  refinement.topology = cage.holes.empty() && cage_report.isolated_vertices == 0 && cage_report.orientable
                            ? refined_topology(cage.mesh, cage_report, cage.options.scheme, levels)
                            : analyze(surface_faces(refinement.cage));
  return refinement;
}

}  // namespace patchwork
