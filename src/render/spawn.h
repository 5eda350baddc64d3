// Where secondary rays start and which t they search (docs/robustness.md).
// Robust rule (pbrt-v4's): a ray leaving a surface starts at the hit point moved along the
// surface's geometric normal, to the side the ray leaves on, by the bound on the point's
// rounding error, each coordinate then rounded one ulp further; it searches t in (0, inf), and a
// shadow ray stops (1 - kShadowEpsilon) of the way to its light. Every length involved is
// relative to the scene's own coordinates, so a scene renders alike in millimetres or in
// kilometres. Naive rule (TRACER_ROBUST=OFF, the first wave's): start at the hit point, ignore
// t < 1e-4 scene units, stop at the light.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "render/triangle.h"
#include "render/types.h"
#include "render/world.h"

namespace tracer {

// The naive rule's t-min (conventions.md: 1e-4 reproduces Figure 1).
constexpr Real kSelfHitEpsilon = 1e-4;
// A shadow ray ignores what lies within this fraction of the distance to its light (so that a
// light on a surface is not shadowed by that surface).
constexpr Real kShadowEpsilon = 1e-4;

// The t range of a primary ray.
constexpr Interval kPrimaryRange{kRobust ? 0 : kSelfHitEpsilon, kInfinity};

// A ray and the part of it to search.
struct SpawnedRay {
    Ray ray;
    Interval range;
};

// The hit point moved off the surface to the side `w` points to (robust rule).
inline Vec3 offset_origin(const SurfaceHit& hit, const Vec3& w) {
    const Vec3& n = hit.geometric_normal;
    const Real distance = glm::dot(glm::abs(n), hit.error);
    Vec3 offset = distance * n;
    if (glm::dot(w, n) < 0) offset = -offset;
    Vec3 origin = hit.point + offset;
    for (int k = 0; k < 3; ++k) {
        if (offset[k] > 0) origin[k] = std::nextafter(origin[k], kInfinity);
        if (offset[k] < 0) origin[k] = std::nextafter(origin[k], -kInfinity);
    }
    return origin;
}

// A ray leaving the surface at `hit` along the unit `direction`.
inline SpawnedRay spawn_ray(const SurfaceHit& hit, const Vec3& direction) {
    if constexpr (kRobust)
        return {{offset_origin(hit, direction), direction}, {0, kInfinity}};
    else
        return {{hit.point, direction}, {kSelfHitEpsilon, kInfinity}};
}

// A ray from the surface at `hit` towards `target` (a light), ending just before it.
inline SpawnedRay spawn_ray_to(const SurfaceHit& hit, const Vec3& target) {
    const Vec3 origin = kRobust ? offset_origin(hit, target - hit.point) : hit.point;
    const Vec3 to_target = target - origin;
    const Real distance = glm::length(to_target);
    if constexpr (kRobust)
        return {{origin, to_target / distance}, {0, distance * (1 - kShadowEpsilon)}};
    else
        return {{origin, to_target / distance}, {kSelfHitEpsilon, distance}};
}

}  // namespace tracer
