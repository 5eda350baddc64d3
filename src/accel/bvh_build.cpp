#include "accel/bvh.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>

#include <oneapi/tbb/parallel_invoke.h>
#include <oneapi/tbb/task_arena.h>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "base/parallel.h"

namespace tracer {

// A primitive as the builder sees it: its float bounds (rounded outwards) and its id. The
// builder partitions an array of these in place, so every pass reads memory in order.
struct BvhBuildRef {
    glm::vec3 lower;
    uint32_t id;
    glm::vec3 upper;
    uint32_t bins;  // scratch: the SAH bin per axis, 8 bits each, from binning to partitioning
    glm::vec3 centre() const { return (lower + upper) * 0.5f; }
};
static_assert(sizeof(BvhBuildRef) == 32);

namespace {

// Runs `first` and `second`, in parallel where a thread of the build's arena is free (oneTBB's
// work stealing); returns when both are done.
template <typename First, typename Second>
void run_both(const First& first, const Second& second) {
    tbb::parallel_invoke(first, second);
}

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

// Four floats (four ints) in one vector register (GCC/Clang vector extensions: portable, no
// intrinsics).
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

v4f load_v4f(const glm::vec3& first) {  // the three floats and the next four bytes (never read back)
    v4f lanes;
    std::memcpy(&lanes, &first, sizeof lanes);
    return lanes;
}

// A reference's centre, lane by lane (lane 3 unused): the same floats as BvhBuildRef::centre.
v4f centre_lanes(const BvhBuildRef& ref) {
    return (load_v4f(ref.lower) + load_v4f(ref.upper)) * 0.5f;
}

// Lower and upper bounds of boxes or points, lane by lane (lane 3 unused). Uninitialised until
// set: arrays of bins are cleared only where used.
struct VectorBounds {
    static constexpr float kInf = std::numeric_limits<float>::infinity();
    v4f lower, upper;

    static VectorBounds empty() {
        VectorBounds bounds;
        bounds.lower = v4f{} + kInf, bounds.upper = v4f{} - kInf;
        return bounds;
    }

    void extend(v4f box_lower, v4f box_upper) {
        lower = lane_min(lower, box_lower), upper = lane_max(upper, box_upper);
    }
    void extend(const VectorBounds& other) { extend(other.lower, other.upper); }
    FloatBounds floats() const { return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}}; }
};

// One SAH bin: the boxes that fell into it and how many.
struct VectorBin {
    VectorBounds box;
    uint32_t count;

    static VectorBin empty() { return {VectorBounds::empty(), 0}; }

    void add(const VectorBin& other) {
        count += other.count;
        box.extend(other.box);
    }
    float half_area() const {
        const v4f d = box.upper - box.lower;
        return count == 0 ? 0.0f : d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    }
};

// A node's range of references with the bounds of their boxes and of their centres.
struct Range {
    uint32_t begin, end;
    FloatBounds bounds, centres;
    uint32_t count() const { return end - begin; }
};

Range measure(const BvhBuildRef* refs, uint32_t begin, uint32_t end) {
    Range range{begin, end, {}, {}};
    for (uint32_t i = begin; i < end; ++i) {
        range.bounds.extend(refs[i].lower, refs[i].upper);
        range.centres.extend(refs[i].centre());
    }
    return range;
}

// Moves the references for which goes_left holds before the others (as std::partition does),
// extending `left` and `right` by the centres of each side; returns the first of the others.
template <typename GoesLeft>
BvhBuildRef* partition(BvhBuildRef* begin, BvhBuildRef* end, GoesLeft goes_left, VectorBounds& left,
                       VectorBounds& right) {
    for (;;) {
        for (; begin < end && goes_left(*begin); ++begin) {
            const v4f c = centre_lanes(*begin);
            left.extend(c, c);
        }
        for (; begin < end && !goes_left(end[-1]); --end) {
            const v4f c = centre_lanes(end[-1]);
            right.extend(c, c);
        }
        if (begin == end) return begin;
        std::swap(*begin, end[-1]);  // now each is on its side
    }
}

}  // namespace

