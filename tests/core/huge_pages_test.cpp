#include "core/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace patchwork {
namespace {

// The advice is a hint: whatever the kernel does with it, the buffer keeps its contents and
// capacity, and edge cases (null, small, unaligned ranges) are harmless.
TEST(HugePages, AdviceKeepsTheBufferAndItsContents) {
  std::vector<std::uint64_t> values;
  reserve_huge(values, std::size_t{3} << 20);  // 24 MiB
  ASSERT_GE(values.capacity(), std::size_t{3} << 20);
  const std::uint64_t* storage = values.data();
  for (std::uint64_t k = 0; k < (std::uint64_t{3} << 20); ++k) values.push_back(k * 2654435761u);
  EXPECT_EQ(values.data(), storage);  // reserved: no reallocation
  advise_huge_pages(values.data() + 1, values.size() * sizeof(std::uint64_t) - 24);  // unaligned
  for (std::uint64_t k = 0; k < values.size(); k += 4099) EXPECT_EQ(values[k], k * 2654435761u);
  advise_huge_pages(nullptr, std::size_t{1} << 30);
  const int small = 7;
  advise_huge_pages(&small, sizeof small);
  EXPECT_EQ(small, 7);
  std::vector<int> empty;
  reserve_huge(empty, 0);
  EXPECT_TRUE(empty.empty());
}

}  // namespace
}  // namespace patchwork
