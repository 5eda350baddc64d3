#include "accel/bvh.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "accel/bvh_builder.h"
#include "base/parallel.h"

namespace tracer {

using bvh_build::FloatBounds;
using bvh_build::Range;

namespace {

// Four floats (four ints) in one vector register (GCC/Clang vector extensions: portable, no
// intrinsics).
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

v4f load_v4f(const glm::vec3& first) {  // the three floats and the next four bytes (never read back)
    v4f lanes;
    std::memcpy(&lanes, &first, sizeof lanes);
    return lanes;
}

// A reference's center, lane by lane (lane 3 unused): the same floats as BvhBuildRef::center.
v4f center_lanes(const BvhBuildRef& ref) {
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

Range measure(const BvhBuildRef* refs, uint32_t begin, uint32_t end) {
    Range range{begin, end, {}, {}};
    for (uint32_t i = begin; i < end; ++i) {
        range.bounds.extend(refs[i].lower, refs[i].upper);
        range.centers.extend(refs[i].center());
    }
    return range;
}

// Moves the references for which goes_left holds before the others (as std::partition does),
// extending `left` and `right` by the centers of each side; returns the first of the others.
template <typename GoesLeft>
BvhBuildRef* partition(BvhBuildRef* begin, BvhBuildRef* end, GoesLeft goes_left, VectorBounds& left,
                       VectorBounds& right) {
    for (;;) {
        for (; begin < end && goes_left(*begin); ++begin) {
            const v4f c = center_lanes(*begin);
            left.extend(c, c);
        }
        for (; begin < end && !goes_left(end[-1]); --end) {
            const v4f c = center_lanes(end[-1]);
            right.extend(c, c);
        }
        if (begin == end) return begin;
        std::swap(*begin, end[-1]);  // now each is on its side
    }
}

// The SAH's bins of a range: how many per axis, and the map from a center to its bins.
struct SahBinning {
    int bin_count;
    glm::vec3 extent;           // of the range's centers
    v4f factor = {0, 0, 0, 0};  // bins per unit of length, per axis
    v4f origin;                 // the centers' lower corner

    SahBinning(const Range& range, int bins)
        : bin_count(bins),
          extent(range.centers.upper - range.centers.lower),
          origin{range.centers.lower.x, range.centers.lower.y, range.centers.lower.z, 0} {
        for (int axis = 0; axis < 3; ++axis) {
            const float scale = float(bin_count) / extent[axis];
            factor[axis] = extent[axis] > 0 && std::isfinite(scale) ? scale : 0.0f;  // also a NaN or infinite extent
        }
    }

    // Bins (boxes and counts) of refs[begin, end) for every axis, four lanes at a time; each
    // reference notes its bins (BvhBuildRef::bins). Only the bins in use are cleared: small
    // nodes are most of the nodes.
    void bin_refs(BvhBuildRef* refs, uint32_t begin, uint32_t end, VectorBin (&bins)[3][kSahBins]) const {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < bin_count; ++b) bins[axis][b] = VectorBin::empty();
        // Copies: the stores below could alias the members, which would be read again each time.
        const v4f lowest = origin, scale = factor, last_bin = v4f{} + float(bin_count - 1);
        for (uint32_t i = begin; i < end; ++i) {
            BvhBuildRef& ref = refs[i];
            // The bin on each axis (lane 3 unused), clamped as floats first: converting a NaN or
            // out-of-range float is undefined.
            const v4i bin =
                __builtin_convertvector(lane_min(lane_max((center_lanes(ref) - lowest) * scale, v4f{}), last_bin), v4i);
            const v4f lower = load_v4f(ref.lower), upper = load_v4f(ref.upper);
            for (int axis = 0; axis < 3; ++axis) {
                VectorBin& into = bins[axis][bin[axis]];
                into.box.extend(lower, upper);
                ++into.count;
            }
            ref.bins = uint32_t(bin[0]) | uint32_t(bin[1]) << 8 | uint32_t(bin[2]) << 16;
        }
    }
};
using AxisBins = VectorBin[3][kSahBins];

// A boundary between bins: left of it, the bins up to `bin` on `axis` (-1: none found), and
// its children's area-weighted tests.
struct SahBoundary {
    int axis = -1, bin = 0;
    double weighted = std::numeric_limits<double>::infinity();
};

// The boundary of least area-weighted tests (tests(n): a leaf of n primitives' cost), sweeping
// right-hand sides from the end. The node's area divides the best only.
template <typename Tests>
SahBoundary cheapest_boundary(const AxisBins& bins, const SahBinning& binning, const Tests& tests) {
    SahBoundary best;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(binning.extent[axis] > 0)) continue;
        float right_area[kSahBins];
        VectorBin accumulated = VectorBin::empty();
        for (int b = binning.bin_count - 1; b > 0; --b) {
            accumulated.add(bins[axis][b]);
            right_area[b] = accumulated.half_area();
        }
        const uint32_t total = accumulated.count + bins[axis][0].count;
        accumulated = VectorBin::empty();
        for (int b = 0; b < binning.bin_count - 1; ++b) {
            accumulated.add(bins[axis][b]);
            const uint32_t right_count = total - accumulated.count;
            if (accumulated.count == 0 || right_count == 0) continue;
            const double weighted = double(accumulated.half_area()) * tests(accumulated.count) +
                                    double(right_area[b + 1]) * tests(right_count);
            if (weighted < best.weighted) best = {axis, b, weighted};
        }
    }
    return best;
}

