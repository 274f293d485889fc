#include "meshes/halfedge_mesh.h"

#include <algorithm>
#include <stdexcept>

#include "core/errors.h"
#include "meshes/edge_table.h"

namespace patchwork {
namespace {

constexpr std::uint32_t invalid = HalfedgeId::invalid_value;

// The faces with a corner at v, ascending, as "3, 8, 12": error messages name them.
std::string faces_around(const std::vector<std::uint32_t>& origin, const std::vector<std::uint32_t>& face,
                         std::uint32_t v) {
  std::vector<std::uint32_t> faces;
  for (std::size_t h = 0; h < origin.size(); ++h) {
    if (origin[h] == v && face[h] != invalid) faces.push_back(face[h]);
  }
  std::sort(faces.begin(), faces.end());
  std::string list;
  for (std::uint32_t f : faces) list += (list.empty() ? "" : ", ") + std::to_string(f);
  return list;
}

}  // namespace

HalfedgeMesh::HalfedgeMesh(const FaceVertexMesh& mesh) : positions_(mesh.positions()) {
  const std::size_t faces = mesh.face_count();
  const auto vertices = static_cast<std::uint32_t>(mesh.vertex_count());
  const std::vector<std::uint32_t>& index = mesh.face_indices();
  if (index.size() >= 0x7fffffffu) {
    throw TopologyError(detail::message("HalfedgeMesh: ", index.size(), " corners exceed 32-bit half-edge ids"));
  }
  // 1. Faces that repeat a vertex.
  for (std::size_t f = 0; f < faces; ++f) {
    if (const auto repeated = repeated_vertex(mesh.face(f))) {
      throw TopologyError(detail::message("HalfedgeMesh: face ", f, " uses vertex ", *repeated, " more than once"));
    }
  }
  // 2. Edges: each undirected edge may be used at most twice, once in each direction.
  // (The table's arrays get room for the half-edges, up to two per corner: see step 3.)
  detail::EdgeTable table(mesh, 2 * index.size());
  const std::size_t edges = table.edge_count();
  for (std::size_t e = 0; e < edges; ++e) {
    const std::uint32_t first = table.first_use(e);
    const std::uint32_t second = table.twin(first);
    if (second == detail::EdgeTable::crowded) {
      const auto [from, to] = table.vertices(e);
      std::string list;
      for (const detail::EdgeUse use : table.uses(e)) list += (list.empty() ? "" : ", ") + std::to_string(use.face);
      throw TopologyError(detail::message("HalfedgeMesh: edge (", from, ",", to, ") used by ", table.use_count(e),
                                          " faces (", list, ")"));
    }
    if (second != detail::EdgeTable::none && index[first] == index[second]) {
      const auto [from, to] = table.vertices(e);
      throw TopologyError(detail::message("HalfedgeMesh: faces ", table.face_of(first), " and ", table.face_of(second),
                                          " both traverse edge (", from, ",", to, ") from ", from,
                                          ": inconsistent orientation (or a non-orientable surface)"));
    }
  }
  // 3. Half-edges: 2e in the direction of the edge's first use, 2e+1 the other way. The table's
  // arrays become the mesh's, whose memory is touched already (at a million faces fresh pages
  // cost more than the work): the twins turn into each corner's half-edge and then into prev_,
  // the first uses into next_, the spare array into vertex_halfedge_.
  const std::size_t halfedges = 2 * edges;
  detail::EdgeTable::Arrays arrays = table.release();
  std::vector<std::uint32_t>& corner_halfedge = arrays.twin;
  origin_.resize(halfedges);
  face_.assign(halfedges, invalid);
  for (std::uint32_t e = 0; e < edges; ++e) {
    const std::uint32_t first = arrays.first_use[e];
    const std::uint32_t second = corner_halfedge[first];  // still the twin: only e's corners are rewritten here
    origin_[2 * e] = index[first];
    origin_[2 * e + 1] = index[table.next_corner(first)];
    face_[2 * e] = table.face_of(first);
    corner_halfedge[first] = 2 * e;
    if (second != detail::EdgeTable::none) {
      face_[2 * e + 1] = table.face_of(second);
      corner_halfedge[second] = 2 * e + 1;
    }
  }
  next_ = std::move(arrays.first_use);
  next_.resize(halfedges);  // every entry is written below (faces here, the boundary in step 4)
  face_halfedge_.resize(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const std::size_t first = mesh.first_corner(f), end = mesh.first_corner(f + 1);
    face_halfedge_[f] = corner_halfedge[first];
    for (std::size_t c = first; c + 1 < end; ++c) next_[corner_halfedge[c]] = corner_halfedge[c + 1];
    next_[corner_halfedge[end - 1]] = corner_halfedge[first];
  }
  prev_ = std::move(corner_halfedge);
  prev_.resize(halfedges);  // likewise
  for (std::uint32_t h = 0; h < halfedges; ++h) {
    if (face_[h] != invalid) prev_[next_[h]] = h;
  }
  // 4. Boundary half-edges: each boundary vertex has exactly one outgoing boundary half-edge on
  // a manifold; the one arriving at v continues with it.
  vertex_halfedge_ = std::move(arrays.spare);
  vertex_halfedge_.assign(vertices, invalid);
  std::vector<std::uint32_t> outgoing_count(vertices, 0);
  for (std::uint32_t h = 0; h < halfedges; ++h) {
    const std::uint32_t v = origin_[h];
    ++outgoing_count[v];
    if (face_[h] == invalid) {
      if (vertex_halfedge_[v] != invalid && face_[vertex_halfedge_[v]] == invalid) {
        throw TopologyError(detail::message("HalfedgeMesh: vertex ", v, " is on the boundary more than once (its faces ",
                                            faces_around(origin_, face_, v), " form several fans)"));
      }
      vertex_halfedge_[v] = h;
    } else if (vertex_halfedge_[v] == invalid) {
      vertex_halfedge_[v] = h;
    }
  }
  for (std::uint32_t h = 0; h < halfedges; ++h) {
    if (face_[h] != invalid) continue;
    const std::uint32_t following = vertex_halfedge_[origin_[h ^ 1u]];  // leaves destination(h)
    next_[h] = following;
    prev_[following] = h;
  }
  // 5. Every vertex's half-edges must form one fan: one rotation visits all of them.
  for (std::uint32_t v = 0; v < vertices; ++v) {
    const HalfedgeId start(vertex_halfedge_[v]);
    if (!start.valid()) continue;
    std::uint32_t visited = 0;
    HalfedgeId h = start;
    do {
      ++visited;
      h = twin(prev(h));
    } while (h != start && visited <= outgoing_count[v]);
    if (visited != outgoing_count[v]) {
      throw TopologyError(detail::message("HalfedgeMesh: the faces around vertex ", v, " (faces ",
                                          faces_around(origin_, face_, v),
                                          ") form several fans (a non-manifold vertex)"));
    }
  }
}

std::size_t HalfedgeMesh::face_size(FaceId f) const {
  std::size_t size = 0;
  HalfedgeId h = halfedge(f);
  do {
    ++size;
    h = next(h);
  } while (h != halfedge(f));
  return size;
}

std::vector<VertexId> HalfedgeMesh::face_vertices(FaceId f) const {
  std::vector<VertexId> result;
  HalfedgeId h = halfedge(f);
  do {
    result.push_back(origin(h));
    h = next(h);
  } while (h != halfedge(f));
  return result;
}

std::vector<VertexId> HalfedgeMesh::vertex_neighbours(VertexId v) const {
  std::vector<VertexId> result;
  const HalfedgeId start = halfedge(v);
  if (!start.valid()) return result;
  HalfedgeId h = start;
  do {
    result.push_back(destination(h));
    h = twin(prev(h));
  } while (h != start);
  return result;
}

void HalfedgeMesh::validate() const {
  const auto fail = [](const std::string& what) { throw std::logic_error("HalfedgeMesh::validate: " + what); };
  const std::size_t H = halfedge_count();
  if (H % 2 != 0 || next_.size() != H || prev_.size() != H || face_.size() != H) fail("array sizes differ");
  for (std::uint32_t i = 0; i < H; ++i) {
    const HalfedgeId h(i);
    if (twin(twin(h)) != h) fail(detail::message("twin(twin(", h, ")) != ", h));
    if (!next(h).valid() || !prev(h).valid()) fail(detail::message(h, " has no next or prev"));
    if (next(prev(h)) != h || prev(next(h)) != h) fail(detail::message("next/prev of ", h, " disagree"));
    if (origin(next(h)) != destination(h)) fail(detail::message("next(", h, ") does not start where ", h, " ends"));
    if (origin(twin(h)) == origin(h)) fail(detail::message(h, " and its twin share their origin"));
    if (face(next(h)) != face(h)) fail(detail::message(h, " and next(", h, ") lie in different faces"));
    if (origin(h).index() >= vertex_count()) fail(detail::message("origin of ", h, " out of range"));
    if (is_boundary(h) && is_boundary(twin(h))) fail(detail::message("edge ", edge(h), " has no face"));
  }
  for (std::uint32_t i = 0; i < face_count(); ++i) {
    const FaceId f(i);
    if (face(halfedge(f)) != f) fail(detail::message("halfedge(", f, ") is not in ", f));
    std::size_t steps = 0;
    HalfedgeId h = halfedge(f);
    do {
      h = next(h);
      if (++steps > H) fail(detail::message("the cycle of ", f, " does not close"));
    } while (h != halfedge(f));
  }
  std::vector<std::uint32_t> outgoing(vertex_count(), 0);
  for (std::uint32_t i = 0; i < H; ++i) ++outgoing[origin(HalfedgeId(i)).index()];
  for (std::uint32_t i = 0; i < vertex_count(); ++i) {
    const VertexId v(i);
    if (is_isolated(v)) {
      if (outgoing[i] != 0) fail(detail::message(v, " has half-edges but none is recorded"));
      continue;
    }
    if (origin(halfedge(v)) != v) fail(detail::message("halfedge(", v, ") does not leave ", v));
    std::uint32_t visited = 0;
    HalfedgeId h = halfedge(v);
    do {
      if (is_boundary(h) && h != halfedge(v)) fail(detail::message(v, " has a second outgoing boundary half-edge"));
      h = twin(prev(h));
      if (++visited > outgoing[i]) break;
    } while (h != halfedge(v));
    if (visited != outgoing[i]) fail(detail::message("the fan of ", v, " is not one cycle"));
  }
}

FaceVertexMesh to_face_vertex_mesh(const HalfedgeMesh& mesh) {
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint32_t> indices;
  sizes.reserve(mesh.face_count());
  for (std::uint32_t f = 0; f < mesh.face_count(); ++f) {
    const std::vector<VertexId> corners = mesh.face_vertices(FaceId(f));
    sizes.push_back(static_cast<std::uint32_t>(corners.size()));
    for (VertexId v : corners) indices.push_back(v.value);
  }
  return FaceVertexMesh(mesh.positions(), std::move(sizes), std::move(indices));
}

}  // namespace patchwork
