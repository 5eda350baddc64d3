// A bounding volume hierarchy over any primitives, in one flat array of 32-byte nodes laid
// out depth first: an inner node's left child follows it, its right child is at `index`.
// Leaves hold a range of `order()`, the primitive ids sorted into leaf order.
//
// Builders: Box (one leaf holding everything: the assignment's Task 3), Median (the
// assignment's Part 2: sort centroids along x, y, z by depth, split at the median) and Sah
// (binned surface-area heuristic). The traversal is the same for all three.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>

#include "frontend/scene.h"
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
    Real half_area() const;  // surface area / 2; 0 for an empty box
};

struct BvhNode {
    float lower[3];
    uint32_t index;  // leaf: first entry of order(); inner: the right child's node index
    float upper[3];
    uint32_t count;  // leaf: number of primitives; inner: 0
};
static_assert(sizeof(BvhNode) == 32, "BVH nodes are 32 bytes");

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
    Bvh(const std::vector<Bounds>& primitives, Accelerator method, int leaf_size);

    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<uint32_t>& order() const { return order_; }
    BvhStats stats() const;

    // Nearest hit: `test(i, range)` tests entry i of order() against the ray, shrinking
    // range.max on a hit and returning true. Children are visited nearest first.
    template <typename Test>
    bool closest(const Ray& ray, const Vec3& inv_dir, Interval& range, TraversalCounts& counts, Test test) const;
    // Any hit: stops at the first entry for which `test(i, range)` returns true.
    template <typename Test>
    bool any(const Ray& ray, const Vec3& inv_dir, Interval range, TraversalCounts& counts, Test test) const;

private:
    uint32_t build(const std::vector<Bounds>& primitives, std::vector<Vec3>& centroids, uint32_t begin,
                   uint32_t end, int depth, Accelerator method, int leaf_size);
    uint32_t split_median(std::vector<Vec3>& centroids, uint32_t begin, uint32_t end, int axis);
    uint32_t split_sah(const std::vector<Bounds>& primitives, const std::vector<Vec3>& centroids,
                       const Bounds& node_bounds, uint32_t begin, uint32_t end, int leaf_size);

    std::vector<BvhNode> nodes_;
    std::vector<uint32_t> order_;
};

// Entry distance of the ray into the node's box, or +infinity if it misses within `range`.
// Slabs are compared so that a NaN (0 * infinity, a ray in a box face) never shrinks the
// interval, and touching counts as entering: zero-thickness boxes are hit.
inline Real enter_box(const BvhNode& node, const Ray& ray, const Vec3& inv_dir, Interval range) {
    Real near = range.min, far = range.max;
    for (int axis = 0; axis < 3; ++axis) {
        Real t0 = (Real(node.lower[axis]) - ray.origin[axis]) * inv_dir[axis];
        Real t1 = (Real(node.upper[axis]) - ray.origin[axis]) * inv_dir[axis];
        if (inv_dir[axis] < 0) std::swap(t0, t1);
        if (t0 > near) near = t0;
        if (t1 < far) far = t1;
    }
    return near <= far ? near : kInfinity;
}

template <typename Test>
bool Bvh::closest(const Ray& ray, const Vec3& inv_dir, Interval& range, TraversalCounts& counts, Test test) const {
    if (nodes_.empty()) return false;
    ++counts.box_tests;
    if (enter_box(nodes_[0], ray, inv_dir, range) == kInfinity) return false;
    struct Pending {
        uint32_t node;
        Real t;  // where the ray enters its box
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
                found = test(i, range) || found;
            }
        } else {
            // Visit the nearer child first; the farther one waits on the stack.
            const uint32_t left = current + 1, right = node.index;
            counts.box_tests += 2;
            const Real t_left = enter_box(nodes_[left], ray, inv_dir, range);
            const Real t_right = enter_box(nodes_[right], ray, inv_dir, range);
            if (t_left != kInfinity && t_right != kInfinity) {
                const bool left_first = t_left <= t_right;
                stack[top++] = left_first ? Pending{right, t_right} : Pending{left, t_left};
                current = left_first ? left : right;
                continue;
            }
            if (t_left != kInfinity || t_right != kInfinity) {
                current = t_left != kInfinity ? left : right;
                continue;
            }
        }
        // Next waiting node, unless a hit found meanwhile lies before its box.
        do {
            if (top == 0) return found;
            --top;
        } while (stack[top].t > range.max);
        current = stack[top].node;
    }
}

template <typename Test>
bool Bvh::any(const Ray& ray, const Vec3& inv_dir, Interval range, TraversalCounts& counts, Test test) const {
    if (nodes_.empty()) return false;
    uint32_t stack[2 * kMaxBvhDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const BvhNode& node = nodes_[stack[--top]];
        ++counts.box_tests;
        if (enter_box(node, ray, inv_dir, range) == kInfinity) continue;
        if (node.count > 0) {
            for (uint32_t i = node.index; i < node.index + node.count; ++i) {
                ++counts.primitive_tests;
                if (test(i, range)) return true;
            }
        } else {
            stack[top++] = node.index;
            stack[top++] = uint32_t(&node - nodes_.data()) + 1;
        }
    }
    return false;
}

}  // namespace tracer
