#pragma once
// Conversion between FaceVertexMesh and CGAL: the Surface_mesh (a half-edge structure, for
// oriented manifold data) and the polygon soup that CGAL's Polygon_mesh_processing repairs and
// orients (points plus index lists, for anything a FaceVertexMesh holds).
//
// Numbering is kept both ways: row v of positions is Surface_mesh vertex v, face f is face f,
// and each face keeps its first corner (CGAL stores a face by the half-edge from its last corner
// to its first; from_cgal() reads the corners from there). So from_cgal(to_cgal_surface_mesh(m))
// == m and from_cgal_polygon_soup(to_cgal_polygon_soup(m)) == m, unreferenced vertices included.
//
// Surface_mesh takes a little more than our HalfedgeMesh: like OpenMesh, CGAL's add_face links a
// vertex where several fans meet (a bowtie) if the faces arrive in an order that allows it.
// What it refuses (an edge walked twice in one direction: a third face at an edge or
// inconsistent orientation; a face repeating a vertex; a vertex already surrounded) is a
// TopologyError naming the face, never a dropped face.
//
// The kernel is Simple_cartesian<double>: the coordinates are ours, unrounded; predicates on it
// are not exact (use an exact kernel for degenerate geometry).

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <cstddef>
#include <vector>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

using CgalKernel = CGAL::Simple_cartesian<double>;
using CgalPoint = CgalKernel::Point_3;
/// CGAL's Surface_mesh on double points: the type to_cgal_surface_mesh() builds.
using CgalSurfaceMesh = CGAL::Surface_mesh<CgalPoint>;

/// A polygon soup in the shape CGAL::Polygon_mesh_processing takes it (orient_polygon_soup,
/// is_polygon_soup_a_polygon_mesh, polygon_soup_to_polygon_mesh).
struct CgalPolygonSoup {
  std::vector<CgalPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
};

/// The mesh as a Surface_mesh: vertex v and face f keep their numbers, every row of positions
/// becomes a vertex (unreferenced ones stay isolated).
/// \throws TopologyError naming the first face CGAL's add_face refuses (see the file comment).
CgalSurfaceMesh to_cgal_surface_mesh(const FaceVertexMesh& mesh);

/// The face list of a Surface_mesh: vertices and faces in index order, removed ones skipped and
/// the rest renumbered; each face starts at the target of its stored half-edge.
/// \throws InvalidInput if a point is not finite.
FaceVertexMesh from_cgal(const CgalSurfaceMesh& mesh);

/// The mesh as a polygon soup (same numbering; any face list converts).
CgalPolygonSoup to_cgal_polygon_soup(const FaceVertexMesh& mesh);

/// The face list of a polygon soup (after orient_polygon_soup, say).
/// \throws TopologyError if a polygon has fewer than 3 corners or an index is out of range;
///         InvalidInput if a point is not finite.
FaceVertexMesh from_cgal_polygon_soup(const CgalPolygonSoup& soup);

}  // namespace patchwork
