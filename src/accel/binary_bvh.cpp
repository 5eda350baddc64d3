// BinaryBvh's walks that are not searches: its cover and the renumbering of its leaves.
#include "accel/binary_bvh.h"

namespace tracer {

std::vector<Bounds> BinaryBvh::cover(int levels) const {
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
        const BvhNode& node = nodes_[visit.node];
        if (node.count > 0 || visit.level >= levels) {
            out.push_back(bounds_of(node));
            continue;
        }
        pending.push_back({visit.node + 1, visit.level + 1});
        pending.push_back({node.index, visit.level + 1});
    }
    return out;
}

void BinaryBvh::renumber_leaves(const std::vector<uint32_t>& start) {
    for (BvhNode& node : nodes_)
        if (node.count > 0) {
            const uint32_t first = node.index;
            node.index = start[first], node.count = start[first + node.count] - start[first];
        }
}

}  // namespace tracer
