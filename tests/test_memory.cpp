// The big arrays' memory (memory/pages.h): whatever page size the
// advice picks, memory keeps what it holds, maps zeroed and whole, and the
// allocators act as a vector's.
#include "memory/arrays.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>

namespace raycast {
namespace {

TEST(HugePages, AdviceKeepsWhatTheMemoryHolds) {
  constexpr size_t n = size_t(9) << 20;  // four whole huge pages and parts
  for (bool always : {false, true}) {
    const std::unique_ptr<uint32_t[]> a(new uint32_t[n / 4]);
    std::iota(a.get(), a.get() + n / 4, uint32_t(always));
    advise_huge_pages(a.get(), n, always);
    for (size_t k = 0; k < n / 4; k += 997) ASSERT_EQ(a[k], uint32_t(k + always)) << k;
    EXPECT_EQ(a[n / 4 - 1], uint32_t(n / 4 - 1 + always));
  }
}

TEST(HugePages, MappedMemoryIsZeroedAndWhole) {
  for (size_t n : {size_t(1), size_t(5 << 20) + 3, size_t(16) << 20})
    for (bool always : {false, true}) {
      auto* p = static_cast<unsigned char*>(map_huge(n, always));
      ASSERT_NE(p, nullptr);
      EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % huge_page_bytes, 0u);
      size_t nonzero = 0;
      for (size_t k = 0; k < n; ++k) nonzero += p[k] != 0;
      EXPECT_EQ(nonzero, 0u) << n;
      std::memset(p, 0xab, n);  // every byte writable
      EXPECT_EQ(p[n - 1], 0xab);
      unmap_huge(p, n);
    }
}

TEST(HugePages, OutOfOrderArraysActAsVectors) {
  out_of_order_array<uint32_t> a(size_t(3) << 20, 7u), b;
  EXPECT_EQ(std::count(a.begin(), a.end(), 7u), ptrdiff_t(a.size()));
  std::iota(a.begin(), a.end(), 0u);
  b = a;
  a.resize(10);
  a.swap(b);
  EXPECT_EQ(a.size(), size_t(3) << 20);
  EXPECT_EQ(a.back(), uint32_t((3 << 20) - 1));
  EXPECT_EQ(b.size(), 10u);
  out_of_order_array<uint32_t> c(b.begin(), b.end());
  EXPECT_EQ(c, b);
}

// Filled later: huge pages where small pages are dear, else the C++
// allocator's; either way the elements written are kept through growth,
// copies and swaps.
TEST(HugePages, FilledLaterArraysActAsVectors) {
  filled_later_array<uint32_t> a(size_t(3) << 20), b;
  // Mapped at a huge page's boundary exactly where small pages are dear
  // (the C++ allocator's blocks start 16 bytes into their chunk).
  EXPECT_EQ(reinterpret_cast<uintptr_t>(a.data()) % huge_page_bytes == 0, small_pages_dear());
  std::iota(a.begin(), a.end(), 0u);
  a.resize(size_t(5) << 20, 9u);  // moved into a bigger block
  EXPECT_EQ(a[(size_t(3) << 20) - 1], uint32_t((3 << 20) - 1));
  EXPECT_EQ(std::count(a.begin() + (3 << 20), a.end(), 9u), ptrdiff_t(2) << 20);
  b = a;
  a.resize(10);
  a.shrink_to_fit();
  a.swap(b);
  EXPECT_EQ(a.size(), size_t(5) << 20);
  EXPECT_EQ(a[12345], 12345u);
  EXPECT_EQ(b.size(), 10u);
  EXPECT_EQ(b[9], 9u);
}

}  // namespace
}  // namespace raycast
