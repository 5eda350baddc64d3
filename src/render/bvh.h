// A bounding volume hierarchy over any primitives, in one flat array of nodes (32 bytes per
// child). Leaves hold a range of `order()`, the primitive ids sorted into leaf order.
//
// Builders: Box (one leaf holding everything: the assignment's Task 3), Median (the
// assignment's Part 2: sort centroids along x, y, z by depth, split at the median) and Sah
// (binned surface-area heuristic). All three build a binary tree. Box and Median keep it, in
// 32-byte nodes laid out depth first: an inner node's left child follows it, its right child
// is at `index`. Sah collapses it into a wide tree (kWide = 8 children per node with AVX,
// else 4) whose nodes hold their children's planes side by side, so that the traversal tests
// all the children's boxes with one vector operation per plane.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "base/large_array.h"
#include "render/bvh_node.h"
#include "render/types.h"

namespace tracer {

// A test of a leaf's entries [first, first + count) at once, which Bvh::closest and Bvh::any
// take in place of a test of one entry: test_leaf(first, count, range) returns true on a hit
// (for closest: shrinking range.max to the nearest).
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

// How a Bvh is built (see the top of this file).
enum class BvhBuild { Box, Median, Sah };

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
    Vec3 centre() const { return (lower + upper) * Real(0.5); }
};

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

struct BvhStats {
    size_t nodes = 0;
    size_t leaves = 0;
    int depth = 0;
    size_t min_leaf = 0;
    size_t max_leaf = 0;
    double mean_leaf = 0;
};

// SAH cost model: cost(node) = kTraversalCost + kIntersectionCost * sum over children of
// (area(child) / area(node)) * tests(child), tests being the primitives counted in groups of
// the leaf test's lanes. Only their ratio matters.
constexpr double kTraversalCost = 1.0;
constexpr double kIntersectionCost = 1.0;
constexpr int kSahBins = 16;
// Builders never go deeper (past it they split at the middle of the range), which bounds the
// traversal stacks.
constexpr int kMaxBvhDepth = 56;

class Bvh {
public:
    Bvh() = default;
    // Builds over the primitives' bounds. `leaf_size`: Median splits nodes with more primitives
    // than this; Sah never makes larger leaves (and makes smaller ones where the SAH says so).
    // Large inputs are built on `threads` threads (0: one per core), the subtrees near the
    // root in parallel. A leaf's primitives are tested `leaf_lanes` at a time (LeafTest): the
    // SAH counts a leaf's cost by such groups, which makes fuller leaves.
    Bvh(const LargeArray<Bounds>& primitives, BvhBuild method, int leaf_size, int threads = 0, int leaf_lanes = 1);

    // Box's and Median's binary tree, depth first: an inner node's left child follows it, its
    // right child is at `index` (empty for Sah).
    const NodeArray& nodes() const { return nodes_; }
    // Sah's wide tree, root at 0 (empty for Box and Median).
    const LargeArray<WideNode>& wide_nodes() const { return wide_; }
    const std::vector<uint32_t>& order() const { return order_; }
    // The box around every primitive (empty if there are none).
    const Bounds& bounds() const { return root_box_; }
    BvhStats stats() const;
    // Bytes held by the nodes and the leaf order.
    size_t memory_bytes() const {
        return nodes_.capacity() * sizeof(BvhNode) + wide_.capacity() * sizeof(WideNode) +
               order_.capacity() * sizeof(uint32_t);
    }
    // Boxes that together hold every primitive: those of the nodes `levels` below the root,
    // and of the leaves above them.
    std::vector<Bounds> cover(int levels) const;
    // Calls f(box, first, count, depth) for every leaf, depth first, children in order: its box,
    // its range of order() and its depth (the root node's is 1; a wide root's children are at 2).
    template <typename F>
    void for_each_leaf(F f) const;

    // Nearest hit: `test(i, range)` tests entry i of order() against the ray, shrinking
    // range.max on a hit and returning true. Children are visited nearest first.
    template <typename Test>
    bool closest(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
        return wide_.empty() ? closest_binary(ray, range, counts, test) : closest_wide(ray, range, counts, test);
    }
    // Any hit: stops at the first entry for which `test(i, range)` returns true.
    template <typename Test>
    bool any(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
        return wide_.empty() ? any_binary(ray, range, counts, test) : any_wide(ray, range, counts, test);
    }

private:
    // A child waiting on a wide traversal's stack: a node (count kInner) or a leaf's range.
    struct WideRef {
        uint32_t index, count;
        float t;  // where the ray enters its box
    };
    // Each wide node visited pushes at most kWide - 1 children more than it pops.
    using WideStack = WideRef[(kWide - 1) * kMaxBvhDepth + 1];

