// parse_gltf and read_gltf (io/gltf.h): the strict reader, its file confinement and the scene
// graph; io/gltf.cpp writes.

#include "io/gltf.h"

// Debian ships tinygltf as a shared library built with its defaults (stb_image, stb_image_write,
// nlohmann/json, the file system callbacks): include the header plainly, without
// TINYGLTF_IMPLEMENTATION or any TINYGLTF_NO_* macro, so our view of its classes is the library's.
#include <tiny_gltf.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "meshes/topology.h"

namespace patchwork {
namespace {

// Y-up back to Z-up: (X, Y, Z) -> (X, -Z, Y), the inverse rotation.
Vec3 from_gltf_axes(const Vec3& v, bool z_up) { return z_up ? Vec3(v.x(), -v.z(), v.y()) : v; }


// tinygltf decodes images while loading; we read no image, so we skip them undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// The file system tinygltf sees while loading: only regular files inside the folder of the glTF
// file, named by relative paths without "..", whatever symbolic links they pass through. tinygltf
// percent-decodes a buffer's or image's URI and joins it to the folder (then to "."); these
// callbacks get the joined path, so they judge exactly what it would open.
struct Confinement {
  std::string prefix;          // the canonical folder and '/', as tinygltf joins a URI to it
  std::filesystem::path root;  // the canonical folder
  std::string refused;         // why the first refused URI was refused; empty if none
};

std::string unexpanded(const std::string& path, void*) { return path; }  // no "~" or "$VAR"

// The canonical path of `path` when it is a regular file inside the folder, else nothing;
// records why not when a URI names a file elsewhere.
std::optional<std::filesystem::path> confined(const std::string& path, Confinement& confinement) {
  namespace fs = std::filesystem;
  if (confinement.root.empty()) {  // the folder has no absolute path (no working directory)
    if (confinement.refused.empty()) confinement.refused = "the folder of the glTF file has no absolute path";
    return std::nullopt;
  }
  if (!path.starts_with(confinement.prefix)) return std::nullopt;  // tinygltf's second try, relative to "."
  const std::string uri = path.substr(confinement.prefix.size());
  const auto refuse = [&](const std::string& why) -> std::optional<fs::path> {
    if (confinement.refused.empty()) {
      confinement.refused =
          detail::message("the file '", uri, "' named by a buffer or image URI (percent-decoded) ", why,
                          ": only data: URIs and files inside the folder of the glTF file are read");
    }
    return std::nullopt;
  };
  if (uri.empty()) return std::nullopt;
  const fs::path relative(uri);
  if (relative.is_absolute()) return refuse("is an absolute path");
  for (const fs::path& part : relative) {
    if (part == "..") return refuse("goes up out of the folder with '..'");
  }
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(fs::path(path), error);
  if (error) return std::nullopt;
  const auto [in_root, in_resolved] =
      std::mismatch(confinement.root.begin(), confinement.root.end(), resolved.begin(), resolved.end());
  if (in_root != confinement.root.end()) {
    return refuse("leads out of the folder through a symbolic link, to " + resolved.string());
  }
  if (!fs::is_regular_file(resolved, error)) return std::nullopt;
  return resolved;
}

bool confined_exists(const std::string& path, void* confinement) {
  return confined(path, *static_cast<Confinement*>(confinement)).has_value();
}

// Reads the canonical path that confined() checked, not the path as joined: the file opened is
// the one judged (a symbolic link put in its place afterwards is not followed, O_NOFOLLOW), and
// its size is checked on the open file before anything is read (a buffer is at most 4 GiB).
bool confined_read(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* confinement) {
  const std::optional<std::filesystem::path> resolved = confined(path, *static_cast<Confinement*>(confinement));
  if (!resolved) {
    *error = "not a file inside the folder of the glTF file";
    return false;
  }
  const int fd = ::open(resolved->c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    *error = detail::message(resolved->string(), ": cannot open: ", std::strerror(errno));
    return false;
  }
  struct stat status {};
  bool ok = ::fstat(fd, &status) == 0 && S_ISREG(status.st_mode);
  if (!ok) *error = detail::message(resolved->string(), ": not a regular file");
  if (ok && static_cast<std::uint64_t>(status.st_size) > std::numeric_limits<unsigned int>::max()) {
    *error = detail::message(resolved->string(), ": ", status.st_size, " bytes, larger than a buffer can be (4 GiB)");
    ok = false;
  }
  if (ok) {
    out->resize(static_cast<std::size_t>(status.st_size));
    std::size_t done = 0;
    while (ok && done < out->size()) {
      const ssize_t got = ::read(fd, out->data() + done, out->size() - done);
      if (got <= 0) {
        *error = detail::message(resolved->string(), ": read failed", got < 0 ? std::string(": ") + std::strerror(errno) : "");
        ok = false;
      } else {
        done += static_cast<std::size_t>(got);
      }
    }
  }
  ::close(fd);
  return ok;
}

bool refuse_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// What an accessor may hold.
enum class Components {
  floats,     // float
  texcoords,  // float, or normalised unsigned byte / unsigned short
  indices,    // unsigned byte, unsigned short or unsigned int, not normalised
};

// The accessors of one loaded model, read as doubles with every range checked.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, std::string name) : model_(model), name_(std::move(name)) {}