// partition over [begin, end) in its two halves at once ([begin, half) and [half, end)); then
// the first half's right part and the second half's left part trade places (as many references
// as the smaller of the two holds).
template <typename GoesLeft>
BvhBuildRef* partition_in_halves(BvhBuildRef* begin, BvhBuildRef* half, BvhBuildRef* end, GoesLeft goes_left,
                                 VectorBounds& left, VectorBounds& right) {
    BvhBuildRef *first_middle, *second_middle;
    VectorBounds first_left = VectorBounds::empty(), first_right = VectorBounds::empty();
    run_both([&] { first_middle = partition(begin, half, goes_left, first_left, first_right); },
             [&] { second_middle = partition(half, end, goes_left, left, right); });
    const size_t trade = std::min(half - first_middle, second_middle - half);
    std::swap_ranges(first_middle, first_middle + trade, second_middle - trade);
    left.extend(first_left), right.extend(first_right);
    return first_middle + (second_middle - half);
}

}  // namespace

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
    return split_sah(range, left, right);
}

// The assignment's split: sort by centroid along the axis, first half left.
bool BvhBuilder::split_median(const Range& range, int axis, Range& left, Range& right) {
    std::sort(refs_ + range.begin, refs_ + range.end,
              [axis](const BvhBuildRef& a, const BvhBuildRef& b) { return a.center()[axis] < b.center()[axis]; });
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
bool BvhBuilder::split_sah(const Range& range, Range& left, Range& right) {
    const uint32_t count = range.count();
    const SahBinning binning(range, int(std::min<uint32_t>({count, kSahBins, 4 + count / 20})));

    // Step 1: bins (boxes and counts) for every axis; ranges of kParallelFrom or more are binned
    // in two halves at once.
    const bool in_parallel = parallel_ && count >= kParallelFrom;
    const uint32_t half = range.begin + count / 2;
    AxisBins bins;
    if (in_parallel) {
        AxisBins first_half;
        run_both([&] { binning.bin_refs(refs_, range.begin, half, first_half); },
                 [&] { binning.bin_refs(refs_, half, range.end, bins); });
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < binning.bin_count; ++b) bins[axis][b].add(first_half[axis][b]);
    } else {
        binning.bin_refs(refs_, range.begin, range.end, bins);
    }

    // Step 2: the cheapest boundary, or a leaf where that costs less.
    const SahBoundary best = cheapest_boundary(bins, binning, [this](uint32_t n) { return tests(n); });
    const double node_area = range.bounds.half_area() > 0 ? range.bounds.half_area() : 1.0;
    const double best_cost = kTraversalCost + kIntersectionCost * best.weighted / node_area;
    const double leaf_cost = kIntersectionCost * tests(count);
    if (count <= uint32_t(leaf_size_) && (best.axis < 0 || leaf_cost <= best_cost)) return false;
    if (best.axis < 0) {  // all centers coincide: any halves will do
        split_at(range, range.begin + count / 2, left, right);
        return true;
    }

    // Step 3: partition, measuring the centers on each side; the children's boxes from the bins.
    const uint32_t shift = 8 * uint32_t(best.axis);
    auto goes_left = [&](const BvhBuildRef& ref) { return int((ref.bins >> shift) & 0xFF) <= best.bin; };
    VectorBounds left_centers = VectorBounds::empty(), right_centers = VectorBounds::empty();
    BvhBuildRef* const middle =
        in_parallel ? partition_in_halves(refs_ + range.begin, refs_ + half, refs_ + range.end, goes_left, left_centers,
                                          right_centers)
                    : partition(refs_ + range.begin, refs_ + range.end, goes_left, left_centers, right_centers);
    VectorBin left_bins = VectorBin::empty(), right_bins = VectorBin::empty();
    for (int b = 0; b < binning.bin_count; ++b) (b <= best.bin ? left_bins : right_bins).add(bins[best.axis][b]);
    left = {range.begin, uint32_t(middle - refs_), left_bins.box.floats(), left_centers.floats()};
    right = {left.end, range.end, right_bins.box.floats(), right_centers.floats()};
    return true;
}

