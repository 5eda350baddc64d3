// Cones, cylinders and discs: their ray tests against the geometry worked out by hand (inside,
// outside, grazing, caps and rims, from both sides), and the world's BVH against brute force.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include "accel/round_shapes.h"
#include "accel/world.h"
#include "render/spawn.h"

namespace tracer {
namespace {

// A cone from the scene description's values, as the world keeps it (capped unless told).
ConeShape cone_shape(const dvec3& base, const dvec3& top, double base_radius, double top_radius, bool caps = true) {
    return make_cone_shape(base, top, base_radius, top_radius, caps);
}

std::optional<ConeHit> cast(const ConeShape& cone, const Vec3& origin, const Vec3& direction) {
    return intersect_cone({origin, glm::normalize(direction)}, cone, {0, kInfinity});
}

TEST(RoundShapes, CylinderFromOutsideAndInside) {
    const ConeShape cylinder = cone_shape({0, -1, 0}, {0, 1, 0}, 0.5, 0.5);
    // Across the axis from outside: the near side at 5 - 0.5.
    auto hit = cast(cylinder, {0, 0, 5}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.5, 1e-12);
    EXPECT_EQ(hit->part, kConeSide);
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    const RoundSurface surface = cone_surface(ray, cylinder, hit->t, hit->part);
    EXPECT_NEAR(surface.normal.z, 1, 1e-12);  // outwards
    EXPECT_NEAR(surface.point.z, 0.5, 1e-12);
    // From the axis: the wall at the radius, in any direction across it.
    hit = cast(cylinder, {0, 0.3, 0}, {1, 0, 1});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.5, 1e-12);
    // Missing beside it, and above it.
    EXPECT_FALSE(cast(cylinder, {0.6, 0, 5}, {0, 0, -1}));
    EXPECT_FALSE(cast(cylinder, {0, 1.2, 5}, {0, 0, -1}));
    // Behind the ray.
    EXPECT_FALSE(cast(cylinder, {0, 0, 5}, {0, 0, 1}));
}

TEST(RoundShapes, CapsCloseTheEndsUnlessOpen) {
    const ConeShape capped = cone_shape({0, -1, 0}, {0, 1, 0}, 0.5, 0.5);
    const ConeShape open = cone_shape({0, -1, 0}, {0, 1, 0}, 0.5, 0.5, false);
    // Down the axis from above: the top cap, normal up; the open tube lets it through.
    auto hit = cast(capped, {0.1, 3, 0}, {0, -1, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->part, kConeWideCap);
    EXPECT_NEAR(hit->t, 2, 1e-12);
    EXPECT_EQ(cone_surface({{0.1, 3, 0}, {0, -1, 0}}, capped, hit->t, hit->part).normal, Vec3(0, 1, 0));
    EXPECT_FALSE(cast(open, {0.1, 3, 0}, {0, -1, 0}));
    // Up from below: the base cap (the tip's: a cylinder is measured from its base), normal down.
    hit = cast(capped, {0, -4, 0.2}, {0, 1, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->part, kConeTipCap);
    EXPECT_NEAR(hit->t, 3, 1e-12);
    EXPECT_EQ(cone_surface({{0, -4, 0.2}, {0, 1, 0}}, capped, hit->t, hit->part).normal, Vec3(0, -1, 0));
    // Slanting in through the top of the open tube: its inside wall.
    hit = cast(open, {0, 3, 0}, {0.2, -1, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->part, kConeSide);
    const Vec3 at = Vec3(0, 3, 0) + hit->t * glm::normalize(Vec3(0.2, -1, 0));
    EXPECT_NEAR(at.x, 0.5, 1e-12);
    EXPECT_NEAR(at.y, 0.5, 1e-12);
    // From inside the closed one, straight up: the top cap from below.
    hit = cast(capped, {0, 0, 0}, {0, 1, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->part, kConeWideCap);
    EXPECT_NEAR(hit->t, 1, 1e-12);
}

TEST(RoundShapes, PointedConeAndFrustum) {
    // Radius 1 at y = 0 to a point at y = 2: at height h the radius is 1 - h/2.
    const ConeShape cone = cone_shape({0, 0, 0}, {0, 2, 0}, 1, 0);
    auto hit = cast(cone, {0, 1, 5}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.5, 1e-12);
    const RoundSurface side = cone_surface({{0, 1, 5}, {0, 0, -1}}, cone, hit->t, hit->part);
    // The side's outward normal: (0, 1, 2) / sqrt(5) where it faces +z.
    EXPECT_NEAR(side.normal.y, 1 / std::sqrt(5.0), 1e-12);
    EXPECT_NEAR(side.normal.z, 2 / std::sqrt(5.0), 1e-12);
    // The other nappe (above the point) is not part of it.
    EXPECT_FALSE(cast(cone, {0, 3, 5}, {0, 0, -1}));
    // Down the axis onto the point: it is met there.
    hit = cast(cone, {0, 4, 0}, {0, -1, 0});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, 1e-12);
    // Along the slope (a = 0 in the quadratic): one root only.
    hit = cast(cone, {-1, -1, 0}, {1, 2, 0});
    EXPECT_FALSE(hit && !std::isfinite(hit->t));
    // A frustum, radius 0.5 at the base and 1 at the top, tilted: the side at mid-height.
    const ConeShape frustum = cone_shape({1, 1, 1}, {1, 1, 3}, 0.5, 1);
    hit = cast(frustum, {1, 6, 2}, {0, -1, 0});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5 - 0.75, 1e-12);
}

TEST(RoundShapes, GrazingRaysHitOnTheTangentOrMiss) {
    const ConeShape cylinder = cone_shape({0, -1, 0}, {0, 1, 0}, 1, 1);
    for (double offset : {-1e-9, 1e-9, 0.0}) {
        const auto hit = cast(cylinder, {1 + offset, 0, 5}, {0, 0, -1});
        if (offset > 0) {
            EXPECT_FALSE(hit);
        }
        if (offset < 0) {
            EXPECT_TRUE(hit);
        }
        if (hit) {
            EXPECT_TRUE(std::isfinite(hit->t));
            EXPECT_NEAR(hit->t, 5, 1e-4);
        }
    }
}

TEST(RoundShapes, RimsLetNoRayThrough) {
    // Rays aimed at points of the rims from outside, entering the solid: each meets it within a
    // hair of the rim.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0, 1);
    const ConeShape cone = cone_shape({0.3, -0.2, 0.1}, {1.1, 1.7, -0.4}, 0.8, 0.35);
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const bool wide_end = i % 2;
        const double angle = 2 * M_PI * unit(random);
        const Vec3 w = cone.axis;
        const Vec3 u = glm::normalize(glm::cross(w, Vec3(1, 0, 0))), v = glm::cross(w, u);
        const Real radius = wide_end ? cone.wide_radius : cone.tip_radius;
        const Vec3 center = cone.tip + (wide_end ? cone.height : 0) * w;
        const Vec3 rim = center + radius * (Real(std::cos(angle)) * u + Real(std::sin(angle)) * v);
        // From a point beyond the cap, inside the rim's circle a little: the ray crosses the edge.
        const Vec3 outward = Real(wide_end ? 1 : -1) * w;
        const Vec3 origin = center + Real(2) * outward + Real(1.5) * (rim - center);
        const auto hit = cast(cone, origin, rim - origin);
        misses += !hit || hit->t > glm::length(rim - origin) * (1 + 1e-9);
    }
    EXPECT_EQ(misses, 0);
}

TEST(RoundShapes, DiscsFromBothSides) {
    const DiscShape disc{{1, 2, 3}, glm::normalize(Vec3(0, 1, 1)), 0.5};
    const Vec3 n = disc.normal;
    auto t = intersect_disc({disc.center + Real(2) * n, -n}, disc, {0, kInfinity});
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 2, 1e-12);
    t = intersect_disc({disc.center - Real(3) * n, n}, disc, {0, kInfinity});
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 3, 1e-12);
    // Beside it, and along its plane.
    const Vec3 across = glm::normalize(glm::cross(n, Vec3(1, 0, 0)));
    EXPECT_FALSE(intersect_disc({disc.center + Real(0.6) * across + n, -n}, disc, {0, kInfinity}));
    EXPECT_FALSE(intersect_disc({disc.center + Real(2) * across, -across}, disc, {0, kInfinity}));
    const RoundSurface s = disc_surface({disc.center + n, -n}, disc, 1);
    EXPECT_NEAR(glm::length(s.point - disc.center), 0, 1e-12);
}