  const tinygltf::Model& model() const { return model_; }

  [[noreturn]] void fail(const std::string& message) const { throw ParseError(name_, 0, 0, message); }

  /// The values of accessor `index` (`components` per element, `count` elements), flat.
  std::vector<double> values(int index, int components, Components allowed, const std::string& what) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
      fail(detail::message(what, ": accessor ", index, " does not exist"));
    }
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
    const std::string where = detail::message(what, " (accessor ", index, ")");
    if (accessor.sparse.isSparse) fail(where + ": sparse accessors are not supported");
    const int type = components == 1 ? TINYGLTF_TYPE_SCALAR : components;
    if (accessor.type != type) fail(detail::message(where, ": type ", accessor.type, ", expected ", type));
    const int component_size = checked_component_size(accessor, allowed, where);
    if (accessor.count == 0) fail(where + ": no elements");
    if (accessor.bufferView < 0 || static_cast<std::size_t>(accessor.bufferView) >= model_.bufferViews.size()) {
      fail(where + ": no bufferView");
    }
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
      fail(where + ": its bufferView has no buffer");
    }
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    const std::uint64_t element_size = static_cast<std::uint64_t>(component_size) * static_cast<std::uint64_t>(components);
    const std::uint64_t stride = view.byteStride != 0 ? view.byteStride : element_size;
    if (stride < element_size) fail(detail::message(where, ": byteStride ", stride, " < element size ", element_size));
    // view within the buffer, accessor within the view (no product can overflow: count is
    // compared with the view's length first).
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset ||
        accessor.byteOffset > view.byteLength || element_size > view.byteLength - accessor.byteOffset ||
        accessor.count - 1 > (view.byteLength - accessor.byteOffset - element_size) / stride) {
      fail(where + ": data outside its bufferView or buffer");
    }
    const unsigned char* base = data.data() + view.byteOffset + accessor.byteOffset;
    std::vector<double> out;
    out.reserve(accessor.count * static_cast<std::size_t>(components));
    for (std::size_t e = 0; e < accessor.count; ++e) {
      for (int c = 0; c < components; ++c) {
        out.push_back(component(base + e * stride + static_cast<std::size_t>(c * component_size), accessor));
      }
    }
    return out;
  }

  /// The number of elements of accessor `index` (which exists: values() was called on it).
  std::size_t count(int index) const { return model_.accessors[static_cast<std::size_t>(index)].count; }

 private:
  int checked_component_size(const tinygltf::Accessor& accessor, Components allowed, const std::string& where) const {
    const int type = accessor.componentType;
    const bool is_float = type == TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized;
    const bool small_unsigned =
        type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    bool ok = false;
    switch (allowed) {
      case Components::floats:
        ok = is_float;
        break;
      case Components::texcoords:
        ok = is_float || (small_unsigned && accessor.normalized);
        break;
      case Components::indices:
        ok = (small_unsigned || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) && !accessor.normalized;
        break;
    }
    if (!ok) {
      fail(detail::message(where, ": componentType ", type, accessor.normalized ? " (normalized)" : "", " not allowed here"));
    }
    return type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 1 : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2 : 4;
  }

  // One component as a double; normalised integers map to [0, 1].
  static double component(const unsigned char* at, const tinygltf::Accessor& accessor) {
    switch (accessor.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float x;
        std::memcpy(&x, at, sizeof x);
        return x;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return accessor.normalized ? *at / 255.0 : *at;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t x;
        std::memcpy(&x, at, sizeof x);
        return accessor.normalized ? x / 65535.0 : x;
      }
      default: {
        std::uint32_t x;
        std::memcpy(&x, at, sizeof x);
        return x;
      }
    }
  }

  const tinygltf::Model& model_;
  std::string name_;
};

