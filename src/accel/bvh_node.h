// The BVHs' nodes (Box's and Median's binary node, Sah's wide node) and a ray's tests against
// their boxes, in float with rounding margins that no box the exact ray touches can slip
// through (see TraversalRay; tests/unit/accel/bvh_node_test.cpp checks them).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE__)
#include <immintrin.h>
#endif

#include "accel/types.h"
#include "base/large_array.h"
#include "base/portable.h"

namespace tracer {

struct BvhNode {
    float box[2][3];  // [0]: lower corner, [1]: upper corner (rounded outwards from the primitives)
    uint32_t index;   // leaf: first entry of order(); inner: the right child's node index
    uint32_t count;   // leaf: number of primitives; inner: 0
};
static_assert(sizeof(BvhNode) == 32, "BVH nodes are 32 bytes");

using NodeArray = LargeArray<BvhNode>;  // 64-byte aligned

// Sah's node: up to kWide children side by side, each child's planes in one lane of six
// kWide-wide rows, so that one vector operation per plane tests all the boxes (the layout of
// Embree's BVH4 and BVH8). 32 bytes per child, as a binary node: 256 bytes (four cache lines)
// for eight children.
#if defined(TRACER_WIDE)  // to compare widths: -DTRACER_WIDE=4
constexpr int kWide = TRACER_WIDE;
#elif defined(__AVX__)
constexpr int kWide = 8;  // one 8-wide vector operation per plane
#else
constexpr int kWide = 4;
#endif

struct WideNode {
    static constexpr uint32_t kInner = ~uint32_t(0);  // count of an inner child
    float planes[2][3][kWide];                        // [0]: lower, [1]: upper corner; [axis]; [child]
    uint32_t index[kWide];                            // leaf: first entry of order(); inner: the child's node index
    uint32_t count[kWide];  // leaf: number of primitives (0: no child in this lane); inner: kInner
};
static_assert(sizeof(WideNode) == 32 * kWide, "wide nodes are 32 bytes per child");

using FloatLanesW = float __attribute__((vector_size(4 * kWide)));  // one lane per child

// What a ray does at a wide node (enter_wide): entry distances and which children it enters.
struct WideEntry {
    FloatLanesW t;
    unsigned mask;
};

// Lane by lane minimum and maximum of GCC vectors; where `a` is NaN the lane takes `b`.
template <typename Lanes>
inline Lanes lane_min(Lanes a, Lanes b) {
    return a < b ? a : b;
}
template <typename Lanes>
inline Lanes lane_max(Lanes a, Lanes b) {
    return a > b ? a : b;
}

// Box tests scale the leaving distance by 1 + 2 gamma_3 (Ize 2013), so that float rounding
// cannot make the ray leave a box before the exact ray does. They scale 1 / d, once per ray:
// the same four roundings and factor as scaling each distance, in another order.
constexpr float kFarGrow = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

// a * b - c, rounded once where the processor has FMA (kFusedSlabs), lane by lane.
#if defined(__FMA__)
constexpr bool kFusedSlabs = true;
template <typename Lanes>
inline Lanes multiply_subtract(Lanes a, float b, float c) {
    if constexpr (sizeof(Lanes) == 32)
        return Lanes(_mm256_fmsub_ps(__m256(a), _mm256_set1_ps(b), _mm256_set1_ps(c)));
    else
        return Lanes(_mm_fmsub_ps(__m128(a), _mm_set1_ps(b), _mm_set1_ps(c)));
}
#else
constexpr bool kFusedSlabs = false;
template <typename Lanes>
inline Lanes multiply_subtract(Lanes a, float b, float c) {
    return a * b - c;
}  // unused: not rounded once
#endif

// A ray prepared for float box tests. The origin is rounded to float and moved |origin| 2^-21
// (at least 4 ulps) away from each slab, t_far is scaled by 1 + 2 gamma_3 (Ize 2013; see
// kFarGrow) and the node boxes are rounded outwards: the margins are meant to keep rounding
// from making a box test miss a primitive the exact ray meets (hard-cases.md A1 and A3;
// tests/unit/accel/bvh_node_test.cpp aims rays at box surfaces to check it).
//
// A plane's distance is (plane - origin) * inv_dir, or in the fused form (wide nodes, where
// the processor has FMA) plane * inv_dir - origin * inv_dir, one operation shorter. Rounding
// origin * inv_dir moves the distance as far as moving the origin by 2^-24 |origin| would,
// which the pad covers as it covers rounding the origin; the FMA's rounding and 1 / d's are
// within kFarGrow. An infinite 1 / d (a zero component) would make the fused form NaN
// (infinity - infinity): such rays take the other form.
struct TraversalRay {
    float origin_near[3];         // origin for the entering planes
    float origin_far[3];          // origin for the leaving planes
    float inv_dir[3];             // 1 / direction; +-infinity for a zero component
    float inv_dir_far[3];         // inv_dir * kFarGrow, for the leaving planes
    float scaled_origin_near[3];  // origin_near * inv_dir, for the fused form
    float scaled_origin_far[3];   // origin_far * inv_dir_far
    bool fused = false;           // the fused form applies: FMA, and the scaled values all finite
    int near_side[3];             // which corner holds the entering plane per axis: 1 for a negative direction
    int near_row[3];              // where enter_wide finds the entering planes per axis, in floats from planes
    int far_row[3];               // and the leaving planes
    float t_min = 0;
    float t_max = 0;

