#include "scene/mesh_facts.h"

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

std::string shape_label(const std::string& kind_or_path, int line) {
    const std::string name = kind_or_path.substr(kind_or_path.find_last_of('/') + 1);
    return line > 0 ? name + " (line " + std::to_string(line) + ")" : name;
}

}  // namespace tracer
