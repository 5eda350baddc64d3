#include "scene/mesh_facts.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include <glm/common.hpp>

#include "scene/placement.h"

namespace tracer {

MeshFacts mesh_facts(const TriangleMesh& mesh, const Placed& placed) {
    MeshFacts facts;
    facts.triangles = mesh.triangles.size();
    const Placement placement(placed);
    std::vector<bool> used(mesh.positions.size(), false);
    for (const auto& triangle : mesh.triangles)
        for (uint32_t v : triangle) used[v] = true;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        if (!used[v]) continue;
        const dvec3 p = placement.point(mesh.positions[v]);
        facts.lower = facts.vertices == 0 ? p : glm::min(facts.lower, p);
        facts.upper = facts.vertices == 0 ? p : glm::max(facts.upper, p);
        ++facts.vertices;
    }
    return facts;
}

std::optional<UnmatchedEdge> unmatched_edge(const TriangleMesh& mesh) {
    // Step 1: each vertex named by the first of those at its point.
    const std::vector<dvec3>& p = mesh.positions;
    std::vector<uint32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0u);
    auto before = [&](uint32_t a, uint32_t b) {
        return std::tie(p[a].x, p[a].y, p[a].z, a) < std::tie(p[b].x, p[b].y, p[b].z, b);
    };
    std::sort(order.begin(), order.end(), before);
    std::vector<uint32_t> welded(p.size());
    for (size_t i = 0; i < order.size(); ++i)
        welded[order[i]] = i > 0 && p[order[i]] == p[order[i - 1]] ? welded[order[i - 1]] : order[i];
    // Step 2: every edge of every triangle, by its lower vertex, its direction kept.
    struct Edge {
        uint32_t low, high;
        bool forward;  // runs from low to high
        bool operator<(const Edge& other) const {
            return std::tie(low, high, forward) < std::tie(other.low, other.high, other.forward);
        }
    };
    std::vector<Edge> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (const auto& triangle : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = welded[triangle[size_t(k)]], b = welded[triangle[size_t((k + 1) % 3)]];
            if (a != b) edges.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    std::sort(edges.begin(), edges.end());
    // Step 3: the first edge run one way more often than the other.
    for (size_t first = 0; first < edges.size();) {
        size_t end = first;
        UnmatchedEdge edge{edges[first].low + 1, edges[first].high + 1, 0, 0};
        for (; end < edges.size() && edges[end].low == edges[first].low && edges[end].high == edges[first].high; ++end)
            ++(edges[end].forward ? edge.forward : edge.backward);
        if (edge.forward != edge.backward) return edge;
        first = end;
    }
    return std::nullopt;
}

std::string shape_label(const std::string& kind_or_path, int line) {
    const std::string name = kind_or_path.substr(kind_or_path.find_last_of('/') + 1);
    return line > 0 ? name + " (line " + std::to_string(line) + ")" : name;
}

}  // namespace tracer
