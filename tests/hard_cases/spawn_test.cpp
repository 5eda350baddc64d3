// Hard cases of secondary rays (hard-cases.md B1, B2, F1, and the random-triangle-soup
// spawn test): a ray spawned off a surface never meets that surface again where it cannot, at
// any scale and any distance from the origin.
#include <random>

#include "../common/nearest_surface.h"
#include "../common/sweep.h"
#include "accel/world.h"
#include "hard_cases.h"
#include "render/camera.h"
#include "render/spawn.h"
#include "render/whitted.h"

namespace tracer::hard_cases {
namespace {

// B2: spheres of radius 0.015 to 1000, one far from the origin. 10^4 primary hits each (seed
// 4); from each, 100 rays into the outward hemisphere and 100 towards points 2r..10r away on
// the outward side: none may meet the sphere (it is convex).
TEST(HardCases, B2_RaysLeavingASphereNeverMeetItAgain) {
    struct Case {
        const char* name;
        Vec3 center;
        Real radius;
    };
    const Case cases[] = {{"b2_sa", {0.0, 0.083, 0.4}, 0.015},
                          {"b2_sb", {0, 0, 0}, 1},
                          {"b2_sc", {0, 0, 0}, 1000},
                          {"b2_sd", {1e4, -3e3, 2e3}, 1}};
    for (const Case& c : cases) {
        SceneDescription scene = empty_scene();
        scene.spheres.push_back({c.center, c.radius, 0});
        const World world(scene);
        std::mt19937 random(4);
        std::uniform_real_distribution<double> unit(0, 1);
        int primary_hits = 0, spawned = 0, rehits = 0, non_finite = 0;
        SearchCounts counts;
        while (primary_hits < 10000) {
            const Vec3 origin = c.center + Real(10) * c.radius * random_direction(random);
            const Vec3 target =
                c.center + c.radius * (Real(2) * Vec3(unit(random), unit(random), unit(random)) - Real(1));
            const Ray ray{origin, glm::normalize(target - origin)};
            const auto hit = nearest_surface(world, ray, kPrimaryRange, counts);
            if (!hit) continue;
            ++primary_hits;
            const Vec3 outward = hit->geometric_normal;
            // On the outward side, decided in double (a target rounded to Real a few ulps below
            // the tangent plane is legitimately behind the sphere's surface).
            auto outside = [&](const Vec3& p) {
                return glm::dot(glm::dvec3(p) - glm::dvec3(hit->point), glm::dvec3(outward)) > 0;
            };
            for (int i = 0; i < 100; ++i) {
                Vec3 d = random_direction(random);
                if (glm::dot(glm::dvec3(d), glm::dvec3(outward)) < 0) d = -d;
                const Vec3 towards = hit->point + c.radius * Real(2 + 8 * unit(random)) * d;
                if (!outside(hit->point + d) || !outside(towards)) {
                    --i;
                    continue;
                }
                const SpawnedRay leaving = spawn_ray(*hit, d);
                rehits += world.nearest_hit(leaving.ray, leaving.range, counts).has_value();
                const SpawnedRay to_point = spawn_ray_to(*hit, towards);
                rehits += world.occluded(to_point.ray, to_point.range, counts);
                non_finite += !std::isfinite(glm::dot(leaving.ray.origin, to_point.ray.direction));
                spawned += 2;
            }
        }
        report(std::string(c.name) + "_spawned", spawned);
        report(std::string(c.name) + "_rehits", rehits);
        EXPECT_EQ(rehits, 0) << c.name;
        EXPECT_EQ(non_finite, 0) << c.name;
    }
}

// A soup of random triangles, each of a size drawn from 10^-4..10^4 and placed about as far
// from the origin as it is large; rays hit them, and from each hit 100 rays leave, half in
// random directions, half grazing the plane from either side: none may meet the triangle it
// left (10^7 rays). Once with the soup placed in the world, once as an
// instance (rotated and scaled: the point's error then includes placing it).
TEST(HardCases, SoupRaysLeavingATriangleNeverMeetItAgain) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0, 1);
    TriangleMesh soup;
    std::vector<Real> sizes;
    for (int i = 0; i < 2000; ++i) {
        const Real size = std::pow(10.0, -4 + 8 * unit(random));
        const Vec3 center = size * 10 * (Real(2) * Vec3(unit(random), unit(random), unit(random)) - Real(1));
        const uint32_t first = uint32_t(soup.positions.size());
        for (int k = 0; k < 3; ++k) soup.positions.push_back(center + size * random_direction(random));
        soup.triangles.push_back({first, first + 1, first + 2});
        sizes.push_back(size);
    }
    for (bool instanced : {false, true}) {
        SceneDescription scene = empty_scene();
        SceneMeshes meshes;
        meshes.files = {share_mesh(soup)};
        Mesh block;
        if (instanced) {
            block.scale = {1.5, 0.75, 1.25};
            block.rotate_axis = glm::normalize(dvec3(0.3, 1, -0.2));
            block.rotate_degrees = 37;
            block.translate = {3e-3, -20, 7};
        }
        // Two blocks name the file when instanced (one far away), one when placed.
        scene.meshes.push_back(block);
        meshes.file_of_block.push_back(0);
        if (instanced) {
            Mesh far = block;
            far.translate = {1e6, 0, 0};
            scene.meshes.push_back(far);
            meshes.file_of_block.push_back(0);
        }
        const World world(scene, meshes, 1);
        const Placement placement(block);
        int primary_hits = 0, spawned = 0, self_hits = 0;
        SearchCounts counts;
        while (primary_hits < int(sweep(50000))) {  // fewer under the sanitizers
            const size_t t = size_t(unit(random) * double(soup.triangles.size()));
            const auto& v = soup.triangles[t];
            double a = unit(random), b = unit(random);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const Vec3 target = Vec3(placement.point((1 - a - b) * soup.positions[v[0]] + a * soup.positions[v[1]] +
                                                     b * soup.positions[v[2]]));
            const Vec3 origin = target + Real(20) * sizes[t] * random_direction(random);
            const Ray ray{origin, glm::normalize(target - origin)};
            const auto hit = world.nearest_hit(ray, kPrimaryRange, counts);
            if (!hit) continue;
            ++primary_hits;
            const SurfaceHit surface = world.surface(ray, *hit);
            const Vec3 n = surface.geometric_normal;
            for (int i = 0; i < 100; ++i) {
                // Half in any direction, half grazing: at 10^-15..10^-1 radians off the plane.
                Vec3 d = random_direction(random);
                if (i % 2) {
                    const Vec3 along = glm::normalize(d - glm::dot(d, n) * n);
                    const Real angle = std::pow(10.0, -15 + 14 * unit(random));
                    d = glm::normalize(along + (i % 4 == 1 ? angle : -angle) * n);
                }
                const SpawnedRay leaving = spawn_ray(surface, d);
                const auto next = world.nearest_hit(leaving.ray, leaving.range, counts);
                self_hits += next && next->object == hit->object && next->primitive == hit->primitive;
                ++spawned;
            }
        }
        const std::string name = instanced ? "soup_instanced" : "soup_placed";
        report(name + "_spawned", spawned);
        report(name + "_self_hits", self_hits);
        EXPECT_EQ(self_hits, 0) << name;
    }
}

