// The C++ side of bench/python_overhead.py: tessellates a file of patches `runs` times with the
// options the Python side uses and prints each run's wall-clock seconds, one a line (the first
// run warms the caches and is printed too; the script drops it).
//
//   tessellate_repeat FILE RELATIVE_TOLERANCE RUNS

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/patch_file.h"
#include "surfaces/tessellator.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: tessellate_repeat FILE RELATIVE_TOLERANCE RUNS\n");
    return 2;
  }
  const patchwork::PatchSet set = patchwork::read_patch_set(argv[1]);
  patchwork::TessellationOptions options;
  options.relative_tolerance = std::stod(argv[2]);
  options.threads = 1;
  options.measure = false;
  const int runs = std::stoi(argv[3]);
  std::size_t triangles = 0;
  for (int k = 0; k < runs; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const patchwork::Tessellation t = patchwork::tessellate(set, options);
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    triangles = t.mesh.triangle_count();
    std::printf("%.9f\n", seconds.count());
  }
  std::fprintf(stderr, "%zu triangles\n", triangles);
  return EXIT_SUCCESS;
}
