// The float box tests (enter_box for binary nodes, enter_wide in both forms for wide ones) must
// enter every box that the exact ray touches, whatever rounding does: rays are aimed at points
// on box surfaces (faces, edges, corners), from near and far, at many scales. And they must not
// enter boxes that a ray clearly misses, or the first check could not fail.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "accel/bvh_node.h"
#include "accel/bvh_search.h"

namespace tracer {
namespace {

struct Case {
    float lower[3], upper[3];
    Ray ray;
};

// A random box and a ray from a random double origin that reaches, at t = 1, a point of its
// surface, or (with `outside`) a point a clear distance outside one of its faces.
Case random_case(std::mt19937& random, bool outside) {
    std::uniform_real_distribution<double> unit(0, 1);
    std::uniform_int_distribution<int> exponent(-12, 16), third(0, 2);
    const double size = std::ldexp(1.0, exponent(random));
    const double offset = size * std::ldexp(1.0, third(random) * 6);  // boxes near or far from 0
    Case c{};
    double target[3];
    for (int axis = 0; axis < 3; ++axis) {
        c.lower[axis] = float(offset * (2 * unit(random) - 1));
        // One box in ten is flat along the axis (a triangle in an axis-parallel plane).
        c.upper[axis] = unit(random) < 0.1 ? c.lower[axis] : float(c.lower[axis] + size * unit(random));
        const int where = third(random);  // on the lower plane, on the upper one, or between
        target[axis] = where == 0   ? c.lower[axis]
                       : where == 1 ? c.upper[axis]
                                    : double(c.lower[axis]) + (double(c.upper[axis]) - c.lower[axis]) * unit(random);
    }
    // The point must lie on the surface: put one axis on a plane.
    const int face_axis = third(random);
    const bool upper_face = unit(random) < 0.5;
    target[face_axis] = upper_face ? c.upper[face_axis] : c.lower[face_axis];
    // A missing ray aims at a point moved off that face by a tenth of the box's size at least.
    if (outside) target[face_axis] += (upper_face ? 1 : -1) * (0.1 + unit(random)) * size;
    // The origin lies on the target's side of the face, 2^-4 to 2^12 sizes away; in one case
    // in ten its coordinate on another axis equals the target's (a zero direction component).
    Vec3 origin;
    for (int axis = 0; axis < 3; ++axis)
        origin[axis] = target[axis] + size * std::ldexp(2 * unit(random) - 1, int(unit(random) * 12) - 4);
    const double away = size * std::ldexp(0.5 + unit(random), int(unit(random) * 16) - 4);
    origin[face_axis] = target[face_axis] + (upper_face ? away : -away);
    if (unit(random) < 0.1) origin[(face_axis + 1) % 3] = target[(face_axis + 1) % 3];
    // The direction reaches the target at t = 1: exactly, or within 2^-53 |origin| of it,
    // far inside the box tests' margins.
    c.ray = {origin, Vec3(target[0], target[1], target[2]) - origin};
    return c;
}

// Lane `lane` of a wide node holds the case's box, the others random boxes or no child.
WideNode wide_node_with(const Case& c, int lane, std::mt19937& random) {
    std::uniform_real_distribution<float> unit(0, 1);
    WideNode node{};
    for (int k = 0; k < kWide; ++k) {
        const bool empty = k != lane && unit(random) < 0.3;
        for (int axis = 0; axis < 3; ++axis) {
            const float a = c.lower[axis] + (c.upper[axis] - c.lower[axis] + 1) * (2 * unit(random) - 1);
            node.planes[0][axis][k] = k == lane ? c.lower[axis] : empty ? kInfinity : a;
            node.planes[1][axis][k] = k == lane ? c.upper[axis] : empty ? -kInfinity : a + unit(random);
        }
        node.count[k] = empty ? 0 : 1;
    }
    return node;
}

struct Outcome {
    int binary = 0, subtract = 0, fused = 0, fused_rays = 0;
};

// How many of `n` random cases each box test enters. A missing ray ends at t = 1: beyond it
// it might go on into the box.
Outcome count_entered(int n, bool outside, uint32_t seed) {
    std::mt19937 random(seed);
    Outcome entered;
    for (int i = 0; i < n; ++i) {
        const Case c = random_case(random, outside);
        const TraversalRay fast(c.ray, {0, outside ? 1 : kInfinity});
        BvhNode binary{};
        for (int axis = 0; axis < 3; ++axis) binary.box[0][axis] = c.lower[axis], binary.box[1][axis] = c.upper[axis];
        entered.binary += enter_box(binary, fast) != kInfinity;
        const int lane = i % kWide;
        const WideNode node = wide_node_with(c, lane, random);
        entered.subtract += (enter_wide<false>(node, fast).mask >> lane) & 1;
        if (!fast.fused) continue;
        ++entered.fused_rays;
        entered.fused += (enter_wide<true>(node, fast).mask >> lane) & 1;
    }
    return entered;
}

TEST(BoxTests, EnterEveryBoxTheRayTouches) {
    constexpr int kRays = 200000;
    const Outcome entered = count_entered(kRays, false, 1);
    EXPECT_EQ(entered.binary, kRays);
    EXPECT_EQ(entered.subtract, kRays);
}

TEST(BoxTests, FusedFormEntersEveryBoxTheRayTouches) {
    if (!kFusedSlabs) GTEST_SKIP() << "this build has no FMA: the fused box test is not used";
    constexpr int kRays = 200000;
    const Outcome entered = count_entered(kRays, false, 1);
    EXPECT_GT(entered.fused_rays, kRays * 8 / 10);  // the others have a zero direction component
    EXPECT_EQ(entered.fused, entered.fused_rays);
}

TEST(BoxTests, EnterNoBoxTheRayClearlyMisses) {
    constexpr int kRays = 200000;
    const Outcome entered = count_entered(kRays, true, 2);
    EXPECT_EQ(entered.binary, 0);
    EXPECT_EQ(entered.subtract, 0);
    EXPECT_EQ(entered.fused, 0);
}

// The world's filter before a mesh (ray_may_meet_box, in Real on a padded box) on the same
// cases: it must let through each ray that touches the box, and nearly none that clearly miss
// (its margin grows with the origin's size: in float a few of those far away pass).
TEST(BoxTests, TheWorldsBoxFilterKeepsEveryRayThatTouchesTheBox) {
    for (const bool outside : {false, true}) {
        std::mt19937 random(outside ? 4 : 3);
        int kept = 0;
        for (int i = 0; i < 200000; ++i) {
            const Case c = random_case(random, outside);
            Bounds box;
            box.extend(Vec3(c.lower[0], c.lower[1], c.lower[2]));
            box.extend(Vec3(c.upper[0], c.upper[1], c.upper[2]));
            kept += ray_may_meet_box(c.ray, padded_for_rays(box), {0, outside ? Real(1) : kInfinity});
        }
        if (outside)
            EXPECT_LT(kept, 200000 / 100) << "rays that clearly miss";
        else
            EXPECT_EQ(kept, 200000) << "rays that touch";
    }
}

}  // namespace
}  // namespace tracer

