// The build's big arrays: cache-line aligned at any size, and ordinary vectors (but elements
// made without arguments are left uninitialised).
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include "base/large_array.h"

namespace tracer {
namespace {

bool aligned(const void* p, uintptr_t alignment) {
    return reinterpret_cast<uintptr_t>(p) % alignment == 0;
}

TEST(LargeArray, SmallArraysStartOnACacheLine) {
    for (size_t n : {1, 3, 1000, 100000}) {
        LargeArray<uint32_t> small(n);
        EXPECT_TRUE(aligned(small.data(), 64)) << n;
    }
}

TEST(LargeArray, BigArraysStartOnACacheLineAndHoldTheirValues) {
    LargeArray<uint64_t> big(size_t(5) << 17);  // 5 MiB
    EXPECT_TRUE(aligned(big.data(), 64));
    std::iota(big.begin(), big.end(), uint64_t(0));
    big.resize(big.size() * 2, 7);  // grows through a second allocation and frees the first
    EXPECT_TRUE(aligned(big.data(), 64));
    EXPECT_EQ(big[12345], 12345u);
    EXPECT_EQ(big.back(), 7u);
    big.resize(10);
    big.shrink_to_fit();
    EXPECT_TRUE(aligned(big.data(), 64));
    EXPECT_EQ(big[9], 9u);
}

TEST(LargeArray, ElementsMadeFromValuesHoldThem) {
    // Only elements made without arguments are left uninitialised; these are all given values.
    struct Pair {
        uint32_t a, b;
    };
    LargeArray<Pair> pairs(1000, Pair{1, 2});
    pairs.emplace_back(Pair{3, 4});
    pairs.push_back({5, 6});
    pairs.resize(2000, Pair{7, 8});
    EXPECT_EQ(pairs[999].b, 2u);
    EXPECT_EQ(pairs[1000].a, 3u);
    EXPECT_EQ(pairs[1001].b, 6u);
    EXPECT_EQ(pairs.back().a, 7u);
}

}  // namespace
}  // namespace tracer
