// The BVH builder's internals, shared by bvh_build.cpp (primitive references, splits, Box's
// and Median's binary tree) and bvh_wide_build.cpp (Sah's wide tree).
#pragma once

#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "accel/bvh.h"
#include "base/parallel.h"

namespace tracer {

// A primitive as the builder sees it: its float bounds (rounded outwards) and its id. The
// builder partitions an array of these in place, so every pass reads memory in order.
struct BvhBuildRef {
    glm::vec3 lower;
    uint32_t id;
    glm::vec3 upper;
    uint32_t bins;  // scratch: the SAH bin per axis, 8 bits each, from binning to partitioning
    glm::vec3 center() const { return (lower + upper) * 0.5f; }
};
static_assert(sizeof(BvhBuildRef) == 32);

namespace bvh_build {

struct FloatBounds {
    glm::vec3 lower{std::numeric_limits<float>::infinity()};
    glm::vec3 upper{-std::numeric_limits<float>::infinity()};
    void extend(const glm::vec3& p) { lower = glm::min(lower, p), upper = glm::max(upper, p); }
    void extend(const glm::vec3& lo, const glm::vec3& hi) { lower = glm::min(lower, lo), upper = glm::max(upper, hi); }
    void extend(const FloatBounds& b) { extend(b.lower, b.upper); }
    double half_area() const {
        const glm::dvec3 d = glm::dvec3(upper) - glm::dvec3(lower);
        return d.x >= 0 && d.y >= 0 && d.z >= 0 ? d.x * d.y + d.y * d.z + d.z * d.x : 0;
    }
};

// A node's range of references with the bounds of their boxes and of their centers.
struct Range {
    uint32_t begin, end;
    FloatBounds bounds, centers;
    uint32_t count() const { return end - begin; }
};

}  // namespace bvh_build

// Builds a binary tree into one node array, its root in slot 0: an inner node's two children
// take two slots side by side, and its `index` is the first of them (Box's and Median's tree,
// and Sah's below kDirectWideFrom primitives, collapsed into a wide tree afterwards). Subtrees
// of kTaskFrom primitives or more, down to depth kTaskDepth, are built as tasks of their own;
// slots are handed out to each task in chunks (an atomic count), so only about as many slots
// as the tree has nodes are touched, mostly in the order the nodes are made. From
// kDirectWideFrom primitives Sah's wide tree is built directly (build_wide_tree).
class BvhBuilder {
public:
    using Range = bvh_build::Range;

    // A child of a wide node in the making: its range and, if split (inner), its split.
    struct WideChild {
        Range range, left, right;
        int depth;   // its depth in the binary tree
        bool inner;  // split: a wide node of its own unless opened
        float area;  // its box's half area if inner (the larger, the sooner opened), else -1
    };

    // `slots` receive binary nodes, `wide_slots` Sah's wide ones built directly.
    BvhBuilder(BvhBuildRef* refs, BvhNode* slots, WideNode* wide_slots, BvhBuild method, int leaf_size, int leaf_lanes,
               bool parallel, const LeafGathering& gathering)
        : refs_(refs),
          slots_(slots),
          wide_slots_(wide_slots),
          method_(method),
          leaf_size_(leaf_size),
          lanes_shift_(uint32_t(std::bit_width(uint32_t(leaf_lanes)) - 1)),
          parallel_(parallel),
          gathering_(gathering) {}

    static constexpr uint32_t kChunk = 256;  // slots a task takes at a time (even)
    // Slots taken by one task and not yet used.
    struct Chunk {
        uint32_t next = 0, end = 0;
    };
    // The most slots a tree over n references can touch: its 2n - 1 nodes and each task's last
    // chunk partly unused (a task per inner node above depth kTaskDepth, and the root's).
    static size_t slots_for(uint32_t n) { return 2 * size_t(n) - 1 + (size_t(2) << kTaskDepth) * kChunk; }

    // Builds the subtree over `range` with its root in slot `first`, its nodes in `chunk`'s slots.
    void build(const Range& range, int depth, uint32_t first, Chunk& chunk);
    // Slots handed out (an upper bound of the tree's nodes).
    uint32_t used_slots() const { return used_slots_.load(); }

