// The built tree's reshaping and the facts about it (the build is in bvh_build.cpp, the
// searches in binary_bvh.h and wide_bvh.h).
#include <algorithm>
#include <limits>

#include "accel/bvh.h"

namespace tracer {

void Bvh::expand(const std::vector<uint32_t>& first_entry) {
    // Where each slot of the leaf order starts among the entries, and the entries in that order.
    std::vector<uint32_t> start(order_.size() + 1);
    std::vector<uint32_t> entries;
    entries.reserve(first_entry.back());
    for (size_t slot = 0; slot < order_.size(); ++slot) {
        start[slot] = uint32_t(entries.size());
        for (uint32_t e = first_entry[order_[slot]]; e < first_entry[order_[slot] + 1]; ++e) entries.push_back(e);
    }
    start[order_.size()] = uint32_t(entries.size());
    std::visit([&start](auto& tree) { tree.renumber_leaves(start); }, tree_);
    order_ = std::move(entries);
    stats_ = counted_stats();
}

BvhStats Bvh::counted_stats() const {
    BvhStats s;
    s.nodes = wide() ? wide()->nodes().size() : binary()->nodes().size();
    s.min_leaf = std::numeric_limits<size_t>::max();
    size_t in_leaves = 0;
    for_each_leaf([&](const Bounds&, uint32_t, uint32_t count, int depth) {
        s.depth = std::max(s.depth, depth);
        ++s.leaves;
        in_leaves += count;
        s.min_leaf = std::min<size_t>(s.min_leaf, count);
        s.max_leaf = std::max<size_t>(s.max_leaf, count);
    });
    if (s.leaves == 0) return BvhStats{};
    s.mean_leaf = double(in_leaves) / double(s.leaves);
    return s;
}

}  // namespace tracer
