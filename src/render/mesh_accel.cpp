#include "render/mesh_accel.h"

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "base/parallel.h"

namespace tracer {

std::vector<Vec3> area_weighted_normals(const std::vector<Vec3>& positions,
                                        const std::vector<std::array<uint32_t, 3>>& triangles) {
    std::vector<Vec3> sums(positions.size(), Vec3(0));
    for (const auto& t : triangles) {
        // The unnormalised cross product is the face normal times twice the area.
        const Vec3 weighted = glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
        for (uint32_t v : t) sums[v] += weighted;
    }
    for (Vec3& n : sums) n = normalize_or_zero(n);
    return sums;
}

MeshAccel::MeshAccel(const TriangleMesh& file, const Placement& placement, const SearchSettings& settings)
    : brute_force_(settings.brute_force) {
    const auto start = std::chrono::steady_clock::now();
    const size_t n = file.triangles.size();
    const int threads = settings.threads;
    // Step 1: the placed vertices and their normals.
    std::vector<Vec3> positions(file.positions.size());
    parallel_for(positions.size(), [&](size_t i) { positions[i] = placement.point(Vec3(file.positions[i])); }, threads);
    const bool file_normals = !file.normal_ids.empty();
    std::vector<Vec3> normals;
    if (file_normals) {
        normals.resize(file.normals.size());
        parallel_for(normals.size(), [&](size_t i) {
            normals[i] = normalize_or_zero(placement.normal * Vec3(file.normals[i]));
        }, threads);
    } else {
        normals = area_weighted_normals(positions, file.triangles);
    }
    const auto& normal_ids = file_normals ? file.normal_ids : file.triangles;

    // Step 2: the accelerator over the triangles' bounds, and the leaf order.
    LargeArray<Bounds> boxes(n);
    parallel_for(n, [&](size_t i) {
        boxes[i] = Bounds{};
        for (uint32_t v : file.triangles[i]) boxes[i].extend(positions[v]);
    }, threads);
    for (const Bounds& box : boxes) bounds_.extend(box);
    if (!brute_force_) bvh_ = Bvh(boxes, settings.build, settings.leaf_size, threads);

    // Step 3: the triangles in that order, as a vertex and two edges, and their hit records.
    edges_.resize(n);
    hit_records_.resize(n);
    parallel_for(n, [&](size_t i) {
        const uint32_t triangle = brute_force_ ? uint32_t(i) : bvh_.order()[i];
        const auto& v = file.triangles[triangle];
        const Vec3& p0 = positions[v[0]];
        edges_[i] = {p0, positions[v[1]] - p0, positions[v[2]] - p0};
        const auto& ids = normal_ids[triangle];
        hit_records_[i] = {{normals[ids[0]], normals[ids[1]], normals[ids[2]]}, triangle};
    }, threads);
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool MeshAccel::intersect(const Ray& ray, Interval& range, MeshHit& out, TraversalCounts& counts) const {
    uint32_t best = 0;
    TriangleHit best_hit;
    auto test = [&](uint32_t i, Interval& r) {
        TriangleHit hit;
        if (!intersect_triangle(ray, edges_[i], r, hit)) return false;
        r.max = hit.t;
        best = i;
        best_hit = hit;
        // Read when the search ends, if no nearer hit: ask for both cache lines it may span.
        __builtin_prefetch(&hit_records_[i]);
        __builtin_prefetch(&hit_records_[i].triangle);
        return true;
    };
    bool found = false;
    if (brute_force_) {
        counts.primitive_tests += edges_.size();
        for (uint32_t i = 0; i < edges_.size(); ++i) found = test(i, range) || found;
    } else {
        found = bvh_.closest(ray, range, counts, test);
    }
    if (found) out = {best, best_hit};
    return found;
}

bool MeshAccel::occluded(const Ray& ray, Interval range, TraversalCounts& counts) const {
    auto test = [&](uint32_t i, Interval& r) {
        TriangleHit hit;
        return intersect_triangle(ray, edges_[i], r, hit);
    };
    if (brute_force_) {
        for (uint32_t i = 0; i < edges_.size(); ++i) {
            ++counts.primitive_tests;
            if (test(i, range)) return true;
        }
        return false;
    }
    return bvh_.any(ray, range, counts, test);
}

Vec3 MeshAccel::geometric_normal(uint32_t slot) const {
    return glm::normalize(glm::cross(edges_[slot].e1, edges_[slot].e2));
}

Vec3 MeshAccel::shading_normal(uint32_t slot, Real u, Real v) const {
    const Vec3(&n)[3] = hit_records_[slot].normals;
    const Vec3 shading = normalize_or_zero((1 - u - v) * n[0] + u * n[1] + v * n[2]);
    return shading != Vec3(0) ? shading : geometric_normal(slot);
}

Vec3 MeshAccel::shading_normal(uint32_t slot, Real u, Real v, const glm::dmat3& normal_map) const {
    const Vec3(&n)[3] = hit_records_[slot].normals;
    const Vec3 shading = normalize_or_zero((1 - u - v) * normalize_or_zero(normal_map * n[0]) +
                                           u * normalize_or_zero(normal_map * n[1]) +
                                           v * normalize_or_zero(normal_map * n[2]));
    return shading != Vec3(0) ? shading : glm::normalize(normal_map * geometric_normal(slot));
}

size_t MeshAccel::memory_bytes() const {
    return bvh_.memory_bytes() + edges_.capacity() * sizeof(TriangleEdges) + hit_records_.capacity() * sizeof(HitRecord);
}

}  // namespace tracer
