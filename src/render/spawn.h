// Where secondary rays start and which t they search (docs/robustness.md).
// Robust rule (pbrt-v4's): a ray leaving a surface starts at the hit point moved along the
// surface's geometric normal, to the side the ray leaves on, by the bound on the point's
// rounding error (grown by the rounding of that move); it searches t in (0, inf), and a
// shadow ray stops (1 - kShadowEpsilon) of the way to its light. Every length involved is
// relative to the scene's own coordinates, so a scene renders alike in millimetres or in
// kilometres. Naive rule (TRACER_ROBUST=OFF, the first wave's): start at the hit point, ignore
// t < 1e-4 scene units, stop at the light.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "accel/triangle.h"
#include "accel/types.h"
#include "accel/world.h"

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

// Rays leaving one surface hit. The robust rule's offset along the normal is worked out once,
// however many rays leave (one per light and the reflection); each ray picks its side with a
// sign, not a branch: a branch on the side mispredicts on curved surfaces
// (docs/bench/code-figures.md).
class SpawnPoint {
public:
    explicit SpawnPoint(const SurfaceHit& hit) : point_(hit.point), normal_(hit.geometric_normal) {
        if constexpr (kRobust) {
            // The error bound along the normal, grown by what rounding p +- offset can take
            // back (half an ulp of each coordinate), so that no next-float step is needed.
            const Vec3 abs_n = abs_each(normal_);
            offset_ = (1 + gamma(2)) * glm::dot(abs_n, hit.error) + gamma(2) * glm::dot(abs_n, abs_each(hit.point));
        }
    }

    // The origin of a ray leaving along `w`, of any length (robust rule: on w's side of the
    // surface).
    Vec3 origin(const Vec3& w) const {
        if constexpr (kRobust) return point_ + std::copysign(offset_, glm::dot(w, normal_)) * normal_;
        return point_;
    }

    // A ray leaving along the unit `direction`.
    SpawnedRay ray(const Vec3& direction) const {
        return {{origin(direction), direction}, {kRobust ? 0 : kSelfHitEpsilon, kInfinity}};
    }

    // A ray towards the point `to_target` away from the hit point (`distance` its length, > 0),
    // stopping short of it. (Robust rule: the origin moves by the offset, some 10^-15 of the
    // point's coordinates, while the end stops kShadowEpsilon of the distance short: it stays
    // short.) The side is read off `to_target` itself, not its unit direction, so that the
    // origin does not wait for the division (docs/bench/code-figures.md).
    SpawnedRay ray_to(const Vec3& to_target, Real distance) const {
        const Vec3 direction = to_target / distance;
        if constexpr (kRobust) return {{origin(to_target), direction}, {0, distance * (1 - kShadowEpsilon)}};
        return {{point_, direction}, {kSelfHitEpsilon, distance}};
    }

private:
    Vec3 point_, normal_;
    Real offset_ = 0;
};

// A ray leaving the surface at `hit` along the unit `direction`.
inline SpawnedRay spawn_ray(const SurfaceHit& hit, const Vec3& direction) {
    return SpawnPoint(hit).ray(direction);
}

// A ray from the surface at `hit` towards `target`, stopping short of it.
inline SpawnedRay spawn_ray_to(const SurfaceHit& hit, const Vec3& target) {
    const Vec3 to_target = target - hit.point;
    const Real distance = glm::length(to_target);
    return SpawnPoint(hit).ray_to(to_target, distance);
}

}  // namespace tracer
