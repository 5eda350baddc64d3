// ShadowFrustum (issue 56): a box or ball holding any point of the pyramid from the apex to the
// light's quadrilateral is never ruled out (random pyramids, random points inside them), and
// what lies clearly beside it, behind the apex or beyond the light is.
#include <gtest/gtest.h>

#include <random>

#include "accel/shadow_frustum.h"

namespace tracer {
namespace {

using glm::dvec3;

// A frustum from `apex` to the parallelogram centre +- e1/2 +- e2/2.
ShadowFrustum make(const dvec3& apex, const dvec3& centre, const dvec3& e1, const dvec3& e2) {
    const dvec3 corners[4] = {centre - 0.5 * e1 - 0.5 * e2, centre + 0.5 * e1 - 0.5 * e2, centre + 0.5 * e1 + 0.5 * e2,
                              centre - 0.5 * e1 + 0.5 * e2};
    return ShadowFrustum(apex, corners);
}

Bounds box_around(const dvec3& p, double half) {
    return {Vec3(p - half), Vec3(p + half)};
}

TEST(ShadowFrustum, NeverRulesOutAPointOfThePyramid) {
    std::mt19937_64 random(56);
    std::uniform_real_distribution<double> unit(-1, 1), fraction(0, 1);
    for (int trial = 0; trial < 2000; ++trial) {
        const double scale = std::pow(10.0, 6 * unit(random));  // 1e-6 .. 1e6
        const dvec3 apex = scale * dvec3(unit(random), unit(random), unit(random));
        const dvec3 centre = apex + scale * dvec3(unit(random), 2 + unit(random), unit(random));
        const dvec3 e1 = scale * dvec3(unit(random), 0.1 * unit(random), unit(random));
        const dvec3 e2 = scale * dvec3(unit(random), unit(random), unit(random));
        const ShadowFrustum frustum = make(apex, centre, e1, e2);
        for (int k = 0; k < 20; ++k) {
            // The light's point at (a, b) of its edges, and the point of its ray at t.
            const double a = fraction(random) - 0.5, b = fraction(random) - 0.5, t = fraction(random);
            const dvec3 on_light = centre + a * e1 + b * e2;
            const dvec3 p = apex + t * (on_light - apex);
            EXPECT_TRUE(frustum.may_meet_box(box_around(p, 0))) << trial << " " << k;
            EXPECT_TRUE(frustum.may_meet_ball(p, 0)) << trial << " " << k;
            EXPECT_TRUE(frustum.may_meet_box(box_around(p, 1e-3 * scale)));
        }
    }
}

TEST(ShadowFrustum, RulesOutWhatLiesBesideBehindOrBeyond) {
    const ShadowFrustum frustum = make({0, 0, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 2});
    EXPECT_TRUE(frustum.may_meet_box(box_around({0, 5, 0}, 0.1)));
    EXPECT_FALSE(frustum.may_meet_box(box_around({3, 5, 0}, 0.1)));   // beside
    EXPECT_FALSE(frustum.may_meet_box(box_around({0, -1, 0}, 0.5)));  // behind the apex
    EXPECT_FALSE(frustum.may_meet_box(box_around({0, 11, 0}, 0.5)));  // beyond the light
    EXPECT_TRUE(frustum.may_meet_box(box_around({0.95, 9.9, 0}, 0.1)));
    EXPECT_FALSE(frustum.may_meet_ball({3, 5, 0}, 1.5));
    EXPECT_TRUE(frustum.may_meet_ball({3, 5, 0}, 2.6));  // reaches over the side
    // A plane crossed by no ray: the floor under the apex, the ceiling over the light.
    EXPECT_FALSE(frustum.may_cross_plane({0, -0.5, 0}, {0, 1, 0}));
    EXPECT_FALSE(frustum.may_cross_plane({0, 12, 0}, {0, 1, 0}));
    EXPECT_TRUE(frustum.may_cross_plane({0, 5, 0}, {0, 1, 0}));
}

TEST(ShadowFrustum, AnApexOnAPlaneIsOnItsSideOfIt) {
    // The floor a shadow ray leaves: its apex just above (spawn.h moves it), the light above too.
    const ShadowFrustum above = make({0, 1e-15, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 2});
    EXPECT_FALSE(above.may_cross_plane({0, 0, 0}, {0, 1, 0}));
    // Exactly on it, every ray meets it at t = 0, which no search counts (the light on either side).
    const ShadowFrustum on = make({0, 0, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 2});
    EXPECT_FALSE(on.may_cross_plane({0, 0, 0}, {0, 1, 0}));
    const ShadowFrustum across = make({0, 0, 0}, {0, 0, 10}, {0, 2, 0}, {2, 0, 0});
    EXPECT_FALSE(across.may_cross_plane({0, 0, 0}, {0, 1, 0}));
    // Just below it, every ray crosses it.
    const ShadowFrustum below = make({0, -1e-15, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 2});
    EXPECT_TRUE(below.may_cross_plane({0, 0, 0}, {0, 1, 0}));
}

TEST(ShadowFrustum, ALineOfSamplesOrAnApexInTheLightsPlaneRulesOutOnlyWhatItCan) {
    // One sample along edge2: the quadrilateral is a segment; nothing in the pyramid is lost.
    const ShadowFrustum line = make({0, 0, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 0});
    EXPECT_TRUE(line.may_meet_box(box_around({0.5, 5, 0}, 0.01)));
    // The apex in the light's own plane: flat, still conservative.
    const ShadowFrustum flat = make({5, 10, 0}, {0, 10, 0}, {2, 0, 0}, {0, 0, 2});
    EXPECT_TRUE(flat.may_meet_box(box_around({3, 10, 0}, 0.01)));
    // Coordinates that overflow when squared rule nothing out.
    const ShadowFrustum huge = make({0, 0, 0}, {0, 1e200, 0}, {1e200, 0, 0}, {0, 0, 1e200});
    EXPECT_TRUE(huge.may_meet_box(box_around({0, 5e199, 0}, 1)));
}

}  // namespace
}  // namespace tracer
