// A1's leak rule for instances (issue 34): the bunny named by two mesh blocks is built once in its
// own coordinates and rays are carried there by each block's placement. At every scale the
// validator accepts (1e-20 to 1e20), mirrored and far from the origin, rays from a point inside
// it aimed at every vertex and edge midpoint (three ways each) must find the surface, as they do
// when the same block alone is placed directly (in the float build: never leak more than it).
// (Where they disagree on t, a few rays in a thousand in double, a ray through a vertex met a
// different one of the triangles around it: reported.)
#include <algorithm>
#include <cstdio>
#include <set>
#include <type_traits>
#include <utility>

#include "../common/sweep.h"
#include "accel/world.h"
#include "hard_cases.h"
#include "render/spawn.h"

namespace tracer::hard_cases {
namespace {

struct Variant {
    std::string name;
    dvec3 scale;
    dvec3 translate;
};

SceneDescription bunny_blocks(const Variant& v, bool shared) {
    SceneDescription scene;
    scene.materials.resize(1);
    Mesh block;
    block.path = "bunny.obj";
    block.scale = v.scale;
    block.translate = v.translate;
    scene.meshes.push_back(block);
    if (shared) {  // a second block of the same file, far off: the file becomes an instance
        Mesh other = block;
        other.translate = v.translate + dvec3(0, 0, -1e3 * std::abs(v.scale.x));
        scene.meshes.push_back(other);
    }
    return scene;
}

TEST(HardCases, InstancesAtEveryScaleLeakNoRay) {
    const TriangleMesh bunny = load_obj("scenes/meshes/bunny.obj");
    // The targets: every vertex, and every edge's midpoint (each edge once).
    std::vector<dvec3> targets(bunny.positions.begin(), bunny.positions.end());
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const auto& t : bunny.triangles)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    for (const auto& [a, b] : edges) targets.push_back(0.5 * (bunny.positions[a] + bunny.positions[b]));
    thin_to_sweep(targets);                    // fewer under the sanitizers
    const dvec3 inside(-0.587, 3.825, 0.624);  // A1's interior point

    std::vector<Variant> variants;
    for (double s : {1e-20, 1e-10, 1e-3, 1.0, 1e3, 1e11, 1e14, 1e20}) {
        char text[16];
        std::snprintf(text, sizeof text, "%g", s);
        variants.push_back({std::string("scale ") + text, dvec3(s), dvec3(0)});
        variants.push_back({std::string("mirrored ") + text, dvec3(-s, s, s), dvec3(0)});
        variants.push_back({std::string("far ") + text, dvec3(s), dvec3(1e6 * s, -2e6 * s, 3e5 * s)});
    }
    for (const Variant& v : variants) {
        SceneMeshes meshes_shared{{share_mesh(bunny)}, {0, 0}}, meshes_placed{{share_mesh(bunny)}, {0}};
        const World shared(bunny_blocks(v, true), meshes_shared, 1), placed(bunny_blocks(v, false), meshes_placed, 1);
        ASSERT_FALSE(shared.instances()[0].placed) << v.name;
        ASSERT_TRUE(placed.instances()[0].placed) << v.name;
        const Placement placement(bunny_blocks(v, false).meshes[0]);
        const Vec3 origin(placement.point(inside));
        int rays = 0, leaks_shared = 0, leaks_placed = 0, t_apart = 0;
        for (const dvec3& target_local : targets) {
            const Vec3 target(placement.point(target_local));
            for (const AimedRay& aimed : aimed_rays(origin, target)) {
                ++rays;
                SearchCounts counts;
                const auto a = shared.nearest_hit(aimed.ray, kPrimaryRange, counts);
                const auto b = placed.nearest_hit(aimed.ray, kPrimaryRange, counts);
                const Real distance = glm::length(target - origin);
                // A1's leak: no hit, or an entering face beyond the target (a ray touching a fold
                // vertex from inside legitimately goes on inside).
                auto leak = [&](const World& world, const std::optional<Hit>& hit) {
                    if (!hit) return true;
                    const SurfaceHit surface = world.surface(aimed.ray, *hit);
                    return glm::dot(surface.geometric_normal, aimed.ray.direction) < 0 &&
                           hit->t > distance * (1 + 1e-4);
                };
                leaks_shared += leak(shared, a);
                leaks_placed += leak(placed, b);
                t_apart += a && b && std::abs(a->t - b->t) > 1e-4 * distance;
            }
        }
        std::printf("  %-16s %d rays: leaks instanced %d, placed %d; t apart %d\n", v.name.c_str(), rays, leaks_shared,
                    leaks_placed, t_apart);
        // An instance never leaks more than the same block placed directly. In double neither
        // leaks; float's own range ends far sooner (its scale test stops at 1e-4 and 1e4:
        // docs/robustness.md), and there the placed mesh leaks first.
        EXPECT_LE(leaks_shared, leaks_placed) << v.name << " (" << rays << " rays)";
        if constexpr (std::is_same_v<Real, double>) {
            EXPECT_EQ(leaks_shared, 0) << v.name << " (" << rays << " rays)";
            EXPECT_EQ(leaks_placed, 0) << v.name;
        }
    }
}

}  // namespace
}  // namespace tracer::hard_cases