// Builds the tree into one node array, its root in slot 0. An inner node's two children take
// two slots side by side, and its `index` is the first of them. Subtrees of kTaskFrom
// primitives or more, down to depth kTaskDepth, are built as tasks of their own; slots are
// handed out to each task in chunks (an atomic count), so only about as many slots as the tree
// has nodes are touched, mostly in the order the nodes are made.
class BvhBuilder {
public:
    BvhBuilder(BvhBuildRef* refs, BvhNode* slots, BvhBuild method, int leaf_size, int leaf_lanes, bool parallel)
        : refs_(refs),
          slots_(slots),
          method_(method),
          leaf_size_(leaf_size),
          lanes_shift_(uint32_t(std::bit_width(uint32_t(leaf_lanes)) - 1)),
          parallel_(parallel) {}

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
    // Whether subtrees may be built in parallel.
    bool parallel() const { return parallel_; }

    // Subtrees of at least kTaskFrom primitives, down to depth kTaskDepth, are tasks of their
    // own (a task costs about a microsecond; a subtree of 1024 primitives some 300).
    static constexpr uint32_t kTaskFrom = 1024;
    static constexpr int kTaskDepth = 8;

private:
    // Nodes of at least kParallelFrom primitives, down to depth kParallelDepth (above the
    // subtrees' tasks), are binned and partitioned in two halves at once.
    static constexpr uint32_t kParallelFrom = 50000;
    static constexpr int kParallelDepth = 2;

    // Splits `range` into two (false: make a leaf).
    bool split(const Range& range, int depth, Range& left, Range& right);
    void split_at(const Range& range, uint32_t middle, Range& left, Range& right);
    bool split_median(const Range& range, int axis, Range& left, Range& right);
    bool split_sah(const Range& range, int depth, Range& left, Range& right);

    BvhBuildRef* refs_;
    BvhNode* slots_;
    std::atomic<uint32_t> used_slots_{1};  // the root's, then chunks
    BvhBuild method_;
    int leaf_size_;
    uint32_t lanes_shift_;  // log2 of the leaf test's lanes
    bool parallel_;

    // The SAH's cost of testing n primitives: one per group of the leaf test's lanes (a shift,
    // not an integer division: it runs twice at every boundary of every node).
    double tests(uint32_t n) const { return double((n + (1u << lanes_shift_) - 1) >> lanes_shift_); }
};

void BvhBuilder::build(const Range& range, int depth, uint32_t first, Chunk& chunk) {
    BvhNode& node = slots_[first];
    for (int axis = 0; axis < 3; ++axis) {
        node.box[0][axis] = range.bounds.lower[axis];
        node.box[1][axis] = range.bounds.upper[axis];
    }
    Range left, right;
    if (!split(range, depth, left, right)) {
        node.index = range.begin;
        node.count = range.count();
        return;
    }
    if (chunk.next == chunk.end) {
        chunk.next = used_slots_.fetch_add(kChunk, std::memory_order_relaxed);
        chunk.end = chunk.next + kChunk;
    }
    const uint32_t children = chunk.next;
    chunk.next += 2;
    node.count = 0;
    node.index = children;
    if (parallel_ && depth < kTaskDepth && range.count() >= kTaskFrom) {
        Chunk own;  // the other task's
        run_both([&] { build(left, depth + 1, children, own); }, [&] { build(right, depth + 1, children + 1, chunk); });
        return;
    }
    build(left, depth + 1, children, chunk);
    build(right, depth + 1, children + 1, chunk);
}

bool BvhBuilder::split(const Range& range, int depth, Range& left, Range& right) {
    const uint32_t count = range.count();
    if (method_ == BvhBuild::Box || count <= 1) return false;
    const bool too_deep = depth >= kMaxBvhDepth - 1;
    if (method_ == BvhBuild::Median || too_deep) {
        if (count <= uint32_t(leaf_size_)) return false;
        if (too_deep) {  // no more levels to spend: any halves will do
            split_at(range, range.begin + count / 2, left, right);
            return true;
        }
        return split_median(range, depth % 3, left, right);
    }
    // A leaf tested in one group of lanes costs no more than the traversal step that any split
    // adds (kIntersectionCost <= kTraversalCost), so the SAH would keep it: no need to bin it.
    if (count <= uint32_t(leaf_size_) && tests(count) * kIntersectionCost <= kTraversalCost) return false;
    return split_sah(range, depth, left, right);
}