// A direction read from a file, renormalised if more than 1e-6 from unit length.
Vec3 read_direction(const double* xyz, const AccessorReader& reader, const char* what, std::size_t v) {
  Vec3 d(xyz[0], xyz[1], xyz[2]);
  if (!d.allFinite()) reader.fail(detail::message(what, " of vertex ", v, " is not finite"));
  const double length = d.norm();
  if (length == 0) reader.fail(detail::message(what, " of vertex ", v, " is zero"));
  if (std::abs(length - 1) > 1e-6) d /= length;
  return d;
}

// Position ids welding equal positions: each vertex gets the first vertex with its position.
std::vector<std::uint32_t> weld_equal_positions(const std::vector<Vec3>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  // Lexicographic on values (-0 == +0); stable, so each run of equal positions starts at its
  // smallest vertex.
  const auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3& p = positions[a];
    const Vec3& q = positions[b];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::stable_sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> ids(positions.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool starts_run = k == 0 || less(order[k - 1], order[k]);
    ids[order[k]] = starts_run ? order[k] : ids[order[k - 1]];
  }
  return ids;
}

// ---------------------------------------------------------------------------------------------
// The scene graph (glTF 2.0, 3.5 "Nodes and Hierarchy")

using Affine = Eigen::Transform<double, 3, Eigen::Affine>;

// "node 3" or "node 3 ('lid')", for messages.
std::string node_name(const tinygltf::Model& model, std::size_t k) {
  const std::string& name = model.nodes[k].name;
  return name.empty() ? detail::message("node ", k) : detail::message("node ", k, " ('", name, "')");
}

// Node k's local transform: its matrix (column-major), or T * R * S from translation, rotation
// (a quaternion x, y, z, w, normalised here) and scale, each the identity when absent.
Affine local_transform(const tinygltf::Model& model, std::size_t k, const AccessorReader& reader) {
  const tinygltf::Node& node = model.nodes[k];
  const auto fail = [&](const std::string& what) { reader.fail(node_name(model, k) + ": " + what); };
  const auto finite = [](const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
  };
  Affine transform = Affine::Identity();
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16 || !finite(node.matrix)) fail("matrix is not 16 finite numbers");
    Eigen::Matrix4d m;
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) m(row, column) = node.matrix[static_cast<std::size_t>(4 * column + row)];
    }
    if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) fail("matrix is not affine (its last row is not 0 0 0 1)");
    transform.matrix() = m;
  } else {
    if (!node.translation.empty() && (node.translation.size() != 3 || !finite(node.translation))) {
      fail("translation is not 3 finite numbers");
    }
    if (!node.rotation.empty() && (node.rotation.size() != 4 || !finite(node.rotation))) {
      fail("rotation is not 4 finite numbers");
    }
    if (!node.scale.empty() && (node.scale.size() != 3 || !finite(node.scale))) fail("scale is not 3 finite numbers");
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    if (!node.rotation.empty()) {
      const Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (!(q.norm() > 0)) fail("rotation is the zero quaternion");
      linear = q.normalized().toRotationMatrix();
    }
    if (!node.scale.empty()) linear = linear * Vec3(node.scale[0], node.scale[1], node.scale[2]).asDiagonal();
    transform.linear() = linear;
    if (!node.translation.empty()) {
      transform.translation() = Vec3(node.translation[0], node.translation[1], node.translation[2]);
    }
  }
  const double det = transform.linear().determinant();
  if (!(det != 0) || !std::isfinite(det)) fail(detail::message("transform is singular (determinant ", det, ")"));
  return transform;
}

// One placement of the mesh: the node holding it (none: the mesh as it is) and its world transform.
struct MeshInstance {
  std::size_t node;
  Affine world;
};
constexpr std::size_t no_node = static_cast<std::size_t>(-1);