// round_down and round_up (branch-free) against their definition: the largest float <= x and
// the smallest float >= x, found with std::nextafter, on random doubles of every magnitude and
// on the edges (zeros of both signs, subnormals, float's largest, past it, infinities, NaN).
TEST(BoxTests, RoundingToFloatNeverShrinksWhatItBounds) {
    auto down = [](double x) {
        float f = float(x);
        return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
    };
    auto up = [](double x) {
        float f = float(x);
        return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
    };
    std::vector<double> values = {0.0,
                                  -0.0,
                                  1e-50,
                                  -1e-50,
                                  double(std::numeric_limits<float>::denorm_min()),
                                  double(std::numeric_limits<float>::denorm_min()) * 0.75,
                                  -double(std::numeric_limits<float>::denorm_min()) * 1.5,
                                  double(std::numeric_limits<float>::max()),
                                  double(std::numeric_limits<float>::max()) * (1 + 1e-12),
                                  -double(std::numeric_limits<float>::max()) * (1 + 1e-12),
                                  1e39,
                                  -1e39,
                                  std::numeric_limits<double>::infinity(),
                                  -std::numeric_limits<double>::infinity()};
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> exponent(-160, 140), mantissa(-1, 1);
    for (int i = 0; i < 200000; ++i) values.push_back(mantissa(random) * std::exp2(exponent(random)));
    for (double x : values) {
        if constexpr (sizeof(tracer::Real) == 4) x = double(float(x));  // a float build rounds nothing
        ASSERT_EQ(std::bit_cast<uint32_t>(tracer::round_down(tracer::Real(x))), std::bit_cast<uint32_t>(down(x))) << x;
        ASSERT_EQ(std::bit_cast<uint32_t>(tracer::round_up(tracer::Real(x))), std::bit_cast<uint32_t>(up(x))) << x;
    }
    EXPECT_TRUE(std::isnan(tracer::round_down(tracer::Real(NAN))));
    EXPECT_TRUE(std::isnan(tracer::round_up(tracer::Real(NAN))));
}