// The assignment's split: sort by centroid along the axis, first half left.
bool BvhBuilder::split_median(const Range& range, int axis, Range& left, Range& right) {
    std::sort(refs_ + range.begin, refs_ + range.end,
              [axis](const BvhBuildRef& a, const BvhBuildRef& b) { return a.centre()[axis] < b.centre()[axis]; });
    split_at(range, range.begin + range.count() / 2, left, right);
    return true;
}

// The references before `middle` go left, the rest right, each with its bounds measured.
void BvhBuilder::split_at(const Range& range, uint32_t middle, Range& left, Range& right) {
    left = measure(refs_, range.begin, middle);
    right = measure(refs_, middle, range.end);
}

// Binned SAH: 4 + n / 20 bins of centroids per axis for n primitives, at most kSahBins and no
// more than n (Embree's rule: small nodes, which are most of the nodes, take few bins), all three
// axes binned in one pass; the cheapest boundary between bins wins.
bool BvhBuilder::split_sah(const Range& range, int depth, Range& left, Range& right) {
    const uint32_t count = range.count();
    const int bin_count = int(std::min<uint32_t>({count, kSahBins, 4 + count / 20}));
    const glm::vec3 extent = range.centres.upper - range.centres.lower;
    v4f factor = {0, 0, 0, 0};
    for (int axis = 0; axis < 3; ++axis) {
        const float scale = float(bin_count) / extent[axis];
        factor[axis] = extent[axis] > 0 && std::isfinite(scale) ? scale : 0.0f;  // also a NaN or infinite extent
    }
    const v4f origin = {range.centres.lower.x, range.centres.lower.y, range.centres.lower.z, 0};

    // Step 1: bins (boxes and counts) for every axis, four lanes at a time. Only the bins in
    // use are cleared: small nodes are most of the nodes. The large ranges near the root (where
    // build() runs subtrees in parallel) are binned in two halves at once.
    using AxisBins = VectorBin[3][kSahBins];
    const v4f last_bin = v4f{} + float(bin_count - 1);
    auto bin_of = [&](const BvhBuildRef& ref) {
        // Clamped as floats first: converting a NaN or out-of-range float is undefined.
        const v4f at = centre_lanes(ref) - origin;
        return __builtin_convertvector(lane_min(lane_max(at * factor, v4f{}), last_bin), v4i);
    };
    auto bin_refs = [&](uint32_t begin, uint32_t end, AxisBins& bins) {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < bin_count; ++b) bins[axis][b] = VectorBin::empty();
        for (uint32_t i = begin; i < end; ++i) {
            BvhBuildRef& ref = refs_[i];
            const v4i bin = bin_of(ref);
            const v4f lower = load_v4f(ref.lower), upper = load_v4f(ref.upper);
            for (int axis = 0; axis < 3; ++axis) {
                VectorBin& into = bins[axis][bin[axis]];
                into.box.extend(lower, upper);
                ++into.count;
            }
            ref.bins = uint32_t(bin[0]) | uint32_t(bin[1]) << 8 | uint32_t(bin[2]) << 16;
        }
    };
    const bool in_parallel = parallel_ && depth < kParallelDepth && count >= kParallelFrom;
    const uint32_t half = range.begin + count / 2;
    AxisBins bins;
    if (in_parallel) {
        AxisBins first_half;
        run_both([&] { bin_refs(range.begin, half, first_half); }, [&] { bin_refs(half, range.end, bins); });
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < bin_count; ++b) bins[axis][b].add(first_half[axis][b]);
    } else {
        bin_refs(range.begin, range.end, bins);
    }

    // Step 2: the cheapest boundary, sweeping right-hand sides from the end. Boundaries are
    // compared by their children's area-weighted tests; the node's area divides the best only.
    double best_weighted = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(extent[axis] > 0)) continue;
        float right_area[kSahBins];
        VectorBin accumulated = VectorBin::empty();
        for (int b = bin_count - 1; b > 0; --b) {
            accumulated.add(bins[axis][b]);
            right_area[b] = accumulated.half_area();
        }
        const uint32_t total = accumulated.count + bins[axis][0].count;
        accumulated = VectorBin::empty();
        for (int b = 0; b < bin_count - 1; ++b) {
            accumulated.add(bins[axis][b]);
            const uint32_t right_count = total - accumulated.count;
            if (accumulated.count == 0 || right_count == 0) continue;
            const double weighted = double(accumulated.half_area()) * tests(accumulated.count) +
                                    double(right_area[b + 1]) * tests(right_count);
            if (weighted < best_weighted) best_weighted = weighted, best_axis = axis, best_bin = b;
        }
    }
    const double node_area = range.bounds.half_area() > 0 ? range.bounds.half_area() : 1.0;
    const double best_cost = kTraversalCost + kIntersectionCost * best_weighted / node_area;
    const double leaf_cost = kIntersectionCost * tests(count);
    if (count <= uint32_t(leaf_size_) && (best_axis < 0 || leaf_cost <= best_cost)) return false;
    if (best_axis < 0) {  // all centres coincide: any halves will do
        split_at(range, range.begin + count / 2, left, right);
        return true;
    }

    // Step 3: partition, measuring the centres on each side; the children's boxes from the bins.
    const uint32_t shift = 8 * uint32_t(best_axis);
    auto goes_left = [&](const BvhBuildRef& ref) { return int((ref.bins >> shift) & 0xFF) <= best_bin; };
    VectorBounds left_centres = VectorBounds::empty(), right_centres = VectorBounds::empty();
    BvhBuildRef* middle;
    if (in_parallel) {
        // Both halves at once, then the first half's right part and the second half's left
        // part trade places (as many references as the smaller of the two holds).
        BvhBuildRef *first_middle, *second_middle;
        VectorBounds first_left = VectorBounds::empty(), first_right = VectorBounds::empty();
        run_both(
            [&] { first_middle = partition(refs_ + range.begin, refs_ + half, goes_left, first_left, first_right); },
            [&] {
                second_middle = partition(refs_ + half, refs_ + range.end, goes_left, left_centres, right_centres);
            });
        const size_t trade = std::min(refs_ + half - first_middle, second_middle - (refs_ + half));
        std::swap_ranges(first_middle, first_middle + trade, second_middle - trade);
        middle = first_middle + (second_middle - (refs_ + half));
        left_centres.extend(first_left), right_centres.extend(first_right);
    } else {
        middle = partition(refs_ + range.begin, refs_ + range.end, goes_left, left_centres, right_centres);
    }
    VectorBin left_bins = VectorBin::empty(), right_bins = VectorBin::empty();
    for (int b = 0; b < bin_count; ++b) (b <= best_bin ? left_bins : right_bins).add(bins[best_axis][b]);
    left = {range.begin, uint32_t(middle - refs_), left_bins.box.floats(), left_centres.floats()};
    right = {left.end, range.end, right_bins.box.floats(), right_centres.floats()};
    return true;
}

