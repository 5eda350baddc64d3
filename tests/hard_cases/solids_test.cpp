// The hard cases' rules applied to solids (CSG, issue 55), at sizes 1e-4, 1 and 1e6 and at 1e6
// from the origin: rays aimed from inside at the edges where two parts meet (a lens's rim, a
// crater's rim in a box, also in a box made of 12 triangles, and that mesh's own edges and
// corners) leak through none of them, aimed in float and in double (+-1 ulp); rays
// spawned off a solid's surface never meet it again where they cannot (a lens is convex; a ray
// leaving a box's face outwards cannot meet what is cut out of the box), nor at once where they
// can (a ray crossing a crater meets its far side a chord away).
#include <random>

#include "../common/nearest_surface.h"
#include "accel/world.h"
#include "hard_cases.h"
#include "render/spawn.h"

namespace tracer::hard_cases {
namespace {

struct SolidCase {
    std::string name;
    double size;
    dvec3 offset;
};

std::vector<SolidCase> solid_cases() {
    return {
        {"tiny", 1e-4, {0, 0, 0}}, {"unit", 1, {0, 0, 0}}, {"huge", 1e6, {0, 0, 0}}, {"unit_far", 1, {1e6, -1e6, 1e6}}};
}

// A lens: two spheres of radius s, 1.2 s apart along z; its rim is the circle of radius 0.8 s
// in the plane z = 0 through the offset.
SceneDescription lens(const SolidCase& c) {
    SceneDescription scene = empty_scene();
    scene.solid_spheres = {{c.offset + dvec3(0, 0, 0.6 * c.size), c.size, 0},
                           {c.offset - dvec3(0, 0, 0.6 * c.size), c.size, 0}};
    scene.solids.push_back(
        {SolidOp::Intersection, {{SolidPart::Kind::Sphere, 0}, {SolidPart::Kind::Sphere, 1}}, false, 0});
    return scene;
}

// A box of side 2 s minus a sphere of radius s / 2 centred on its top face: its rim is the circle
// of radius s / 2 round the top face's centre.
SceneDescription cratered_box(const SolidCase& c) {
    SceneDescription scene = empty_scene();
    Box box;
    box.min = -dvec3(c.size);
    box.max = dvec3(c.size);
    box.translate = c.offset;
    scene.solid_boxes.push_back(box);
    scene.solid_spheres.push_back({c.offset + dvec3(0, c.size, 0), 0.5 * c.size, 0});
    scene.solids.push_back({SolidOp::Difference, {{SolidPart::Kind::Box, 0}, {SolidPart::Kind::Sphere, 0}}, false, 0});
    return scene;
}

// The same with the box a closed mesh of 12 triangles (two across each face).
struct SolidWorld {
    SceneDescription scene;
    SceneMeshes meshes;
};
SolidWorld cratered_mesh_box(const SolidCase& c) {
    SolidWorld out{cratered_box(c), {}};
    TriangleMesh cube;
    for (int i = 0; i < 8; ++i) cube.positions.push_back({i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1});
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces)
        cube.triangles.push_back({f[0], f[1], f[2]}), cube.triangles.push_back({f[0], f[2], f[3]});
    out.meshes.files.push_back(share_mesh(cube));
    out.meshes.file_of_solid_mesh = {0};
    Mesh mesh;
    mesh.scale = dvec3(c.size);
    mesh.translate = c.offset;
    out.scene.solid_meshes.push_back(mesh);
    out.scene.solid_boxes.clear();
    out.scene.solids[0].parts[0] = {SolidPart::Kind::Mesh, 0};
    return out;
}

enum class Kind { Lens, Crater, MeshCrater };
constexpr Kind kKinds[] = {Kind::Lens, Kind::Crater, Kind::MeshCrater};
const char* name_of(Kind kind) {
    return kind == Kind::Lens ? "lens_" : kind == Kind::Crater ? "crater_" : "mesh_crater_";
}
SolidWorld solid_world(Kind kind, const SolidCase& c) {
    if (kind == Kind::MeshCrater) return cratered_mesh_box(c);
    return {kind == Kind::Lens ? lens(c) : cratered_box(c), {}};
}

// A point on an edge of the cube of side 2 round the origin (or a face's diagonal, the edge
// between its two triangles), but the top face's diagonal, which the crater cuts.
dvec3 on_cube_edge(std::mt19937& random) {
    std::uniform_real_distribution<double> along(-1, 1);
    std::uniform_int_distribution<int> pick(0, 16);
    const int which = pick(random);
    const double s = along(random);
    if (which < 12) {  // an edge: two coordinates at +-1, the third along it
        const int axis = which / 4;
        dvec3 p;
        p[axis] = s;
        p[(axis + 1) % 3] = which & 1 ? 1 : -1;
        p[(axis + 2) % 3] = which & 2 ? 1 : -1;
        return p;
    }
    const int face = which - 12;  // a diagonal from the face's first corner to its third
    const dvec3 diagonals[5][2] = {{{-1, -1, -1}, {1, 1, -1}},
                                   {{-1, -1, 1}, {1, 1, 1}},
                                   {{-1, -1, -1}, {1, -1, 1}},
                                   {{-1, -1, -1}, {-1, 1, 1}},
                                   {{1, -1, -1}, {1, 1, 1}}};
    return diagonals[face][0] + (s + 1) / 2 * (diagonals[face][1] - diagonals[face][0]);
}

// A1's leak criterion at the rims: from a point inside, rays aimed at 2,000 points of the rim,
// each seven ways (aimed_rays): every ray meets the surface at the target's distance, to 10^-4
// and a few ulps of the coordinates.
TEST(HardCases, SolidsLeakNoRayAimedAtTheEdgesWherePartsMeet) {
    for (const SolidCase& c : solid_cases()) {
        for (const Kind kind : kKinds) {
            const bool crater = kind != Kind::Lens;
            const SolidWorld made = solid_world(kind, c);
            const World world(made.scene, made.meshes);
            const Real slack =
                4 * ulp(Real(std::max({std::abs(c.offset.x), std::abs(c.offset.y), std::abs(c.offset.z), c.size})));
            std::mt19937 random(2);
            std::uniform_real_distribution<double> unit(0, 2 * M_PI);
            AimedTally tally;
            for (int i = 0; i < 2000; ++i) {
                const double angle = unit(random);
                const dvec3 rim = crater ? dvec3(0.5 * std::cos(angle), 1, 0.5 * std::sin(angle))
                                         : dvec3(0.8 * std::cos(angle), 0.8 * std::sin(angle), 0);
                const Vec3 target(c.offset + c.size * rim);
                // Inside, and so placed that the line to the rim stays inside: a crater's rim is
                // its sphere's equator, reached from outside that sphere (from further out).
                const dvec3 from =
                    crater ? dvec3(0.9 * std::cos(angle), 0.5, 0.9 * std::sin(angle)) : dvec3(0.1, -0.2, 0.05);
                tally.aim(world, Vec3(c.offset + c.size * from), target, slack);
                if (kind == Kind::MeshCrater)  // and at the mesh's own edges and corners
                    tally.aim(world, Vec3(c.offset + c.size * dvec3(0.1, -0.2, 0.05)),
                              Vec3(c.offset + c.size * on_cube_edge(random)), slack);
            }
            const std::string name = "solid_" + std::string(name_of(kind)) + c.name;
            report(name + "_aimed_rays", tally.rays);
            report(name + "_leaks", tally.leaks);
            EXPECT_EQ(tally.leaks, 0) << name;
            EXPECT_EQ(tally.early, 0) << name;
            EXPECT_EQ(tally.non_finite, 0) << name;
        }
    }
}

// B2 for solids: 3,000 hits on each from outside; from each, 40 rays into the side the ray came
// from. Off the lens (convex) and off the box's own faces (the cut-out box lies within the box)
// none may meet the solid again; off the crater (concave) one may, but only across it: no
// sooner than a tenth of the crater's radius (rays within 60 degrees of its inward normal cross
// a chord of at least its radius, or leave by its mouth).
TEST(HardCases, SolidsRaysLeavingThemNeverMeetThemAgainWhereTheyCannot) {
    for (const SolidCase& c : solid_cases()) {
        for (const Kind kind : kKinds) {
            const bool crater = kind != Kind::Lens;
            const SolidWorld made = solid_world(kind, c);
            const World world(made.scene, made.meshes);
            std::mt19937 random(4);
            std::uniform_real_distribution<double> unit(-1, 1);
            int hits = 0, spawned = 0, rehits = 0;
            SearchCounts counts;
            for (int tries = 0; hits < 3000 && tries < 100000; ++tries) {
                const Vec3 origin = Vec3(c.offset) + Real(5 * c.size) * random_direction(random);
                const Vec3 target(c.offset + c.size * dvec3(unit(random), unit(random), unit(random)));
                const Ray ray{origin, glm::normalize(target - origin)};
                const auto hit = nearest_surface(world, ray, kPrimaryRange, counts);
                if (!hit) continue;
                ++hits;
                const Vec3 outward =
                    glm::dot(hit->geometric_normal, ray.direction) < 0 ? hit->geometric_normal : -hit->geometric_normal;
                // On the crater: the hit's distance from the sphere's centre is its radius (to the
                // point's error bound: 0.06 for a unit crater at 10^6 in float).
                const dvec3 from_crater = dvec3(hit->point) - (c.offset + dvec3(0, c.size, 0));
                const double error = 2 * std::max({hit->error.x, hit->error.y, hit->error.z});
                const bool on_crater =
                    crater && std::abs(glm::length(from_crater) - 0.5 * c.size) < 1e-3 * c.size + error;
                for (int i = 0; i < 40; ++i) {
                    Vec3 d = random_direction(random);
                    if (glm::dot(d, outward) < 0) d = -d;
                    if (on_crater && glm::dot(d, outward) < Real(0.5)) continue;  // within 60 degrees
                    const SpawnedRay leaving = spawn_ray(*hit, d);
                    const auto again = world.nearest_hit(leaving.ray, leaving.range, counts);
                    rehits += again && (!on_crater || again->t < 0.05 * c.size);
                    ++spawned;
                }
            }
            const std::string name = "solid_" + std::string(name_of(kind)) + c.name;
            report(name + "_spawned", spawned);
            report(name + "_rehits", rehits);
            EXPECT_EQ(hits, 3000) << name;
            EXPECT_EQ(rehits, 0) << name;
        }
    }
}

}  // namespace
}  // namespace tracer::hard_cases
