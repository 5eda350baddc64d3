// A bounding volume hierarchy over any primitives, in one flat array of 32-byte nodes.
// Leaves hold a range of `order()`, the primitive ids sorted into leaf order.
//
// Builders: Box (one leaf holding everything: the assignment's Task 3), Median (the
// assignment's Part 2: sort centroids along x, y, z by depth, split at the median) and Sah
// (binned surface-area heuristic). Box and Median lay the nodes out depth first: an inner
// node's left child follows it, its right child is at `index`. Sah stores siblings side by
// side in one 64-byte cache line (children at `index` and `index + 1`), and the traversal
// tests both with one 8-wide vector operation.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "frontend/scene.h"
#include "render/large_array.h"
#include "render/types.h"

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
    Vec3 centre() const { return (lower + upper) * Real(0.5); }
};

struct BvhNode {
    float box[2][3];  // [0]: lower corner, [1]: upper corner (rounded outwards from the primitives)
    uint32_t index;   // leaf: first entry of order(); inner: the right child's node index
    uint32_t count;   // leaf: number of primitives; inner: 0
};
static_assert(sizeof(BvhNode) == 32, "BVH nodes are 32 bytes");

using NodeArray = LargeArray<BvhNode>;  // 64-byte aligned: an even node index starts a cache line

// A ray prepared for float box tests. The origin is rounded to float and moved |origin| 2^-21
// (at least 4 ulps) away from each slab, t_far is scaled by 1 + 2 gamma_3 (Ize 2013; see
// kFarGrow) and the node boxes are rounded outwards: the margins are meant to keep rounding
// from making a box test miss a primitive the exact ray meets (hard-cases.md A1 and A3 will
// test it).
using FloatLanes8 = float __attribute__((vector_size(32)));
using IntLanes8 = int32_t __attribute__((vector_size(32)));

// Lane by lane minimum and maximum of GCC vectors; where `a` is NaN the lane takes `b`.
template <typename Lanes>
inline Lanes lane_min(Lanes a, Lanes b) { return a < b ? a : b; }
template <typename Lanes>
inline Lanes lane_max(Lanes a, Lanes b) { return a > b ? a : b; }

// Box tests scale the leaving distance by 1 + 2 gamma_3 (Ize 2013), so that float rounding
// cannot make the ray leave a box before the exact ray does. They scale 1 / d, once per ray:
// the same four roundings and factor as scaling each distance, in another order.
constexpr float kFarGrow = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

struct TraversalRay {
    float origin_near[3];  // origin for the entering planes
    float origin_far[3];   // origin for the leaving planes
    float inv_dir[3];      // 1 / direction; +-infinity for a zero component
    float inv_dir_far[3];  // inv_dir * kFarGrow, for the leaving planes
    int near_side[3];      // which corner holds the entering plane per axis: 1 when the direction is negative
    float t_min = 0;
    float t_max = 0;
    // The same per axis in enter_pair's lanes: x, y, z of the left box in lanes 0-2 and of
    // the right box in lanes 5-7; lanes 3 and 4 (origin 0, inv_dir NaN) never decide.
    FloatLanes8 origin_near8, origin_far8, inv_dir8, inv_dir_far8;
    IntLanes8 negative8;  // -1 where the direction is negative

    TraversalRay(const Ray& ray, Interval range);
    // Shrinks the float t_max after a hit (never below the double one).
    void clip(Real t);
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
// (area(child) / area(node)) * primitives(child). Only their ratio matters.
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
    // root in parallel.
    Bvh(const LargeArray<Bounds>& primitives, Accelerator method, int leaf_size, int threads = 0);

    const NodeArray& nodes() const { return nodes_; }
    // The children of inner node `parent`, left then right, in either layout (Sah's: at index
    // and index + 1, an even index).
    std::pair<uint32_t, uint32_t> children(uint32_t parent) const {
        const uint32_t index = nodes_[parent].index;
        return paired_ ? std::pair{index, index + 1} : std::pair{parent + 1, index};
    }
    const std::vector<uint32_t>& order() const { return order_; }
    BvhStats stats() const;

