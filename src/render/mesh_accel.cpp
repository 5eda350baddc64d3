#include "render/mesh_accel.h"

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/parallel.h"

namespace tracer {

// Puts the mesh's triangles in the order `ids` (slot i <- triangle ids[i]) and renumbers its
// vertex normals in order of first use, so that the triangles rays meet one after another
// find their shading data close together in memory.
static void to_leaf_order(TriangleMesh& mesh, const std::vector<uint32_t>& ids, int threads) {
    const size_t n = ids.size();
    // Step 1: the triangles' vertex and normal ids in slot order.
    std::vector<std::array<uint32_t, 3>> vertices(n), normal_ids(n);
    parallel_for(n, [&](size_t i) {
        vertices[i] = mesh.vertices[ids[i]];
        normal_ids[i] = mesh.normal_ids[ids[i]];
    }, threads);
    // Step 2: the normals in order of first use.
    constexpr uint32_t kUnseen = ~0u;
    std::vector<uint32_t> new_id(mesh.normals.size(), kUnseen);
    std::vector<Vec3> normals;
    normals.reserve(mesh.normals.size());
    for (auto& triangle : normal_ids)
        for (uint32_t& id : triangle) {
            if (new_id[id] == kUnseen) {
                new_id[id] = uint32_t(normals.size());
                normals.push_back(mesh.normals[id]);
            }
            id = new_id[id];
        }
    mesh.vertices = std::move(vertices);
    mesh.normal_ids = std::move(normal_ids);
    mesh.normals = std::move(normals);
}

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
        ids_ = bvh_.order();
    } else {
        ids_.resize(n);
        for (size_t i = 0; i < n; ++i) ids_[i] = uint32_t(i);
    }
    // Step 2: the mesh in that order, and its triangles as a vertex and two edges.
    if (accel_ != Accelerator::None) to_leaf_order(mesh_, ids_, threads);
    edges_.resize(n);
    parallel_for(n, [&](size_t i) {
        const auto& v = mesh_.vertices[i];
        const Vec3& p0 = mesh_.positions[v[0]];
        edges_[i] = {p0, mesh_.positions[v[1]] - p0, mesh_.positions[v[2]] - p0};
    }, threads);
    // Step 3: may_hit's sphere, around the root box (which holds every triangle), 10^-6 wider.
    if (accel_ != Accelerator::None) {
        const Bounds& box = bvh_.bounds();
        const Real radius = glm::length(box.upper - box.lower) * Real(0.5);
        if (std::isfinite(radius)) {
            sphere_centre_ = box.centre();
            sphere_radius2_ = radius * radius * (1 + 1e-6);
        }
    }
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool MeshAccel::may_hit(const Ray& ray) const {
    // Squared distance of the centre from the ray's line, times |d|^2 (no division); the
    // margin covers its rounding, which grows with the centre's distance squared.
    const Vec3 to_centre = sphere_centre_ - ray.origin;
    const Real along = glm::dot(to_centre, ray.direction);
    const Real dd = glm::dot(ray.direction, ray.direction), cc = glm::dot(to_centre, to_centre);
    return !(cc * dd - along * along > (sphere_radius2_ + cc * 1e-12) * dd);  // NaN: may hit
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
        return true;
    };
    bool found = false;
    if (accel_ == Accelerator::None) {
        counts.primitive_tests += edges_.size();
        for (uint32_t i = 0; i < edges_.size(); ++i) found = test(i, range) || found;
    } else {
        found = bvh_.closest(ray, range, counts, test);
    }
    if (found) out = {ids_[best], best, best_hit};
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

Vec3 MeshAccel::geometric_normal(uint32_t slot) const {
    return glm::normalize(glm::cross(edges_[slot].e1, edges_[slot].e2));
}

Vec3 MeshAccel::shading_normal(const MeshHit& hit) const {
    const auto& n = mesh_.normal_ids[hit.slot];
    const Real u = hit.hit.u, v = hit.hit.v;
    const Vec3 shading =
        normalize_or_zero((1 - u - v) * mesh_.normals[n[0]] + u * mesh_.normals[n[1]] + v * mesh_.normals[n[2]]);
    return shading != Vec3(0) ? shading : geometric_normal(hit.slot);
}

}  // namespace tracer
