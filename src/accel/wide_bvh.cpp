// WideBvh's walks that are not searches: its cover and the renumbering of its leaves.
#include "accel/wide_bvh.h"

namespace tracer {

std::vector<Bounds> WideBvh::cover(int levels) const {
    std::vector<Bounds> out;
    struct Visit {
        uint32_t node;
        int level;
    };
    std::vector<Visit> pending;
    if (!nodes_.empty()) pending.push_back({0, 0});
    while (!pending.empty()) {
        const Visit visit = pending.back();
        pending.pop_back();
        const WideNode& node = nodes_[visit.node];
        for (int lane = 0; lane < kWide; ++lane) {
            if (node.count[lane] == 0) continue;
            if (node.count[lane] == WideNode::kInner && visit.level + 1 < levels)
                pending.push_back({node.index[lane], visit.level + 1});
            else
                out.push_back(bounds_of(node, lane));
        }
    }
    return out;
}

void WideBvh::renumber_leaves(const std::vector<uint32_t>& start) {
    for (WideNode& node : nodes_)
        for (int lane = 0; lane < kWide; ++lane)
            if (node.count[lane] != WideNode::kInner && node.count[lane] != 0) {
                const uint32_t first = node.index[lane];
                node.index[lane] = start[first], node.count[lane] = start[first + node.count[lane]] - start[first];
            }
}

}  // namespace tracer
