#include "subdivision/cage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/errors.h"
#include "meshes/edge_table.h"
#include "meshes/orientation.h"
#include "meshes/topology.h"

namespace patchwork {

namespace {

void check_sharpness(double sharpness, const char* what, std::size_t index) {
  if (std::isnan(sharpness) || sharpness < 0.0) {
    throw InvalidInput(detail::message("validate_cage: ", what, " ", index, " has sharpness ", sharpness,
                                       " (must be >= 0; infinity for infinitely sharp)"));
  }
}

void check_topology(const FaceVertexMesh& mesh) {
  const TopologyReport report = analyze(mesh);
  if (!report.faces_repeating_a_vertex.empty()) {
    throw TopologyError(detail::message("validate_cage: face ", report.faces_repeating_a_vertex.front(),
                                        " uses a vertex more than once"));
  }
  if (!report.non_manifold_edges.empty()) {
    const auto& e = report.non_manifold_edges.front();
    throw TopologyError(
        detail::message("validate_cage: edge (", e[0], ", ", e[1], ") has more than two faces (non-manifold)"));
  }
  if (!report.non_manifold_vertices.empty()) {
    throw TopologyError(detail::message("validate_cage: vertex ", report.non_manifold_vertices.front(),
                                        " is non-manifold (its faces form more than one fan)"));
  }
  // Two faces on an edge must walk it in opposite directions, in every orientable component
  // (orient_cage() makes them so). A non-orientable component (a Moebius band, a Klein bottle)
  // has such edges wherever it is cut: OpenSubdiv refines them as non-manifold seams.
  const detail::EdgeTable table(mesh);
  // Which components are orientable is needed only when one is not.
  std::optional<detail::OrientationWalk> walk;
  if (!report.orientable) walk = detail::walk_orientation(mesh, table);
  const auto orientable = [&](std::uint32_t face) {
    return !walk || walk->component_orientable[walk->components.of_face[face]];
  };
  const auto& corners = mesh.face_indices();
  for (std::uint32_t c = 0; c < corners.size(); ++c) {
    const std::uint32_t t = table.twin(c);
    if (t >= detail::EdgeTable::crowded) continue;
    if (corners[c] == corners[t] && orientable(table.face_of(c))) {
      throw TopologyError(detail::message("validate_cage: faces ", table.face_of(c), " and ", table.face_of(t),
                                          " walk edge (", corners[c], ", ", corners[table.next_corner(c)],
                                          ") in the same direction (orient_cage() the cage first)"));
    }
  }
}

// Two triangles on the same three vertices (a "pillow") are a closed surface, but Loop
// refinement joins their edge points by two edges with the same ends (one inside each triangle),
// which a face-vertex mesh cannot tell apart: the refined mesh would read as non-manifold.
// Found by fuzz_subdivision (tests/fuzz/regressions/fuzz_subdivision).
void check_distinct_triangles(const FaceVertexMesh& mesh) {
  std::vector<std::array<std::uint32_t, 4>> triangles;  // sorted vertices, then the face
  triangles.reserve(mesh.face_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    std::array<std::uint32_t, 4> key = {face[0], face[1], face[2], static_cast<std::uint32_t>(f)};
    std::sort(key.begin(), key.begin() + 3);
    triangles.push_back(key);
  }
  std::sort(triangles.begin(), triangles.end());
  for (std::size_t k = 1; k < triangles.size(); ++k) {
    const auto& a = triangles[k - 1];
    const auto& b = triangles[k];
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) {
      throw TopologyError(detail::message("validate_cage: faces ", a[3], " and ", b[3], " are both the triangle (",
                                          a[0], ", ", a[1], ", ", a[2],
                                          "): Loop refinement would join them by edges with the "
                                          "same ends, which a face-vertex mesh cannot tell apart (use catmull-clark)"));
    }
  }
}

}  // namespace

