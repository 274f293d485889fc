// libFuzzer target: the BPT reader on arbitrary bytes; a patch set that parses must survive the
// adjacency analysis and a round trip through the writer.

#include "io/bpt.h"
#include "surfaces/patch_set.h"
#include "tests/fuzz/fuzz_support.h"

using namespace patchwork;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_documented_errors_only([&] {
    const std::vector<BezierPatch3> patches = parse_bpt(fuzz::as_text(data, size), "fuzz.bpt");
    PATCHWORK_FUZZ_CHECK(parse_bpt(format_bpt(patches), "back.bpt") == patches);
    const PatchSet set(patches);
    (void)report(set);
  });
  return 0;
}
