// Sah's wide tree: collapsed from the binary build (collapse_to_wide) or built directly
// (BvhBuilder::build_wide_tree), the same tree either way.
#include <algorithm>

#include "accel/bvh_builder.h"

namespace tracer {

using bvh_build::Range;

namespace {

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
int wide_children(const NodeArray& nodes, const LeafRule& leaves, uint32_t from, uint32_t (&children)[kWide]) {
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
size_t wide_node_count(const NodeArray& nodes, const LeafRule& leaves) {
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

}  // namespace

LargeArray<WideNode> collapse_to_wide(const NodeArray& nodes, const std::vector<uint32_t>& order,
                                      const LeafGathering& gathering) {
    const LeafRule leaves(nodes, order, gathering);
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

LargeArray<WideNode> in_traversal_order(const LargeArray<WideNode>& slots, uint32_t used) {
    LargeArray<WideNode> wide(1);
    wide.reserve(used);
    struct Move {
        uint32_t from, to;
    };
    std::vector<Move> pending{{0, 0}};
    while (!pending.empty()) {
        const Move move = pending.back();
        pending.pop_back();
        WideNode node = slots[move.from];
        for (int lane = 0; lane < kWide; ++lane) {
            if (node.count[lane] != WideNode::kInner) continue;
            pending.push_back({node.index[lane], uint32_t(wide.size())});
            node.index[lane] = uint32_t(wide.size());
            wide.emplace_back();
        }
        wide[move.to] = node;
    }
    return wide;
}

bool BvhBuilder::gathered(const Range& range) const {
    if (gathering_.most <= 1 || range.count() > gathering_.most) return false;
    for (uint32_t k = range.begin; k < range.end; ++k)
        if (!gathering_.gatherable(refs_[k].id)) return false;
    return true;
}

BvhBuilder::WideChild BvhBuilder::wide_child(const Range& range, int depth) {
    WideChild child{range, {}, {}, depth, false, -1.0f};
    child.inner = !gathered(range) && split(range, depth, child.left, child.right);
    if (child.inner) {
        const glm::vec3 d = range.bounds.upper - range.bounds.lower;
        child.area = d.x * d.y + d.y * d.z + d.z * d.x;
    }
    return child;
}

// A wide node of `children` (at most kWide), lane by lane: leaves as ranges of the order, inner
// children as the nodes in consecutive slots from `first_inner`; lanes without a child hold an
// empty box.
static WideNode wide_node(const BvhBuilder::WideChild* children, int count, uint32_t first_inner) {
    WideNode node;
    for (int lane = 0; lane < kWide; ++lane) {
        for (int axis = 0; axis < 3; ++axis) {
            node.planes[0][axis][lane] = lane < count ? children[lane].range.bounds.lower[axis] : float(kInfinity);
            node.planes[1][axis][lane] = lane < count ? children[lane].range.bounds.upper[axis] : -float(kInfinity);
        }
        node.index[lane] = 0, node.count[lane] = 0;  // no child
        if (lane >= count) continue;
        const BvhBuilder::WideChild& child = children[lane];
        node.index[lane] = child.inner ? first_inner++ : child.range.begin;
        node.count[lane] = child.inner ? WideNode::kInner : child.range.count();
    }
    return node;
}

void BvhBuilder::build_wide_tree(const Range& root) {
    Range left, right;
    if (split(root, 0, left, right)) {
        build_wide(left, right, 0, 0);
        return;
    }
    // A root that is a leaf: a wide root with that one child.
    const WideChild leaf{root, {}, {}, 0, false, -1.0f};
    wide_slots_[0] = wide_node(&leaf, 1, 0);
}

void BvhBuilder::build_wide(const Range& left, const Range& right, int depth, uint32_t to) {
    // Step 1: the children: the split's two sides, then, while there are fewer than kWide, the
    // two sides of the inner child of largest area in its place (the first of equals). Two sides
    // are split at once from kSidesAtOnceFrom primitives between them.
    auto split_sides = [&](const Range& first, const Range& second, int sides_depth, WideChild& a, WideChild& b) {
        if (parallel_ && first.count() + second.count() >= kSidesAtOnceFrom)
            run_both([&] { a = wide_child(first, sides_depth); }, [&] { b = wide_child(second, sides_depth); });
        else
            a = wide_child(first, sides_depth), b = wide_child(second, sides_depth);
    };
    WideChild children[kWide];
    split_sides(left, right, depth + 1, children[0], children[1]);
    int count = 2;
    while (count < kWide) {
        int largest = 0;  // as std::max_element, so that NaN areas choose as in collapse_to_wide
        for (int k = 1; k < count; ++k)
            if (children[largest].area < children[k].area) largest = k;
        if (children[largest].area < 0) break;  // leaves only
        const WideChild opened = children[largest];
        split_sides(opened.left, opened.right, opened.depth + 1, children[largest], children[count]);
        ++count;
    }

    // Step 2: the node, its inner children's nodes in consecutive slots.
    int inner_lanes[kWide], inner_count = 0;
    for (int lane = 0; lane < count; ++lane)
        if (children[lane].inner) inner_lanes[inner_count++] = lane;
    const uint32_t first_inner =
        inner_count > 0 ? used_wide_.fetch_add(uint32_t(inner_count), std::memory_order_relaxed) : 0;
    const WideNode node = wide_node(children, count, first_inner);
    wide_slots_[to] = node;

    // Step 3: the inner children's subtrees, in parallel if the node holds kTaskFrom primitives
    // or more (its children are then often smaller: 3,674 triangles make eight of some 460
    // each, which the other thread should share): the lanes in halves, each half a task.
    auto build_lanes = [&](auto& self, int first, int end) -> void {
        if (end - first > 1 && parallel_ && left.count() + right.count() >= kTaskFrom) {
            const int middle = (first + end) / 2;
            run_both([&] { self(self, first, middle); }, [&] { self(self, middle, end); });
            return;
        }
        for (int k = first; k < end; ++k) {
            const WideChild& child = children[inner_lanes[k]];
            build_wide(child.left, child.right, child.depth, node.index[inner_lanes[k]]);
        }
    };
    build_lanes(build_lanes, 0, inner_count);
}

}  // namespace tracer
