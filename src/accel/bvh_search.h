// What both BVH layouts (BinaryBvh, WideBvh) share: the box around primitives, the two forms
// of the primitive test a search takes, per-ray counts, the depth bound, and the leaf visit.
#pragma once

#include <cstdint>

#include <glm/common.hpp>

#include "accel/bvh_node.h"
#include "accel/types.h"

namespace tracer {

struct Bounds {
    Vec3 lower{kInfinity};
    Vec3 upper{-kInfinity};

    void extend(const Vec3& p) {
        lower = glm::min(lower, p);
        upper = glm::max(upper, p);
    }
    void extend(const Bounds& b) {
        lower = glm::min(lower, b.lower);
        upper = glm::max(upper, b.upper);
    }
    Vec3 center() const { return (lower + upper) * Real(0.5); }
};

// A test of a leaf's entries [first, first + count) at once, which a search takes in place of
// a test of one entry: test_leaf(first, count, range) returns true on a hit (for the nearest
// hit: shrinking range.max to the nearest).
template <typename F>
struct LeafTest {
    F test_leaf;
};
template <typename F>
LeafTest(F) -> LeafTest<F>;  // for compilers without aggregate deduction (Clang before 17)
template <typename T>
constexpr bool kIsLeafTest = false;
template <typename F>
constexpr bool kIsLeafTest<LeafTest<F>> = true;

// Per-ray work, for --stats.
struct TraversalCounts {
    uint64_t box_tests = 0;
    uint64_t primitive_tests = 0;
    TraversalCounts& operator+=(const TraversalCounts& other) {
        box_tests += other.box_tests;
        primitive_tests += other.primitive_tests;
        return *this;
    }
};

// Builders never go deeper (past it they split at the middle of the range), which bounds the
// traversal stacks.
constexpr int kMaxBvhDepth = 56;

// A leaf's entries [first, first + count) for the nearest hit, with `test` in either form (an
// entry's test(i, range), or a LeafTest): true if one was hit (range and fast's t_max then end
// at it).
template <typename Test>
inline bool nearest_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalRay& fast,
                            TraversalCounts& counts, Test& test) {
    if constexpr (kIsLeafTest<Test>) {
        counts.primitive_tests += count;
        if (!test.test_leaf(first, count, range)) return false;
        fast.clip(range.max);
        return true;
    } else {
        bool found = false;
        for (uint32_t i = first; i < first + count; ++i) {
            ++counts.primitive_tests;
            if (test(i, range)) {
                found = true;
                fast.clip(range.max);
            }
        }
        return found;
    }
}

// True at the leaf's first entry that `test` hits.
template <typename Test>
inline bool any_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalCounts& counts, Test& test) {
    if constexpr (kIsLeafTest<Test>) {
        counts.primitive_tests += count;
        return test.test_leaf(first, count, range);
    } else {
        for (uint32_t i = first; i < first + count; ++i) {
            ++counts.primitive_tests;
            if (test(i, range)) return true;
        }
        return false;
    }
}

}  // namespace tracer
