// A bounding volume hierarchy over any primitives: builds the tree its method asks for and
// keeps the leaf order, `order()`, the primitive ids sorted into leaf order (a leaf holds a
// range of it). One class per tree layout does the searching:
//   - BinaryBvh (binary_bvh.h): Box (one leaf holding everything: the assignment's Task 3) and
//     Median (the assignment's Part 2: sort centroids along x, y, z by depth, split at the
//     median) keep their binary tree of 32-byte nodes;
//   - WideBvh (wide_bvh.h): Sah (binned surface-area heuristic) makes a wide tree of kWide
//     children per node, built directly or collapsed from a binary one.
// closest() and any() pass a query to the tree that was built; a caller that needs one layout
// (ray packets need the wide tree) asks for it with binary() or wide().
//
// Usage:
//   LargeArray<Bounds> boxes = ...;              // one per primitive
//   Bvh bvh(std::move(boxes), BvhBuild::Sah, 4);  // leaves of at most 4
//   Interval range{0, kInfinity};
//   TraversalCounts counts;
//   bool hit = bvh.closest(ray, range, counts, [&](uint32_t entry, Interval& r) {
//       return test_primitive(bvh.order()[entry], ray, r);  // shrinks r.max on a hit
//   });
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <variant>
#include <vector>

#include "accel/binary_bvh.h"
#include "accel/bvh_node.h"
#include "accel/bvh_search.h"
#include "accel/types.h"
#include "accel/wide_bvh.h"
#include "base/large_array.h"

namespace tracer {

struct BvhBuildRef;  // a primitive as the builder sees it (bvh_build.cpp)

// How a Bvh is built (see the top of this file).
enum class BvhBuild { Box, Median, Sah };

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

    // The tree the build made, or nullptr for the other layout: a WideBvh for Sah over at
    // least one primitive, else a BinaryBvh (empty if there are no primitives).
    const BinaryBvh* binary() const { return std::get_if<BinaryBvh>(&tree_); }
    const WideBvh* wide() const { return std::get_if<WideBvh>(&tree_); }
    const std::vector<uint32_t>& order() const { return order_; }
    // order(), moved out: for an owner that puts its primitives in leaf order, and needs it no more.
    std::vector<uint32_t> take_order() { return std::move(order_); }
    // The box around every primitive (empty if there are none).
    const Bounds& bounds() const { return root_box_; }
    // The tree's shape (counted once, when it is built).
    const BvhStats& stats() const { return stats_; }
    // Bytes held by the nodes and the leaf order.
    size_t memory_bytes() const {
        return std::visit([](const auto& tree) { return tree.memory_bytes(); }, tree_) +
               order_.capacity() * sizeof(uint32_t);
    }
    // Boxes that together hold every primitive: those of the nodes `levels` below the root,
    // and of the leaves above them.
    std::vector<Bounds> cover(int levels) const {
        return std::visit([levels](const auto& tree) { return tree.cover(levels); }, tree_);
    }
    // Calls f(box, first, count, depth) for every leaf, depth first, children in order: its box,
    // its range of order() and its depth (the root node's is 1; a wide root's children are at 2).
    template <typename F>
    void for_each_leaf(F f) const {
        std::visit([&f](const auto& tree) { tree.for_each_leaf(f); }, tree_);
    }

    // Calls leaf(box, first, count) for each leaf whose box, and every box above it, `meets`
    // (a predicate on Bounds); stops as soon as leaf returns false, and returns false then.
    template <typename Meets, typename Leaf>
    bool leaves_meeting(Meets meets, Leaf leaf) const {
        return std::visit([&](const auto& tree) { return tree.leaves_meeting(meets, leaf); }, tree_);
    }

    // Nearest hit: `test(i, range)` (or a LeafTest) tests entry i of order() against the ray,
    // shrinking range.max on a hit and returning true. Children are visited nearest first.
    template <typename Test>
    bool closest(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
        if (const WideBvh* tree = wide()) return tree->closest(ray, range, counts, test);
        return std::get_if<BinaryBvh>(&tree_)->closest(ray, range, counts, test);
    }
    // Any hit: stops at the first entry for which `test(i, range)` returns true.
    template <typename Test>
    bool any(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
        if (const WideBvh* tree = wide()) return tree->any(ray, range, counts, test);
        return std::get_if<BinaryBvh>(&tree_)->any(ray, range, counts, test);
    }

private:
    // Walks the tree's leaves: their number, sizes and depth.
    BvhStats counted_stats() const;
    // Builds the tree over the references (rounded bounds and ids), freeing them once read.
    void build(LargeArray<BvhBuildRef>& refs, BvhBuild method, int leaf_size, int threads, int leaf_lanes,
               const LeafGathering& gathering = {}, uint32_t direct_wide_from = kDirectWideFrom);

    std::variant<BinaryBvh, WideBvh> tree_;
    BvhStats stats_;  // counted_stats() of the tree as built
    std::vector<uint32_t> order_;
    Bounds root_box_;
};

}  // namespace tracer
