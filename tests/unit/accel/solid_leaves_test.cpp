// The spans of CSG's leaves (accel/solid_leaves.h) against their shapes' own definitions: random
// lines through random spheres, boxes and planes; every point of the line away from the ends is
// inside the span exactly when it is inside the shape. A box's ends name the face they lie on;
// a sphere's first end past the origin is intersect_sphere's hit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/geometry.h"
#include "accel/solid_leaves.h"

namespace tracer {
namespace {

Vec3 random_point(std::mt19937& random, Real reach) {
    std::uniform_real_distribution<Real> unit(-reach, reach);
    return {unit(random), unit(random), unit(random)};
}

// Points of the line at t spaced along [-20, 20], skipping those within 1e-6 of an end.
template <typename Inside>
void expect_membership(const Ray& ray, const std::optional<SolidSpan>& span, Inside inside, int trial) {
    for (Real t = -20; t <= 20; t += Real(0.37)) {
        if (span && (std::abs(t - span->enter.t) < 1e-6 || std::abs(t - span->leave.t) < 1e-6)) continue;
        const bool in_span = span && span->enter.t <= t && t <= span->leave.t;
        ASSERT_EQ(in_span, inside(ray.at(t))) << "trial " << trial << " t " << t;
    }
}

TEST(SolidLeaves, SpheresBoxesAndHalfSpacesHoldTheirInsides) {
    std::mt19937 random(11);
    std::uniform_real_distribution<Real> size(Real(0.2), 3);
    for (int trial = 0; trial < 20000; ++trial) {
        const Ray ray{random_point(random, 4), glm::normalize(random_point(random, 1)) * size(random)};
        const Vec3 center = random_point(random, 2);
        const Real radius = size(random);
        const auto sphere = sphere_span(ray, center, radius, 7);
        expect_membership(
            ray, sphere, [&](const Vec3& p) { return glm::length(p - center) < radius; }, trial);
        if (sphere) {  // the first end past the origin is the nearest hit
            const auto hit = intersect_sphere(ray, center, radius, {0, kInfinity});
            const Real first = sphere->enter.t > 0 ? sphere->enter.t : sphere->leave.t;
            if (sphere->leave.t > 0) {
                ASSERT_TRUE(hit && std::abs(*hit - first) <= 1e-12 * (1 + first));
            }
        }
        const Vec3 lower = center - Vec3(size(random), size(random), size(random)), upper = center + radius;
        const auto box = box_span(ray, lower, upper, 8);
        expect_membership(
            ray, box,
            [&](const Vec3& p) { return glm::all(glm::lessThan(lower, p)) && glm::all(glm::lessThan(p, upper)); },
            trial);
        if (box) {
            for (const SpanEnd& end : {box->enter, box->leave}) {
                const int axis = end.part / 2;
                const Real plane = end.part % 2 ? upper[axis] : lower[axis];
                ASSERT_NEAR(ray.at(end.t)[axis], plane, 1e-9 * (1 + std::abs(plane))) << "trial " << trial;
            }
        }
        const Vec3 normal = glm::normalize(random_point(random, 1));
        expect_membership(
            ray, half_space_span(ray, center, normal, 9),
            [&](const Vec3& p) { return glm::dot(p - center, normal) < 0; }, trial);
    }
}

TEST(SolidLeaves, LinesAlongAFaceOrPlaneCountAsInside) {
    const Ray along{{-5, 1, 0.5}, {1, 0, 0}};  // in the plane y = 1 of the box's top face
    const auto box = box_span(along, {0, 0, 0}, {1, 1, 1}, 0);
    ASSERT_TRUE(box);
    EXPECT_EQ(box->enter.t, 5);
    EXPECT_EQ(box->leave.t, 6);
    EXPECT_FALSE(box_span({{-5, 1.5, 0.5}, {1, 0, 0}}, {0, 0, 0}, {1, 1, 1}, 0));
    const auto half = half_space_span(along, {0, 1, 0}, {0, 1, 0}, 0);
    ASSERT_TRUE(half);
    EXPECT_EQ(half->enter.t, -kInfinity);
    EXPECT_EQ(half->leave.t, kInfinity);
    EXPECT_FALSE(half_space_span(along, {0, 0, 0}, {0, 1, 0}, 0));  // above the plane y = 0
}

}  // namespace
}  // namespace tracer
