#include "core/streaming_store.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <vector>

namespace patchwork {
namespace {

// Every length from 0 to 300 bytes at every offset of the destination within a cache line and
// beyond: the bytes arrive as memcpy would put them, and nothing outside the range changes
// (the ordinary stores at the ends and the streaming ones between must meet exactly).
TEST(StreamingStore, CopiesEveryLengthAtEveryAlignment) {
  std::vector<unsigned char> source(512);
  for (std::size_t k = 0; k < source.size(); ++k) source[k] = static_cast<unsigned char>(k * 37 + 11);
  std::vector<unsigned char> target(1024);
  std::vector<unsigned char> expected(1024);
  for (std::size_t offset = 0; offset < 80; ++offset) {
    for (std::size_t bytes = 0; bytes <= 300; ++bytes) {
      std::fill(target.begin(), target.end(), 0xA5);
      std::fill(expected.begin(), expected.end(), 0xA5);
      stream_copy(target.data() + offset, source.data() + 3, bytes);
      stream_fence();
      std::memcpy(expected.data() + offset, source.data() + 3, bytes);
      ASSERT_EQ(target, expected) << bytes << " bytes at offset " << offset;
    }
  }
}

}  // namespace
}  // namespace patchwork
