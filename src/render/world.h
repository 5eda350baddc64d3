// The renderer's view of a scene: flat arrays of primitives, lights and materials, and the
// two ray queries the shading needs (nearest hit, and "is anything in the way").
#pragma once

#include <optional>
#include <vector>

#include "frontend/scene.h"
#include "render/mesh_accel.h"
#include "render/types.h"

namespace tracer {

struct SurfaceHit {
    Real t = 0;
    Vec3 point{0};
    Vec3 normal{0};    // shading normal, unit length, not yet turned towards the ray
    int material = 0;  // index into World::materials()
};

class World {
public:
    // The shapes of a validated scene, with its meshes as loaded by load_meshes (in the
    // scene's order), each behind the scene's accelerator, built on `threads` threads (0: all).
    World(const SceneDescription& scene, std::vector<TriangleMesh> meshes = {}, int threads = 0);

    // The nearest surface along `ray` with t inside `range`.
    std::optional<SurfaceHit> intersect(const Ray& ray, Interval range, TraversalCounts& counts) const;
    // True if any surface lies along `ray` with t inside `range` (for shadow rays).
    bool occluded(const Ray& ray, Interval range, TraversalCounts& counts) const;
    // False only if the ray's line misses every shape's bounding sphere (planes: never).
    bool may_hit(const Ray& ray) const;

    const std::vector<Material>& materials() const { return materials_; }
    const std::vector<Light>& lights() const { return lights_; }
    const std::vector<MeshAccel>& meshes() const { return meshes_; }

private:
    struct SphereShape {
        Vec3 center;
        Real radius;
        int material;
    };
    struct PlaneShape {
        Vec3 point;
        Vec3 normal;
        int material;
    };
    std::vector<SphereShape> spheres_;
    std::vector<PlaneShape> planes_;
    std::vector<MeshAccel> meshes_;
    std::vector<Material> materials_;
    std::vector<Light> lights_;
};

}  // namespace tracer
