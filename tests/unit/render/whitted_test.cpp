// The shading rules of conventions.md, each on a scene small enough to work out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../../common/nearest_surface.h"
#include "render/spawn.h"
#include "render/whitted.h"

namespace tracer {
namespace {

SceneDescription one_sphere(Material material, Light light) {
    SceneDescription scene;
    scene.materials = {material};
    scene.spheres = {{{0, 0, 0}, 1.0, 0}};
    scene.lights = {light};
    return scene;
}

Material phong(dvec3 ka, dvec3 kd, dvec3 ks, double n, dvec3 km = dvec3(0)) {
    Material m;
    m.ka = ka, m.kd = kd, m.ks = ks, m.n = n, m.km = km;
    return m;
}

const Ray kDown{{0, 0, 5}, {0, 0, -1}};  // hits the unit sphere at (0, 0, 1), normal +z

TEST(Whitted, PhongTermsAddUpWithLightColourOnDiffuseAndSpecularOnly) {
    SceneDescription scene =
        one_sphere(phong(dvec3(0.1), dvec3(0.2, 0.4, 0.6), dvec3(0.5), 10), {{0, 0, 10}, {0.5, 1.0, 0.25}});
    World world(scene);
    RayCounts counts;
    Color c = trace(world, scene.render, kDown, counts);
    // N.L = 1 and R.V = 1: colour = ka + Lc (kd + ks); ambient is not scaled by the light.
    EXPECT_NEAR(c.r, 0.1 + 0.5 * (0.2 + 0.5), 1e-12);
    EXPECT_NEAR(c.g, 0.1 + 1.0 * (0.4 + 0.5), 1e-12);
    EXPECT_NEAR(c.b, 0.1 + 0.25 * (0.6 + 0.5), 1e-12);
    EXPECT_EQ(counts.primary, 1u);
    EXPECT_EQ(counts.primary_hits, 1u);
    EXPECT_EQ(counts.shadow, 1u);
}

TEST(Whitted, SpecularUsesPhongReflectionNotTheHalfVector) {
    // Light 45 degrees off the normal, viewer on the normal: Phong's R.V is cos 45 degrees,
    // Blinn-Phong's N.H would be cos 22.5 degrees.
    SceneDescription scene = one_sphere(phong(dvec3(0), dvec3(0), dvec3(1), 1), {{10, 0, 11}, dvec3(1)});
    World world(scene);
    RayCounts counts;
    Color c = trace(world, scene.render, kDown, counts);
    EXPECT_NEAR(c.r, std::cos(M_PI / 4), 1e-12);
}

TEST(Whitted, ShadowedPointKeepsOnlyAmbient) {
    SceneDescription scene = one_sphere(phong(dvec3(0.1), dvec3(1), dvec3(1), 10), {{0, 0, 10}, dvec3(1)});
    scene.spheres.push_back({{0, 0, 3}, 0.5, 0});  // hides the light from (0, 0, 1)
    World world(scene);
    RayCounts counts;
    Ray beside_blocker{{0.8, 0, 5}, {0, 0, -1}};  // hits (0.8, 0, 0.6); its shadow ray passes the blocker
    EXPECT_GT(trace(world, scene.render, beside_blocker, counts).r, 0.1);
    Ray behind_blocker{{0, 0, 2}, {0, 0, -1}};
    EXPECT_NEAR(trace(world, scene.render, behind_blocker, counts).r, 0.1, 1e-12);

    scene.render.shadows = false;
    World no_shadows(scene);
    RayCounts no_shadow_counts;
    EXPECT_GT(trace(no_shadows, scene.render, behind_blocker, no_shadow_counts).r, 0.1);
    EXPECT_EQ(no_shadow_counts.shadow, 0u);
}

TEST(Whitted, MirrorRecursionStopsAfterMaxDepthBounces) {
    // Two facing mirrors; a ray along their normal bounces forever. Each mirror also has
    // ambient 1, so the colour counts the levels shaded: 1 + 0.5 + 0.25 + ...
    SceneDescription scene;
    scene.materials = {phong(dvec3(1), dvec3(0), dvec3(0), 1, dvec3(0.5))};
    scene.planes = {{{0, 0, -1}, {0, 0, 1}, 0}, {{0, 0, 1}, {0, 0, -1}, 0}};
    scene.render.background = dvec3(7);  // must not appear: the level past max_depth is black
    for (int depth : {0, 1, 4, 10}) {
        scene.render.max_depth = depth;
        World world(scene);
        RayCounts counts;
        Color c = trace(world, scene.render, {{0, 0, 0}, {0, 0, 1}}, counts);
        EXPECT_NEAR(c.r, 2 - std::pow(0.5, depth), 1e-12) << "depth " << depth;
        EXPECT_EQ(counts.reflection, uint64_t(depth));
    }
}

TEST(Whitted, MissesReturnTheBackgroundWeightedByTheMirror) {
    SceneDescription scene = one_sphere(phong(dvec3(0), dvec3(0), dvec3(0), 1, dvec3(0.5)), {{0, 0, 10}, dvec3(0)});
    scene.render.background = dvec3(0.2);
    World world(scene);
    RayCounts counts;
    EXPECT_NEAR(trace(world, scene.render, {{0, 0, 5}, {0, 1, 0}}, counts).r, 0.2, 1e-12);
    EXPECT_NEAR(trace(world, scene.render, kDown, counts).r, 0.1, 1e-12);  // 0.5 x background
}

TEST(Whitted, NormalFacesTheRaySoInsidesAreLit) {
    // Camera inside a sphere, light inside too: the inner surface is lit.
    SceneDescription scene = one_sphere(phong(dvec3(0), dvec3(1), dvec3(0), 1), {{0, 0.5, 0}, dvec3(1)});
    World world(scene);
    RayCounts counts;
    Color c = trace(world, scene.render, {{0, 0, 0}, {0, 1, 0}}, counts);
    EXPECT_NEAR(c.r, 1.0, 1e-12);
}

// trace() answers rays that World::may_hit rules out with the background at once: that must
// never skip a surface. Rays aimed at points on and just off the sphere's silhouette.
TEST(Whitted, MayHitNeverRulesOutARayThatHits) {
    SceneDescription scene = one_sphere(phong(dvec3(0.1), dvec3(0), dvec3(0), 1), {{0, 0, 10}, dvec3(0)});
    scene.spheres[0].center = {0.3, -0.2, 0.1};
    scene.spheres[0].radius = 0.7;
    World world(scene);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), exponent(-12, -4), far(2, 50);
    int hits = 0, ruled_out = 0;
    for (int i = 0; i < 100000; ++i) {
        const double a = angle(random), b = angle(random), distance = far(random);
        const Vec3 origin = Vec3(scene.spheres[0].center) +
                            Real(distance) * Vec3(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b));
        // A point on the silhouette seen from the origin, nudged in or out by 1e-12 to 1e-4.
        const Vec3 to_center = Vec3(scene.spheres[0].center) - origin;
        const Vec3 side = glm::normalize(glm::cross(to_center, Vec3(0.3, 1, 0.2)));
        const double r = scene.spheres[0].radius, d = glm::length(to_center);
        const double nudge = (i % 2 ? 1 : -1) * std::pow(10.0, exponent(random));
        const Vec3 target =
            origin + to_center * Real(1 - r * r / (d * d)) + side * Real(r * std::sqrt(d * d - r * r) / d + nudge);
        const Ray ray{origin, glm::normalize(target - origin)};
        SearchCounts counts;
        const bool hit = nearest_surface(world, ray, kPrimaryRange, counts).has_value();
        const bool may_hit = world.may_hit(ray);
        hits += hit;
        ruled_out += !may_hit;
        if (hit) {
            ASSERT_TRUE(may_hit) << "ray " << i;
        }
    }
    EXPECT_GT(hits, 1000);       // the test aims at the silhouette: some rays hit ...
    EXPECT_GT(ruled_out, 1000);  // ... and some are ruled out
    RayCounts counts;
    EXPECT_EQ(trace(world, scene.render, {{5, 5, 5}, {1, 0, 0}}, counts), scene.render.background);
    EXPECT_EQ(counts.primary, 1u);
    EXPECT_EQ(counts.primary_hits, 0u);
    // A plane is unbounded: nothing is ruled out.
    scene.planes = {{{0, -100, 0}, {0, 1, 0}, 0}};
    EXPECT_TRUE(World(scene).may_hit({{5, 5, 5}, {1, 0, 0}}));
}

}  // namespace
}  // namespace tracer

