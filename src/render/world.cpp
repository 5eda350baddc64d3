#include "render/world.h"

#include <chrono>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render/geometry.h"

namespace tracer {
namespace {

// The top level's leaves hold at most this many objects (measured: docs/performance.md).
constexpr int kTopLeafSize = 1;
// How far below a shared mesh's BVH root its instances' world boxes are taken from: the placed
// corners of the boxes there (up to 64 in a wide tree) bound a rotated mesh far more tightly
// than the placed corners of its whole box.
constexpr int kInstanceBoxLevels = 2;

SearchSettings search_settings(const RenderSettings& render, int threads) {
    SearchSettings settings;
    settings.brute_force = render.accel == Accelerator::None;
    settings.build = render.accel == Accelerator::Box      ? BvhBuild::Box
                     : render.accel == Accelerator::Median ? BvhBuild::Median
                                                           : BvhBuild::Sah;
    settings.leaf_size = render.leaf_size;
    settings.threads = threads;
    return settings;
}

// The box around `box` placed by `linear` and `translate` (its eight corners placed).
Bounds placed_box(const Bounds& box, const glm::dmat3& linear, const Vec3& translate) {
    Bounds out;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{(corner & 1 ? box.upper : box.lower).x, (corner & 2 ? box.upper : box.lower).y,
                     (corner & 4 ? box.upper : box.lower).z};
        out.extend(linear * p + translate);
    }
    return out;
}

}  // namespace

World::World(const SceneDescription& scene, const SceneMeshes& meshes, int threads, bool flatten_shared)
    : materials_(scene.materials), lights_(scene.lights) {
    const SearchSettings settings = search_settings(scene.render, threads);
    // Step 1: spheres and planes.
    for (const Sphere& s : scene.spheres) {
        const uint32_t index = uint32_t(spheres_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::Sphere, index, s.material});
        spheres_.push_back({Vec3(s.center), Real(s.radius)});
        bounded_.push_back({Vec3(s.center), Real(s.radius), object, index, ObjectKind::Sphere});
        boxes_.push_back({Vec3(s.center) - Real(s.radius), Vec3(s.center) + Real(s.radius)});
    }
    for (const Plane& p : scene.planes) {
        objects_.push_back({ObjectKind::Plane, uint32_t(planes_.size()), p.material});
        planes_.push_back({Vec3(p.point), Vec3(p.normal), uint32_t(objects_.size() - 1)});
    }
    // Step 2: the meshes, each file built once, and an instance per mesh block.
    add_meshes(scene, meshes, settings, flatten_shared);
    // Step 3: the top level over every bounded object.
    build_top_level(settings);
}

void World::add_bounded(const Bounds& box, uint32_t object, uint32_t instance) {
    const Real radius = glm::length(box.upper - box.lower) * Real(0.5);
    bounded_.push_back({box.centre(), std::isfinite(radius) ? radius : kInfinity, object, instance,
                        ObjectKind::MeshInstance});
    boxes_.push_back(box);
}

void World::add_meshes(const SceneDescription& scene, const SceneMeshes& meshes, const SearchSettings& settings,
                       bool flatten_shared) {
    std::vector<int> blocks_of_file(meshes.files.size(), 0);
    for (uint32_t file : meshes.file_of_block) ++blocks_of_file[file];
    std::map<uint32_t, uint32_t> shared_mesh;  // file -> index into meshes_
    std::vector<MeshPart> merged;              // the blocks built placed, in one mesh
    std::vector<uint32_t> merged_instances;
    for (size_t block = 0; block < scene.meshes.size() && block < meshes.file_of_block.size(); ++block) {
        const Mesh& mesh = scene.meshes[block];
        const uint32_t file = meshes.file_of_block[block];
        const Placement placement(mesh);
        const uint32_t index = uint32_t(instances_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::MeshInstance, index, mesh.material});
        MeshInstance instance;
        if (blocks_of_file[file] == 1 || flatten_shared) {
            // Placed in world coordinates, with every other such block, in one mesh.
            merged.push_back({&meshes.files[file], placement, object});
            merged_instances.push_back(index);
        } else {
            // Shared: built once in the file's coordinates; rays are carried there.
            auto [known, is_new] = shared_mesh.try_emplace(file, uint32_t(meshes_.size()));
            if (is_new) meshes_.emplace_back(meshes.files[file], Placement(), settings);
            instance.mesh = known->second;
            instance.placed = false;
            instance.to_object = glm::inverse(placement.linear);
            instance.translate = placement.translate;
            const MeshAccel& shared = meshes_[instance.mesh];
            const std::vector<Bounds> cover =
                shared.brute_force() ? std::vector<Bounds>{shared.bounds()} : shared.bvh().cover(kInstanceBoxLevels);
            Bounds box;
            for (const Bounds& part : cover) box.extend(placed_box(part, placement.linear, placement.translate));
            add_bounded(box, object, index);
        }
        instances_.push_back(instance);
    }
    if (merged.empty()) return;
    for (uint32_t index : merged_instances) instances_[index].mesh = uint32_t(meshes_.size());
    meshes_.emplace_back(merged, settings);
    add_bounded(meshes_.back().bounds(), kObjectOfTriangle, merged_instances.front());
}