// The world transform of every node holding mesh 0, in the order a depth-first walk of the
// scene meets them: the roots of the default scene (scene 0 if none is named), or, without
// scenes, every node that is no node's child. Without nodes, the mesh once as it is. A skinned
// node is refused (its joints move the vertices, which is not read).
std::vector<MeshInstance> mesh_instances(const tinygltf::Model& model, const AccessorReader& reader) {
  const std::size_t count = model.nodes.size();
  if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) >= model.scenes.size()) {
    reader.fail(detail::message("the default scene ", model.defaultScene, " does not exist (the file has ",
                                model.scenes.size(), " scenes)"));
  }
  if (count == 0) return {{no_node, Affine::Identity()}};
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  std::vector<std::size_t> parent(count, none);
  for (std::size_t k = 0; k < count; ++k) {
    for (const int child : model.nodes[k].children) {
      if (child < 0 || static_cast<std::size_t>(child) >= count) {
        reader.fail(detail::message(node_name(model, k), ": child ", child, " does not exist"));
      }
      const auto c = static_cast<std::size_t>(child);
      if (parent[c] != none) {
        reader.fail(detail::message(node_name(model, c), " has two parents (", parent[c], " and ", k,
                                    "): the nodes do not form trees"));
      }
      parent[c] = k;
    }
  }
  // A cycle: walking up from a node comes back to it. Each walk stops at a node already cleared.
  std::vector<std::uint8_t> state(count, 0);  // 0 unvisited, 1 on the current walk, 2 cleared
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t v = k;
    while (v != none && state[v] == 0) {
      state[v] = 1;
      v = parent[v];
    }
    if (v != none && state[v] == 1) {
      reader.fail(detail::message(node_name(model, v), " is its own ancestor (a cycle in the node hierarchy)"));
    }
    for (v = k; v != none && state[v] == 1; v = parent[v]) state[v] = 2;
  }
  std::vector<std::size_t> roots;
  if (!model.scenes.empty()) {
    const std::size_t scene = model.defaultScene >= 0 ? static_cast<std::size_t>(model.defaultScene) : 0;
    std::vector<bool> listed(count, false);
    for (const int root : model.scenes[scene].nodes) {
      if (root < 0 || static_cast<std::size_t>(root) >= count) {
        reader.fail(detail::message("scene ", scene, ": node ", root, " does not exist"));
      }
      const auto r = static_cast<std::size_t>(root);
      if (parent[r] != none) {
        reader.fail(detail::message("scene ", scene, " lists ", node_name(model, r), ", a child of node ", parent[r],
                                    ", as a root"));
      }
      if (listed[r]) reader.fail(detail::message("scene ", scene, " lists ", node_name(model, r), " twice"));
      listed[r] = true;
      roots.push_back(r);
    }
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      if (parent[k] == none) roots.push_back(k);
    }
  }
  std::vector<MeshInstance> instances;
  std::vector<std::pair<std::size_t, Affine>> stack;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.emplace_back(*root, Affine::Identity());
  while (!stack.empty()) {
    const auto [k, above] = stack.back();
    stack.pop_back();
    const Affine world = above * local_transform(model, k, reader);
    const double det = world.linear().determinant();
    if (!(det != 0) || !std::isfinite(det)) {
      reader.fail(detail::message(node_name(model, k),
                                  ": transform composed with its ancestors' is singular (determinant ", det, ")"));
    }
    const tinygltf::Node& node = model.nodes[k];
    if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) >= model.meshes.size()) {
      reader.fail(detail::message(node_name(model, k), ": mesh ", node.mesh, " does not exist"));
    }
    if (node.mesh == 0 && node.skin >= 0) {
      reader.fail(detail::message(node_name(model, k), " is skinned (skin ", node.skin,
                                  "): parse_gltf reads static meshes, not joints"));
    }
    if (node.mesh == 0) instances.push_back({k, world});
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
      stack.emplace_back(static_cast<std::size_t>(*child), world);
    }
  }
  if (instances.empty()) reader.fail("no node of the scene holds the mesh");
  return instances;
}