// The builder's tree (whose inner nodes' children are at `index` and `index` + 1) depth first:
// an inner node's left child follows it, its right child is at `index`.
static NodeArray depth_first(const NodeArray& slots, size_t used) {
    NodeArray ordered;
    ordered.reserve(used);
    constexpr uint32_t kNoParent = ~uint32_t(0);
    struct Move {
        uint32_t from, parent;  // parent: the node whose `index` is to point here (right children)
    };
    std::vector<Move> pending{{0, kNoParent}};
    while (!pending.empty()) {
        const Move move = pending.back();
        pending.pop_back();
        const uint32_t to = uint32_t(ordered.size());
        ordered.push_back(slots[move.from]);
        if (move.parent != kNoParent) ordered[move.parent].index = to;
        if (slots[move.from].count > 0) continue;
        pending.push_back({slots[move.from].index + 1, to});
        pending.push_back({slots[move.from].index, kNoParent});
    }
    return ordered;
}

// Whether the wide tree takes binary node i as a leaf: a binary leaf, or a subtree that
// `gathering` gathers (its primitives, a run of the leaf order, in first and count).
class LeafRule {
public:
    LeafRule(const NodeArray& nodes, const std::vector<uint32_t>& order, const LeafGathering& gathering)
        : nodes_(nodes), order_(order), gathering_(gathering) {}

