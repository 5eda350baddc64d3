#include "accel/bvh_node.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace tracer {

TraversalRay::TraversalRay(const Ray& ray, Interval range) {
    for (int axis = 0; axis < 3; ++axis) {
        const float origin = float(ray.origin[axis]);
        // |origin| 2^-21 is at least 4 ulps of it: rounding the origin moved it by half an ulp.
        const float pad = std::fabs(origin) * 0x1p-21f;
        // The sign bit, not `< 0`: 1 / -0 is -infinity, so a -0 direction enters through the
        // upper plane, like any negative one (with `< 0` it missed every box).
        const bool negative = std::signbit(ray.direction[axis]);
        near_side[axis] = negative ? 1 : 0;
        near_row[axis] = (near_side[axis] * 3 + axis) * kWide;
        far_row[axis] = ((1 - near_side[axis]) * 3 + axis) * kWide;
        // Widen the box by `pad` on both sides: the entering plane moves towards the origin's
        // side (lower - pad - o = lower - (o + pad) for a positive direction), the leaving plane
        // away from it.
        origin_near[axis] = negative ? origin - pad : origin + pad;
        origin_far[axis] = negative ? origin + pad : origin - pad;
        inv_dir[axis] = float(Real(1) / ray.direction[axis]);
        inv_dir_far[axis] = inv_dir[axis] * kFarGrow;  // see kFarGrow
        scaled_origin_near[axis] = origin_near[axis] * inv_dir[axis];
        scaled_origin_far[axis] = origin_far[axis] * inv_dir_far[axis];
    }
    // The fused form needs finite products: an infinite one would not round to the nearest float.
    fused = kFusedSlabs;
    for (int axis = 0; axis < 3; ++axis)
        fused = fused && std::isfinite(inv_dir_far[axis]) && std::isfinite(scaled_origin_near[axis]) &&
                std::isfinite(scaled_origin_far[axis]);
    t_min = round_down(range.min);
    t_max = round_up(range.max);
}

void TraversalRay::clip(Real t) {
    t_max = std::min(t_max, round_up(t));
}

}  // namespace tracer
