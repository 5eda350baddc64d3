#include "render/bvh.h"

#include <bit>
#include <cmath>
#include <numeric>

namespace tracer {
namespace {

// The next float towards +infinity (or -infinity), by stepping the bit pattern; no libm call.
float next_up(float f) {
    if (!(f < std::numeric_limits<float>::infinity())) return f;  // +inf and NaN stay
    if (f == 0) return std::numeric_limits<float>::denorm_min();
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? bits + 1 : bits - 1);
}
float next_down(float f) { return -next_up(-f); }

// Floats that never shrink the box (or interval) they bound.
float round_down(Real x) {
    const float f = float(x);
    return Real(f) > x ? next_down(f) : f;
}
float round_up(Real x) {
    const float f = float(x);
    return Real(f) < x ? next_up(f) : f;
}

}  // namespace

TraversalRay::TraversalRay(const Ray& ray, Interval range) {
    for (int axis = 0; axis < 3; ++axis) {
        const float origin = float(ray.origin[axis]);
        // |origin| 2^-21 is at least 4 ulps of it: rounding the origin moved it by half an ulp.
        const float pad = std::fabs(origin) * 0x1p-21f;
        const bool negative = ray.direction[axis] < 0;
        near_side[axis] = negative ? 1 : 0;
        origin_near[axis] = negative ? origin + pad : origin - pad;
        origin_far[axis] = negative ? origin - pad : origin + pad;
        inv_dir[axis] = float(Real(1) / ray.direction[axis]);
    }
    t_min = round_down(range.min);
    t_max = round_up(range.max);
}

void TraversalRay::clip(Real t) { t_max = std::min(t_max, round_up(t)); }

