#pragma once
// glTF 2.0 output of a render mesh (meshes/render_mesh.h), and reading one triangle mesh back.
//
//   .glb   binary glTF: a 12-byte header, a JSON chunk and a BIN chunk holding the buffer
//   .gltf  JSON only, the buffer embedded as a data: URI (one self-contained file)
//
// What write_gltf produces (the Khronos validator reports no error and no warning on it,
// tests/io/gltf_test.cpp checks that with tools/gltf-validate):
//   asset         version "2.0", generator "patchwork"
//   scene 0       one node (named by GltfOptions::name, its translation the centre of the
//                 positions' box) holding one mesh (the same name) of one primitive, mode
//                 TRIANGLES, with material 0
//   material 0    "default": pbrMetallicRoughness with baseColorFactor (0.8, 0.8, 0.8, 1),
//                 metallicFactor 0, roughnessFactor 0.5; doubleSided as GltfOptions::double_sided
//   attributes    POSITION (float VEC3, with min/max), NORMAL (float VEC3), TEXCOORD_0 (float
//                 VEC2), TANGENT (float VEC4): each present when the mesh has it
//   indices       UNSIGNED_SHORT when the mesh has at most 65535 vertices (so the restart value
//                 65535 never appears), else UNSIGNED_INT
//   buffer        one buffer; one bufferView per accessor, in the order above with the indices
//                 last, each starting at a multiple of 4 bytes (zero padding), no byteStride,
//                 target ARRAY_BUFFER (34962) for attributes, ELEMENT_ARRAY_BUFFER (34963) for
//                 indices; the buffer's length is a multiple of 4
//
// Conventions. Units are meters, as in glTF. Triangles keep their order and their corners, so
// counter-clockwise front faces stay front faces. patchwork is Z-up, glTF is Y-up: with z_up
// set (the default) every position, normal and tangent direction (x, y, z) is written as
// (x, z, -y) and read back as (X, -Z, Y), a rotation about +x by -90 degrees (so it keeps the
// winding; negation is exact, so the map itself loses nothing). Values are stored as float32:
//   positions  relative to the centre t of their box (glTF's axes), stored as the node's
//              translation (JSON numbers are doubles, kept exactly): each position p is written
//              as the float f = float(fl(p - t)), and reads back as fl(f + t). The rounding
//              |fl(f + t) - p| is then relative to the box's half extent, not to |p| (the teapot
//              moved to (1e5, -2e5, 3e4): about 1e-7 instead of 0.0078); its bound is returned
//              by encode_gltf_levels / write_gltf (position_rounding). POSITION min/max are the
//              min/max of the stored floats. A centred mesh (t = 0) gets no translation.
//   normals    normalised in double (validate() allows 1e-6 slack), then rounded to float once,
//              so the stored length is 1 to within about 1e-7
//   tangents   xyz as normals; w is +1 or -1 exactly
//   uvs        rounded to float, written as they are (glTF puts uv (0, 0) at the top-left
//              corner of an image; patchwork's uvs are surface parameters and are not flipped)
// Reading a file written here therefore gives every value rounded to float and back, exactly,
// the positions as fl(float(fl(p - t)) + t).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meshes/render_mesh.h"

