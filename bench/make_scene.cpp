// make_scene INPUT.bpt COPIES OUTPUT.bpt: a scene of COPIES rotated copies of INPUT's patches
// (bench/scene.h), written as BPT, for the scale runs of scripts/report and by hand.

#include <cstdio>
#include <exception>
#include <string>

#include "bench/scene.h"
#include "io/bpt.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: make_scene INPUT.bpt COPIES OUTPUT.bpt\n");
    return 2;
  }
  try {
    std::size_t used = 0;
    const long copies = std::stol(argv[2], &used);
    if (used != std::string(argv[2]).size() || copies < 1) {
      std::fprintf(stderr, "make_scene: COPIES '%s' is not a positive whole number\n", argv[2]);
      return 2;
    }
    patchwork::write_bpt(
        argv[3], patchwork::bench::rotated_copies(patchwork::read_bpt(argv[1]), static_cast<std::size_t>(copies)));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "make_scene: %s\n", error.what());
    return 1;
  }
  return 0;
}
