// The build's big arrays: cache-line aligned when small, on 2 MiB boundaries (huge pages)
// from 4 MiB on, and ordinary vectors either way.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include "render/large_array.h"

namespace tracer {
namespace {

bool aligned(const void* p, uintptr_t alignment) { return reinterpret_cast<uintptr_t>(p) % alignment == 0; }

TEST(LargeArray, SmallArraysStartOnACacheLine) {
    for (size_t n : {1, 3, 1000, 100000}) {
        LargeArray<uint32_t> small(n);
        EXPECT_TRUE(aligned(small.data(), 64)) << n;
    }
}

TEST(LargeArray, BigArraysStartOnAHugePageAndHoldTheirValues) {
    LargeArray<uint64_t> big(size_t(5) << 17);  // 5 MiB
    EXPECT_TRUE(aligned(big.data(), size_t(2) << 20));
    std::iota(big.begin(), big.end(), uint64_t(0));
    big.resize(big.size() * 2, 7);  // grows through a second allocation and frees the first
    EXPECT_TRUE(aligned(big.data(), size_t(2) << 20));
    EXPECT_EQ(big[12345], 12345u);
    EXPECT_EQ(big.back(), 7u);
    big.resize(10);
    big.shrink_to_fit();  // back to the small kind of allocation
    EXPECT_TRUE(aligned(big.data(), 64));
    EXPECT_EQ(big[9], 9u);
}

}  // namespace
}  // namespace tracer
