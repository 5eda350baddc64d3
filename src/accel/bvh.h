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
#include <functional>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "accel/bvh_node.h"
#include "accel/types.h"
#include "base/large_array.h"

namespace tracer {

struct BvhBuildRef;  // a primitive as the builder sees it (bvh_build.cpp)

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
    Vec3 center() const { return (lower + upper) * Real(0.5); }
};

// Writes the bounds of primitives [first, first + count) to out[0 .. count). Called for
// disjoint blocks from several threads at once.
using BoundsSource = std::function<void(size_t first, size_t count, Bounds* out)>;

// Small subtrees that a wide tree gathers into one leaf instead of a node of their own (a node
// per handful of primitives leaves most of its lanes empty): those of at most `most`
// primitives, each of which `gatherable(id)` allows. The default gathers none.
struct LeafGathering {
    uint32_t most = 1;
    std::function<bool(uint32_t id)> gatherable;
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
// Sah builds wide trees of this many primitives or more directly (see Bvh's constructor).
constexpr uint32_t kDirectWideFrom = 8192;

class Bvh {
public:
    Bvh() = default;
    // Builds over the primitives' bounds. `leaf_size`: Median splits nodes with more primitives
    // than this; Sah never makes larger leaves (and makes smaller ones where the SAH says so).
    // Large inputs are built on `threads` threads (0: one per core): subtrees of 1024
    // primitives or more as oneTBB tasks, the splits near the root in two halves at once.
    // A leaf's primitives are tested `leaf_lanes` at a time (LeafTest): the SAH counts a
    // leaf's cost by such groups (a power of two), which makes fuller leaves. `primitives` is
    // freed once read, and each work array once used: the peak stays near the tree's size plus
    // the input's. Sah builds its wide tree directly from `direct_wide_from` primitives on, and
    // below collapses a binary tree into it: the same tree either way (the direct build has
    // fewer serial steps; below 8,192 primitives its extra waits between threads cost more).
    Bvh(LargeArray<Bounds> primitives, BvhBuild method, int leaf_size, int threads = 0, int leaf_lanes = 1,
        const LeafGathering& gathering = {}, uint32_t direct_wide_from = kDirectWideFrom);
    // The same over `count` primitives whose bounds `source` gives a block at a time: they are
    // rounded to float as they come, never all kept in double.
    Bvh(size_t count, const BoundsSource& source, BvhBuild method, int leaf_size, int threads = 0, int leaf_lanes = 1);

    // Makes each primitive a run of entries: primitive p of the build becomes entries
    // first_entry[p] .. first_entry[p + 1] - 1 (a box's twelve triangles, say), in that order;
    // order() and the leaves count entries from then on. first_entry has one element more than
    // the build had primitives, and ends with the number of entries.
    void expand(const std::vector<uint32_t>& first_entry);

    // Box's and Median's binary tree, depth first: an inner node's left child follows it, its
    // right child is at `index` (empty for Sah).
    const NodeArray& nodes() const { return nodes_; }
    // Sah's wide tree, root at 0 (empty for Box and Median).
    const LargeArray<WideNode>& wide_nodes() const { return wide_; }
    const std::vector<uint32_t>& order() const { return order_; }
    // order(), moved out: for an owner that puts its primitives in leaf order, and needs it no more.
    std::vector<uint32_t> take_order() { return std::move(order_); }
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
    // Builds the tree over the references (rounded bounds and ids), freeing them once read.
    void build(LargeArray<BvhBuildRef>& refs, BvhBuild method, int leaf_size, int threads, int leaf_lanes,
               const LeafGathering& gathering = {}, uint32_t direct_wide_from = kDirectWideFrom);

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
                                TraversalCounts& counts, Test& test);
    // True at the leaf's first entry that `test` hits.
    template <typename Test>
    static bool any_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalCounts& counts, Test& test);
    // Asks for the cache lines of the inner children in `mask` before they are visited.
    void prefetch_children(const WideNode& node, unsigned mask) const;
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

}  // namespace tracer

#include "accel/bvh_traversal.inl"  // the traversals' template definitions
