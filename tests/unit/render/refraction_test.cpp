// Refraction (kt, ior), each rule on a scene small enough to work out by hand: Snell's law,
// entering and leaving by the geometric normal, total internal reflection, the depth limit
// along any path, and the ray counts.
#include <gtest/gtest.h>

#include <cmath>

#include "render/whitted.h"

namespace tracer {
namespace {

// A clear glass sphere (kt 1, nothing else) of radius 1 at the origin, with a background.
SceneDescription glass_sphere(double ior, int max_depth = 4) {
    SceneDescription scene;
    Material glass;
    glass.kt = dvec3(1.0);
    glass.ior = ior;
    scene.materials = {glass};
    scene.spheres = {{{0, 0, 0}, 1.0, 0}};
    scene.render.background = {0.2, 0.4, 0.6};
    scene.render.max_depth = max_depth;
    scene.render.shadows = false;
    return scene;
}

// Glass filling z < 0 (the plane z = 0, normal up, out of the glass) and a small marker
// sphere of ambient 1 (seen as 1.0 when a ray reaches it, else 0): where the marker sits
// tells which way the rays went.
SceneDescription glass_floor_with_marker(double kt, Vec3 marker_center, double marker_radius) {
    SceneDescription scene;
    Material glass, marker;
    glass.kt = dvec3(kt), glass.ior = 1.5;
    marker.ka = dvec3(1.0);
    scene.materials = {glass, marker};
    scene.planes = {{{0, 0, 0}, {0, 0, 1}, 0}};
    scene.spheres = {{dvec3(marker_center), marker_radius, 1}};
    scene.render.shadows = false;
    return scene;
}

TEST(Refraction, IndexOneLetsTheRayThroughUnbent) {
    SceneDescription scene = glass_sphere(1.0);
    World world(scene);
    RayCounts counts;
    const Color c = trace(world, scene.render, {{0.3, 0.2, 5}, {0, 0, -1}}, counts);
    EXPECT_NEAR(c.r, 0.2, 1e-12);
    EXPECT_NEAR(c.g, 0.4, 1e-12);
    EXPECT_NEAR(c.b, 0.6, 1e-12);
    EXPECT_EQ(counts.refraction, 2u);    // in, then out
    EXPECT_EQ(counts.primary_hits, 1u);  // the refracted paths are not primary rays
    EXPECT_EQ(counts.reflection, 0u);    // km 0: no reflected ray is traced
}

TEST(Refraction, SnellsLawThroughAFlatInterface) {
    // A ray at 45 degrees into the glass floor (ior 1.5); a marker 10 below the surface where
    // Snell's law says the refracted ray passes: sin(out) = sin(45) / 1.5.
    const double sin_out = std::sin(M_PI / 4) / 1.5;
    const double tan_out = sin_out / std::sqrt(1 - sin_out * sin_out);
    SceneDescription scene = glass_floor_with_marker(1.0, {10 * tan_out, 0, -10}, 0.01);
    World world(scene);
    RayCounts counts;
    const Ray ray{{-1, 0, 1}, glm::normalize(Vec3(1, 0, -1))};           // reaches the floor at the origin
    EXPECT_NEAR(trace(world, scene.render, ray, counts).r, 1.0, 1e-12);  // the marker, seen through the glass
    // Two degrees off the law, the marker is missed.
    SceneDescription off = scene;
    const double wrong = std::tan(std::asin(sin_out) + 2 * M_PI / 180);
    off.spheres[0].center.x = 10 * wrong;
    World off_world(off);
    EXPECT_EQ(trace(off_world, off.render, ray, counts).r, 0.0);
}

TEST(Refraction, TotalInternalReflectionSendsTheWeightAlongTheMirrorRay) {
    // From inside a glass slab (the ray starts below the plane, whose normal points up, out of
    // the glass), at 60 degrees from the normal: sin 60 * 1.5 > 1, so nothing leaves; the
    // whole kt goes to the reflected ray, which finds a marker at the mirror position.
    const Vec3 in = glm::normalize(Vec3(std::sin(M_PI / 3), 0, std::cos(M_PI / 3)));
    // The marker on the reflected ray's way, distance 2.
    SceneDescription scene = glass_floor_with_marker(0.75, {2 * in.x, 0, -2 * in.z}, 0.05);
    World world(scene);
    RayCounts counts;
    const Color c = trace(world, scene.render, {-in, in}, counts);  // starts 1 below, hits the origin
    EXPECT_NEAR(c.r, 0.75, 1e-12);
    EXPECT_EQ(counts.refraction, 0u);
    EXPECT_EQ(counts.reflection, 1u);
}

TEST(Refraction, EnteringAndLeavingFollowTheGeometricNormal) {
    // A ball lens (ior 1.5): bent towards the inside on the way in (1 -> 1.5) and again on the
    // way out (1.5 -> 1), a ray parallel to the axis at height 0.3 crosses the axis behind the
    // sphere (paraxial focus 1.5 from the center) and meets a marker that lies wholly below
    // the axis. Unbent it would pass above the marker; with entering and leaving swapped the
    // lens would spread the ray upwards, away from it.
    SceneDescription scene = glass_sphere(1.5);
    scene.render.background = dvec3(0);
    Material marker;
    marker.ka = dvec3(1.0);
    scene.materials.push_back(marker);
    scene.spheres.push_back({{0, -2, -3}, 1.7, 1});
    World world(scene);
    RayCounts counts;
    EXPECT_NEAR(trace(world, scene.render, {{0, 0.3, 5}, {0, 0, -1}}, counts).r, 1.0, 1e-12);
    EXPECT_EQ(counts.refraction, 2u);
    // Through the center the ray is not bent: it passes above the marker.
    EXPECT_EQ(trace(world, scene.render, {{0, 0, 5}, {0, 0, -1}}, counts).r, 0.0);
}

TEST(Refraction, MaxDepthCountsRefractionsAlongAPath) {
    // Entering and leaving a sphere are two levels: with max_depth 1 the ray that would leave
    // is not traced (black), with 2 it reaches the background.
    for (int depth : {0, 1, 2}) {
        SceneDescription scene = glass_sphere(1.0, depth);
        World world(scene);
        RayCounts counts;
        const Color c = trace(world, scene.render, {{0, 0, 5}, {0, 0, -1}}, counts);
        EXPECT_NEAR(c.b, depth >= 2 ? 0.6 : 0.0, 1e-12) << depth;
        EXPECT_EQ(counts.refraction, uint64_t(std::min(depth, 2))) << depth;
    }
}

TEST(Refraction, GlassThatAlsoReflectsTracesBothBranches) {
    // km 0.25, kt 0.75 (ior 1): the mirror ray off the front leaves to the background, the
    // refracted one goes through; both weigh in: 0.25 + 0.75 (with the inside reflections,
    // each leaving the sphere in the end) of the background.
    SceneDescription scene = glass_sphere(1.0, 6);
    scene.materials[0].km = dvec3(0.25);
    scene.materials[0].kt = dvec3(0.75);
    scene.render.background = dvec3(1.0);
    World world(scene);
    RayCounts counts;
    const Color c = trace(world, scene.render, {{0, 0, 5}, {0, 0, -1}}, counts);
    EXPECT_GT(c.r, 0.95);  // all but the paths cut at depth 6
    EXPECT_LE(c.r, 1.0 + 1e-12);
    EXPECT_GE(counts.refraction, 2u);
    EXPECT_GE(counts.reflection, 2u);
}

TEST(Refraction, PathologicalGlassStaysBounded) {
    // km = kt = 1 everywhere would make 2^max_depth rays; the branch budget keeps it finite.
    SceneDescription scene = glass_sphere(1.5, 200);
    scene.materials[0].km = dvec3(1.0);
    scene.spheres.push_back({{0, 0, -3}, 1.0, 0});
    World world(scene);
    RayCounts counts;
    trace(world, scene.render, {{0.1, 0.2, 5}, {0, 0, -1}}, counts);
    EXPECT_LE(counts.refraction, 4096u);
}

}  // namespace
}  // namespace tracer
