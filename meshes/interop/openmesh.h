#pragma once
// Conversion between FaceVertexMesh and OpenMesh's polygon mesh (array kernel, double points).
//
// Numbering is kept both ways: row v of positions is OpenMesh's vertex v, face f is OpenMesh's
// face f, and each face keeps its first corner (OpenMesh stores a face by the half-edge from its
// last corner to its first; from_openmesh() reads the corners from there). So
// from_openmesh(to_openmesh(mesh)) == mesh, unreferenced vertices included.
//
// OpenMesh's half-edge structure takes more than our HalfedgeMesh: a vertex where several fans
// of faces meet (a bowtie) is stored with several boundary gaps, if the faces arrive in an order
// that lets add_face link them. What it cannot store (an edge walked twice in one direction: a
// third face at an edge, or two faces oriented inconsistently; a face repeating a vertex; a
// vertex that is already surrounded) is a TopologyError naming the face, never a dropped face.

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "meshes/face_vertex_mesh.h"

namespace patchwork {

/// OpenMesh traits with double-precision points and normals (OpenMesh's default is float).
struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};

/// OpenMesh's polygon mesh with double points: the type to_openmesh() builds.
using OpenMeshPolyMesh = OpenMesh::PolyMesh_ArrayKernelT<OpenMeshTraits>;

/// The mesh as an OpenMesh polygon mesh: vertex v and face f keep their numbers, every row of
/// positions becomes a vertex (unreferenced ones stay isolated).
/// \throws TopologyError naming the first face OpenMesh cannot add (see the file comment);
///         the check on repeated vertices runs before OpenMesh sees the face.
OpenMeshPolyMesh to_openmesh(const FaceVertexMesh& mesh);

/// The face list of an OpenMesh mesh: vertices and faces in handle order (deleted ones, if the
/// mesh has status attributes and no garbage collection ran, are skipped and the rest renumbered);
/// each face starts at the target of its stored half-edge.
/// \throws InvalidInput if a point is not finite.
FaceVertexMesh from_openmesh(const OpenMeshPolyMesh& mesh);

}  // namespace patchwork
