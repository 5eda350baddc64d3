// WideBvh: the wide tree that the Sah build makes (kWide = 8 children per node with AVX, else
// 4), whose nodes hold their children's planes side by side, so that a search tests all the
// children's boxes with one vector operation per plane; a leaf holds a range of the leaf order
// (Bvh::order()). A search keeps the children it enters on one stack, sorted so that the one to
// visit next comes off first: nearest first for the nearest hit, farthest first for any hit.
// Packets of coherent rays (ray_packet.h) walk the same tree with the same stack and order.
//
// Usage (a Bvh built with BvhBuild::Sah holds one):
//   const WideBvh& tree = *bvh.wide();
//   Interval range{0, kInfinity};
//   TraversalCounts counts;
//   bool hit = tree.closest(ray, range, counts, [&](uint32_t entry, Interval& r) {
//       return test_primitive(bvh.order()[entry], ray, r);  // shrinks r.max on a hit
//   });
//   bool blocked = tree.any(shadow_ray, {0, distance}, counts, test);
#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh_node.h"
#include "accel/bvh_search.h"
#include "accel/ray_packet.h"
#include "base/large_array.h"

namespace tracer {

class WideBvh {
public:
    WideBvh() = default;
    explicit WideBvh(LargeArray<WideNode> nodes) : nodes_(std::move(nodes)) {}

    // Root at 0.
    const LargeArray<WideNode>& nodes() const { return nodes_; }
    size_t memory_bytes() const { return nodes_.capacity() * sizeof(WideNode); }

    // Nearest hit: `test(i, range)` (or a LeafTest) tests entry i of the leaf order against the
    // ray, shrinking range.max on a hit and returning true. Children are visited nearest first.
    template <typename Test>
    bool closest(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
        if (nodes_.empty()) return false;
        TraversalRay fast(ray, range);
        return fast.fused ? closest<true>(fast, range, counts, test) : closest<false>(fast, range, counts, test);
    }
    // Any hit: stops at the first entry for which `test(i, range)` returns true.
    template <typename Test>
    bool any(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
        if (nodes_.empty()) return false;
        const TraversalRay fast(ray, range);
        return fast.fused ? any<true>(fast, range, counts, test) : any<false>(fast, range, counts, test);
    }
    // The nearest-hit search of a packet, every ray starting at the root: inner nodes are tested
    // against the packet's frustum (enter_frustum), each leaf against each ray (enter_child);
    // leaf(rays, first, count) tests leaf entries [first, first + count) for the rays in the bit
    // mask `rays`, each shrinking its own search's range and packet.t_max's lane on a hit.
    // Nodes are visited nearest first, and skipped once every ray has a hit before them. (The
    // frustum suits rays from one point: for shadow rays from a row's hits, whose origins spread
    // over several surfaces, an any-hit search built the same way was slower than single rays
    // where the hits spread; docs/bench/performance.md.)
    template <typename Leaf>
    void closest_in_packet(TraversalPacket& packet, TraversalCounts& counts, Leaf leaf) const {
        if (nodes_.empty()) return;
        packet.fused ? closest_in_packet<true>(packet, counts, leaf) : closest_in_packet<false>(packet, counts, leaf);
    }

    // Calls f(box, first, count, depth) for every leaf, depth first, children in order (the
    // root's children are at depth 2).
    template <typename F>
    void for_each_leaf(F f) const;
    // Calls leaf(box, first, count) for each leaf whose box, and every box above it, `meets`
    // (a predicate on Bounds); stops as soon as leaf returns false, and returns false then.
    template <typename Meets, typename Leaf>
    bool leaves_meeting(Meets meets, Leaf leaf) const;
    // The boxes of the nodes `levels` below the root, and of the leaves above them.
    std::vector<Bounds> cover(int levels) const;
    // Renumbers each leaf's range of the leaf order: [first, first + count) becomes
    // [start[first], start[first + count]).
    void renumber_leaves(const std::vector<uint32_t>& start);

private:
    // A child waiting on a search's stack: a node (count kInner) or a leaf's range.
    struct WideRef {
        uint32_t index, count;
        float t;  // where the ray enters its box
    };
    // Each node visited pushes at most kWide - 1 children more than it pops.
    static constexpr int kStackSize = (kWide - 1) * kMaxBvhDepth + 1;
    using WideStack = WideRef[kStackSize];

    template <bool kFused, typename Test>
    bool closest(TraversalRay& fast, Interval& range, TraversalCounts& counts, Test& test) const;
    template <bool kFused, typename Test>
    bool any(const TraversalRay& fast, Interval range, TraversalCounts& counts, Test& test) const;
    template <bool kFused, typename Leaf>
    void closest_in_packet(TraversalPacket& packet, TraversalCounts& counts, Leaf& leaf) const;
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
    // Puts `ref` on the stack's entries above `bottom`, below those that come off before it:
    // the one sort of every search.
    template <typename Ref, typename ComesOffFirst>
    static void push_in_order(Ref* stack, int& top, int bottom, const Ref& ref, ComesOffFirst comes_off_first) {
        int at = top++;
        for (; at > bottom && comes_off_first(stack[at - 1].t, ref.t); --at) stack[at] = stack[at - 1];
        stack[at] = ref;
    }
    static Bounds bounds_of(const WideNode& node, int lane) {
        Bounds box;
        for (int axis = 0; axis < 3; ++axis)
            box.lower[axis] = node.planes[0][axis][lane], box.upper[axis] = node.planes[1][axis][lane];
        return box;
    }

    LargeArray<WideNode> nodes_;
};

}  // namespace tracer

#include "accel/wide_bvh_search.inl"  // the searches' template definitions