void validate_cage(const SubdivisionCage& cage) {
  const FaceVertexMesh& mesh = cage.mesh;
  if (mesh.face_count() == 0) throw InvalidInput("validate_cage: the cage has no face");
  if (cage.options.scheme == SubdivisionScheme::loop) {
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
      if (mesh.face_sizes()[f] != 3) {
        throw TopologyError(detail::message("validate_cage: Loop subdivision needs triangles; face ", f, " has ",
                                            mesh.face_sizes()[f], " corners (triangulate it or use catmull-clark)"));
      }
    }
    check_distinct_triangles(mesh);
  }
  check_topology(mesh);

  const auto vertex_count = mesh.vertex_count();
  const detail::EdgeTable table(mesh);
  for (std::size_t k = 0; k < cage.creases.size(); ++k) {
    const Crease& crease = cage.creases[k];
    if (crease.a >= vertex_count || crease.b >= vertex_count) {
      throw InvalidInput(detail::message("validate_cage: crease ", k, " names vertex ", std::max(crease.a, crease.b),
                                         " of ", vertex_count));
    }
    check_sharpness(crease.sharpness, "crease", k);
  }
  if (!cage.creases.empty()) {
    // Each crease must be an edge of the cage.
    std::vector<std::vector<std::uint32_t>> neighbours(vertex_count);
    for (std::size_t e = 0; e < table.edge_count(); ++e) {
      const auto [a, b] = table.vertices(e);
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
    for (std::size_t k = 0; k < cage.creases.size(); ++k) {
      const auto& around = neighbours[cage.creases[k].a];
      if (std::find(around.begin(), around.end(), cage.creases[k].b) == around.end()) {
        throw InvalidInput(detail::message("validate_cage: crease ", k, " (", cage.creases[k].a, ", ",
                                           cage.creases[k].b, ") is not an edge of the cage"));
      }
    }
  }
  for (std::size_t k = 0; k < cage.corners.size(); ++k) {
    if (cage.corners[k].vertex >= vertex_count) {
      throw InvalidInput(
          detail::message("validate_cage: corner ", k, " names vertex ", cage.corners[k].vertex, " of ", vertex_count));
    }
    check_sharpness(cage.corners[k].sharpness, "corner", k);
  }
  for (std::size_t k = 0; k < cage.holes.size(); ++k) {
    if (cage.holes[k] >= mesh.face_count()) {
      throw InvalidInput(
          detail::message("validate_cage: hole ", k, " names face ", cage.holes[k], " of ", mesh.face_count()));
    }
  }
  if (cage.vertex_data.cols() > 0 && static_cast<std::size_t>(cage.vertex_data.rows()) != vertex_count) {
    throw InvalidInput(detail::message("validate_cage: vertex data has ", cage.vertex_data.rows(), " rows for ",
                                       vertex_count, " vertices"));
  }
  if (!cage.vertex_data.allFinite()) throw InvalidInput("validate_cage: vertex data has a value that is not finite");
  if (cage.face_varying) {
    const FaceVaryingData& data = *cage.face_varying;
    if (data.indices.size() != mesh.face_indices().size()) {
      throw InvalidInput(detail::message("validate_cage: face-varying data has ", data.indices.size(), " indices for ",
                                         mesh.face_indices().size(), " face corners"));
    }
    for (std::size_t c = 0; c < data.indices.size(); ++c) {
      if (data.indices[c] >= static_cast<std::size_t>(data.values.rows())) {
        throw InvalidInput(detail::message("validate_cage: face-varying index ", c, " is ", data.indices[c], " of ",
                                           data.values.rows(), " values"));
      }
    }
    if (data.values.cols() == 0) throw InvalidInput("validate_cage: face-varying values have no column");
    if (!data.values.allFinite()) {
      throw InvalidInput("validate_cage: face-varying data has a value that is not finite");
    }
  }
}

void validate_limit_cage(const SubdivisionCage& cage, const char* function) {
  validate_cage(cage);
  const detail::EdgeTable table(cage.mesh);
  const detail::OrientationWalk walk = detail::walk_orientation(cage.mesh, table);
  const auto non_orientable = std::find(walk.component_orientable.begin(), walk.component_orientable.end(), false);
  if (non_orientable != walk.component_orientable.end()) {
    const auto component = static_cast<std::size_t>(non_orientable - walk.component_orientable.begin());
    const auto face = std::find(walk.components.of_face.begin(), walk.components.of_face.end(), component) -
                      walk.components.of_face.begin();
    throw TopologyError(detail::message(function, ": the cage is not orientable (the component of face ", face,
                                        "; a Moebius band or Klein bottle): its limit surface has no consistent "
                                        "normal and is not supported; uniform refinement is"));
  }
}

const char* scheme_name(SubdivisionScheme scheme) {
  switch (scheme) {
    case SubdivisionScheme::catmull_clark:
      return "catmull-clark";
    case SubdivisionScheme::loop:
      return "loop";
    case SubdivisionScheme::bilinear:
      return "bilinear";
  }
  return "?";
}

SubdivisionScheme parse_scheme(const std::string& name) {
  for (auto scheme : {SubdivisionScheme::catmull_clark, SubdivisionScheme::loop, SubdivisionScheme::bilinear}) {
    if (name == scheme_name(scheme)) return scheme;
  }
  throw InvalidInput(
      detail::message("unknown subdivision scheme '", name, "' (expected catmull-clark, loop or bilinear)"));
}

}  // namespace patchwork