namespace patchwork {

/// The two glTF containers.
enum class GltfFormat {
  glb,   ///< binary .glb
  gltf,  ///< JSON .gltf with the buffer as a data: URI
};

/// How write_gltf orients, shows and names the mesh.
struct GltfOptions {
  /// The mesh is Z-up (patchwork's convention): write (x, y, z) as (x, z, -y) for glTF's +Y up.
  bool z_up = true;
  /// The material's doubleSided; unset: true exactly when the mesh has a boundary edge, an edge
  /// of welded_faces(mesh) used by one triangle (an open surface shows its back side).
  std::optional<bool> double_sided = std::nullopt;
  /// The name of the node and of the mesh.
  std::string name = "patchwork";
};

/// The bytes of the glTF file of `mesh` in `format` (see the file comment for the layout).
/// \throws InvalidInput if validate(mesh) fails, the mesh has no triangle (glTF accessors hold at
///         least one element), it has tangents but no normals (glTF ignores tangents without
///         normals), a value does not fit in a float, or the buffer would exceed 4 GiB.
std::string format_gltf(const RenderMesh& mesh, GltfFormat format, const GltfOptions& options = {});

/// A level-of-detail chain in one file (glTF's MSFT_lod on nodes): levels[0] is the finest and is
/// node 0, the one node of the scene; levels[k] is node and mesh k, named "<name>_lod<k>", outside
/// the scene and listed in node 0's extension "MSFT_lod": {"ids": [1, ..., K]}; node 0's extras
/// hold "MSFT_screencoverage": coverage, one value per level, the screen coverage down to which
/// that level is meant to be shown (non-increasing, in [0, 1]; the last is where nothing need be
/// drawn). All levels share material 0 (doubleSided from levels[0] unless given). A client that
/// knows no MSFT_lod shows levels[0]. Every level is stored from the centre of levels[0]'s box,
/// every node's translation. One level gives exactly format_gltf's file.
/// \throws InvalidInput as format_gltf for any level, for no level, or if more than one level
///         comes without exactly one coverage per level or with coverages out of order.
std::string format_gltf_levels(std::span<const RenderMesh> levels, std::span<const double> coverage, GltfFormat format,
                               const GltfOptions& options = {});

/// A glTF file's bytes, and how far its positions are from the mesh's.
struct GltfEncoding {
  std::string bytes;
  /// Per level (one for a single mesh): a bound, rigorous under round-to-nearest, on the largest
  /// distance between a vertex's position p and where the file puts it, both the exact f + t of
  /// its float offset f and node translation t and the double fl(f + t) parse_gltf returns. A
  /// mesh whose error from a surface is at most e is, as written, within e + position_rounding,
  /// for a consumer that adds the translation in double precision (a float32 pipeline rounds
  /// f + t to float again and can do no better than float itself at |t|).
  std::vector<double> position_rounding;
};

/// The file format_gltf_levels gives, with the rounding of its positions.
/// \throws InvalidInput as format_gltf_levels.
GltfEncoding encode_gltf_levels(std::span<const RenderMesh> levels, std::span<const double> coverage, GltfFormat format,
                                const GltfOptions& options = {});

/// Writes `mesh` as .glb or .gltf, chosen by the extension (compared without regard to case),
/// atomically (io/atomic_file.h): a failed write leaves no partial file. The file has format_gltf's
/// bytes, but the buffer is never held whole: it goes to the file straight from the mesh's arrays,
/// detail::gltf_chunk_elements elements at a time (docs/io.md, "Memory"). Returns the bound on the
/// rounding of its positions (GltfEncoding::position_rounding).
/// \throws IoError naming the path for another extension or a failed write; InvalidInput as
///         format_gltf (nothing written: every check runs before the file is created).
double write_gltf(const std::filesystem::path& path, const RenderMesh& mesh, const GltfOptions& options = {});

/// Writes a level-of-detail chain (format_gltf_levels) as write_gltf writes one mesh; returns the
/// position rounding of each level.
std::vector<double> write_gltf_levels(const std::filesystem::path& path, std::span<const RenderMesh> levels,
                                      std::span<const double> coverage, const GltfOptions& options = {});

namespace detail {

/// How many elements (vertices of one attribute, or indices) the writer converts to the file's
/// types at once: the part of the buffer it holds (at most 16 bytes an element, 1 MiB).
inline constexpr std::size_t gltf_chunk_elements = std::size_t{1} << 16;

/// format_gltf_levels converting `chunk` elements at a time instead of gltf_chunk_elements: the
/// same bytes for every chunk (what tests check). \throws InvalidInput as format_gltf_levels, or
/// for a chunk of 0.
std::string format_gltf_levels_in_chunks(std::span<const RenderMesh> levels, std::span<const double> coverage,
                                         GltfFormat format, const GltfOptions& options, std::size_t chunk);

}  // namespace detail

/// The most memory parse_gltf lets the scene graph's placements of the mesh take (8 GiB): a
/// small file can place a large mesh many times.
inline constexpr std::uint64_t gltf_max_expanded_bytes = std::uint64_t{8} << 30;

/// Parses the bytes of a .glb or .gltf file (told apart by the "glTF" magic) written by anyone,
/// holding exactly one mesh primitive, of mode TRIANGLES: POSITION (float), optional NORMAL
/// (float), TEXCOORD_0 (float, or normalised unsigned byte/short) and TANGENT (float), indices
/// unsigned byte/short/int or none (then vertices 0 1 2, 3 4 5, ...). Positions, normals and
/// tangents are converted back to Z-up when `z_up` is set. Normals and tangents more than 1e-6
/// from unit length are renormalised. position_ids weld vertices with equal positions (equal
/// floats; -0 equals +0): a vertex's id is the first vertex with its position. The mesh is placed
/// by the scene graph (docs/io.md "Node transforms"): once per node holding it in the default
/// scene (scene 0 if none is named; without scenes, under every node that is no node's child;
/// without nodes, once as stored), each node's matrix or T * R * S composed down the hierarchy, in
/// glTF's axes before the Z-up map; normals by the inverse transpose, renormalised; a negative
/// determinant swaps each triangle's last two corners and flips tangent w. Materials and other
/// attributes are not read. `path` names the file in messages, and its folder
/// is where buffers (and images) in other files are read: a URI is a data: URI or a relative path
/// (percent-decoded, as tinygltf decodes it) to a regular file inside that folder, with no ".."
/// and no symbolic link leading out of it; the file read is the one checked (its canonical path,
/// not followed if a link replaced it since), its size checked before it is read.
/// \throws ParseError naming `path` if the bytes are no such glTF (a required extension, sparse
///         accessors, values that are not finite, a zero normal, tangent w other than +-1, an
///         index out of range, data outside its buffer, a buffer file that cannot be read, a
///         buffer or image URI naming a file outside the folder, naming the URI; a node hierarchy
///         with a cycle or a node with two parents, a singular or non-affine transform, a
///         non-finite one, a zero quaternion, a skinned node, a vertex not finite after its
///         node's transform, naming the node; a default scene that does not exist; morph
///         targets; placements taking more than gltf_max_expanded_bytes).
RenderMesh parse_gltf(std::string_view bytes, const std::filesystem::path& path, bool z_up = true);

/// Reads a .glb or .gltf file as parse_gltf does.
/// \throws IoError if it cannot be read, ParseError (naming the file) if it is malformed.
RenderMesh read_gltf(const std::filesystem::path& path, bool z_up = true);

}  // namespace patchwork
