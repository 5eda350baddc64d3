#include "render/bvh.h"

#include <bit>
#include <cmath>
#include <thread>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

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

namespace {

// A primitive as the builder sees it: its float bounds (rounded outwards) and its id. The
// builder partitions an array of these in place, so every pass reads memory in order.
struct PrimRef {
    glm::vec3 lower;
    uint32_t id;
    glm::vec3 upper;
    uint32_t unused;
    glm::vec3 centre() const { return (lower + upper) * 0.5f; }
};
static_assert(sizeof(PrimRef) == 32);

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

// A node's range of references with the bounds of their boxes and of their centres.
struct Range {
    uint32_t begin, end;
    FloatBounds bounds, centres;
    uint32_t count() const { return end - begin; }
};

Range measure(const PrimRef* refs, uint32_t begin, uint32_t end) {
    Range range{begin, end, {}, {}};
    for (uint32_t i = begin; i < end; ++i) {
        range.bounds.extend(refs[i].lower, refs[i].upper);
        range.centres.extend(refs[i].centre());
    }
    return range;
}

}  // namespace

// Builds one subtree into its own node array; two builders can run on disjoint ranges.
class BvhBuilder {
public:
    BvhBuilder(PrimRef* refs, Accelerator method, int leaf_size) : refs_(refs), method_(method), leaf_size_(leaf_size) {}

    uint32_t build(const Range& range, int depth);
    std::vector<BvhNode> nodes;

    // Splits `range` into two (false: make a leaf). Public for the two-thread root split.
    bool split(const Range& range, int depth, Range& left, Range& right);

private:
    bool split_median(const Range& range, int axis, Range& left, Range& right);
    bool split_sah(const Range& range, Range& left, Range& right);

    PrimRef* refs_;
    Accelerator method_;
    int leaf_size_;
};

uint32_t BvhBuilder::build(const Range& range, int depth) {
    const uint32_t index = uint32_t(nodes.size());
    nodes.emplace_back();
    for (int axis = 0; axis < 3; ++axis) {
        nodes[index].box[0][axis] = range.bounds.lower[axis];
        nodes[index].box[1][axis] = range.bounds.upper[axis];
    }
    Range left, right;
    if (!split(range, depth, left, right)) {
        nodes[index].index = range.begin;
        nodes[index].count = range.count();
        return index;
    }
    build(left, depth + 1);  // the left child follows its parent
    const uint32_t right_index = build(right, depth + 1);
    nodes[index].index = right_index;
    nodes[index].count = 0;
    return index;
}

bool BvhBuilder::split(const Range& range, int depth, Range& left, Range& right) {
    const uint32_t count = range.count();
    if (method_ == Accelerator::Box || count <= 1) return false;
    const bool too_deep = depth >= kMaxBvhDepth - 1;
    if (method_ == Accelerator::Median || too_deep) {
        if (count <= uint32_t(leaf_size_)) return false;
        if (too_deep) {  // no more levels to spend: any halves will do
            left = measure(refs_, range.begin, range.begin + count / 2);
            right = measure(refs_, range.begin + count / 2, range.end);
            return true;
        }
        return split_median(range, depth % 3, left, right);
    }
    return split_sah(range, left, right);
}

// The assignment's split: sort by centroid along the axis, first half left.
bool BvhBuilder::split_median(const Range& range, int axis, Range& left, Range& right) {
    std::sort(refs_ + range.begin, refs_ + range.end,
              [axis](const PrimRef& a, const PrimRef& b) { return a.centre()[axis] < b.centre()[axis]; });
    const uint32_t middle = range.begin + range.count() / 2;
    left = measure(refs_, range.begin, middle);
    right = measure(refs_, middle, range.end);
    return true;
}

