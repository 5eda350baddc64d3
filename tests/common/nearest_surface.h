// The nearest surface along a ray, for tests: World::nearest_hit, then World::surface, as the
// Whitted loop uses them.
#pragma once

#include <optional>

#include "accel/world.h"

namespace tracer {

// The surface of the nearest hit along `ray` inside `range`, or nothing.
inline std::optional<SurfaceHit> nearest_surface(const World& world, const Ray& ray, Interval range,
                                                 SearchCounts& counts) {
    const auto hit = world.nearest_hit(ray, range, counts);
    if (!hit) return std::nullopt;
    return world.surface(ray, *hit);
}

}  // namespace tracer
