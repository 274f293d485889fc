#include "meshes/interop/add_faces.h"

#include "core/errors.h"

namespace patchwork::detail {
namespace {

// Why the library refused `face`.
std::string refusal_reason(const HalfedgeLibrary& library, std::span<const std::uint32_t> face) {
  for (std::size_t k = 0; k < face.size(); ++k) {
    for (std::size_t j = k + 1; j < face.size(); ++j) {
      if (face[k] == face[j]) return message("it uses vertex ", face[k], " more than once");
    }
  }
  for (std::size_t k = 0; k < face.size(); ++k) {
    const std::uint32_t a = face[k];
    const std::uint32_t b = face[(k + 1) % face.size()];
    const std::int64_t walking = library.face_walking(a, b);
    if (walking >= 0) {
      return message("edge (", a, ",", b, ") is already walked from ", a, " to ", b, " by face ", walking,
                     " (an edge with three faces, or inconsistent orientation)");
    }
  }
  for (std::uint32_t v : face) {
    if (library.surrounded(v)) return message("vertex ", v, " is already surrounded by faces (a non-manifold vertex)");
  }
  return "its vertices' fans cannot be linked (a non-manifold vertex)";
}

}  // namespace

void add_faces(const FaceVertexMesh& mesh, const char* function, const HalfedgeLibrary& library) {
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    if (!library.add_face(face)) {
      throw TopologyError(message(function, ": ", library.name, " cannot add face ", f, " (", corners_text(face),
                                  "): ", refusal_reason(library, face)));
    }
  }
}

std::string corners_text(std::span<const std::uint32_t> face) {
  std::string text;
  for (std::uint32_t v : face) {
    if (!text.empty()) text += ' ';
    text += std::to_string(v);
  }
  return text;
}

}  // namespace patchwork::detail
