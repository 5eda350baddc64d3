// An area light's samples seen from one hit (docs/guide/lights.md, "How it is fast"). Each
// sample is a point light with its own shadow ray, as direct_light.h has it; the rays share
// their origin, so they are searched together: the grid of samples is split into rectangles,
// and for each the world is asked once what may lie in the pyramid from the point to it
// (World::shadow_candidates). A rectangle whose pyramid holds nothing is lit all through; one
// whose four corner rays meet one convex opaque shape (a sphere, a closed cone, a disc) is
// blocked all through (the rays meeting a convex shape from one point form a convex set);
// the others split in two, down to a few samples, each ray then tested against the candidates
// alone. The answer is each sample's own, added in the samples' order.
#pragma once

#include "render/direct_light.h"

namespace tracer {

// Adds to `sum` the Phong terms of `light`'s samples (light_samples.h) that `point` sees (each
// as point_light_term has it), `light_index` its place in the scene, `last` its blocker cache.
// Adaptive sampling takes a region of the grid to be as its corner samples are where they agree
// (POV-Ray's corners-then-subdivide); otherwise every sample's answer is its own.
void add_area_light(const ShadingPoint& point, const Light& light, size_t light_index, Occluder& last, Color& sum,
                    RayCounts& counts);

}  // namespace tracer
