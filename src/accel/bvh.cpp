// The built tree's reshaping and the facts about it (the build is in bvh_build.cpp, the
// traversals in bvh_traversal.inl).
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
    auto widen = [&](uint32_t& index, uint32_t& count) {
        const uint32_t first = index;
        index = start[first], count = start[first + count] - start[first];
    };
    for (WideNode& node : wide_)
        for (int lane = 0; lane < kWide; ++lane)
            if (node.count[lane] != WideNode::kInner && node.count[lane] != 0)
                widen(node.index[lane], node.count[lane]);
    for (BvhNode& node : nodes_)
        if (node.count > 0) widen(node.index, node.count);
    order_ = std::move(entries);
}

BvhStats Bvh::stats() const {
    BvhStats s;
    s.nodes = wide_.empty() ? nodes_.size() : wide_.size();
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

std::vector<Bounds> Bvh::cover(int levels) const {
    std::vector<Bounds> out;
    struct Visit {
        uint32_t node;
        int level;
    };
    std::vector<Visit> pending;
    if (!wide_.empty()) {
        pending.push_back({0, 0});
        while (!pending.empty()) {
            const Visit visit = pending.back();
            pending.pop_back();
            const WideNode& node = wide_[visit.node];
            for (int lane = 0; lane < kWide; ++lane) {
                if (node.count[lane] == 0) continue;
                if (node.count[lane] == WideNode::kInner && visit.level + 1 < levels) {
                    pending.push_back({node.index[lane], visit.level + 1});
                    continue;
                }
                Bounds box;
                for (int axis = 0; axis < 3; ++axis)
                    box.lower[axis] = node.planes[0][axis][lane], box.upper[axis] = node.planes[1][axis][lane];
                out.push_back(box);
            }
        }
    } else if (!nodes_.empty()) {
        pending.push_back({0, 0});
        while (!pending.empty()) {
            const Visit visit = pending.back();
            pending.pop_back();
            const BvhNode& node = nodes_[visit.node];
            if (node.count > 0 || visit.level >= levels) {
                const float(&b)[2][3] = node.box;
                out.push_back(Bounds{{b[0][0], b[0][1], b[0][2]}, {b[1][0], b[1][1], b[1][2]}});
                continue;
            }
            pending.push_back({visit.node + 1, visit.level + 1});
            pending.push_back({node.index, visit.level + 1});
        }
    }
    return out;
}

}  // namespace tracer
