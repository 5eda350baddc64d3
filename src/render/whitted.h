// Whitted ray tracing with Phong shading, exactly as conventions.md states it:
//   colour = ka + sum over unblocked lights of Lc (kd max(0, N.L) + ks max(0, R.V)^n)
//          + km trace(reflected ray) + kt trace(refracted ray)
// (on total internal reflection the refracted ray's weight kt goes to the reflected ray).
#pragma once

#include <cstdint>

#include "accel/types.h"
#include "accel/world.h"
#include "scene/scene.h"

namespace tracer {

struct RayCounts {
    uint64_t primary = 0;
    uint64_t shadow = 0;
    uint64_t reflection = 0;
    uint64_t refraction = 0;
    uint64_t primary_hits = 0;                // primary rays that met a surface (a subset of primary)
    uint64_t total_internal_reflections = 0;  // transmitting hits that made no refracted ray
    SearchCounts traversal;                   // box, object and triangle tests of all those rays

    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounts& operator+=(const RayCounts& other);
};

// The colour seen along a primary ray: its hit shaded, plus up to settings.max_depth mirror
// bounces or refractions along any path (the ray that would be one more returns black).
Color trace(const World& world, const RenderSettings& settings, Ray ray, RayCounts& counts);

}  // namespace tracer