    TraversalRay(const Ray& ray, Interval range);
    // Shrinks the float t_max after a hit (never below the double one).
    void clip(Real t);
};

// The largest float <= x and the smallest float >= x: bounds that never shrink what they bound.
// Branch-free (a build rounds six per primitive, and which way is a coin toss): x rounded to
// the nearest float, then stepped by one ulp where that went the wrong way. The step is on the
// bit pattern, away from zero for one sign and towards it for the other; it is never taken
// where it would leave the floats (+-0 going the wrong way is -0 below a negative x, +0 above
// a positive one; NaN and the infinity past a huge x stay).
inline float round_down(Real x) {
    const float nearest = float(x);
    const uint32_t bits = tracer::bit_cast<uint32_t>(nearest);
    const uint32_t wrong_way = 0u - uint32_t(Real(nearest) > x);  // all ones, or zero
    return tracer::bit_cast<float>(bits + ((2 * (bits >> 31) - 1) & wrong_way));
}
inline float round_up(Real x) {
    const float nearest = float(x);
    const uint32_t bits = tracer::bit_cast<uint32_t>(nearest);
    const uint32_t wrong_way = 0u - uint32_t(Real(nearest) < x);
    return tracer::bit_cast<float>(bits + ((1 - 2 * (bits >> 31)) & wrong_way));
}

// Entry distance of the ray into the node's box, or +infinity if it misses within
// [t_min, t_max]. Comparisons are written so that a NaN (0 * infinity: an origin exactly on a
// slab of an axis-parallel ray) never shrinks the interval, and touching counts as entering:
// zero-thickness boxes are hit.
inline float enter_box(const BvhNode& node, const TraversalRay& ray) {
    float near = ray.t_min, far = ray.t_max;
    for (int axis = 0; axis < 3; ++axis) {
        const float t0 = (node.box[ray.near_side[axis]][axis] - ray.origin_near[axis]) * ray.inv_dir[axis];
        const float t1 = (node.box[1 - ray.near_side[axis]][axis] - ray.origin_far[axis]) * ray.inv_dir_far[axis];
        near = t0 > near ? t0 : near;
        far = t1 < far ? t1 : far;
    }
    return near <= far ? near : std::numeric_limits<float>::infinity();
}

// Bit i set where lane i of a comparison's result is true.
template <typename Lanes>
inline unsigned lane_mask(Lanes hit) {
#if defined(__AVX__)
    if constexpr (sizeof(Lanes) == 32) return unsigned(_mm256_movemask_ps(__m256(hit)));
#endif
#if defined(__SSE__)
    if constexpr (sizeof(Lanes) == 16) return unsigned(_mm_movemask_ps(__m128(hit)));
#endif
    unsigned mask = 0;
    for (int i = 0; i < int(sizeof(Lanes) / 4); ++i) mask |= unsigned(hit[i] & 1) << i;
    return mask;
}

// enter_box for the children of a wide node at once: `t` lane i is child i's entry
// distance, bit i of `mask` is set where the ray enters child i. The same NaN rules as
// enter_box, and without kFused the same arithmetic and results. Lanes without a child hold
// an empty box (lower +infinity, upper -infinity).
template <bool kFused>
inline WideEntry enter_wide(const WideNode& node, const TraversalRay& ray) {
    using Lanes = FloatLanesW;
    const float* planes = &node.planes[0][0][0];
    Lanes near = Lanes{} + ray.t_min, far = Lanes{} + ray.t_max;
    for (int axis = 0; axis < 3; ++axis) {
        Lanes near_plane, far_plane;
        std::memcpy(&near_plane, planes + ray.near_row[axis], sizeof near_plane);
        std::memcpy(&far_plane, planes + ray.far_row[axis], sizeof far_plane);
        if constexpr (kFused) {
            near = lane_max(multiply_subtract(near_plane, ray.inv_dir[axis], ray.scaled_origin_near[axis]), near);
            far = lane_min(multiply_subtract(far_plane, ray.inv_dir_far[axis], ray.scaled_origin_far[axis]), far);
        } else {
            near = lane_max((near_plane - ray.origin_near[axis]) * ray.inv_dir[axis], near);
            far = lane_min((far_plane - ray.origin_far[axis]) * ray.inv_dir_far[axis], far);
        }
    }
    const auto hit = near <= far;
    return {near, lane_mask(hit)};
}

}  // namespace tracer
