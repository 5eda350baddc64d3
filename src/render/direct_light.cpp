#include "render/direct_light.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/area_shadows.h"

namespace tracer {

// The most surfaces one transparent shadow ray crosses; past them the light counts as blocked.
constexpr int kMostShadowCrossings = 1024;

// Each crossing continues as a ray of its own, from the far side of the surface, counted as a
// shadow ray; the product of kt over the surfaces crossed, 0 at the first that transmits nothing.
Color light_through(const World& world, SpawnedRay shadow, const Vec3* target, uint32_t left_behind,
                    RayCounts& counts) {
    Color through(1.0);
    for (int crossings = 0; crossings < kMostShadowCrossings; ++crossings) {
        const auto found = world.nearest_hit(shadow.ray, shadow.range, counts.traversal, left_behind);
        if (!found) return through;
        const SurfaceHit hit = world.surface(shadow.ray, *found);
        through *= world.materials()[size_t(hit.material)].kt;
        if (through == Color(0.0)) return through;
        ++counts.shadow;
        shadow = target ? spawn_ray_to(hit, *target) : spawn_ray(hit, shadow.ray.direction);
        left_behind = object_left_behind(hit, shadow.ray.direction);
    }
    return Color(0.0);
}

// POV-Ray's spotlight step: 0 below `low`, 1 from `high` on, (3 - 2x) x^2 between.
static double cubic_step(double low, double high, double x) {
    if (x < low) return 0;
    if (x >= high) return 1;
    x = (x - low) / (high - low);
    return (3 - 2 * x) * x * x;
}

double light_attenuation(const Light& light, const Vec3& to_light, Real distance) {
    double attenuation = 1;
    if (light.kind == Light::Kind::Spot) {
        constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180;
        const double cos_angle = -glm::dot(glm::dvec3(to_light), light.direction);
        if (!(cos_angle > 0)) return 0;
        if (light.tightness != 0) attenuation = std::pow(cos_angle, light.tightness);
        const double cos_radius = std::cos(light.radius * kRadiansPerDegree);
        if (cos_angle < cos_radius)
            attenuation *= cubic_step(std::cos(light.falloff * kRadiansPerDegree), cos_radius, cos_angle);
    }
    if (light.fade_distance > 0)
        attenuation *= 2 / (1 + std::pow(double(distance) / light.fade_distance, light.fade_power));
    return attenuation;
}

// Under tracer's rules a light whose unshadowed term is exactly zero (a mirror with kd = ks = 0,
// a back face without specular) adds nothing either way, so it costs no shadow ray; under the
// SPD's, a shadow ray goes wherever the normal faces the light, and nowhere else.
Color point_light_term(const ShadingPoint& point, const Light& light, const Vec3& position, const Color& color,
                       Occluder& last, RayCounts& counts) {
    const RenderSettings& settings = point.settings;
    const bool spd_rules = settings.spawn_rules == SpawnRules::Spd;
    const bool parallel = light.kind == Light::Kind::Parallel;
    const Vec3 light_offset = parallel ? -Vec3(light.direction) : position - point.hit.point;
    const Real distance = parallel ? kInfinity : glm::length(light_offset);
    if (!(distance > 0)) return Color(0.0);  // a light exactly at the point lights nothing there
    const Vec3 to_light = parallel ? light_offset : light_offset / distance;
    const Real n_dot_l = glm::dot(point.normal, to_light);
    Color term = phong_term(point, to_light, n_dot_l, color);
    if (light.attenuates()) term *= light_attenuation(light, to_light, distance);
    if (spd_rules ? !(n_dot_l > 0) : term == Color(0.0)) return Color(0.0);
    if (settings.shadows) {
        ++counts.shadow;
        const SpawnedRay shadow = parallel ? point.spawn.ray(to_light) : point.spawn.ray_to(light_offset, distance);
        const uint32_t left_behind = object_left_behind(point.hit, to_light);
        const World& world = point.world;
        if (settings.transparent_shadows && world.refracts()) {
            // Most shadow rays meet nothing: the any-hit search (the same tests, fewer steps)
            // says so; only the others are followed through each surface they cross.
            if (world.occluded(shadow.ray, shadow.range, counts.traversal, last, left_behind))
                term *= light_through(world, shadow, parallel ? nullptr : &position, left_behind, counts);
        } else if (world.occluded(shadow.ray, shadow.range, counts.traversal, last, left_behind)) {
            return Color(0.0);
        }
    }
    return term;
}

Color direct_light(const ShadingPoint& point, std::span<Occluder> last_blockers, RayCounts& counts) {
    Color sum(0.0);
    const std::vector<Light>& lights = point.world.lights();
    for (size_t l = 0; l < lights.size(); ++l) {
        // Up to kMostLightSamples point lights: every 64th looks at the cancel flag (the image is
        // then discarded), so that a cancelled render does not shade on for seconds.
        if ((l & 63) == 63 && point.cancel && point.cancel->load(std::memory_order_relaxed)) [[unlikely]]
            break;
        const Light& light = lights[l];
        if (light.samples() == 1)
            sum += point_light_term(point, light, Vec3(light.position), light.color, last_blockers[l], counts);
        else
            add_area_light(point, light, l, last_blockers[l], sum, counts);
    }
    return sum;
}

}  // namespace tracer
