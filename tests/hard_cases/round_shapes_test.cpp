// The hard cases' rules applied to cones, cylinders and discs (hard-cases.md's B2, C1 and A1
// criteria): rays spawned off them never meet them again where they cannot; closed ones leak no
// ray aimed from inside at their rims, sides and caps (aimed in float and in double, +-1 ulp);
// a thin cylinder far away is hit or missed as the exact geometry says.
#include <random>

#include "../common/nearest_surface.h"
#include "accel/world.h"
#include "hard_cases.h"
#include "render/spawn.h"

namespace tracer::hard_cases {
namespace {

using L = long double;
using LVec = glm::vec<3, L>;

struct RoundCase {
    const char* name;
    Cone cone;
};

// Closed cones (convex solids) of sizes 0.015 to 1000, one far from the origin.
std::vector<RoundCase> closed_cones() {
    return {{"cylinder", {{0, -1, 0}, {0, 1, 0}, 1, 1, true, 0}},
            {"small_cone", {{0, 0.083, 0.4}, {0.01, 0.1, 0.41}, 0.015, 0, true, 0}},
            {"large_frustum", {{-300, 200, 100}, {500, -900, 300}, 1000, 250, true, 0}},
            {"far_tilted_cylinder", {{1e4, -3e3, 2e3}, {1e4 + 1, -3e3 + 2, 2e3 - 0.5}, 0.5, 0.5, true, 0}}};
}

// B2 for round shapes: 5,000 hits on each closed cone and on a disc; from each, 50 rays into the
// outward half-space and 50 towards points outside it: none may meet the shape (a cone closed by
// its caps is convex; a disc is flat).
TEST(HardCases, RoundShapesRaysLeavingThemNeverMeetThemAgain) {
    std::vector<std::pair<std::string, SceneDescription>> scenes;
    for (const RoundCase& c : closed_cones()) {
        SceneDescription scene = empty_scene();
        scene.cones.push_back(c.cone);
        scenes.emplace_back(c.name, scene);
    }
    SceneDescription disc_scene = empty_scene();
    disc_scene.discs.push_back({{3e3, 1e3, -2e3}, glm::normalize(dvec3(1, 2, 3)), 40, 0});
    scenes.emplace_back("far_disc", disc_scene);
    for (const auto& [name, scene] : scenes) {
        const World world(scene);
        const dvec3 center =
            scene.cones.empty() ? scene.discs[0].center : 0.5 * (scene.cones[0].base + scene.cones[0].top);
        const double size = scene.cones.empty() ? scene.discs[0].radius
                                                : glm::length(scene.cones[0].top - scene.cones[0].base) +
                                                      std::max(scene.cones[0].base_radius, scene.cones[0].top_radius);
        std::mt19937 random(4);
        std::uniform_real_distribution<double> unit(-1, 1);
        int hits = 0, spawned = 0, rehits = 0, non_finite = 0;
        SearchCounts counts;
        while (hits < 5000) {
            const Vec3 origin = Vec3(center) + Real(4 * size) * random_direction(random);
            const Vec3 target = Vec3(center + size * dvec3(unit(random), unit(random), unit(random)));
            const Ray ray{origin, glm::normalize(target - origin)};
            const auto hit = nearest_surface(world, ray, kPrimaryRange, counts);
            if (!hit) continue;
            ++hits;
            // The side of the surface the ray came from (a disc is left on both sides).
            const Vec3 outward =
                glm::dot(hit->geometric_normal, ray.direction) < 0 ? hit->geometric_normal : -hit->geometric_normal;
            auto outside = [&](const Vec3& p) {
                return glm::dot(glm::dvec3(p) - glm::dvec3(hit->point), glm::dvec3(outward)) > 0;
            };
            for (int i = 0; i < 50; ++i) {
                Vec3 d = random_direction(random);
                if (glm::dot(glm::dvec3(d), glm::dvec3(outward)) < 0) d = -d;
                const Vec3 towards = hit->point + Real(size * (0.5 + unit(random) * 0.4)) * d;
                if (!outside(hit->point + d) || !outside(towards)) continue;
                const SpawnedRay leaving = spawn_ray(*hit, d);
                rehits += world.nearest_hit(leaving.ray, leaving.range, counts).has_value();
                const SpawnedRay to_point = spawn_ray_to(*hit, towards);
                rehits += world.occluded(to_point.ray, to_point.range, counts);
                non_finite += !std::isfinite(glm::dot(leaving.ray.origin, to_point.ray.direction));
                spawned += 2;
            }
        }
        report("round_" + name + "_spawned", spawned);
        report("round_" + name + "_rehits", rehits);
        EXPECT_EQ(rehits, 0) << name;
        EXPECT_EQ(non_finite, 0) << name;
    }
}

// A1's leak criterion for closed cones: from a point inside, rays aimed at 2,000 points of each
// rim, 2,000 of the side and 2,000 of each cap, each aimed three ways (float, double, double +-1
// ulp per component): every ray meets the surface, at the target's distance to 10^-4 and a few
// ulps of the coordinates (no leak, and no early hit).
TEST(HardCases, RoundShapesClosedConesLeakNoRay) {
    for (const RoundCase& c : closed_cones()) {
        SceneDescription scene = empty_scene();
        scene.cones.push_back(c.cone);
        const World world(scene);
        const dvec3 base = c.cone.base, top = c.cone.top;
        const dvec3 w = glm::normalize(top - base);
        const dvec3 u = glm::normalize(glm::cross(w, std::abs(w.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0)));
        const dvec3 v = glm::cross(w, u);
        const double height = glm::length(top - base);
        auto radius_at = [&](double h) { return c.cone.base_radius + (c.cone.top_radius - c.cone.base_radius) * h; };
        auto surface_point = [&](double h, double rho, double angle) {
            return base + h * height * w + rho * (std::cos(angle) * u + std::sin(angle) * v);
        };
        const Vec3 inside(surface_point(0.4, 0.3 * radius_at(0.4), 1.0));
        // The targets are rounded to Real: off the curved surface by up to half an ulp of their
        // coordinates (10^-3 at 10^4 in float), which the criterion allows for.
        const Real slack = 4 * ulp(Real(std::max({std::abs(base.x), std::abs(base.y), std::abs(base.z)})));
        std::mt19937 random(1);
        std::uniform_real_distribution<double> unit(0, 1);
        AimedTally tally;
        for (int kind = 0; kind < 5; ++kind) {
            for (int i = 0; i < 2000; ++i) {
                const double angle = 2 * M_PI * unit(random);
                const double h = kind == 0 ? 0 : kind == 1 ? 1 : kind == 2 ? unit(random) : kind == 3 ? 0 : 1;
                const double rho = kind <= 2 ? radius_at(h) : radius_at(h) * std::sqrt(unit(random));
                if (rho == 0 && kind <= 2 && h == 1 && c.cone.top_radius == 0) continue;
                tally.aim(world, inside, Vec3(surface_point(h, rho, angle)), slack);
            }
        }
        const std::string name = std::string("round_") + c.name;
        report(name + "_aimed_rays", tally.rays);
        report(name + "_leaks", tally.leaks);
        EXPECT_EQ(tally.leaks, 0) << c.name;
        EXPECT_EQ(tally.early, 0) << c.name;
        EXPECT_EQ(tally.non_finite, 0) << c.name;
    }
}

// C1 for cylinders: radius 0.01 seen from 10^4 away, radius 1 from 10^5, the axis across the
// view (10^5 rays each, seed 5, to random points of a box 2r wide around the axis): hit or miss
// as the exact distance of the ray's line from the axis says (outside a band of 10^-3 r), and t
// within a relative 10^-5 in float, 10^-12 in double, where the ray is well inside the outline.
TEST(HardCases, RoundShapesThinCylinderFarAwayIsHitExactly) {
    struct Case {
        const char* name;
        double radius, distance;
    };
    for (const Case& c : {Case{"round_thin_cylinder_1e4", 0.01, 1e4}, Case{"round_cylinder_1e5", 1, 1e5}}) {
        SceneDescription scene = empty_scene();
        scene.cones.push_back({{0, -50 * c.radius, 0}, {0, 50 * c.radius, 0}, c.radius, c.radius, false, 0});
        const World world(scene);
        std::mt19937 random(5);
        std::uniform_real_distribution<double> unit(-1, 1);
        int misclassified = 0, excluded = 0, hits = 0, t_off = 0;
        const Vec3 origin(0, 0, Real(c.distance));
        for (int i = 0; i < 100000; ++i) {
            const Vec3 target(Real(2 * c.radius * unit(random)), Real(20 * c.radius * unit(random)),
                              Real(2 * c.radius * unit(random)));
            const Ray ray{origin, glm::normalize(target - origin)};
            // The exact answer in long double: the ray's line against the y axis.
            const LVec o(ray.origin), d = glm::normalize(LVec(ray.direction));
            const L a = d.x * d.x + d.z * d.z, b = o.x * d.x + o.z * d.z, cc = o.x * o.x + o.z * o.z;
            const L across = std::abs(o.x * d.z - o.z * d.x) / std::sqrt(a);  // distance of the lines
            if (std::abs(across / L(c.radius) - 1) < 1e-3L) {
                ++excluded;
                continue;
            }
            const bool exact_hit = across < L(c.radius);
            SearchCounts counts;
            const auto hit = world.nearest_hit(ray, kPrimaryRange, counts);
            misclassified += hit.has_value() != exact_hit;
            if (!hit || !exact_hit) continue;
            ++hits;
            const L disc = b * b - a * (cc - L(c.radius) * L(c.radius));
            const L exact_t = (-b - std::sqrt(disc)) / a / glm::length(LVec(ray.direction));
            if (across < 0.9L * L(c.radius))
                t_off += std::abs(L(hit->t) - exact_t) > (std::is_same_v<Real, float> ? 1e-5L : 1e-12L) * exact_t;
        }
        report(std::string(c.name) + "_misclassified", misclassified);
        report(std::string(c.name) + "_excluded_near_outline", excluded);
        EXPECT_GT(hits, 20000) << c.name;
        EXPECT_EQ(misclassified, 0) << c.name;
        EXPECT_EQ(t_off, 0) << c.name;
    }
}

}  // namespace
}  // namespace tracer::hard_cases