    template <typename Test>
    bool closest_binary(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const;
    template <typename Test>
    bool any_binary(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const;
    // The wide traversals pick the fused box test where it applies (see TraversalRay).
    template <typename Test>
    bool closest_wide(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
        TraversalRay fast(ray, range);
        return fast.fused ? closest_wide<true>(fast, range, counts, test)
                          : closest_wide<false>(fast, range, counts, test);
    }
    template <typename Test>
    bool any_wide(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
        const TraversalRay fast(ray, range);
        return fast.fused ? any_wide<true>(fast, range, counts, test) : any_wide<false>(fast, range, counts, test);
    }
    template <bool kFused, typename Test>
    bool closest_wide(TraversalRay& fast, Interval& range, TraversalCounts& counts, Test& test) const;
    template <bool kFused, typename Test>
    bool any_wide(const TraversalRay& fast, Interval range, TraversalCounts& counts, Test& test) const;
    // A leaf's entries [first, first + count) for the nearest hit: true if one was hit (range
    // and fast's t_max then end at it).
    template <typename Test>
    static bool nearest_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalRay& fast,
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
    static bool any_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalCounts& counts, Test& test) {
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
    // Asks for the cache lines of the inner children in `mask` before they are visited.
    void prefetch_children(const WideNode& node, unsigned mask) const {
        for (; mask != 0; mask &= mask - 1) {
            const int lane = __builtin_ctz(mask);
            if (node.count[lane] != WideNode::kInner) continue;
            const char* child = reinterpret_cast<const char*>(&wide_[node.index[lane]]);
            for (size_t line = 0; line < sizeof(WideNode); line += 64) __builtin_prefetch(child + line);
        }
    }
    // Tests the children of inner node `current` against the ray; if it enters any, `current`
    // becomes the one that comes off first and the others go on the stack (see next_child).
    template <bool kFused, typename ComesOffFirst>
    bool descend(WideRef& current, const TraversalRay& fast, WideStack& stack, int& top, TraversalCounts& counts,
                 ComesOffFirst comes_off_first) const;
    template <typename ComesOffFirst>
    static WideRef next_child(const WideNode& node, const WideEntry& entry, WideStack& stack, int& top,
                              ComesOffFirst comes_off_first);

    NodeArray nodes_;
    LargeArray<WideNode> wide_;
    std::vector<uint32_t> order_;
    Bounds root_box_;
};

template <typename Test>
bool Bvh::closest_binary(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
    if (nodes_.empty()) return false;
    constexpr float kMiss = std::numeric_limits<float>::infinity();
    TraversalRay fast(ray, range);
    ++counts.box_tests;
    if (enter_box(nodes_[0], fast) == kMiss) return false;
    struct Pending {
        uint32_t node;
        float t;  // where the ray enters its box
    };
    Pending stack[kMaxBvhDepth + 1];
    int top = 0;
    uint32_t current = 0;
    bool found = false;
    for (;;) {
        const BvhNode& node = nodes_[current];
        if (node.count > 0) {
            found |= nearest_in_leaf(node.index, node.count, range, fast, counts, test);
        } else {
            // Visit the nearer child first; the farther one waits on the stack.
            const uint32_t left = current + 1, right = node.index;
            counts.box_tests += 2;
            const float t_left = enter_box(nodes_[left], fast), t_right = enter_box(nodes_[right], fast);
            if (t_left != kMiss && t_right != kMiss) {
                const bool left_first = t_left <= t_right;
                stack[top++] = left_first ? Pending{right, t_right} : Pending{left, t_left};
                current = left_first ? left : right;
                continue;
            }
            if (t_left != kMiss || t_right != kMiss) {
                current = t_left != kMiss ? left : right;
                continue;
            }
        }
        // Next waiting node, unless a hit found meanwhile lies before its box.
        do {
            if (top == 0) return found;
            --top;
        } while (stack[top].t > fast.t_max);
        current = stack[top].node;
    }
}

template <typename Test>
bool Bvh::any_binary(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
    if (nodes_.empty()) return false;
    constexpr float kMiss = std::numeric_limits<float>::infinity();
    const TraversalRay fast(ray, range);
    ++counts.box_tests;
    if (enter_box(nodes_[0], fast) == kMiss) return false;
    uint32_t stack[kMaxBvhDepth + 1];
    int top = 0;
    uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes_[current];
        if (node.count > 0) {
            if (any_in_leaf(node.index, node.count, range, counts, test)) return true;
        } else {
            const uint32_t left = current + 1, right = node.index;
            counts.box_tests += 2;
            const float t_left = enter_box(nodes_[left], fast), t_right = enter_box(nodes_[right], fast);
            // Farther child first: a shadow ray starts on a surface, whose own neighbourhood (the
            // nearer box) seldom blocks it; the blocker lies farther on (measured: 54 -> 33 box
            // tests per blocked shadow ray on the bunny).
            if (t_left != kMiss && t_right != kMiss) {
                const bool left_first = t_left > t_right;
                stack[top++] = left_first ? right : left;
                current = left_first ? left : right;
                continue;
            }
            if (t_left != kMiss || t_right != kMiss) {
                current = t_left != kMiss ? left : right;
                continue;
            }
        }
        if (top == 0) return false;
        current = stack[--top];
    }
}

template <bool kFused, typename ComesOffFirst>
bool Bvh::descend(WideRef& current, const TraversalRay& fast, WideStack& stack, int& top, TraversalCounts& counts,
                  ComesOffFirst comes_off_first) const {
    const WideNode& node = wide_[current.index];
    counts.box_tests += kWide;
    const WideEntry entry = enter_wide<kFused>(node, fast);
    prefetch_children(node, entry.mask);
    if (entry.mask == 0) return false;
    current = next_child(node, entry, stack, top, comes_off_first);
    return true;
}

template <bool kFused, typename Test>
bool Bvh::closest_wide(TraversalRay& fast, Interval& range, TraversalCounts& counts, Test& test) const {
    WideStack stack;
    int top = 0;
    WideRef current{0, WideNode::kInner, 0};
    bool found = false;
    for (;;) {
        if (current.count != WideNode::kInner) {
            found |= nearest_in_leaf(current.index, current.count, range, fast, counts, test);
        } else if (descend<kFused>(current, fast, stack, top, counts, [](float a, float b) { return a < b; })) {
            continue;  // the nearest child next, the others on the stack, nearer ones above farther
        }
        // Next waiting node, unless a hit found meanwhile lies before its box.
        do {
            if (top == 0) return found;
            --top;
        } while (stack[top].t > fast.t_max);
        current = stack[top];
    }
}

template <bool kFused, typename Test>
bool Bvh::any_wide(const TraversalRay& fast, Interval range, TraversalCounts& counts, Test& test) const {
    WideStack stack;
    int top = 0;
    WideRef current{0, WideNode::kInner, 0};
    for (;;) {
        if (current.count != WideNode::kInner) {
            if (any_in_leaf(current.index, current.count, range, counts, test)) return true;
        } else if (descend<kFused>(current, fast, stack, top, counts, [](float a, float b) { return a > b; })) {
            continue;  // farthest child first (see any_binary)
        }
        if (top == 0) return false;
        current = stack[--top];
    }
}

template <typename F>
void Bvh::for_each_leaf(F f) const {
    struct Visit {
        uint32_t node;
        int lane;  // wide trees: the lane of a leaf of `node`, or -1 for the node itself
        int depth;
    };
    std::vector<Visit> pending;
    if (!nodes_.empty() || !wide_.empty()) pending.push_back({0, -1, 1});
    while (!pending.empty()) {
        const Visit visit = pending.back();
        pending.pop_back();
        if (!wide_.empty()) {
            const WideNode& node = wide_[visit.node];
            if (visit.lane >= 0) {
                const int lane = visit.lane;
                Bounds box;
                for (int axis = 0; axis < 3; ++axis)
                    box.lower[axis] = node.planes[0][axis][lane], box.upper[axis] = node.planes[1][axis][lane];
                f(box, node.index[lane], node.count[lane], visit.depth);
                continue;
            }
            for (int lane = kWide - 1; lane >= 0; --lane) {
                if (node.count[lane] == WideNode::kInner)
                    pending.push_back({node.index[lane], -1, visit.depth + 1});
                else if (node.count[lane] > 0)
                    pending.push_back({visit.node, lane, visit.depth + 1});
            }
            continue;
        }
        const BvhNode& node = nodes_[visit.node];
        if (node.count > 0) {
            const float(&b)[2][3] = node.box;
            f(Bounds{{b[0][0], b[0][1], b[0][2]}, {b[1][0], b[1][1], b[1][2]}}, node.index, node.count, visit.depth);
            continue;
        }
        pending.push_back({node.index, -1, visit.depth + 1});
        pending.push_back({visit.node + 1, -1, visit.depth + 1});
    }
}

// The child to visit next among those the ray enters: the one that `comes_off_first(its t,
// every other's)`; the others go on the stack, each below those that come off before it.
template <typename ComesOffFirst>
Bvh::WideRef Bvh::next_child(const WideNode& node, const WideEntry& entry, WideStack& stack, int& top,
                             ComesOffFirst comes_off_first) {
    unsigned mask = entry.mask;
    auto take_lane = [&mask] {
        const int lane = __builtin_ctz(mask);
        mask &= mask - 1;
        return lane;
    };
    auto child = [&](int lane) { return WideRef{node.index[lane], node.count[lane], entry.t[lane]}; };
    // One or two children (most visits): no stack or one push.
    const int first = take_lane();
    if (mask == 0) return child(first);
    const int second = take_lane();
    if (mask == 0) {
        const bool second_first = comes_off_first(entry.t[second], entry.t[first]);
        stack[top++] = child(second_first ? first : second);
        return child(second_first ? second : first);
    }
    // Three or four: insertion into the stack's top entries.
    const int bottom = top;
    auto insert = [&](const WideRef& ref) {
        int at = top++;
        for (; at > bottom && comes_off_first(stack[at - 1].t, ref.t); --at) stack[at] = stack[at - 1];
        stack[at] = ref;
    };
    insert(child(first));
    insert(child(second));
    while (mask != 0) insert(child(take_lane()));
    return stack[--top];
}

}  // namespace tracer