    // Builds Sah's wide tree over `root` into wide slots from 0 on: a wide node per binary split
    // that no wide node above opens (see build_wide). At most max(n - 1, 1) slots are used.
    void build_wide_tree(const Range& root);
    // Wide slots used, from 0 on: the wide tree's nodes.
    uint32_t used_wide_slots() const { return used_wide_.load(); }

    // Subtrees of at least kTaskFrom primitives, down to depth kTaskDepth, are tasks of their
    // own (a task costs about a microsecond; a subtree of 1024 primitives some 300).
    static constexpr uint32_t kTaskFrom = 1024;
    static constexpr int kTaskDepth = 8;

private:
    // Nodes of at least kParallelFrom primitives are binned and partitioned in two halves at
    // once, at any depth: a lopsided split leaves one side for one thread (gears' root splits
    // off its two-triangle floor, and the next node holds the other 36,608).
    static constexpr uint32_t kParallelFrom = 8192;
    // A wide node's children are split two at a time (the sides of the child it opens), at once
    // from this many primitives between them: a wide node is the direct build's serial step.
    static constexpr uint32_t kSidesAtOnceFrom = 256;

    // Splits `range` into two (false: make a leaf).
    bool split(const Range& range, int depth, Range& left, Range& right);
    void split_at(const Range& range, uint32_t middle, Range& left, Range& right);
    bool split_median(const Range& range, int axis, Range& left, Range& right);
    bool split_sah(const Range& range, Range& left, Range& right);

    // The child over `range` at binary depth `depth`, split now unless it is to be a leaf.
    WideChild wide_child(const Range& range, int depth);
    // True if `range` is small enough for gathering_ and all of its primitives may be gathered.
    bool gathered(const Range& range) const;
    // Builds wide node `to` from the split of a range at binary depth `depth` into `left` and
    // `right`, then its inner children's nodes.
    void build_wide(const Range& left, const Range& right, int depth, uint32_t to);

    BvhBuildRef* refs_;
    BvhNode* slots_;
    WideNode* wide_slots_;
    std::atomic<uint32_t> used_slots_{1};  // the root's, then chunks
    std::atomic<uint32_t> used_wide_{1};   // the root's, then each node's inner children
    BvhBuild method_;
    int leaf_size_;
    uint32_t lanes_shift_;  // log2 of the leaf test's lanes
    bool parallel_;
    const LeafGathering& gathering_;

    // The SAH's cost of testing n primitives: one per group of the leaf test's lanes (a shift,
    // not an integer division: it runs twice at every boundary of every node).
    double tests(uint32_t n) const { return double((n + (1u << lanes_shift_) - 1) >> lanes_shift_); }
};

// Box's and Median's binary tree from the builder's slots (whose inner nodes' children are at
// `index` and `index` + 1), depth first: an inner node's left child follows it, its right child
// is at `index`. `used`: the slots handed out, at most the tree's 2n - 1 nodes.
NodeArray depth_first(const NodeArray& slots, size_t used);

// Sah's wide tree made from the binary tree in `slots`: a wide node per binary node that no wide
// node above opens (the one of largest area first, while it has fewer than kWide children; the
// leaves, and the subtrees `gathering` gathers, are never opened). `order` maps the leaves'
// entries to primitive ids. The nodes are numbered by a walk from the root that numbers each
// node's inner children side by side when it reaches the node, and goes on from the last.
LargeArray<WideNode> collapse_to_wide(const NodeArray& slots, const std::vector<uint32_t>& order,
                                      const LeafGathering& gathering);

// The wide tree that BvhBuilder::build_wide_tree wrote to `slots` (root at 0, `used` nodes),
// in an array of exactly that size, numbered as collapse_to_wide numbers its nodes: the same
// bytes whichever thread took which slot, and whichever of the two builds made it.
LargeArray<WideNode> in_traversal_order(const LargeArray<WideNode>& slots, uint32_t used);

}  // namespace tracer
