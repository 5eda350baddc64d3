#include "render/world.h"

#include "render/geometry.h"

namespace tracer {

World::World(const SceneDescription& scene, std::vector<TriangleMesh> meshes, int threads)
    : materials_(scene.materials), lights_(scene.lights) {
    for (const Sphere& s : scene.spheres) spheres_.push_back({Vec3(s.center), Real(s.radius), s.material});
    for (const Plane& p : scene.planes) planes_.push_back({Vec3(p.point), Vec3(p.normal), p.material});
    for (TriangleMesh& mesh : meshes) meshes_.emplace_back(std::move(mesh), scene.render.accel, scene.render.leaf_size, threads);
}

std::optional<SurfaceHit> World::intersect(const Ray& ray, Interval range, TraversalCounts& counts) const {
    // Each hit shrinks range.max, so later primitives only count when they are nearer.
    const SphereShape* nearest_sphere = nullptr;
    const PlaneShape* nearest_plane = nullptr;
    const MeshAccel* nearest_mesh = nullptr;
    MeshHit mesh_hit;
    for (const SphereShape& s : spheres_) {
        if (auto t = intersect_sphere(ray, s.center, s.radius, range)) {
            range.max = *t;
            nearest_sphere = &s;
        }
    }
    for (const PlaneShape& p : planes_) {
        if (auto t = intersect_plane(ray, p.point, p.normal, range)) {
            range.max = *t;
            nearest_plane = &p;
            nearest_sphere = nullptr;
        }
    }
    for (const MeshAccel& mesh : meshes_) {
        if (mesh.intersect(ray, range, mesh_hit, counts)) {
            nearest_mesh = &mesh;
            nearest_plane = nullptr;
            nearest_sphere = nullptr;
        }
    }
    if (!nearest_sphere && !nearest_plane && !nearest_mesh) return std::nullopt;

    SurfaceHit hit;
    hit.t = range.max;
    hit.point = ray.at(hit.t);
    if (nearest_mesh) {
        hit.normal = nearest_mesh->shading_normal(mesh_hit);
        hit.material = nearest_mesh->mesh().material;
    } else if (nearest_plane) {
        hit.normal = nearest_plane->normal;
        hit.material = nearest_plane->material;
    } else {
        hit.normal = (hit.point - nearest_sphere->center) / nearest_sphere->radius;
        hit.material = nearest_sphere->material;
    }
    return hit;
}

bool World::may_hit(const Ray& ray) const {
    if (!planes_.empty()) return true;
    for (const SphereShape& s : spheres_)
        if (line_may_meet_sphere(ray, s.center, s.radius * s.radius)) return true;
    for (const MeshAccel& mesh : meshes_)
        if (mesh.may_hit(ray)) return true;
    return false;
}

bool World::occluded(const Ray& ray, Interval range, TraversalCounts& counts) const {
    for (const SphereShape& s : spheres_)
        if (intersect_sphere(ray, s.center, s.radius, range)) return true;
    for (const PlaneShape& p : planes_)
        if (intersect_plane(ray, p.point, p.normal, range)) return true;
    for (const MeshAccel& mesh : meshes_)
        if (mesh.occluded(ray, range, counts)) return true;
    return false;
}

}  // namespace tracer