NodeArray depth_first(const NodeArray& slots, size_t used) {
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
         const LeafGathering& gathering, uint32_t direct_wide_from) {
    LargeArray<BvhBuildRef> refs = float_refs(
        primitives.size(),
        [&](size_t first, size_t count, Bounds* out) { std::copy_n(primitives.data() + first, count, out); }, threads);
    primitives = LargeArray<Bounds>();
    build(refs, method, leaf_size, threads, leaf_lanes, gathering, direct_wide_from);
    stats_ = counted_stats();
}

Bvh::Bvh(size_t count, const BoundsSource& source, BvhBuild method, int leaf_size, int threads, int leaf_lanes) {
    LargeArray<BvhBuildRef> refs = float_refs(count, source, threads);
    build(refs, method, leaf_size, threads, leaf_lanes);
    stats_ = counted_stats();
}

void Bvh::build(LargeArray<BvhBuildRef>& refs, BvhBuild method, int leaf_size, int threads, int leaf_lanes,
                const LeafGathering& gathering, uint32_t direct_wide_from) {
    const uint32_t n = uint32_t(refs.size());
    order_.resize(n);
    if (n == 0) return;
    leaf_size = std::max(leaf_size, 1);
    const Range root = measure(refs.data(), 0, n);

    const bool parallel = thread_count(threads) > 1 && n >= 2 * BvhBuilder::kTaskFrom;
    auto run = [&](const auto& build_tree) {
        if (!parallel) return build_tree();
        run_on_threads(threads, build_tree);
    };
    const int lanes = std::max(leaf_lanes, 1);
    NodeArray slots;  // the binary tree, unless Sah's wide one is built directly
    const bool built_wide = method == BvhBuild::Sah && n >= direct_wide_from;
    if (built_wide) {
        LargeArray<WideNode> wide_slots(std::max<size_t>(n - 1, 1));  // uninitialised: only the tree's are touched
        BvhBuilder builder(refs.data(), nullptr, wide_slots.data(), method, leaf_size, lanes, parallel, gathering);
        run([&] { builder.build_wide_tree(root); });
        tree_ = WideBvh(in_traversal_order(wide_slots, builder.used_wide_slots()));
    } else {
        slots.resize(BvhBuilder::slots_for(n));  // uninitialised: only the tree's nodes are touched
        BvhBuilder builder(refs.data(), slots.data(), nullptr, method, leaf_size, lanes, parallel, gathering);
        BvhBuilder::Chunk chunk;
        run([&] { builder.build(root, 0, 0, chunk); });
        if (method != BvhBuild::Sah)
            tree_ = BinaryBvh(depth_first(slots, std::min<size_t>(builder.used_slots(), 2 * size_t(n) - 1)));
    }
    parallel_for(
        n, [&](size_t i) { order_[i] = refs[i].id; }, threads);
    refs = LargeArray<BvhBuildRef>();
    if (method == BvhBuild::Sah && !built_wide) tree_ = WideBvh(collapse_to_wide(slots, order_, gathering));
    for (int axis = 0; axis < 3; ++axis) {
        root_box_.lower[axis] = root.bounds.lower[axis];
        root_box_.upper[axis] = root.bounds.upper[axis];
    }
}

}  // namespace tracer