namespace tracer {
namespace {

// A lit unit sphere seen head on, a glass sphere (kt 0.5, 0.25, 0) between it and the light.
SceneDescription lit_through_glass(bool transparent) {
    SceneDescription scene = one_sphere(phong(dvec3(0), dvec3(1), dvec3(0), 1), {{0, 0, 10}, dvec3(1)});
    Material glass;
    glass.kt = dvec3(0.5, 0.25, 0);
    glass.ior = 1.5;
    scene.materials.push_back(glass);
    scene.spheres.push_back({{0, 0, 3}, 0.5, 1});
    scene.render.transparent_shadows = transparent;
    return scene;
}

// Transparent shadows: the light crosses two surfaces of the glass, kt at each (not refracted);
// a channel with kt 0 is blocked. Opaque shadows block it all.
TEST(Whitted, TransparentShadowsMultiplyTheLightByKtAtEachSurfaceCrossed) {
    const Ray at_lit_point{{0, 0, 1.5}, {0, 0, -1}};  // starts between the spheres: (0, 0, 1) first
    for (bool transparent : {true, false}) {
        const SceneDescription scene = lit_through_glass(transparent);
        const World world(scene);
        RayCounts counts;
        const Color c = trace(world, scene.render, at_lit_point, counts);
        EXPECT_NEAR(c.r, transparent ? 0.25 : 0, 1e-12);
        EXPECT_NEAR(c.g, transparent ? 0.0625 : 0, 1e-12);
        EXPECT_EQ(c.b, 0);
        // The shadow ray, and under transparent shadows its two continuations past each surface.
        EXPECT_EQ(counts.shadow, transparent ? 3u : 1u);
    }
}

// The SPD's spawn rules: a reflection ray at a transmitting surface with km = 0 and a shadow ray
// wherever the normal faces the light (here onto black glass); tracer's rules spawn neither.
// The colour is the same.
TEST(Whitted, SpdSpawnRulesAddRaysButNotColour) {
    SceneDescription scene = one_sphere(phong(dvec3(0.1), dvec3(0), dvec3(0), 1), {{0, 0, 10}, dvec3(1)});
    scene.materials[0].kt = dvec3(0.5);
    scene.materials[0].ior = 1.5;
    scene.spheres.push_back({{0, 0, -4}, 1, 0});
    Color colours[2];
    RayCounts counts[2];
    for (int spd = 0; spd < 2; ++spd) {
        scene.render.spawn_rules = spd ? SpawnRules::Spd : SpawnRules::Tracer;
        const World world(scene);
        colours[spd] = trace(world, scene.render, kDown, counts[spd]);
    }
    EXPECT_EQ(colours[0], colours[1]);
    EXPECT_EQ(counts[0].reflection, 0u);
    EXPECT_GT(counts[1].reflection, 0u);
    EXPECT_EQ(counts[0].shadow, 0u);  // kd = ks = 0: no Phong term, no shadow ray
    EXPECT_GT(counts[1].shadow, 0u);
    EXPECT_GE(counts[1].refraction, counts[0].refraction);  // the reflection rays' own subtrees
}

}  // namespace
}  // namespace tracer
