#pragma once
// A subdivision cage: a polygon mesh with the tags and options that decide its limit surface
// (seed 3.2.1; the conventions of OpenSubdiv's Sdc, whose library does the work, see
// subdivision/refine.h). No OpenSubdiv type appears here.
//
//   scheme            Catmull-Clark (any polygons; quads after one level), Loop (triangles only)
//                     or bilinear (any polygons; the limit is the bilinear cage itself)
//   creases           edges with a sharpness: 0 smooth, s > 0 sharp for s levels then smooth,
//                     infinity (or >= 10, OpenSubdiv's infinite) sharp for ever
//   corners           vertices with a sharpness, likewise
//   holes             faces that take part in the refinement of their neighbours but produce no
//                     surface of their own
//   boundary          how boundary vertices are interpolated: none (the boundary faces are only
//                     support), edges (boundary edges become B-spline curves), edges and corners
//                     (and corners of valence 2 stay put)
//   face-varying      one optional channel of per-corner values (UVs: values plus an index per
//                     face corner, so seams can have two values at one vertex), with its own
//                     linear-interpolation rule
//   vertex data       any number of per-vertex columns (colours, a second UV set) interpolated
//                     like the positions
//
// validate_cage() checks everything before OpenSubdiv sees it: OpenSubdiv clamps some values
// silently and accepts topology (non-manifold, inconsistently oriented) whose limit surface is
// not a surface. A non-orientable cage (Moebius band, Klein bottle) refines uniformly; its limit
// surface is refused (validate_limit_cage()).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// The subdivision rules.
enum class SubdivisionScheme { catmull_clark, loop, bilinear };

/// How boundary vertices are interpolated (Sdc::Options::VtxBoundaryInterpolation).
enum class BoundaryInterpolation { none, edges, edges_and_corners };

/// Where face-varying values are interpolated linearly (Sdc::Options::FVarLinearInterpolation).
enum class FaceVaryingInterpolation { none, corners_only, corners_plus1, corners_plus2, boundaries, all };

/// A sharp edge: the cage edge from `a` to `b` (either direction).
struct Crease {
  std::uint32_t a;
  std::uint32_t b;
  /// >= 0; infinity (or anything >= 10) is infinitely sharp.
  double sharpness;
};

/// A sharp vertex.
struct Corner {
  std::uint32_t vertex;
  /// >= 0; infinity (or anything >= 10) is infinitely sharp.
  double sharpness;
};

/// Per-corner values with their own indices (UVs with seams).
struct FaceVaryingData {
  /// One row per value.
  Eigen::MatrixXd values;
  /// One value index per face corner, in face_indices() order.
  std::vector<std::uint32_t> indices;
};

struct SubdivisionOptions {
  SubdivisionScheme scheme = SubdivisionScheme::catmull_clark;
  BoundaryInterpolation boundary = BoundaryInterpolation::edges_and_corners;
  FaceVaryingInterpolation face_varying = FaceVaryingInterpolation::all;
};

struct SubdivisionCage {
  FaceVertexMesh mesh;
  std::vector<Crease> creases;
  std::vector<Corner> corners;
  /// Face indices.
  std::vector<std::uint32_t> holes;
  /// One row per vertex, any number of columns (zero columns: none).
  Eigen::MatrixXd vertex_data;
  std::optional<FaceVaryingData> face_varying;
  SubdivisionOptions options;
};

/// The sharpness OpenSubdiv treats as infinite.
inline constexpr double infinitely_sharp = 10.0;

/// Checks that the cage can be subdivided: at least one face; a manifold mesh (each edge in at
/// most two faces, every vertex one fan) whose orientable components are consistently oriented
/// (the two faces of an edge walk it in opposite directions; orient_cage() makes them so);
/// non-orientable components are accepted (OpenSubdiv refines an edge walked the same way by
/// both its faces as a non-manifold seam, an infinitely sharp edge);
/// triangles only for Loop, no two of them on the same three vertices; creases on cage edges, corners and holes in
/// range, sharpness >= 0 and not NaN; vertex data with one row per vertex; face-varying indices one per corner and in
/// range; every value finite.
/// \throws TopologyError for the connectivity, InvalidInput for the rest, naming the element.
void validate_cage(const SubdivisionCage& cage);

/// validate_cage(), and every component orientable, as the limit surface needs (a consistent
/// normal): the check of LimitSurface and limit_at_vertices, named `function` in the message.
/// \throws what validate_cage() throws; TopologyError for a non-orientable cage.
void validate_limit_cage(const SubdivisionCage& cage, const char* function);

/// Readable scheme name: "catmull-clark", "loop", "bilinear".
const char* scheme_name(SubdivisionScheme scheme);
/// The scheme with that name. \throws InvalidInput for any other name.
SubdivisionScheme parse_scheme(const std::string& name);

}  // namespace patchwork