// B1: an infinite plane n.x = D tilted and far from the origin, lit by one light: no shading
// point is shadowed by the plane itself, and every pixel is the exact Lambert value within
// 1/255 (on >= 99.99% of the pixels).
TEST(HardCases, B1_TiltedPlaneFarFromTheOriginHasNoAcne) {
    const Vec3 n = glm::normalize(Vec3(0.3, 1, 0.2));
    for (Real d : {10.0, 1e3, 1e5}) {
        const Vec3 q = d * n;
        SceneDescription scene = empty_scene(0.8);
        scene.planes.push_back({q, n, 0});
        const Vec3 light = q + Real(20) * n + Vec3(-7, 2, 4);
        scene.lights.push_back({light, dvec3(1.0)});
        scene.camera.eye = q + Real(10) * n + Vec3(5, 0, 3);
        scene.camera.lookat = q;
        scene.camera.fovy_degrees = 90;
        scene.render.width = scene.render.height = 512;
        const World world(scene);
        const PinholeCamera camera(scene.camera, 512, 512);
        int hits = 0, self_occluded = 0, off = 0;
        SearchCounts search;
        RayCounts counts;
        for (int y = 0; y < 512; ++y)
            for (int x = 0; x < 512; ++x) {
                const Ray ray = camera.ray_through(x + 0.5, y + 0.5);
                const auto hit = nearest_surface(world, ray, kPrimaryRange, search);
                if (!hit) continue;
                ++hits;
                const SpawnedRay shadow = spawn_ray_to(*hit, light);
                self_occluded += world.occluded(shadow.ray, shadow.range, search);
                // The exact value, from the hit point worked out in long double.
                using L = glm::vec<3, long double>;
                const L o(ray.origin), dir(ray.direction), ln(n), lq(q);
                const L p = o + glm::dot(lq - o, ln) / glm::dot(dir, ln) * dir;
                const long double cosine = glm::dot(ln, glm::normalize(L(light) - p));
                const double exact = 0.8 * double(std::max(0.0L, cosine));
                off += std::abs(trace(world, scene.render, ray, counts).x - exact) > 1.0 / 255;
            }
        const std::string name = "b1_d" + std::to_string(int(std::log10(d)));
        report(name + "_self_occluded", self_occluded);
        report(name + "_pixels_off", off);
        EXPECT_GT(hits, 100000);
        EXPECT_EQ(self_occluded, 0) << name;
        EXPECT_LE(off, 512 * 512 / 10000) << name;
    }
}