// The mesh `local` (glTF's axes) placed once per transform, then turned Z-up when `z_up` is set:
// positions by the transform; normals by the inverse transpose of its linear part and tangents
// by the linear part, both renormalised (unless the linear part is the identity); where the
// determinant is negative (a mirror) every triangle's last two corners swap, keeping the
// winding, and tangent w flips (the bitangent n x t w is mirrored too).
RenderMesh instanced(const RenderMesh& local, const std::vector<MeshInstance>& instances, bool z_up,
                     const AccessorReader& reader) {
  const std::size_t n = local.vertex_count();
  if (n * instances.size() > detail::max_mesh_vertices) {
    reader.fail(detail::message(instances.size(), " instances of ", n, " vertices exceed 32-bit ids"));
  }
  // A small file can place a large mesh many times: the expanded mesh is refused beyond
  // gltf_max_expanded_bytes, before any of it is made.
  const std::uint64_t vertex_bytes = sizeof(Vec3) + (local.normals.empty() ? 0 : sizeof(Vec3)) +
                                     (local.uvs.empty() ? 0 : sizeof(Vec2)) + (local.tangents.empty() ? 0 : sizeof(Vec4)) +
                                     2 * sizeof(std::uint32_t);  // position ids, and their welding
  const std::uint64_t bytes = instances.size() * (n * vertex_bytes + local.indices.size() * sizeof(std::uint32_t));
  if (bytes > gltf_max_expanded_bytes) {
    reader.fail(detail::message(instances.size(), " instances of a mesh of ", n, " vertices and ",
                                local.indices.size() / 3, " triangles would take ", bytes >> 20, " MiB (the limit is ",
                                gltf_max_expanded_bytes >> 20, " MiB)"));
  }
  RenderMesh mesh;
  mesh.positions.reserve(n * instances.size());
  mesh.indices.reserve(local.indices.size() * instances.size());
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const Affine& transform = instances[i].world;
    const std::string placed =
        instances[i].node == no_node ? std::string() : " after the transform of " + node_name(reader.model(), instances[i].node);
    const Eigen::Matrix3d normal_map = transform.linear().inverse().transpose();
    const bool mirror = transform.linear().determinant() < 0;
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    // Without a linear part, directions stay exactly as read (and renormalised by read_direction).
    const bool moves_directions = transform.linear() != Eigen::Matrix3d::Identity();
    const auto direction = [&](const Vec3& d, const char* what, std::size_t v) {
      const Vec3 mapped = moves_directions ? d.normalized() : d;
      if (!mapped.allFinite() || mapped == Vec3::Zero()) {
        reader.fail(detail::message(what, " of vertex ", v, " is degenerate", placed));
      }
      return from_gltf_axes(mapped, z_up);
    };
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3 p = transform * local.positions[v];
      if (!p.allFinite()) reader.fail(detail::message("POSITION of vertex ", v, " is not finite", placed));
      mesh.positions.push_back(from_gltf_axes(p, z_up));
    }
    for (std::size_t v = 0; v < local.normals.size(); ++v) {
      mesh.normals.push_back(direction(normal_map * local.normals[v], "NORMAL", v));
    }
    mesh.uvs.insert(mesh.uvs.end(), local.uvs.begin(), local.uvs.end());
    for (std::size_t v = 0; v < local.tangents.size(); ++v) {
      const Vec4& t = local.tangents[v];
      Vec4 tangent;
      tangent << direction(transform.linear() * t.head<3>(), "TANGENT", v), mirror ? -t.w() : t.w();
      mesh.tangents.push_back(tangent);
    }
    for (std::size_t k = 0; k < local.indices.size(); k += 3) {
      const std::uint32_t a = local.indices[k], b = local.indices[k + 1], c = local.indices[k + 2];
      for (const std::uint32_t corner : {a, mirror ? c : b, mirror ? b : c}) mesh.indices.push_back(base + corner);
    }
  }
  return mesh;
}

}  // namespace

