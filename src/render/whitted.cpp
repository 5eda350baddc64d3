#include "render/whitted.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/spawn.h"

namespace tracer {

RayCounts& RayCounts::operator+=(const RayCounts& other) {
    primary += other.primary;
    shadow += other.shadow;
    reflection += other.reflection;
    traversal += other.traversal;
    return *this;
}

// Phong terms of every light that the point sees (no ambient). A light whose unshadowed
// term is exactly zero (a mirror with kd = ks = 0, a back face without specular) adds
// nothing either way, so it costs no shadow ray.
static Color direct_light(const World& world, const RenderSettings& settings, const Material& material,
                          const SurfaceHit& hit, const SpawnPoint& spawn, const Vec3& normal, const Vec3& to_viewer,
                          RayCounts& counts) {
    Color sum(0.0);
    for (const Light& light : world.lights()) {
        Vec3 to_light = Vec3(light.position) - hit.point;
        const Real distance = glm::length(to_light);
        if (!(distance > 0)) continue;  // a light exactly at the point lights nothing there
        to_light /= distance;
        const Real n_dot_l = glm::dot(normal, to_light);
        const Vec3 reflected_light = 2 * n_dot_l * normal - to_light;  // R = 2(N.L)N - L
        const Real r_dot_v = std::max(Real(0), glm::dot(reflected_light, to_viewer));
        const Color diffuse = material.kd * double(std::max(Real(0), n_dot_l));
        const Color specular =
            material.ks == Color(0.0) ? Color(0.0) : material.ks * std::pow(double(r_dot_v), material.n);
        const Color term = light.color * (diffuse + specular);
        if (term == Color(0.0)) continue;
        if (settings.shadows) {
            ++counts.shadow;
            const SpawnedRay shadow = spawn.ray_to(to_light, distance);
            if (world.occluded(shadow.ray, shadow.range, counts.traversal)) continue;
        }
        sum += term;
    }
    return sum;
}

// trace() for a ray that may meet a surface. The recursion colour = local + km *
// trace(reflected) has a single child, so it runs as a loop: `weight` is the product of the
// km of the mirrors passed so far. This keeps any max_depth off the call stack and stops as
// soon as a surface reflects nothing.
[[gnu::noinline]] static Color trace_surfaces(const World& world, const RenderSettings& settings, Ray ray,
                                              RayCounts& counts) {
    Color color(0.0);
    Color weight(1.0);
    Interval range = kPrimaryRange;
    for (int depth = 0;; ++depth) {
        // Step 1: the nearest surface, or the background.
        const auto hit = world.intersect(ray, range, counts.traversal);
        if (!hit) return color + weight * settings.background;

        // Step 2: local Phong shading with the normal facing the incoming ray.
        const Material& material = world.materials()[size_t(hit->material)];
        const Vec3 normal = glm::dot(hit->normal, ray.direction) > 0 ? -hit->normal : hit->normal;
        const Vec3 to_viewer = -ray.direction;
        const SpawnPoint spawn(*hit);
        color +=
            weight * (material.ka + direct_light(world, settings, material, *hit, spawn, normal, to_viewer, counts));

        // Step 3: continue along the mirror direction D - 2(D.N)N.
        weight *= material.km;
        if (depth == settings.max_depth || weight == Color(0.0)) return color;
        ++counts.reflection;
        const SpawnedRay reflected = spawn.ray(ray.direction - 2 * glm::dot(ray.direction, normal) * normal);
        ray = reflected.ray;
        range = reflected.range;
    }
}

// A ray that can meet nothing (most of a frame around a lone mesh) returns the background
// here, without the set-up of the nearest-hit search, which trace_surfaces keeps out of line
// (measured: the full bunny frame renders in 0.68x the time).
Color trace(const World& world, const RenderSettings& settings, Ray ray, RayCounts& counts) {
    ++counts.primary;
    if (!world.may_hit(ray)) return settings.background;
    return trace_surfaces(world, settings, ray, counts);
}

}  // namespace tracer