// Binned SAH: kSahBins bins of centroids per axis, all three axes binned in one pass; the
// cheapest boundary between bins wins.
bool BvhBuilder::split_sah(const Range& range, Range& left, Range& right) {
    const uint32_t count = range.count();
    const glm::vec3 extent = range.centres.upper - range.centres.lower;
    glm::vec3 scale;
    for (int axis = 0; axis < 3; ++axis) scale[axis] = extent[axis] > 0 ? kSahBins / extent[axis] : 0.0f;
    auto bin_of = [&](const PrimRef& ref, int axis) {
        return std::min(kSahBins - 1, int((ref.centre()[axis] - range.centres.lower[axis]) * scale[axis]));
    };

    // Step 1: bins (boxes, centres and counts) for every axis.
    FloatBounds boxes[3][kSahBins], centres[3][kSahBins];
    uint32_t counts[3][kSahBins] = {};
    for (uint32_t i = range.begin; i < range.end; ++i) {
        const PrimRef& ref = refs_[i];
        for (int axis = 0; axis < 3; ++axis) {
            const int bin = bin_of(ref, axis);
            ++counts[axis][bin];
            boxes[axis][bin].extend(ref.lower, ref.upper);
            centres[axis][bin].extend(ref.centre());
        }
    }

    // Step 2: the cheapest boundary, sweeping right-hand sides from the end.
    const double node_area = range.bounds.half_area() > 0 ? range.bounds.half_area() : 1.0;
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(extent[axis] > 0)) continue;
        double right_area[kSahBins];
        uint32_t right_count[kSahBins];
        FloatBounds accumulated;
        uint32_t accumulated_count = 0;
        for (int b = kSahBins - 1; b > 0; --b) {
            accumulated.extend(boxes[axis][b]);
            accumulated_count += counts[axis][b];
            right_area[b] = accumulated.half_area();
            right_count[b] = accumulated_count;
        }
        accumulated = FloatBounds();
        accumulated_count = 0;
        for (int b = 0; b < kSahBins - 1; ++b) {
            accumulated.extend(boxes[axis][b]);
            accumulated_count += counts[axis][b];
            if (accumulated_count == 0 || right_count[b + 1] == 0) continue;
            const double cost = kTraversalCost + kIntersectionCost *
                                                     (accumulated.half_area() * accumulated_count +
                                                      right_area[b + 1] * right_count[b + 1]) / node_area;
            if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
        }
    }
    const double leaf_cost = kIntersectionCost * count;
    if (count <= uint32_t(leaf_size_) && (best_axis < 0 || leaf_cost <= best_cost)) return false;
    if (best_axis < 0) {  // all centres coincide: any halves will do
        left = measure(refs_, range.begin, range.begin + count / 2);
        right = measure(refs_, range.begin + count / 2, range.end);
        return true;
    }

    // Step 3: partition, and the children's bounds from the bins.
    const PrimRef* middle = std::partition(refs_ + range.begin, refs_ + range.end,
                                           [&](const PrimRef& ref) { return bin_of(ref, best_axis) <= best_bin; });
    left = {range.begin, uint32_t(middle - refs_), {}, {}};
    right = {left.end, range.end, {}, {}};
    for (int b = 0; b < kSahBins; ++b) {
        Range& side = b <= best_bin ? left : right;
        side.bounds.extend(boxes[best_axis][b]);
        side.centres.extend(centres[best_axis][b]);
    }
    return true;
}

Bvh::Bvh(const std::vector<Bounds>& primitives, Accelerator method, int leaf_size) {
    const uint32_t n = uint32_t(primitives.size());
    order_.resize(n);
    if (n == 0) return;
    std::vector<PrimRef> refs(n);
    for (uint32_t i = 0; i < n; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            refs[i].lower[axis] = round_down(primitives[i].lower[axis]);
            refs[i].upper[axis] = round_up(primitives[i].upper[axis]);
        }
        refs[i].id = i;
    }
    leaf_size = std::max(leaf_size, 1);
    const Range root = measure(refs.data(), 0, n);

    // Large inputs: split the root here, then build its two subtrees on two threads and
    // append them in depth-first order (left subtree right after the root).
    constexpr uint32_t kParallelFrom = 50000;
    BvhBuilder main(refs.data(), method, leaf_size);
    Range left, right;
    if (n >= kParallelFrom && std::thread::hardware_concurrency() > 1 && main.split(root, 0, left, right)) {
        BvhBuilder other(refs.data(), method, leaf_size);
        std::thread worker([&] { other.build(left, 1); });
        main.build(right, 1);
        worker.join();
        nodes_.reserve(1 + other.nodes.size() + main.nodes.size());
        nodes_.emplace_back();
        for (int axis = 0; axis < 3; ++axis) {
            nodes_[0].box[0][axis] = root.bounds.lower[axis];
            nodes_[0].box[1][axis] = root.bounds.upper[axis];
        }
        nodes_[0].count = 0;
        nodes_[0].index = uint32_t(1 + other.nodes.size());
        auto append = [&](const std::vector<BvhNode>& subtree) {
            const uint32_t offset = uint32_t(nodes_.size());
            for (BvhNode node : subtree) {
                if (node.count == 0) node.index += offset;  // inner nodes point at node indices
                nodes_.push_back(node);
            }
        };
        append(other.nodes);
        append(main.nodes);
    } else {
        main.nodes.reserve(2 * size_t(n));
        main.build(root, 0);
        nodes_ = std::move(main.nodes);
    }
    for (uint32_t i = 0; i < n; ++i) order_[i] = refs[i].id;
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
