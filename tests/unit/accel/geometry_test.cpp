#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "accel/geometry.h"

namespace tracer {
namespace {

const Interval kAll{1e-4, kInfinity};

TEST(Sphere, HitFromOutsideReturnsTheNearSide) {
    auto t = intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, kAll);
    ASSERT_TRUE(t);
    EXPECT_DOUBLE_EQ(*t, 4);
}

TEST(Sphere, HitFromInsideReturnsTheFarSide) {
    auto t = intersect_sphere({{0, 0, 0.5}, {0, 0, -1}}, {0, 0, 0}, 1, kAll);
    ASSERT_TRUE(t);
    EXPECT_DOUBLE_EQ(*t, 1.5);
}

TEST(Sphere, BehindTheRayOrBeyondTheRangeMisses) {
    EXPECT_FALSE(intersect_sphere({{0, 0, 5}, {0, 0, 1}}, {0, 0, 0}, 1, kAll));
    EXPECT_FALSE(intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, {1e-4, 3.9}));
}

TEST(Sphere, GrazingRaysHitAtTheTangentOrMissJustOutside) {
    auto t = intersect_sphere({{1, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, kAll);
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 5, 1e-12);
    EXPECT_FALSE(intersect_sphere({{1 + 1e-9, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, kAll));
}

TEST(Sphere, RayLeavingTheSurfaceDoesNotHitItAgain) {
    // A reflection ray from the top of the sphere, pointing away: no hit beyond epsilon.
    EXPECT_FALSE(intersect_sphere({{0, 1, 0}, glm::normalize(Vec3(1, 1, 0))}, {0, 0, 0}, 1, kAll));
}

TEST(Sphere, TinySphereFarAwayKeepsItsPrecision) {
    // Hard case C1 (i): r = 0.01 at 1e4. The naive discriminant loses every digit here.
    const Vec3 origin{0, 0, 1e4};
    const Vec3 target{0.005, 0, 0};  // b = r/2: a clean hit
    auto t = intersect_sphere({origin, glm::normalize(target - origin)}, {0, 0, 0}, 0.01, kAll);
    ASSERT_TRUE(t);
    const double exact = std::sqrt(1e8 + 0.005 * 0.005) - std::sqrt(0.01 * 0.01 - 0.005 * 0.005);
    EXPECT_NEAR(*t, exact, 4e-12 * 1e4);
}

TEST(Plane, HitFromBothSides) {
    const Vec3 point{0, -1, 0}, normal{0, 1, 0};
    auto above = intersect_plane({{0, 1, 0}, {0, -1, 0}}, point, normal, kAll);
    auto below = intersect_plane({{0, -3, 0}, {0, 1, 0}}, point, normal, kAll);
    ASSERT_TRUE(above);
    ASSERT_TRUE(below);
    EXPECT_DOUBLE_EQ(*above, 2);
    EXPECT_DOUBLE_EQ(*below, 2);
}

TEST(Plane, ParallelRayMissesWithoutNaN) {
    EXPECT_FALSE(intersect_plane({{0, 1, 0}, {1, 0, 0}}, {0, -1, 0}, {0, 1, 0}, kAll));
    EXPECT_FALSE(intersect_plane({{0, -1, 0}, {1, 0, 0}}, {0, -1, 0}, {0, 1, 0}, kAll));  // in the plane
}

TEST(Plane, RayStartingOnThePlaneDoesNotHitIt) {
    EXPECT_FALSE(intersect_plane({{3, -1, 2}, glm::normalize(Vec3(1, 1, 0))}, {0, -1, 0}, {0, 1, 0}, kAll));
}

}  // namespace
}  // namespace tracer