Real Bounds::half_area() const {
    const Vec3 d = upper - lower;
    if (!(d.x >= 0 && d.y >= 0 && d.z >= 0)) return 0;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

Bvh::Bvh(const std::vector<Bounds>& primitives, Accelerator method, int leaf_size) {
    const uint32_t n = uint32_t(primitives.size());
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    if (n == 0) return;
    std::vector<Vec3> centroids(n);
    for (uint32_t i = 0; i < n; ++i) centroids[i] = primitives[i].centre();
    nodes_.reserve(2 * size_t(n));
    build(primitives, centroids, 0, n, 0, method, std::max(leaf_size, 1));
}

uint32_t Bvh::build(const std::vector<Bounds>& primitives, std::vector<Vec3>& centroids, uint32_t begin,
                    uint32_t end, int depth, Accelerator method, int leaf_size) {
    // Step 1: the node's box.
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.emplace_back();
    Bounds bounds;
    for (uint32_t i = begin; i < end; ++i) bounds.extend(primitives[order_[i]]);
    for (int axis = 0; axis < 3; ++axis) {
        nodes_[index].box[0][axis] = round_down(bounds.lower[axis]);
        nodes_[index].box[1][axis] = round_up(bounds.upper[axis]);
    }

    // Step 2: where to split, if at all (`end` means: make a leaf).
    const uint32_t count = end - begin;
    uint32_t middle = end;
    if (method != Accelerator::Box && count > 1) {
        if (depth >= kMaxBvhDepth - 1)
            middle = count > uint32_t(leaf_size) ? begin + count / 2 : end;
        else if (method == Accelerator::Median)
            middle = count > uint32_t(leaf_size) ? split_median(centroids, begin, end, depth % 3) : end;
        else
            middle = split_sah(primitives, centroids, bounds, begin, end, leaf_size);
    }
    if (middle == end) {
        nodes_[index].index = begin;
        nodes_[index].count = count;
        return index;
    }

    // Step 3: children, left one right after this node.
    build(primitives, centroids, begin, middle, depth + 1, method, leaf_size);
    const uint32_t right = build(primitives, centroids, middle, end, depth + 1, method, leaf_size);
    nodes_[index].index = right;
    nodes_[index].count = 0;
    return index;
}

// The assignment's split: sort by centroid along the axis, first half left.
uint32_t Bvh::split_median(std::vector<Vec3>& centroids, uint32_t begin, uint32_t end, int axis) {
    std::sort(order_.begin() + begin, order_.begin() + end,
              [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    return begin + (end - begin) / 2;
}

// Binned SAH: kSahBins bins of centroids per axis, the cheapest boundary between bins.
uint32_t Bvh::split_sah(const std::vector<Bounds>& primitives, const std::vector<Vec3>& centroids,
                        const Bounds& node_bounds, uint32_t begin, uint32_t end, int leaf_size) {
    const uint32_t count = end - begin;
    Bounds centre_bounds;
    for (uint32_t i = begin; i < end; ++i) centre_bounds.extend(centroids[order_[i]]);
    const Real node_area = node_bounds.half_area() > 0 ? node_bounds.half_area() : Real(1);

    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const Real extent = centre_bounds.upper[axis] - centre_bounds.lower[axis];
        if (!(extent > 0)) continue;
        const Real scale = kSahBins / extent;
        Bounds bin_bounds[kSahBins];
        uint32_t bin_count[kSahBins] = {};
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t id = order_[i];
            const int bin = std::min(kSahBins - 1, int((centroids[id][axis] - centre_bounds.lower[axis]) * scale));
            ++bin_count[bin];
            bin_bounds[bin].extend(primitives[id]);
        }
        // Right-hand sides swept from the end, left-hand sides from the start.
        Real right_area[kSahBins];
        uint32_t right_count[kSahBins];
        Bounds accumulated;
        uint32_t accumulated_count = 0;
        for (int b = kSahBins - 1; b > 0; --b) {
            accumulated.extend(bin_bounds[b]);
            accumulated_count += bin_count[b];
            right_area[b] = accumulated.half_area();
            right_count[b] = accumulated_count;
        }
        accumulated = Bounds();
        accumulated_count = 0;
        for (int b = 0; b < kSahBins - 1; ++b) {
            accumulated.extend(bin_bounds[b]);
            accumulated_count += bin_count[b];
            if (accumulated_count == 0 || right_count[b + 1] == 0) continue;
            const double cost = kTraversalCost + kIntersectionCost *
                                                     (accumulated.half_area() * accumulated_count +
                                                      right_area[b + 1] * right_count[b + 1]) / node_area;
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_bin = b;
            }
        }
    }

    const double leaf_cost = kIntersectionCost * count;
    if (count <= uint32_t(leaf_size) && (best_axis < 0 || leaf_cost <= best_cost)) return end;
    if (best_axis < 0) return begin + count / 2;  // all centroids coincide: any halves will do

    const Real scale = kSahBins / (centre_bounds.upper[best_axis] - centre_bounds.lower[best_axis]);
    auto left_of_split = [&](uint32_t id) {
        return std::min(kSahBins - 1, int((centroids[id][best_axis] - centre_bounds.lower[best_axis]) * scale)) <=
               best_bin;
    };
    auto middle = std::partition(order_.begin() + begin, order_.begin() + end, left_of_split);
    return uint32_t(middle - order_.begin());
}

BvhStats Bvh::stats() const {
    BvhStats s;
    s.nodes = nodes_.size();
    if (nodes_.empty()) return s;
    s.min_leaf = std::numeric_limits<size_t>::max();
    size_t in_leaves = 0;
    std::vector<std::pair<uint32_t, int>> stack{{0, 1}};
    while (!stack.empty()) {
        auto [index, depth] = stack.back();
        stack.pop_back();
        s.depth = std::max(s.depth, depth);
        const BvhNode& node = nodes_[index];
        if (node.count > 0) {
            ++s.leaves;
            in_leaves += node.count;
            s.min_leaf = std::min<size_t>(s.min_leaf, node.count);
            s.max_leaf = std::max<size_t>(s.max_leaf, node.count);
        } else {
            stack.push_back({index + 1, depth + 1});
            stack.push_back({node.index, depth + 1});
        }
    }
    s.mean_leaf = double(in_leaves) / double(s.leaves);
    return s;
}

}  // namespace tracer
