// The C++ side of the Python module's bit-for-bit test (test_tessellation.py): tessellates a file
// of patches with the options given and writes the result's arrays raw, so that the test compares
// them with the module's, byte for byte.
//
//   tessellate_reference FILE RELATIVE_TOLERANCE OUT
//
// OUT holds: vertex count and triangle count (uint64 each), then positions, normals (n x 3
// float64), uvs (n x 2 float64), indices (m x 3 uint32), triangle_patches (m uint32), and
// error_bound and measured_error (float64).

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "io/patch_file.h"
#include "surfaces/tessellator.h"

namespace {

template <class T>
void write_raw(std::ofstream& out, const T* data, std::size_t count) {
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(count * sizeof(T)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: tessellate_reference FILE RELATIVE_TOLERANCE OUT\n";
    return 2;
  }
  const patchwork::PatchSet set = patchwork::read_patch_set(argv[1]);
  patchwork::TessellationOptions options;
  options.relative_tolerance = std::stod(argv[2]);
  const patchwork::Tessellation t = patchwork::tessellate(set, options);
  const patchwork::RenderMesh& mesh = t.mesh;
  std::ofstream out(argv[3], std::ios::binary);
  const std::uint64_t counts[2] = {mesh.vertex_count(), mesh.triangle_count()};
  write_raw(out, counts, 2);
  write_raw(out, mesh.positions.front().data(), 3 * mesh.vertex_count());
  write_raw(out, mesh.normals.front().data(), 3 * mesh.vertex_count());
  write_raw(out, mesh.uvs.front().data(), 2 * mesh.vertex_count());
  write_raw(out, mesh.indices.data(), mesh.indices.size());
  write_raw(out, t.triangle_patches.data(), t.triangle_patches.size());
  const double errors[2] = {t.error_bound, t.measured_error};
  write_raw(out, errors, 2);
  return out ? EXIT_SUCCESS : EXIT_FAILURE;
}