    bool is_leaf(uint32_t i, uint32_t& first, uint32_t& count) const {
        if (nodes_[i].count > 0) {
            first = nodes_[i].index, count = nodes_[i].count;
            return true;
        }
        if (gathering_.most <= 1 || !small(i, gathering_.most, first, count)) return false;
        for (uint32_t k = first; k < first + count; ++k)
            if (!gathering_.gatherable(order_[k])) return false;
        return true;
    }
    bool is_leaf(uint32_t i) const {
        uint32_t first, count;
        return is_leaf(i, first, count);
    }

private:
    // True if subtree i holds at most `most` primitives (its depth is then below `most`, which
    // bounds the walk): their run in first and count.
    bool small(uint32_t i, uint32_t most, uint32_t& first, uint32_t& count) const {
        const BvhNode& node = nodes_[i];
        if (node.count > 0) {
            first = node.index, count = node.count;
            return count <= most;
        }
        uint32_t right_first, right_count;
        if (most < 2 || !small(node.index, most - 1, first, count)) return false;
        if (!small(node.index + 1, most - count, right_first, right_count)) return false;
        count += right_count;
        return right_first == first + count - right_count;
    }

    const NodeArray& nodes_;
    const std::vector<uint32_t>& order_;
    const LeafGathering& gathering_;
};

// The children a wide node made from binary node `from` takes (whose inner nodes' children are
// at `index` and `index` + 1): its two children and, while it has fewer than kWide, the two
// children of its inner child of largest surface area in place of that child (leaves, as
// `leaves` takes them, are never opened). A binary leaf takes itself. Returns how many (at most
// kWide), written to `children`.
static int wide_children(const NodeArray& nodes, const LeafRule& leaves, uint32_t from, uint32_t (&children)[kWide]) {
    auto half_area = [&](uint32_t i) {
        const float(&box)[2][3] = nodes[i].box;
        const float dx = box[1][0] - box[0][0], dy = box[1][1] - box[0][1], dz = box[1][2] - box[0][2];
        return dx * dy + dy * dz + dz * dx;
    };
    float area[kWide] = {-1};  // -1: a leaf, never opened
    auto add = [&](int k, uint32_t child) {
        children[k] = child;
        area[k] = leaves.is_leaf(child) ? -1.0f : half_area(child);
    };
    children[0] = from;
    if (nodes[from].count > 0) return 1;
    add(0, nodes[from].index), add(1, nodes[from].index + 1);
    int count = 2;
    while (count < kWide) {
        const int largest = int(std::max_element(area, area + count) - area);
        if (area[largest] < 0) break;
        const uint32_t opened = children[largest];
        add(largest, nodes[opened].index);
        add(count++, nodes[opened].index + 1);
    }
    return count;
}

// How many wide nodes collapse_to_wide makes of the binary tree (so that it allocates them once).
static size_t wide_node_count(const NodeArray& nodes, const LeafRule& leaves) {
    size_t made = 0;
    std::vector<uint32_t> pending{0};
    while (!pending.empty()) {
        const uint32_t from = pending.back();
        pending.pop_back();
        ++made;
        uint32_t children[kWide];
        const int count = wide_children(nodes, leaves, from, children);
        for (int lane = 0; lane < count; ++lane)
            if (!leaves.is_leaf(children[lane])) pending.push_back(children[lane]);
    }
    return made;
}

// Sah's wide tree from the builder's binary one: a wide node per binary node that
// wide_children does not open, starting from the root. A binary tree that is one leaf becomes
// a wide root with one child.
static LargeArray<WideNode> collapse_to_wide(const NodeArray& nodes, const LeafRule& leaves) {
    LargeArray<WideNode> wide(1);
    wide.reserve(wide_node_count(nodes, leaves));  // exactly: no growth, no capacity left unused
    struct Move {
        uint32_t from, to;  // the binary node whose children make wide node `to`
    };
    std::vector<Move> pending{{0, 0}};
    while (!pending.empty()) {
        const Move move = pending.back();
        pending.pop_back();
        // Step 1: the children.
        uint32_t children[kWide];
        const int count = wide_children(nodes, leaves, move.from, children);
        // Step 2: their boxes lane by lane, leaves as ranges, inner children as new wide nodes.
        WideNode node;
        for (int lane = 0; lane < kWide; ++lane) {
            for (int axis = 0; axis < 3; ++axis) {
                node.planes[0][axis][lane] = lane < count ? nodes[children[lane]].box[0][axis] : kInfinity;
                node.planes[1][axis][lane] = lane < count ? nodes[children[lane]].box[1][axis] : -kInfinity;
            }
            node.index[lane] = 0, node.count[lane] = 0;  // no child
            if (lane >= count) continue;
            if (leaves.is_leaf(children[lane], node.index[lane], node.count[lane])) continue;
            node.index[lane] = uint32_t(wide.size()), node.count[lane] = WideNode::kInner;
            pending.push_back({children[lane], uint32_t(wide.size())});
            wide.emplace_back();
        }
        wide[move.to] = node;
    }
    return wide;
}