void World::build_top_level(const SearchSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    Bounds all;
    for (const Bounds& box : boxes_) all.extend(box);
    if (!bounded_.empty()) {
        const Real radius = glm::length(all.upper - all.lower) * Real(0.5);
        sphere_centre_ = all.centre();
        sphere_radius2_ = std::isfinite(radius) ? radius * radius : kInfinity;
    }
    linear_ = settings.brute_force || bounded_.size() <= kLinearObjects;
    if (!linear_) {
        top_ = Bvh(boxes_, BvhBuild::Sah, kTopLeafSize, settings.threads);
        std::vector<Bounded> in_leaf_order;
        in_leaf_order.reserve(bounded_.size());
        for (uint32_t i : top_.order()) in_leaf_order.push_back(bounded_[i]);
        bounded_ = std::move(in_leaf_order);
    }
    boxes_ = {};  // only the build needs them
    top_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

[[gnu::always_inline]] inline bool World::hit_instance(uint32_t index, uint32_t object, const Ray& ray, Interval& range, Hit& hit,
                         SearchCounts& counts) const {
    const MeshInstance& instance = instances_[index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    MeshHit mesh_hit;
    const bool found = instance.placed ? mesh.intersect(ray, range, mesh_hit, counts.triangles)
                                       : mesh.intersect(instance.to_mesh(ray), range, mesh_hit, counts.triangles);
    if (found)
        hit = {object != kObjectOfTriangle ? object : mesh.tag_of(mesh_hit.slot), mesh_hit.slot, range.max,
               mesh_hit.hit.u, mesh_hit.hit.v};
    return found;
}

bool World::instance_blocks(uint32_t index, const Ray& ray, Interval range, SearchCounts& counts) const {
    const MeshInstance& instance = instances_[index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    return instance.placed ? mesh.occluded(ray, range, counts.triangles)
                           : mesh.occluded(instance.to_mesh(ray), range, counts.triangles);
}

[[gnu::always_inline]] inline bool World::nearest_plane(const Ray& ray, Interval& range, Hit& hit) const {
    bool found = false;
    for (const PlaneShape& p : planes_) {
        if (auto t = intersect_plane(ray, p.point, p.normal, range)) {
            range.max = *t;
            hit = {p.object, 0, *t, 0, 0};
            found = true;
        }
    }
    return found;
}

[[gnu::always_inline]] inline bool World::nearest_one_by_one(const Ray& ray, Interval& range, Hit& hit, SearchCounts& counts) const {
    // Spheres, planes, then meshes (objects are numbered in this order; bounded_ lists the
    // spheres, then the meshes).
    bool found = false;
    const uint32_t spheres = uint32_t(spheres_.size());
    for (uint32_t i = 0; i < spheres; ++i) {
        if (auto t = intersect_sphere(ray, spheres_[i].center, spheres_[i].radius, range)) {
            range.max = *t;
            hit = {i, 0, *t, 0, 0};
            found = true;
        }
    }
    found = nearest_plane(ray, range, hit) || found;
    for (size_t i = spheres; i < bounded_.size(); ++i) {
        const Bounded& b = bounded_[i];
        if (line_may_meet_sphere(ray, b.centre, b.radius * b.radius))
            found = hit_instance(b.index, b.object, ray, range, hit, counts) || found;
    }
    counts.objects.primitive_tests += bounded_.size();
    return found;
}

std::optional<Hit> World::nearest_hit(const Ray& ray, Interval range, SearchCounts& counts) const {
    Hit hit;
    bool found = false;
    if (linear_) {
        found = nearest_one_by_one(ray, range, hit, counts);
    } else {
        // Each hit shrinks range.max, so later objects only count when they are nearer. Planes
        // first: a floor's hit lets the top level skip every box behind it.
        found = nearest_plane(ray, range, hit);
        auto test = [&](uint32_t i, Interval& r) {
            const Bounded& b = bounded_[i];
            if (b.kind != ObjectKind::Sphere) return hit_instance(b.index, b.object, ray, r, hit, counts);
            const auto t = intersect_sphere(ray, b.centre, b.radius, r);
            if (!t) return false;
            r.max = *t;
            hit = {b.object, 0, *t, 0, 0};
            return true;
        };
        found = top_.closest(ray, range, counts.objects, test) || found;
    }
    if (!found) return std::nullopt;
    return hit;
}

// Inlined into intersect(): as a call of its own it costs the bunny's primary rays 10% (the
// hit's fields go through memory).
[[gnu::always_inline]] inline SurfaceHit World::surface_at(const Ray& ray, const Hit& hit) const {
    const Object& object = objects_[hit.object];
    SurfaceHit out;
    out.t = hit.t;
    out.point = ray.at(hit.t);
    out.material = object.material;
    switch (object.kind) {
        case ObjectKind::Sphere: {
            const SphereShape& s = spheres_[object.index];
            out.normal = (out.point - s.center) / s.radius;
            break;
        }
        case ObjectKind::Plane: out.normal = planes_[object.index].normal; break;
        case ObjectKind::MeshInstance: {
            const MeshInstance& instance = instances_[object.index];
            const MeshAccel& mesh = meshes_[instance.mesh];
            // Normals map by the inverse transpose of the placement: transpose(to_object).
            out.normal = instance.placed ? mesh.shading_normal(hit.primitive, hit.u, hit.v)
                                         : mesh.shading_normal(hit.primitive, hit.u, hit.v,
                                                               glm::transpose(instance.to_object));
            break;
        }
    }
    return out;
}

SurfaceHit World::surface(const Ray& ray, const Hit& hit) const { return surface_at(ray, hit); }

std::optional<SurfaceHit> World::intersect(const Ray& ray, Interval range, SearchCounts& counts) const {
    const auto hit = nearest_hit(ray, range, counts);
    if (!hit) return std::nullopt;
    return surface_at(ray, *hit);
}

bool World::may_hit(const Ray& ray) const {
    if (!planes_.empty()) return true;
    if (!linear_) return line_may_meet_sphere(ray, sphere_centre_, sphere_radius2_);
    for (const Bounded& b : bounded_)
        if (line_may_meet_sphere(ray, b.centre, b.radius * b.radius)) return true;
    return false;
}

bool World::occluded(const Ray& ray, Interval range, SearchCounts& counts) const {
    if (linear_) {
        for (const SphereShape& s : spheres_)
            if (intersect_sphere(ray, s.center, s.radius, range)) return true;
    }
    for (const PlaneShape& p : planes_)
        if (intersect_plane(ray, p.point, p.normal, range)) return true;
    if (linear_) {
        counts.objects.primitive_tests += spheres_.size();
        for (size_t i = spheres_.size(); i < bounded_.size(); ++i) {
            const Bounded& b = bounded_[i];
            ++counts.objects.primitive_tests;
            if (line_may_meet_sphere(ray, b.centre, b.radius * b.radius) && instance_blocks(b.index, ray, range, counts))
                return true;
        }
        return false;
    }
    // Through the BVH the ray has entered an instance's box before it is tested, so the
    // bounding sphere (which holds the box) would rule nothing out.
    auto test = [&](uint32_t i, Interval& r) {
        const Bounded& b = bounded_[i];
        if (b.kind == ObjectKind::Sphere) return intersect_sphere(ray, b.centre, b.radius, r).has_value();
        return instance_blocks(b.index, ray, r, counts);
    };
    return top_.any(ray, range, counts.objects, test);
}

size_t World::top_level_memory_bytes() const {
    return top_.memory_bytes() + bounded_.capacity() * sizeof(Bounded) + objects_.capacity() * sizeof(Object) +
           instances_.capacity() * sizeof(MeshInstance) + spheres_.capacity() * sizeof(SphereShape) +
           planes_.capacity() * sizeof(PlaneShape);
}

}  // namespace tracer
