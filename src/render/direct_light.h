// The lights' share of a hit's Phong shading (whitted.h's sum over unblocked lights): each
// light's term, shadowed by its shadow rays. An area light's samples are point lights; their
// shadow rays are searched together (area_shadows.h).
#pragma once

#include <atomic>
#include <span>

#include "accel/types.h"
#include "accel/world.h"
#include "render/spawn.h"
#include "render/whitted.h"
#include "scene/scene.h"

namespace tracer {

// What the lights' terms at one hit depend on.
struct ShadingPoint {
    const World& world;
    const RenderSettings& settings;
    const Material& material;
    const Color& kd;  // the material's, or its pattern's value here
    const SurfaceHit& hit;
    const SpawnPoint& spawn;
    const Vec3& normal;  // the shading normal, turned to face the incoming ray
    const Vec3& to_viewer;
    const std::atomic<bool>* cancel;  // the render's (or null): the lights' loops look at it
};

// The Phong terms of every light that the point sees (no ambient), each shadowed by the
// light's cache in `last_blockers` (one Occluder per light).
Color direct_light(const ShadingPoint& point, std::span<Occluder> last_blockers, RayCounts& counts);

// The unshadowed Phong term of a light of `color` in the unit direction `to_light`:
// color (kd max(0, N.L) + ks max(0, R.V)^n); `n_dot_l` is N.L.
[[gnu::always_inline]] inline Color phong_term(const ShadingPoint& point, const Vec3& to_light, Real n_dot_l,
                                               const Color& color) {
    const Vec3 reflected_light = 2 * n_dot_l * point.normal - to_light;  // R = 2(N.L)N - L
    const Real r_dot_v = std::max(Real(0), glm::dot(reflected_light, point.to_viewer));
    const Color diffuse = point.kd * double(std::max(Real(0), n_dot_l));
    // pow(+0, n) is +0 for every n > 0: no call where R points away from the viewer.
    const bool dark = r_dot_v == 0 && point.material.n > 0;
    const Color specular = point.material.ks == Color(0.0) ? Color(0.0)
                           : dark                          ? point.material.ks * 0.0
                                  : point.material.ks * std::pow(double(r_dot_v), point.material.n);
    return color * (diffuse + specular);
}

// The Phong term of `light` (a point, a spotlight, a parallel light, or one sample of an area
// light: `position`, with `color`), attenuated (light_attenuation) and shadowed (with the
// light's blocker cache `last`): 0 if something opaque lies in the way.
Color point_light_term(const ShadingPoint& point, const Light& light, const Vec3& position, const Color& color,
                       Occluder& last, RayCounts& counts);

// The fraction of a light's colour that reaches a point before shadows, the light `distance`
// away along the unit `to_light`: a spotlight's cone (POV-Ray's formula: cos^tightness, then a
// smooth step from the falloff to the radius) times fading, 2 / (1 + (d / fade_distance)^power).
double light_attenuation(const Light& light, const Vec3& to_light, Real distance);

// The fraction of a light's colour that reaches the point along `shadow` through transmitting
// surfaces (transparent shadows), `left_behind` the object the first ray cannot meet again;
// each further ray heads for `target`, or along the first one's direction if it is null (a
// parallel light).
Color light_through(const World& world, SpawnedRay shadow, const Vec3* target, uint32_t left_behind, RayCounts& counts);

}  // namespace tracer
