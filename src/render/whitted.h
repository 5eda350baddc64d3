// Whitted ray tracing with Phong shading, exactly as conventions.md states it:
//   colour = ka + sum over unblocked lights of Lc (kd max(0, N.L) + ks max(0, R.V)^n)
//          + km trace(reflected ray) + kt trace(refracted ray)
// (on total internal reflection the refracted ray's weight kt goes to the reflected ray).
#pragma once

#include <atomic>
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
    uint64_t trees_cut = 0;                   // primary rays whose tree reached kMostRaysPerTree
    SearchCounts traversal;                   // box, object and triangle tests of all those rays

    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounts& operator+=(const RayCounts& other);
};

// The most reflected and refracted rays one primary ray may spawn, every branch and every mirror
// path counted: past it the rest of the tree returns black, as past max_depth (so a hall of
// parallel glass at max_depth 100000 costs at most this many rays a pixel, and lights' shadow
// rays at each hit).
constexpr int kMostRaysPerTree = 10'000;

// The colour seen along a primary ray: its hit shaded, plus up to settings.max_depth mirror
// bounces or refractions along any path (the ray that would be one more returns black). When
// `cancel` becomes true the tree stops within 256 rays and the colour is meaningless.
Color trace(const World& world, const RenderSettings& settings, Ray ray, RayCounts& counts,
            const std::atomic<bool>* cancel = nullptr);

// trace() for each of *rays[0 .. count) (at most kPacket: a tile of primary rays), out[i] the
// colour of *rays[i]: the same colours, their nearest hits searched for together
// (World::nearest_hits) where that pays (World::packet_shares_a_mesh). The rays are read in place:
// copies made just before would stall their reads (store-to-load forwarding).
void trace_packet(const World& world, const RenderSettings& settings, const Ray* const* rays, int count, Color* out,
                  RayCounts& counts, const std::atomic<bool>* cancel = nullptr);

}  // namespace tracer
