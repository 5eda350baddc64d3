// Packets of coherent rays (a row of primary rays, say) through a wide BVH together
// (WideBvh::closest_in_packet walks the tree with them): each node is loaded once for all of
// them, and its children's boxes are tested against every ray of the packet at once, one ray
// per vector lane. The rays' searches are otherwise their own: each ray tests the leaves it
// enters with its own exact primitive test, so each finds what it would alone, bit for bit (the
// box tests are each ray's own arithmetic, lane by lane; testing a leaf a ray alone would have
// skipped finds nothing nearer, and ties do not depend on the order of the tests).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "accel/bvh_node.h"

namespace tracer {

constexpr int kPacket = 8;  // rays in a packet: one 8-wide float vector (AVX)
using PacketLanes = float __attribute__((vector_size(4 * kPacket)));

// The TraversalRays of up to kPacket rays side by side (lane i: ray i). Only for rays whose
// directions have the same signs and that take the same form of the box test (make() says).
struct TraversalPacket {
    PacketLanes origin_near[3], origin_far[3], inv_dir[3], inv_dir_far[3];
    PacketLanes scaled_origin_near[3], scaled_origin_far[3];
    PacketLanes t_min, t_max;  // a lane without a ray: t_min +infinity, t_max -infinity (never enters)
    int near_side[3];
    bool fused;
    // The frustum around the packet's rays, for testing a node's children against all of them
    // at once (enter_frustum): per axis the extremes of the rays' padded origins and of their
    // 1 / direction (finite: make() refuses rays with a zero component).
    float near_origin_low[3], near_origin_high[3], far_origin_low[3], far_origin_high[3];
    float inv_low[3], inv_high[3], inv_far_low[3], inv_far_high[3];
    int near_row[3], far_row[3];

    // The packet of rays[0 .. count), or false if they differ in a direction's sign or in the
    // form of their box test (then each must be traced alone).
    static bool make(const TraversalRay* rays, int count, TraversalPacket& out) {
        for (int i = 1; i < count; ++i) {
            if (rays[i].fused != rays[0].fused) return false;
            for (int axis = 0; axis < 3; ++axis)
                if (rays[i].near_side[axis] != rays[0].near_side[axis]) return false;
        }
        constexpr float kInf = std::numeric_limits<float>::infinity();
        out.t_min = PacketLanes{} + kInf;
        out.t_max = PacketLanes{} - kInf;
        for (int axis = 0; axis < 3; ++axis) {
            out.near_side[axis] = rays[0].near_side[axis];
            // Lanes without a ray copy ray 0's values: finite, and never entering (t range empty).
            for (int i = 0; i < kPacket; ++i) {
                const TraversalRay& r = rays[i < count ? i : 0];
                out.origin_near[axis][i] = r.origin_near[axis];
                out.origin_far[axis][i] = r.origin_far[axis];
                out.inv_dir[axis][i] = r.inv_dir[axis];
                out.inv_dir_far[axis][i] = r.inv_dir_far[axis];
                out.scaled_origin_near[axis][i] = r.scaled_origin_near[axis];
                out.scaled_origin_far[axis][i] = r.scaled_origin_far[axis];
            }
        }
        for (int i = 0; i < count; ++i) out.t_min[i] = rays[i].t_min, out.t_max[i] = rays[i].t_max;
        out.fused = rays[0].fused;
        for (int axis = 0; axis < 3; ++axis) {
            out.near_row[axis] = rays[0].near_row[axis];
            out.far_row[axis] = rays[0].far_row[axis];
            auto low_high = [&](float(TraversalRay::*field)[3], float& low, float& high) {
                low = high = (rays[0].*field)[axis];
                for (int i = 1; i < count; ++i) {
                    low = std::min(low, (rays[i].*field)[axis]);
                    high = std::max(high, (rays[i].*field)[axis]);
                }
            };
            low_high(&TraversalRay::origin_near, out.near_origin_low[axis], out.near_origin_high[axis]);
            low_high(&TraversalRay::origin_far, out.far_origin_low[axis], out.far_origin_high[axis]);
            low_high(&TraversalRay::inv_dir, out.inv_low[axis], out.inv_high[axis]);
            low_high(&TraversalRay::inv_dir_far, out.inv_far_low[axis], out.inv_far_high[axis]);
            if (!std::isfinite(out.inv_low[axis]) || !std::isfinite(out.inv_high[axis]) ||
                !std::isfinite(out.inv_far_low[axis]) || !std::isfinite(out.inv_far_high[axis]))
                return false;
        }
        return true;
    }
};

// a * b - c lane by lane, rounded once (the fused box test's form, kFusedSlabs).
inline PacketLanes fused_lanes(PacketLanes a, float b, PacketLanes c) {
#if defined(__FMA__) && defined(__AVX__)
    return PacketLanes(_mm256_fmsub_ps(__m256(a), _mm256_set1_ps(b), __m256(c)));
#else
    return a * b - c;  // not rounded once: unused (kFusedSlabs is false without FMA)
#endif
}

// enter_wide turned sideways: child `child` of `node` against every ray of the packet. Lane i
// is ray i's entry distance where ray i enters, else +infinity; each lane does ray i's own
// operations of enter_wide<kFused> (a * b - c is the same rounding as b * a - c).
template <bool kFused>
inline PacketLanes enter_child(const WideNode& node, int child, const TraversalPacket& packet) {
    PacketLanes near = packet.t_min, far = packet.t_max;
    for (int axis = 0; axis < 3; ++axis) {
        const float near_plane = node.planes[packet.near_side[axis]][axis][child];
        const float far_plane = node.planes[1 - packet.near_side[axis]][axis][child];
        if constexpr (kFused) {
            near = lane_max(fused_lanes(packet.inv_dir[axis], near_plane, packet.scaled_origin_near[axis]), near);
            far = lane_min(fused_lanes(packet.inv_dir_far[axis], far_plane, packet.scaled_origin_far[axis]), far);
        } else {
            near = lane_max((near_plane - packet.origin_near[axis]) * packet.inv_dir[axis], near);
            far = lane_min((far_plane - packet.origin_far[axis]) * packet.inv_dir_far[axis], far);
        }
    }
    return near <= far ? near : PacketLanes{} + std::numeric_limits<float>::infinity();
}

// The smallest lane.
inline float lowest_lane(PacketLanes t) {
#if defined(__AVX__)
    __m256 m = __m256(t);
    m = _mm256_min_ps(m, _mm256_permute2f128_ps(m, m, 1));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, 0x4e));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, 0xb1));
    return _mm256_cvtss_f32(m);
