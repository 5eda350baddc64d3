// What both BVH layouts (BinaryBvh, WideBvh) share: the box around primitives, the two forms
// of the primitive test a search takes, per-ray counts, the depth bound, and the leaf visit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

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

// The relative margin of ray_may_meet_box, far above the rounding of any primitive's test (a
// triangle's is a few ulps of its vertices' and the ray origin's size).
constexpr Real kBoxMargin = sizeof(Real) == sizeof(float) ? Real(1e-5) : Real(1e-9);

// The box grown by kBoxMargin of its coordinates' size on every side, for ray_may_meet_box.
inline Bounds padded_for_rays(const Bounds& box) {
    const Vec3 size = glm::abs(box.lower) + glm::abs(box.upper) + (box.upper - box.lower);
    const Vec3 pad = size * kBoxMargin + std::numeric_limits<Real>::min();
    return {box.lower - pad, box.upper + pad};
}

// False only if `ray` passes outside `box` (a padded_for_rays box) between t = 0 and range.max:
// a slab test in Real on the box grown by kBoxMargin of the origin's size, the far end grown by
// kBoxMargin; an axis whose distances are NaN (an origin on a slab of an axis-parallel ray)
// rules nothing out. A cheap filter before a mesh's own set-up, never its answer.
[[gnu::always_inline]] inline bool ray_may_meet_box(const Ray& ray, const Bounds& box, Interval range) {
    const Vec3 o = ray.origin;
    const Vec3 inverse = Real(1) / ray.direction;  // +-infinity for a zero component
    const Real reach = kBoxMargin * std::max({std::abs(o.x), std::abs(o.y), std::abs(o.z)});
    Real near = 0, far = range.max;
    for (int axis = 0; axis < 3; ++axis) {
        const Real t0 = (box.lower[axis] - reach - o[axis]) * inverse[axis];
        const Real t1 = (box.upper[axis] + reach - o[axis]) * inverse[axis];
        if (t0 != t0 || t1 != t1) continue;
        near = std::max(near, std::min(t0, t1));
        far = std::min(far, std::max(t0, t1));
    }
    return near <= far * (1 + kBoxMargin);
}

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