// A scene of many cones, cylinders, discs and spheres, found through the top level's BVH and
// one by one (accel none): the same hit for every ray, and the same answer to occluded().
TEST(RoundShapes, BvhAgreesWithBruteForce) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0, 1);
    auto point = [&](double size) { return size * dvec3(unit(random), unit(random), unit(random)) - size / 2; };
    SceneDescription scene;
    scene.materials.resize(1);
    for (int i = 0; i < 400; ++i) {
        const dvec3 base = point(10);
        const dvec3 top = base + point(1.5);
        const double r = 0.05 + 0.3 * unit(random);
        scene.cones.push_back({base, top, r, i % 3 == 0 ? r : (i % 3 == 1 ? 0.0 : 0.5 * r), i % 2 == 0, 0});
        scene.discs.push_back({point(10), glm::normalize(point(2)), 0.05 + 0.3 * unit(random), 0});
        if (i % 4 == 0) scene.spheres.push_back({point(10), 0.2, 0});
    }
    SceneDescription linear = scene;
    linear.render.accel = Accelerator::None;
    const World bvh(scene), brute(linear);
    ASSERT_FALSE(bvh.top_level_linear());
    ASSERT_TRUE(brute.top_level_linear());
    int hits = 0, disagree = 0;
    for (int i = 0; i < 20000; ++i) {
        const Ray ray{Vec3(point(14)), Vec3(glm::normalize(point(2)))};
        SearchCounts counts;
        const auto a = bvh.nearest_hit(ray, {0, kInfinity}, counts);
        const auto b = brute.nearest_hit(ray, {0, kInfinity}, counts);
        hits += a.has_value();
        // The same object at the same t to 4096 ulps (the compiler fuses multiply-adds differently
        // where a test is inlined: spheres' t differ by a few ulps too).
        disagree += a.has_value() != b.has_value() ||
                    (a && (a->object != b->object ||
                           std::abs(a->t - b->t) > 4096 * std::numeric_limits<Real>::epsilon() * a->t));
        disagree += bvh.occluded(ray, {0, 20}, counts) != brute.occluded(ray, {0, 20}, counts);
    }
    EXPECT_GT(hits, 4000);
    EXPECT_EQ(disagree, 0);
    // Long cones leaning across the axes are cut into pieces at the top level (cone_piece_boxes).
    EXPECT_GT(bvh.top_level_entries(), bvh.bounded_objects() + 100);
    EXPECT_EQ(brute.top_level_entries(), brute.bounded_objects());
}

