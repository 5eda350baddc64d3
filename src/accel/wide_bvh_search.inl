// WideBvh's searches and leaf walk, defined here because they are templates over the primitive
// test (included by wide_bvh.h; read wide_bvh.h for their contracts). Nearest hit: nearest
// child first, a waiting node skipped once a hit lies before its box. Any hit: farthest child
// first, stop at the first hit.
#pragma once

#include "accel/wide_bvh.h"

namespace tracer {

inline void WideBvh::prefetch_children(const WideNode& node, unsigned mask) const {
    for (; mask != 0; mask &= mask - 1) {
        const int lane = __builtin_ctz(mask);
        if (node.count[lane] != WideNode::kInner) continue;
        const char* child = reinterpret_cast<const char*>(&nodes_[node.index[lane]]);
        for (size_t line = 0; line < sizeof(WideNode); line += 64) __builtin_prefetch(child + line);
    }
}

template <bool kFused, typename ComesOffFirst>
bool WideBvh::descend(WideRef& current, const TraversalRay& fast, WideStack& stack, int& top, TraversalCounts& counts,
                      ComesOffFirst comes_off_first) const {
    const WideNode& node = nodes_[current.index];
    counts.box_tests += kWide;
    const WideEntry entry = enter_wide<kFused>(node, fast);
    prefetch_children(node, entry.mask);
    if (entry.mask == 0) return false;
    current = next_child(node, entry, stack, top, comes_off_first);
    return true;
}

template <bool kFused, typename Test>
bool WideBvh::closest(TraversalRay& fast, Interval& range, TraversalCounts& counts, Test& test) const {
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
bool WideBvh::any(const TraversalRay& fast, Interval range, TraversalCounts& counts, Test& test) const {
    WideStack stack;
    int top = 0;
    WideRef current{0, WideNode::kInner, 0};
    for (;;) {
        if (current.count != WideNode::kInner) {
            if (any_in_leaf(current.index, current.count, range, counts, test)) return true;
        } else if (descend<kFused>(current, fast, stack, top, counts, [](float a, float b) { return a > b; })) {
            continue;  // farthest child first (see BinaryBvh::any)
        }
        if (top == 0) return false;
        current = stack[--top];
    }
}

template <bool kFused, typename Leaf>
void WideBvh::closest_in_packet(TraversalPacket& packet, TraversalCounts& counts, Leaf& leaf) const {
    struct Waiting {
        float t;        // no ray enters the box before this
        uint32_t node;  // the parent (a leaf), or the node itself
        int lane;       // a leaf's lane in its parent, or -1 for a node
    };
    Waiting stack[kStackSize];
    int top = 0;
    const float t_min = lowest_lane(packet.t_min);
    stack[top++] = {t_min, 0, -1};
    while (top > 0) {
        const Waiting waiting = stack[--top];
        const float t_max = -lowest_lane(-packet.t_max);
        if (waiting.t > t_max) continue;
        const WideNode& node = nodes_[waiting.node];
        if (waiting.lane >= 0) {
            // A leaf: which rays enter it, each by its own arithmetic.
            const PacketLanes t = enter_child<kFused>(node, waiting.lane, packet);
            const unsigned rays = lane_mask(t <= packet.t_max);
            counts.box_tests += 1;
            if (rays != 0) leaf(rays, node.index[waiting.lane], node.count[waiting.lane]);
            continue;
        }
        counts.box_tests += kWide;
        const WideEntry entry = enter_frustum(node, packet, t_min, t_max);
        // The children entered, nearer ones above farther (they come off first).
        const int bottom = top;
        for (unsigned mask = entry.mask; mask != 0; mask &= mask - 1) {
            const int lane = __builtin_ctz(mask);
            const bool inner = node.count[lane] == WideNode::kInner;
            const Waiting child{entry.t[lane], inner ? node.index[lane] : waiting.node, inner ? -1 : lane};
            push_in_order(stack, top, bottom, child, [](float a, float b) { return a < b; });
        }
    }
}

template <typename F>
void WideBvh::for_each_leaf(F f) const {
    struct Visit {
        uint32_t node;
        int lane;  // the lane of a leaf of `node`, or -1 for the node itself
        int depth;
    };
    std::vector<Visit> pending;
    if (!nodes_.empty()) pending.push_back({0, -1, 1});
    while (!pending.empty()) {
        const Visit visit = pending.back();
        pending.pop_back();
        const WideNode& node = nodes_[visit.node];
        if (visit.lane >= 0) {
            f(bounds_of(node, visit.lane), node.index[visit.lane], node.count[visit.lane], visit.depth);
            continue;
        }
        for (int lane = kWide - 1; lane >= 0; --lane) {
            if (node.count[lane] == WideNode::kInner)
                pending.push_back({node.index[lane], -1, visit.depth + 1});
            else if (node.count[lane] > 0)
                pending.push_back({visit.node, lane, visit.depth + 1});
        }
    }
}

template <typename Meets, typename Leaf>
bool WideBvh::leaves_meeting(Meets meets, Leaf leaf) const {
    if (nodes_.empty()) return true;
    uint32_t stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const WideNode& node = nodes_[stack[--top]];
        for (int lane = 0; lane < kWide; ++lane) {
            if (node.count[lane] == 0) continue;
            const Bounds box = bounds_of(node, lane);
            if (!meets(box)) continue;
            if (node.count[lane] == WideNode::kInner)
                stack[top++] = node.index[lane];
            else if (!leaf(box, node.index[lane], node.count[lane]))
                return false;
        }
    }
    return true;
}

// The child to visit next among those the ray enters: the one that `comes_off_first(its t,
// every other's)`; the others go on the stack, each below those that come off before it.
template <typename ComesOffFirst>
WideBvh::WideRef WideBvh::next_child(const WideNode& node, const WideEntry& entry, WideStack& stack, int& top,
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
    // Three or more: each put into the stack's top entries in order.
    const int bottom = top;
    push_in_order(stack, top, bottom, child(first), comes_off_first);
    push_in_order(stack, top, bottom, child(second), comes_off_first);
    while (mask != 0) push_in_order(stack, top, bottom, child(take_lane()), comes_off_first);
    return stack[--top];
}

}  // namespace tracer
