// The apex of a pointed cone (hostile inputs, fourth round): rays aimed at it from around it,
// at every scale and offset the hard cases use, aimed three ways (float, double, double +-1
// ulp per component). A ray whose direction lies inside the cone's angle enters the cone at the
// apex; one outside it only touches the apex, and meets the cone nowhere else.
#include <limits>
#include <random>

#include "../common/nearest_surface.h"
#include "accel/world.h"
#include "hard_cases.h"
#include "render/spawn.h"

namespace tracer::hard_cases {
namespace {

using dvec3 = glm::dvec3;

// A closed cone, radius 0.7 size at its base, its apex `size` away along a tilted axis, the
// base at `offset` (1, 0.6, -0.3).
Cone pointed_cone(double size, double offset) {
    const dvec3 base = offset * dvec3(1, 0.6, -0.3);
    const dvec3 axis = glm::normalize(dvec3(0.3, 1, -0.5));
    return {base, base + size * axis, 0.7 * size, 0, true, 0};
}

}  // namespace

// Cones of sizes 10^-4 to 100 at the origin and at 10^3 and 10^6 (each one the Real type can
// hold: at least 2^10 ulps of its coordinates across); 400 origins 3 sizes from the apex (seed
// 9), half within 0.9 of the cone's half-angle around its axis beyond the apex, half between
// 1.1 of it and the plane across the axis. Entering rays meet the cone first at the apex, on a
// face turned towards them: to a relative 64 epsilon of the distance when aimed in Real, 10^-5
// (and 8 ulps of the coordinates) when aimed in float; touching rays meet it nowhere but there.
// The exit is at least a third farther away.
TEST(HardCases, ConeApexRaysEnterAtTheApexAndNowhereElse) {
    const double half_angle = std::atan(0.7);
    int rays = 0, wrong = 0, facing_away = 0, skipped = 0, touching_hits = 0;
    double worst_float_aimed = 0, worst_double_aimed = 0;  // |t - distance| / distance, entering
    for (double size : {1e-4, 1e-2, 1.0, 100.0}) {
        for (double offset : {0.0, 1e3, 1e6}) {
            if (size < 1024 * ulp(Real(offset))) {
                ++skipped;
                continue;
            }
            SceneDescription scene = empty_scene();
            scene.cones.push_back(pointed_cone(size, offset));
            const World world(scene);
            const Vec3 apex(scene.cones[0].top);  // the tip, as the world keeps it
            const dvec3 w = glm::normalize(scene.cones[0].top - scene.cones[0].base);
            const dvec3 u = glm::normalize(glm::cross(w, dvec3(1, 0, 0))), v = glm::cross(w, u);
            const Real slack = 8 * ulp(std::max({std::abs(apex.x), std::abs(apex.y), std::abs(apex.z)}));
            std::mt19937 random(9);
            std::uniform_real_distribution<double> unit(0, 1);
            int case_wrong = 0;
            for (int i = 0; i < 400; ++i) {
                const bool entering = i % 2 == 0;
                const double theta = entering ? 0.9 * half_angle * unit(random)
                                              : 1.1 * half_angle + (M_PI / 2 - 1.1 * half_angle) * unit(random);
                const double phi = 2 * M_PI * unit(random);
                const dvec3 away = std::cos(theta) * w + std::sin(theta) * (std::cos(phi) * u + std::sin(phi) * v);
                const Vec3 origin(dvec3(apex) + 3 * size * away);
                const Real distance = glm::length(apex - origin);
                for (const AimedRay& aimed : aimed_rays(origin, apex)) {
                    ++rays;
                    SearchCounts counts;
                    const auto hit = nearest_surface(world, aimed.ray, kPrimaryRange, counts);
                    // Aimed in float, the ray passes up to 10^-7 of the distance off the apex and
                    // enters near it; aimed in Real, it meets the apex itself.
                    const Real tolerance = aimed.way[0] == 'f' ? Real(1e-5) * distance + slack
                                                               : 64 * std::numeric_limits<Real>::epsilon() * distance;
                    const bool at_apex = hit && std::abs(hit->t - distance) <= tolerance;
                    if (entering) {
                        case_wrong += !at_apex;
                        if (hit) {
                            double& worst = aimed.way[0] == 'f' ? worst_float_aimed : worst_double_aimed;
                            worst = std::max(worst, double(std::abs(hit->t - distance) / distance));
                        }
                        facing_away += at_apex && glm::dot(hit->geometric_normal, aimed.ray.direction) >= 0;
                    } else {
                        case_wrong += hit && !at_apex;
                        touching_hits += at_apex;
                    }
                }
            }
            EXPECT_EQ(case_wrong, 0) << "size " << size << " at " << offset;
            wrong += case_wrong;
        }
    }
    report("cone_apex_rays", rays);
    report("cone_apex_wrong", wrong);
    report("cone_apex_facing_away", facing_away);
    report("cone_apex_touching_rays_hit_at_apex", touching_hits);
    report("cone_apex_cases_skipped", skipped);
    report("cone_apex_worst_t_error_float_aimed", worst_float_aimed);
    report("cone_apex_worst_t_error_double_aimed", worst_double_aimed);
    EXPECT_EQ(facing_away, 0);
}

}  // namespace tracer::hard_cases