// A ray leaving a sphere or cone outwards, or a disc on either side, cannot meet it again, so
// the searches skip it (object_left_behind): for rays spawned off hits as the renderer spawns
// them, in every direction, a search that skips the object finds what one testing it finds, and
// that is never the object itself. A ray going in does meet it again, and is not skipped.
TEST(RoundShapes, RaysLeavingAConvexShapeNeverMeetItAgain) {
    if constexpr (!kRobust) GTEST_SKIP() << "the naive rule skips nothing (its self-hits are what it shows)";
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0, 1);
    auto point = [&](double size) { return size * dvec3(unit(random), unit(random), unit(random)) - size / 2; };
    SceneDescription scene;
    scene.materials.resize(1);
    for (int i = 0; i < 300; ++i) {
        const dvec3 base = point(6);
        const double r = 0.05 + 0.3 * unit(random);
        scene.cones.push_back({base, base + point(2), r, i % 2 == 0 ? r : 0.3 * r, i % 3 == 0, 0});
        scene.discs.push_back({point(6), glm::normalize(point(2)), 0.05 + 0.3 * unit(random), 0});
        scene.spheres.push_back({point(6), 0.05 + 0.3 * unit(random), 0});
    }
    const World world(scene);
    int skipped = 0, met_again_going_in = 0, disagree = 0;
    for (int i = 0; i < 20000; ++i) {
        SearchCounts counts;
        const Ray primary{Vec3(point(10)), Vec3(glm::normalize(point(2)))};
        const auto first = world.nearest_hit(primary, {0, kInfinity}, counts);
        if (!first) continue;
        const SurfaceHit hit = world.surface(primary, *first);
        const Vec3 direction = glm::normalize(Vec3(point(2)));
        const SpawnedRay spawned = SpawnPoint(hit).ray(direction);
        const uint32_t left_behind = object_left_behind(hit, direction);
        const auto testing_all = world.nearest_hit(spawned.ray, spawned.range, counts);
        if (left_behind == kNoObject) {
            met_again_going_in += testing_all && testing_all->object == first->object;
            continue;
        }
        ++skipped;
        const auto skipping = world.nearest_hit(spawned.ray, spawned.range, counts, left_behind);
        disagree += testing_all.has_value() != skipping.has_value() ||
                    (testing_all && (testing_all->object == left_behind || testing_all->object != skipping->object ||
                                     testing_all->t != skipping->t));
        Occluder none, last;
        const Interval to_light{spawned.range.min, 3};
        disagree += world.occluded(spawned.ray, to_light, counts, none) !=
                    world.occluded(spawned.ray, to_light, counts, last, left_behind);
    }
    EXPECT_GT(skipped, 3000);
    EXPECT_GT(met_again_going_in, 1000);
    EXPECT_EQ(disagree, 0);
}

}  // namespace
}  // namespace tracer
