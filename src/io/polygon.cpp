#include "io/polygon.h"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <mapbox/earcut.hpp>

namespace tracer {

// Newell's normal: the polygon's area-weighted normal, robust for non-planar and non-convex
// polygons alike; zero for a degenerate one.
static glm::dvec3 newell_normal(const std::vector<glm::dvec3>& corners) {
    glm::dvec3 normal(0.0);
    for (size_t i = 0; i < corners.size(); ++i) {
        const glm::dvec3& a = corners[i];
        const glm::dvec3& b = corners[(i + 1) % corners.size()];
        normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return normal;
}

// True if triangle (a, b, c) of `corners` faces the same side as `normal` (or has no area).
static bool faces(const std::vector<glm::dvec3>& corners, uint32_t a, uint32_t b, uint32_t c,
                  const glm::dvec3& normal) {
    return glm::dot(glm::cross(corners[b] - corners[a], corners[c] - corners[a]), normal) >= 0;
}

bool triangulate_polygon(const std::vector<glm::dvec3>& corners, std::vector<std::array<uint32_t, 3>>& out) {
    const size_t n = corners.size();
    if (n < 3) return true;
    if (n == 3) {
        out.push_back({0, 1, 2});
        return true;
    }
    const glm::dvec3 normal = newell_normal(corners);
    if (normal == glm::dvec3(0.0)) {  // no area at all: a fan of slivers, dropped later as such
        for (uint32_t i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
        return true;
    }

    // Quads: the shorter diagonal (as tinyobjloader splits them), unless that leaves one half
    // facing backwards, which happens only across the reflex corner of a non-convex quad.
    if (n == 4) {
        const bool short_02 = glm::length(corners[2] - corners[0]) < glm::length(corners[3] - corners[1]);
        const bool ok_02 = faces(corners, 0, 1, 2, normal) && faces(corners, 0, 2, 3, normal);
        const bool ok_13 = faces(corners, 0, 1, 3, normal) && faces(corners, 1, 2, 3, normal);
        if ((short_02 && ok_02) || !ok_13) {
            out.push_back({0, 1, 2});
            out.push_back({0, 2, 3});
        } else {
            out.push_back({0, 1, 3});
            out.push_back({1, 2, 3});
        }
        return true;
    }

    // Larger polygons: drop the normal's largest axis and let Earcut cut the 2D outline.
    const glm::dvec3 size = glm::abs(normal);
    const int drop = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    std::vector<std::vector<std::array<double, 2>>> outline(1);
    outline[0].reserve(n);
    for (const glm::dvec3& p : corners) outline[0].push_back({p[u], p[v]});
    const std::vector<uint32_t> indices = mapbox::earcut<uint32_t>(outline);
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        std::array<uint32_t, 3> triangle = {indices[i], indices[i + 1], indices[i + 2]};
        if (!faces(corners, triangle[0], triangle[1], triangle[2], normal)) std::swap(triangle[1], triangle[2]);
        out.push_back(triangle);
    }
    return indices.size() / 3 == n - 2;
}

}  // namespace tracer
