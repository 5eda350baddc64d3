#include "render/mesh_accel.h"

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/geometry.h"
#include "render/parallel.h"

namespace tracer {

MeshAccel::MeshAccel(TriangleMesh mesh, Accelerator accel, int leaf_size, int threads)
    : mesh_(std::move(mesh)), accel_(accel) {
    const auto start = std::chrono::steady_clock::now();
    const size_t n = mesh_.vertices.size();
    // Step 1: the accelerator over the triangles' bounds, and the leaf order.
    if (accel_ != Accelerator::None) {
        LargeArray<Bounds> bounds(n);
        parallel_for(n, [&](size_t i) {
            for (uint32_t v : mesh_.vertices[i]) bounds[i].extend(mesh_.positions[v]);
        }, threads);
        bvh_ = Bvh(bounds, accel_, leaf_size, threads);
    }
    // Step 2: the triangles in that order, as a vertex and two edges, and their hit records.
    edges_.resize(n);
    hit_records_.resize(n);
    parallel_for(n, [&](size_t i) {
        const uint32_t triangle = accel_ != Accelerator::None ? bvh_.order()[i] : uint32_t(i);
        const auto& v = mesh_.vertices[triangle];
        const Vec3& p0 = mesh_.positions[v[0]];
        edges_[i] = {p0, mesh_.positions[v[1]] - p0, mesh_.positions[v[2]] - p0};
        const auto& normal = mesh_.normal_ids[triangle];
        hit_records_[i] = {{mesh_.normals[normal[0]], mesh_.normals[normal[1]], mesh_.normals[normal[2]]}, triangle};
    }, threads);
    // Step 3: may_hit's sphere, around the root box (which holds every triangle).
    if (accel_ != Accelerator::None) {
        const Bounds& box = bvh_.bounds();
        const Real radius = glm::length(box.upper - box.lower) * Real(0.5);
        if (std::isfinite(radius)) {
            sphere_centre_ = box.centre();
            sphere_radius2_ = radius * radius;
        }
    }
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool MeshAccel::may_hit(const Ray& ray) const {
    return line_may_meet_sphere(ray, sphere_centre_, sphere_radius2_);
}

bool MeshAccel::intersect(const Ray& ray, Interval& range, MeshHit& out, TraversalCounts& counts) const {
    if (accel_ != Accelerator::None && !may_hit(ray)) return false;
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
    if (accel_ == Accelerator::None) {
        counts.primitive_tests += edges_.size();
        for (uint32_t i = 0; i < edges_.size(); ++i) found = test(i, range) || found;
    } else {
        found = bvh_.closest(ray, range, counts, test);
    }
    if (found) out = {hit_records_[best].triangle, best, best_hit};
    return found;
}

bool MeshAccel::occluded(const Ray& ray, Interval range, TraversalCounts& counts) const {
    if (accel_ != Accelerator::None && !may_hit(ray)) return false;
    auto test = [&](uint32_t i, Interval& r) {
        TriangleHit hit;
        return intersect_triangle(ray, edges_[i], r, hit);
    };
    if (accel_ == Accelerator::None) {
        for (uint32_t i = 0; i < edges_.size(); ++i) {
            ++counts.primitive_tests;
            if (test(i, range)) return true;
        }
        return false;
    }
    return bvh_.any(ray, range, counts, test);
}

Vec3 MeshAccel::geometric_normal(uint32_t triangle) const {
    const auto& v = mesh_.vertices[triangle];
    const Vec3& p0 = mesh_.positions[v[0]];
    return glm::normalize(glm::cross(mesh_.positions[v[1]] - p0, mesh_.positions[v[2]] - p0));
}

Vec3 MeshAccel::shading_normal(const MeshHit& hit) const {
    const Vec3(&n)[3] = hit_records_[hit.slot].normals;
    const Real u = hit.hit.u, v = hit.hit.v;
    const Vec3 shading = normalize_or_zero((1 - u - v) * n[0] + u * n[1] + v * n[2]);
    return shading != Vec3(0) ? shading : geometric_normal(hit.triangle);
}

}  // namespace tracer
