// The large arrays' allocator: large ones whole 2 MiB pages of their own, small ones the
// heap's; either way a vector that holds, grows and copies its values.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include "search/LargePages.h"

using gbx::rt::LargePages;
using gbx::rt::LargeVector;

TEST(LargePages, ALargeArrayStartsOnAHugePageBoundary) {
  LargeVector<std::uint32_t> v(LargePages<std::uint32_t>::kLeast / sizeof(std::uint32_t) + 1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % LargePages<std::uint32_t>::kPage, 0u);
  std::iota(v.begin(), v.end(), 0u);
  EXPECT_EQ(v.back(), v.size() - 1);
}

TEST(LargePages, GrowingAcrossTheThresholdKeepsTheValues) {
  LargeVector<std::uint64_t> v;
  for (std::uint64_t i = 0; i < 3 * LargePages<std::uint64_t>::kPage / sizeof(std::uint64_t); ++i)
    v.push_back(i * 7);
  for (std::uint64_t i = 0; i < v.size(); i += 4099)
    ASSERT_EQ(v[i], i * 7);
  LargeVector<std::uint64_t> copy = v;
  EXPECT_EQ(copy, v);
  v.clear();
  v.shrink_to_fit();
  EXPECT_EQ(copy[copy.size() - 1], (copy.size() - 1) * 7);
}

TEST(LargePages, ASmallArrayComesFromTheHeap) {
  LargeVector<double> v(100, 1.5);
  EXPECT_EQ(v.size(), 100u);
  EXPECT_DOUBLE_EQ(v[99], 1.5);
}