// F1: two parallel mirrors z = 0 and z = 1 and a red sphere at (3.003, 0, 0.5). The oblique
// ray bounces exactly 291 times, alternating mirrors, each hit where it should be within
// 10^-3, then meets the sphere; the perpendicular one bounces until the depth limit.
TEST(HardCases, F1_ParallelMirrorsAlternateWithoutDrift) {
    SceneDescription scene = empty_scene(0, 0.9);
    Material red;
    red.kd = {1, 0, 0};
    scene.materials.push_back(red);
    scene.planes.push_back({{0, 0, 0}, {0, 0, 1}, 0});
    scene.planes.push_back({{0, 0, 1}, {0, 0, -1}, 0});
    scene.spheres.push_back({{3.003, 0, 0.5}, 0.1, 1});
    scene.lights.push_back({{0, 2, 0.5}, dvec3(1.0)});
    const World world(scene);
    const uint32_t sphere = 0, floor = 1, ceiling = 2;  // objects: spheres, then planes
    // Follows a ray through the mirrors: the objects it meets in order, and where.
    auto follow = [&](Ray ray, int max_bounces, std::vector<uint32_t>& objects, std::vector<Real>& xs) {
        Interval range = kPrimaryRange;
        SearchCounts counts;
        for (int bounce = 0; bounce <= max_bounces; ++bounce) {
            const auto hit = world.nearest_hit(ray, range, counts);
            if (!hit) return;
            const SurfaceHit s = world.surface(ray, *hit);
            objects.push_back(hit->object);
            xs.push_back(s.point.x);
            if (hit->object == sphere) return;
            const Vec3 normal = glm::dot(s.normal, ray.direction) > 0 ? -s.normal : s.normal;
            const SpawnedRay next = spawn_ray(s, ray.direction - 2 * glm::dot(ray.direction, normal) * normal);
            ray = next.ray;
            range = next.range;
        }
    };
    std::vector<uint32_t> objects;
    std::vector<Real> xs;
    follow({{0, 0, 0.5}, Vec3(glm::vec3(glm::normalize(glm::dvec3(0.01, 0, 1))))}, 1000, objects, xs);
    ASSERT_FALSE(objects.empty());
    const int mirror_hits = int(objects.size()) - 1;
    report("f1_mirror_reflections", mirror_hits);
    EXPECT_EQ(objects.back(), sphere);
    EXPECT_EQ(mirror_hits, 291);
    int same_mirror_twice = 0;
    Real worst_drift = 0;
    for (int k = 0; k < mirror_hits; ++k) {
        EXPECT_EQ(objects[size_t(k)], k % 2 == 0 ? ceiling : floor) << "hit " << k + 1;
        same_mirror_twice += k > 0 && objects[size_t(k)] == objects[size_t(k - 1)];
        const Real exact = 0.005 + 0.01 * k;
        worst_drift = std::max(worst_drift, std::abs(xs[size_t(k)] - exact) / exact);
    }
    report("f1_max_relative_drift", worst_drift);
    EXPECT_EQ(same_mirror_twice, 0);
    EXPECT_LE(worst_drift, 1e-3);

    // Straight up and down: bounces until the limit, without ever reaching the sphere.
    objects.clear();
    xs.clear();
    follow({{0, 0, 0.5}, {0, 0, 1}}, 1000, objects, xs);
    EXPECT_EQ(objects.size(), 1001u);
    EXPECT_EQ(std::count(objects.begin(), objects.end(), sphere), 0);

    // The renderer: a depth of 10^5 finishes (the recursion is a loop) at the bound on the rays
    // one camera ray spawns, and the rays traced grow at most linearly with the depth.
    RenderSettings settings = scene.render;
    RayCounts deep, eight, sixty_four;
    settings.max_depth = 100000;
    const Color c = trace(world, settings, {{0, 0, 0.5}, {0, 0, 1}}, deep);
    EXPECT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    EXPECT_EQ(deep.reflection, uint64_t(kMostRaysPerTree));
    EXPECT_EQ(deep.trees_cut, 1u);
    const PinholeCamera camera({{0, 0, 0.5}, {1, 0, 0.3}, {0, 0, 1}, 45, 1}, 64, 64);
    for (auto [depth, counts] : {std::pair{8, &eight}, std::pair{64, &sixty_four}}) {
        settings.max_depth = depth;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const Color pixel = trace(world, settings, camera.ray_through(x + 0.5, y + 0.5), *counts);
                EXPECT_TRUE(std::isfinite(pixel.x) && std::isfinite(pixel.y) && std::isfinite(pixel.z));
            }
    }
    EXPECT_LE(double(sixty_four.total()), 1.5 * 8 * double(eight.total()));
}

}  // namespace
}  // namespace tracer::hard_cases
