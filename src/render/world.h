// The renderer's view of a scene: flat arrays of primitives, lights and materials, and the
// two ray queries the shading needs (nearest hit, and "is anything in the way").
#pragma once

#include <optional>
#include <vector>

#include "frontend/scene.h"
#include "render/types.h"

namespace tracer {

struct SurfaceHit {
    Real t = 0;
    Vec3 point{0};
    Vec3 normal{0};    // geometric normal, unit length, not yet turned towards the ray
    int material = 0;  // index into World::materials()
};

class World {
public:
    // Copies the shapes of a validated scene (meshes are not rendered yet).
    explicit World(const SceneDescription& scene);

    // The nearest surface along `ray` with t inside `range`.
    std::optional<SurfaceHit> intersect(const Ray& ray, Interval range) const;
    // True if any surface lies along `ray` with t inside `range` (for shadow rays).
    bool occluded(const Ray& ray, Interval range) const;

    const std::vector<Material>& materials() const { return materials_; }
    const std::vector<Light>& lights() const { return lights_; }

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
    std::vector<Material> materials_;
    std::vector<Light> lights_;
};

}  // namespace tracer