// Each primitive's bounds rounded outwards to float, with its id; `source` is asked for blocks.
static LargeArray<BvhBuildRef> float_refs(size_t n, const BoundsSource& source, int threads) {
    constexpr size_t kBlock = 256;
    LargeArray<BvhBuildRef> refs(n);
    parallel_for((n + kBlock - 1) / kBlock,
                 [&](size_t block) {
                     Bounds bounds[kBlock];
                     const size_t first = block * kBlock, count = std::min(kBlock, n - first);
                     source(first, count, bounds);
                     for (size_t k = 0; k < count; ++k) {
                         BvhBuildRef& ref = refs[first + k];
                         for (int axis = 0; axis < 3; ++axis) {
                             ref.lower[axis] = round_down(bounds[k].lower[axis]);
                             ref.upper[axis] = round_up(bounds[k].upper[axis]);
                         }
                         ref.id = uint32_t(first + k);
                     }
                 },
                 threads, kSerialBelow / kBlock);
    return refs;
}

Bvh::Bvh(LargeArray<Bounds> primitives, BvhBuild method, int leaf_size, int threads, int leaf_lanes,
         const LeafGathering& gathering) {
    LargeArray<BvhBuildRef> refs = float_refs(
        primitives.size(),
        [&](size_t first, size_t count, Bounds* out) { std::copy_n(primitives.data() + first, count, out); }, threads);
    primitives = LargeArray<Bounds>();
    build(refs, method, leaf_size, threads, leaf_lanes, gathering);
}

Bvh::Bvh(size_t count, const BoundsSource& source, BvhBuild method, int leaf_size, int threads, int leaf_lanes) {
    LargeArray<BvhBuildRef> refs = float_refs(count, source, threads);
    build(refs, method, leaf_size, threads, leaf_lanes);
}

void Bvh::build(LargeArray<BvhBuildRef>& refs, BvhBuild method, int leaf_size, int threads, int leaf_lanes,
                const LeafGathering& gathering) {
    const uint32_t n = uint32_t(refs.size());
    order_.resize(n);
    if (n == 0) return;
    leaf_size = std::max(leaf_size, 1);
    const Range root = measure(refs.data(), 0, n);

    NodeArray slots(BvhBuilder::slots_for(n));  // uninitialised: only the tree's nodes are touched
    BvhBuilder builder(refs.data(), slots.data(), method, leaf_size, std::max(leaf_lanes, 1),
                       thread_count(threads) > 1 && n >= 2 * BvhBuilder::kTaskFrom);
    BvhBuilder::Chunk chunk;
    if (builder.parallel()) {
        tbb::task_arena arena(thread_count(threads));
        arena.execute([&] { builder.build(root, 0, 0, chunk); });
    } else {
        builder.build(root, 0, 0, chunk);
    }
    parallel_for(
        n, [&](size_t i) { order_[i] = refs[i].id; }, threads);
    refs = LargeArray<BvhBuildRef>();
    if (method == BvhBuild::Sah)
        wide_ = collapse_to_wide(slots, LeafRule(slots, order_, gathering));
    else
        nodes_ = depth_first(slots, std::min<size_t>(builder.used_slots(), 2 * size_t(n) - 1));  // the tree at most
    for (int axis = 0; axis < 3; ++axis) {
        root_box_.lower[axis] = root.bounds.lower[axis];
        root_box_.upper[axis] = root.bounds.upper[axis];
    }
}

}  // namespace tracer