#else
    float lowest = t[0];
    for (int i = 1; i < kPacket; ++i) lowest = t[i] < lowest ? t[i] : lowest;
    return lowest;
#endif
}

// The children of `node` that some ray of the packet may enter: lane i holds a distance
// before which no ray enters child i, and bit i of the mask is set unless no ray enters it
// within [t_min, t_max]. Each plane's distance is bounded over the frustum's corners: as float
// subtraction and multiplication are monotonic, the bound holds for every ray's own rounded
// distance (in the unfused form, TraversalRay's), which the margins make safe for the exact ray.
inline WideEntry enter_frustum(const WideNode& node, const TraversalPacket& packet, float t_min, float t_max) {
    using Lanes = FloatLanesW;
    const float* planes = &node.planes[0][0][0];
    Lanes near = Lanes{} + t_min, far = Lanes{} + t_max;
    for (int axis = 0; axis < 3; ++axis) {
        Lanes near_plane, far_plane;
        std::memcpy(&near_plane, planes + packet.near_row[axis], sizeof near_plane);
        std::memcpy(&far_plane, planes + packet.far_row[axis], sizeof far_plane);
        // A positive direction enters by the lower plane: farthest origin, smallest distance.
        const bool positive = packet.near_side[axis] == 0;
        const Lanes to_near = near_plane - (positive ? packet.near_origin_high[axis] : packet.near_origin_low[axis]);
        const Lanes to_far = far_plane - (positive ? packet.far_origin_low[axis] : packet.far_origin_high[axis]);
        near = lane_max(lane_min(to_near * packet.inv_low[axis], to_near * packet.inv_high[axis]), near);
        far = lane_min(lane_max(to_far * packet.inv_far_low[axis], to_far * packet.inv_far_high[axis]), far);
    }
    return {near, lane_mask(near <= far)};
}

}  // namespace tracer