RenderMesh parse_gltf(std::string_view bytes, const std::filesystem::path& path, bool z_up) {
  const std::string name = path.string();
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    throw ParseError(name, 0, 0, "parse_gltf: larger than 4 GiB");
  }
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  std::string error;
  std::string warning;
  // The folder made absolute, so that tinygltf's second try (the URI relative to ".") never
  // lands inside it by accident.
  Confinement confinement;
  {
    std::error_code ignored;
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    confinement.root = std::filesystem::weakly_canonical(std::filesystem::absolute(folder, ignored), ignored);
    confinement.prefix = confinement.root.string();
    if (!confinement.prefix.ends_with('/')) confinement.prefix += '/';
  }
  loader.SetFsCallbacks({&confined_exists, &unexpanded, &confined_read, &refuse_write, &confinement});
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool loaded =
      bytes.substr(0, 4) == "glTF"
          ? loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                        size, confinement.root.string())
          : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), size, confinement.root.string());
  if (!confinement.refused.empty()) throw ParseError(name, 0, 0, confinement.refused);
  while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back()))) error.pop_back();
  if (!loaded) throw ParseError(name, 0, 0, "not a glTF 2.0 file: " + error);

  const AccessorReader reader(model, name);
  if (!model.extensionsRequired.empty()) {
    reader.fail("requires the extension " + model.extensionsRequired.front() + ", which parse_gltf does not read");
  }
  if (model.meshes.size() != 1) {
    reader.fail(detail::message("parse_gltf reads one mesh of one primitive; the file has ", model.meshes.size(), " meshes"));
  }
  if (model.meshes[0].primitives.size() != 1) {
    reader.fail(detail::message("parse_gltf reads one mesh of one primitive; the mesh has ",
                                model.meshes[0].primitives.size(), " primitives"));
  }
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
    reader.fail(detail::message("primitive mode ", primitive.mode, " is not TRIANGLES (4)"));
  }
  const auto attribute = [&](const char* key) {
    const auto found = primitive.attributes.find(key);
    return found == primitive.attributes.end() ? -1 : found->second;
  };
  if (attribute("POSITION") < 0) reader.fail("the primitive has no POSITION");
  if (!primitive.targets.empty()) reader.fail("the primitive has morph targets, which parse_gltf does not read");

  // The primitive as stored, in glTF's axes; placed by the scene's nodes at the end.
  RenderMesh mesh;
  const std::vector<double> xyz = reader.values(attribute("POSITION"), 3, Components::floats, "POSITION");
  const std::size_t n = reader.count(attribute("POSITION"));
  if (n > detail::max_mesh_vertices) reader.fail(detail::message(n, " vertices exceed 32-bit ids"));
  const auto per_vertex = [&](const char* key, int components, Components allowed) {
    std::vector<double> values = reader.values(attribute(key), components, allowed, key);
    if (reader.count(attribute(key)) != n) {
      reader.fail(detail::message(key, " has ", reader.count(attribute(key)), " elements for ", n, " vertices"));
    }
    return values;
  };
  mesh.positions.reserve(n);
  for (std::size_t v = 0; v < n; ++v) {
    mesh.positions.emplace_back(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    if (!mesh.positions.back().allFinite()) reader.fail(detail::message("POSITION of vertex ", v, " is not finite"));
  }
  if (attribute("NORMAL") >= 0) {
    const std::vector<double> values = per_vertex("NORMAL", 3, Components::floats);
    for (std::size_t v = 0; v < n; ++v) mesh.normals.push_back(read_direction(&values[3 * v], reader, "NORMAL", v));
  }
  if (attribute("TEXCOORD_0") >= 0) {
    const std::vector<double> values = per_vertex("TEXCOORD_0", 2, Components::texcoords);
    for (std::size_t v = 0; v < n; ++v) {
      mesh.uvs.emplace_back(values[2 * v], values[2 * v + 1]);
      if (!mesh.uvs.back().allFinite()) reader.fail(detail::message("TEXCOORD_0 of vertex ", v, " is not finite"));
    }
  }
  if (attribute("TANGENT") >= 0) {
    const std::vector<double> values = per_vertex("TANGENT", 4, Components::floats);
    for (std::size_t v = 0; v < n; ++v) {
      const double w = values[4 * v + 3];
      if (w != 1.0 && w != -1.0) reader.fail(detail::message("TANGENT of vertex ", v, " has w = ", w, ", not +1 or -1"));
      Vec4 tangent;
      tangent << read_direction(&values[4 * v], reader, "TANGENT", v), w;
      mesh.tangents.push_back(tangent);
    }
  }
  if (primitive.indices >= 0) {
    const std::vector<double> indices = reader.values(primitive.indices, 1, Components::indices, "indices");
    if (indices.size() % 3 != 0) reader.fail(detail::message(indices.size(), " indices are not whole triangles"));
    mesh.indices.reserve(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) {
      if (indices[k] >= static_cast<double>(n)) {
        reader.fail(detail::message("triangle ", k / 3, " uses vertex ", indices[k], " of ", n));
      }
      mesh.indices.push_back(static_cast<std::uint32_t>(indices[k]));
    }
  } else {
    if (n % 3 != 0) reader.fail(detail::message(n, " vertices without indices are not whole triangles"));
    mesh.indices.resize(n);
    std::iota(mesh.indices.begin(), mesh.indices.end(), 0u);
  }
  mesh = instanced(mesh, mesh_instances(model, reader), z_up, reader);
  mesh.position_ids = weld_equal_positions(mesh.positions);
  try {
    validate(mesh);  // every condition was checked above; this keeps the reader honest
  } catch (const InvalidInput& e) {
    reader.fail(e.what());
  }
  return mesh;
}

RenderMesh read_gltf(const std::filesystem::path& path, bool z_up) { return parse_gltf(read_file(path), path, z_up); }

}  // namespace patchwork