    // Nearest hit: `test(i, range)` tests entry i of order() against the ray, shrinking
    // range.max on a hit and returning true. Children are visited nearest first.
    template <typename Test>
    bool closest(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const;
    // Any hit: stops at the first entry for which `test(i, range)` returns true.
    template <typename Test>
    bool any(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const;

private:
    friend class BvhBuilder;

    NodeArray nodes_;
    std::vector<uint32_t> order_;
    bool paired_ = false;
};

// Entry distance of the ray into the node's box, or +infinity if it misses within
// [t_min, t_max]. Comparisons are written so that a NaN (0 * infinity: an origin exactly on a
// slab of an axis-parallel ray) never shrinks the interval, and touching counts as entering:
// zero-thickness boxes are hit.
inline float enter_box(const BvhNode& node, const TraversalRay& ray) {
    float near = ray.t_min, far = ray.t_max;
    for (int axis = 0; axis < 3; ++axis) {
        const float t0 = (node.box[ray.near_side[axis]][axis] - ray.origin_near[axis]) * ray.inv_dir[axis];
        const float t1 = (node.box[1 - ray.near_side[axis]][axis] - ray.origin_far[axis]) * ray.inv_dir_far[axis];
        near = t0 > near ? t0 : near;
        far = t1 < far ? t1 : far;
    }
    return near <= far ? near : std::numeric_limits<float>::infinity();
}

// enter_box for two sibling nodes at once (Sah's layout; `pair` is 64-byte aligned): one
// 8-wide vector holds both boxes' planes, the left box's x, y, z in lanes 0-2 and the right
// box's in lanes 5-7, gathered by three overlapping loads from the pair's cache line and a
// blend each for the lower and the upper planes (no shuffle across the vector's halves).
// Same arithmetic, same NaN rules, same results as enter_box.
struct PairEntry {
    float left, right;  // +infinity: missed
};
inline PairEntry enter_pair(const BvhNode* pair, const TraversalRay& ray) {
    using Lanes = FloatLanes8;
    using Indices = IntLanes8;
    // The pair's 16 words: left lower x y z, upper x y z, index, count, then the right node's.
    const float* words = &pair[0].box[0][0];
    static_assert(offsetof(BvhNode, box) == 0 && sizeof(BvhNode) == 8 * sizeof(float));
    Lanes from0, from3, from6;  // words 0-7, 3-10 and 6-13
    std::memcpy(&from0, words, sizeof from0);
    std::memcpy(&from3, words + 3, sizeof from3);
    std::memcpy(&from6, words + 6, sizeof from6);
    // Lanes 3-4 hold other coordinates of the boxes (never an index or count bit pattern).
    const Lanes lower = __builtin_shuffle(from0, from3, Indices{0, 1, 2, 3, 4, 13, 14, 15});
    const Lanes upper = __builtin_shuffle(from3, from6, Indices{0, 1, 2, 11, 12, 13, 14, 15});
    const Lanes near_planes = ray.negative8 ? upper : lower;
    const Lanes far_planes = ray.negative8 ? lower : upper;
    // NaN lanes (lanes 3-4 always) take t_min and t_max here, so the reductions below see none.
    Lanes near = lane_max((near_planes - ray.origin_near8) * ray.inv_dir8, Lanes{} + ray.t_min);
    Lanes far = lane_min((far_planes - ray.origin_far8) * ray.inv_dir_far8, Lanes{} + ray.t_max);
    // Largest entry and smallest exit within each half (box): swap neighbours, then pairs.
    auto swap_neighbours = [](Lanes v) { return __builtin_shuffle(v, Indices{1, 0, 3, 2, 5, 4, 7, 6}); };
    auto swap_pairs = [](Lanes v) { return __builtin_shuffle(v, Indices{2, 3, 0, 1, 6, 7, 4, 5}); };
    near = lane_max(near, swap_neighbours(near));
    near = lane_max(near, swap_pairs(near));
    far = lane_min(far, swap_neighbours(far));
    far = lane_min(far, swap_pairs(far));
    constexpr float kMiss = std::numeric_limits<float>::infinity();
    return {near[0] <= far[0] ? near[0] : kMiss, near[4] <= far[4] ? near[4] : kMiss};
}

template <typename Test>
bool Bvh::closest(const Ray& ray, Interval& range, TraversalCounts& counts, Test test) const {
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
            for (uint32_t i = node.index; i < node.index + node.count; ++i) {
                ++counts.primitive_tests;
                if (test(i, range)) {
                    found = true;
                    fast.clip(range.max);
                }
            }
        } else {
            // Visit the nearer child first; the farther one waits on the stack.
            const auto [left, right] = children(current);
            counts.box_tests += 2;
            const PairEntry t = paired_ ? enter_pair(&nodes_[left], fast)
                                        : PairEntry{enter_box(nodes_[left], fast), enter_box(nodes_[right], fast)};
            const float t_left = t.left, t_right = t.right;
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
bool Bvh::any(const Ray& ray, Interval range, TraversalCounts& counts, Test test) const {
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
            for (uint32_t i = node.index; i < node.index + node.count; ++i) {
                ++counts.primitive_tests;
                if (test(i, range)) return true;
            }
        } else {
            const auto [left, right] = children(current);
            counts.box_tests += 2;
            const PairEntry t = paired_ ? enter_pair(&nodes_[left], fast)
                                        : PairEntry{enter_box(nodes_[left], fast), enter_box(nodes_[right], fast)};
            // Farther child first: a shadow ray starts on a surface, whose own neighbourhood (the
            // nearer box) seldom blocks it; the blocker lies farther on (measured: 54 -> 33 box
            // tests per blocked shadow ray on the bunny).
            if (t.left != kMiss && t.right != kMiss) {
                const bool left_first = t.left > t.right;
                stack[top++] = left_first ? right : left;
                current = left_first ? left : right;
                continue;
            }
            if (t.left != kMiss || t.right != kMiss) {
                current = t.left != kMiss ? left : right;
                continue;
            }
        }
        if (top == 0) return false;
        current = stack[--top];
    }
}

}  // namespace tracer
