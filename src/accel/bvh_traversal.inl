// Bvh's traversals and leaf walk, defined here because they are templates over the primitive
// test (included by bvh.h; read bvh.h for their contracts). Nearest hit: nearer child first, a
// waiting node skipped once a hit lies before its box. Any hit: farther child first, stop at the
// first hit.
#pragma once

#include "accel/bvh.h"

namespace tracer {

template <typename Test>
inline bool Bvh::nearest_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalRay& fast,
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

template <typename Test>
inline bool Bvh::any_in_leaf(uint32_t first, uint32_t count, Interval& range, TraversalCounts& counts, Test& test) {
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

inline void Bvh::prefetch_children(const WideNode& node, unsigned mask) const {
    for (; mask != 0; mask &= mask - 1) {
        const int lane = __builtin_ctz(mask);
        if (node.count[lane] != WideNode::kInner) continue;
        const char* child = reinterpret_cast<const char*>(&wide_[node.index[lane]]);
        for (size_t line = 0; line < sizeof(WideNode); line += 64) __builtin_prefetch(child + line);
    }
}

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
    // Three or more: each inserted into the stack's top entries in order.
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
