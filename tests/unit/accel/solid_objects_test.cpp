// Solids in the world (CSG) against brute force: random trees of spheres, placed boxes, cones,
// half-spaces and closed meshes (an L-shaped prism: two spans along some lines), nested up to
// three deep, and random rays from inside and outside. The
// expected hit is the first place along the ray where a point test of the whole tree (inside
// each leaf, combined by each operation's truth table) changes; the world must find that t, the
// leaf's material there, and a normal that points out of the solid.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "../../common/sweep.h"
#include "accel/solid_leaves.h"
#include "accel/world.h"
#include "render/spawn.h"
#include "scene/placement.h"

namespace tracer {
namespace {

using glm::dvec3;

// An L-shaped prism, z from 0 to 1, over the outline (0, 0) (2, 0) (2, 1) (1, 1) (1, 2) (0, 2):
// a closed mesh that is not convex. Its inside is that of two boxes together (l_arms).
TriangleMesh l_prism() {
    TriangleMesh mesh;
    const double outline[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    for (double z : {0.0, 1.0})
        for (const auto& p : outline) mesh.positions.push_back({p[0], p[1], z});
    for (uint32_t i = 1; i + 1 < 6; ++i) {  // the caps: fans from (0, 0), which sees every corner
        mesh.triangles.push_back({0, i + 1, i});
        mesh.triangles.push_back({6, 6 + i, 6 + i + 1});
    }
    for (uint32_t i = 0; i < 6; ++i) {  // the sides, facing out of the counter-clockwise outline
        const uint32_t j = (i + 1) % 6;
        mesh.triangles.push_back({i, j, 6 + j});
        mesh.triangles.push_back({i, 6 + j, 6 + i});
    }
    return mesh;
}
// The two boxes whose union is the L-shaped prism `mesh` (placed as it is).
std::array<Box, 2> l_arms(const Mesh& mesh) {
    std::array<Box, 2> arms;
    for (Box& arm : arms) static_cast<Placed&>(arm) = mesh;
    arms[0].min = arms[1].min = {0, 0, 0};
    arms[0].max = {2, 1, 1};
    arms[1].max = {1, 2, 1};
    return arms;
}

// A random scene of solids; each leaf its own material (its index), so a hit names its leaf.
struct RandomSolids {
    SceneDescription scene;
    std::mt19937 random;
    SceneMeshes meshes{{share_mesh(l_prism())}, {}, {}};
    std::uniform_real_distribution<double> unit{0, 1};

    double in(double low, double high) { return low + (high - low) * unit(random); }
    dvec3 point(double reach) { return {in(-reach, reach), in(-reach, reach), in(-reach, reach)}; }
    dvec3 direction() {
        for (;;) {
            const dvec3 d = point(1);
            if (glm::length(d) > 0.1 && glm::length(d) < 1) return glm::normalize(d);
        }
    }
    int material() {
        scene.materials.emplace_back();
        return int(scene.materials.size()) - 1;
    }

    SolidPart leaf() {
        const int kind = int(in(0, 5));
        if (kind == 4) {
            Mesh mesh;
            mesh.scale = dvec3(in(0.5, 1.1));
            mesh.rotate_axis = direction();
            mesh.rotate_degrees = in(0, 360);
            mesh.translate = point(1) - mesh.scale;  // around its corner (0, 0, 0)
            mesh.material = material();
            scene.solid_meshes.push_back(mesh);
            meshes.file_of_solid_mesh.push_back(0);
            return {SolidPart::Kind::Mesh, uint32_t(scene.solid_meshes.size() - 1)};
        }
        if (kind == 0) {
            scene.solid_spheres.push_back({point(1), in(0.3, 1.2), material()});
            return {SolidPart::Kind::Sphere, uint32_t(scene.solid_spheres.size() - 1)};
        }
        if (kind == 1) {
            Box box;
            box.min = point(1);
            box.max = box.min + dvec3(in(0.3, 1.5), in(0.3, 1.5), in(0.3, 1.5));
            box.scale = {in(0.5, 1.5), in(0.5, 1.5), in(0.5, 1.5)};
            box.rotate_axis = direction();
            box.rotate_degrees = in(0, 360);
            box.translate = point(0.5);
            box.material = material();
            scene.solid_boxes.push_back(box);
            return {SolidPart::Kind::Box, uint32_t(scene.solid_boxes.size() - 1)};
        }
        if (kind == 2) {
            Cone cone;
            cone.base = point(1);
            cone.top = cone.base + in(0.5, 2) * direction();
            cone.base_radius = in(0, 1) < 0.3 ? 0 : in(0.2, 0.8);
            cone.top_radius = in(0.2, 0.8);
            cone.material = material();
            scene.solid_cones.push_back(cone);
            return {SolidPart::Kind::Cone, uint32_t(scene.solid_cones.size() - 1)};
        }
        scene.half_spaces.push_back({point(0.8), direction(), material()});
        return {SolidPart::Kind::HalfSpace, uint32_t(scene.half_spaces.size() - 1)};
    }

    // A solid of 2 to 4 parts, a part nested (to `depth` more levels) one time in three.
    uint32_t solid(int depth, bool nested) {
        const uint32_t index = uint32_t(scene.solids.size());
        scene.solids.push_back({SolidOp(int(in(0, 3))), {}, nested, 0});
        const int parts = int(in(2, 5));
        for (int i = 0; i < parts; ++i) {
            const SolidPart part =
                depth > 0 && in(0, 1) < 0.33 ? SolidPart{SolidPart::Kind::Solid, solid(depth - 1, true)} : leaf();
            scene.solids[index].parts.push_back(part);
        }
        return index;
    }
};

// Brute force: the point tests of the leaves and of the tree.
struct Truth {
    const SceneDescription& scene;

    bool inside_leaf(const SolidPart& part, const dvec3& p) const {
        switch (part.kind) {
            case SolidPart::Kind::Sphere: {
                const Sphere& s = scene.solid_spheres[part.index];
                return glm::length(p - s.center) <= s.radius;
            }
            case SolidPart::Kind::Box: return inside_box(scene.solid_boxes[part.index], p);
            case SolidPart::Kind::Cone: {
                const Cone& cone = scene.solid_cones[part.index];
                const dvec3 axis = cone.top - cone.base;
                const double length = glm::length(axis);
                const double h = glm::dot(p - cone.base, axis / length);
                if (h < 0 || h > length) return false;
                const double radius = cone.base_radius + (cone.top_radius - cone.base_radius) * h / length;
                return glm::length(p - cone.base - h * axis / length) <= radius;
            }
            case SolidPart::Kind::HalfSpace: {
                const Plane& plane = scene.half_spaces[part.index];
                return glm::dot(p - plane.point, plane.normal) <= 0;
            }
            case SolidPart::Kind::Mesh: {
                for (const Box& arm : l_arms(scene.solid_meshes[part.index]))
                    if (inside_box(arm, p)) return true;
                return false;
            }
            case SolidPart::Kind::Solid: return inside(part.index, p);
        }
        return false;
    }

    static bool inside_box(const Box& box, const dvec3& p) {
        const Placement placement(box);
        const dvec3 own = glm::inverse(placement.linear) * (p - placement.translate);
        return glm::all(glm::greaterThanEqual(own, box.min)) && glm::all(glm::lessThanEqual(own, box.max));
    }

    bool inside(uint32_t solid, const dvec3& p) const {
        const Solid& s = scene.solids[solid];
        bool result = inside_leaf(s.parts[0], p);
        for (size_t i = 1; i < s.parts.size(); ++i) {
            const bool part = inside_leaf(s.parts[i], p);
            result = s.op == SolidOp::Union          ? result || part
                     : s.op == SolidOp::Intersection ? result && part
                                                     : result && !part;
        }
        return result;
    }
};

// Every t where the ray's line crosses a leaf's surface, with the leaf's material (and for a
// mesh, where it crosses its two boxes' faces: some are inside it, and change nothing).
void crossings(const SceneDescription& scene, const Ray& ray, std::vector<std::pair<double, int>>& out) {
    auto add = [&](const std::optional<SolidSpan>& span, int material) {
        if (!span) return;
        for (double t : {double(span->enter.t), double(span->leave.t)})
            if (std::isfinite(t)) out.push_back({t, material});
    };
    auto add_box = [&](const Box& box, int material) {
        const Placement placement(box);
        const glm::dmat3 to_object = glm::inverse(placement.linear);
        const Ray own{Vec3(to_object * (dvec3(ray.origin) - placement.translate)),
                      Vec3(to_object * dvec3(ray.direction))};
        add(box_span(own, Vec3(box.min), Vec3(box.max), 0), material);
    };
    for (const Sphere& s : scene.solid_spheres) add(sphere_span(ray, Vec3(s.center), Real(s.radius), 0), s.material);
    for (const Box& box : scene.solid_boxes) add_box(box, box.material);
    for (const Mesh& mesh : scene.solid_meshes)
        for (const Box& arm : l_arms(mesh)) add_box(arm, mesh.material);
    for (const Cone& c : scene.solid_cones)
        add(cone_span(ray, make_cone_shape(c.base, c.top, c.base_radius, c.top_radius, true), 0), c.material);
    for (const Plane& p : scene.half_spaces) add(half_space_span(ray, Vec3(p.point), Vec3(p.normal), 0), p.material);
    std::sort(out.begin(), out.end());
}

constexpr double kStep = 1e-6;  // either side of a crossing, for the point tests

// The expected hit along `ray`: the first crossing past kStep where the tree's inside changes,
// with its leaf's material; `ambiguous` if another crossing is too near it to tell.
std::optional<std::pair<double, int>> expected_hit(const SceneDescription& scene, const Truth& truth, const Ray& ray,
                                                   bool& ambiguous) {
    std::vector<std::pair<double, int>> ts;
    crossings(scene, ray, ts);
    ambiguous = false;
    for (size_t i = 0; i < ts.size(); ++i) {
        const double t = ts[i].first;
        if (t <= 4 * kStep) continue;
        const dvec3 o(ray.origin), d(ray.direction);
        if (truth.inside(0, o + (t - kStep) * d) == truth.inside(0, o + (t + kStep) * d)) continue;
        ambiguous =
            (i > 0 && t - ts[i - 1].first < 4 * kStep) || (i + 1 < ts.size() && ts[i + 1].first - t < 4 * kStep);
        return ts[i];
    }
    return std::nullopt;
}

TEST(SolidObjects, RandomTreesMatchPointTestsAlongEachRay) {
    if constexpr (!std::is_same_v<Real, double>) GTEST_SKIP() << "brute force in double only";
    int checked = 0, hits = 0, spawned = 0, mesh_hits = 0;
    const size_t scenes = sweep(150);
    for (uint32_t seed = 1; seed <= scenes; ++seed) {
        RandomSolids made{{}, std::mt19937(seed)};
        made.solid(2, false);
        const World world(made.scene, made.meshes);
        const Truth truth{made.scene};
        for (int r = 0; r < 200; ++r) {
            const Ray ray{Vec3(made.point(2.5)), Vec3(made.direction())};
            bool ambiguous = false;
            const auto expected = expected_hit(made.scene, truth, ray, ambiguous);
            if (ambiguous) continue;
            ++checked;
            SearchCounts counts;
            const auto hit = world.nearest_hit(ray, {0, kInfinity}, counts);
            ASSERT_EQ(hit.has_value(), expected.has_value()) << "seed " << seed << " ray " << r;
            if (!hit) continue;
            ++hits;
            EXPECT_NEAR(hit->t, expected->first, 1e-7) << "seed " << seed << " ray " << r;
            const SurfaceHit surface = world.surface(ray, *hit);
            EXPECT_EQ(surface.material, expected->second) << "seed " << seed << " ray " << r;
            for (const Mesh& mesh : made.scene.solid_meshes) mesh_hits += mesh.material == expected->second;
            // The normal points out of the solid.
            EXPECT_TRUE(truth.inside(0, dvec3(surface.point) - 1e-5 * dvec3(surface.normal)))
                << "seed " << seed << " ray " << r;
            EXPECT_FALSE(truth.inside(0, dvec3(surface.point) + 1e-5 * dvec3(surface.normal)))
                << "seed " << seed << " ray " << r;
            // A ray spawned off the hit, to either side, meets what brute force meets from there:
            // not the surface it leaves, and not past a surface it should meet.
            const dvec3 away = made.direction();
            const SpawnedRay next = spawn_ray(surface, Vec3(away));
            const auto next_expected = expected_hit(made.scene, truth, next.ray, ambiguous);
            if (ambiguous) continue;
            ++spawned;
            const auto next_hit = world.nearest_hit(next.ray, next.range, counts);
            ASSERT_EQ(next_hit.has_value(), next_expected.has_value()) << "seed " << seed << " spawned " << r;
            if (next_hit) {
                EXPECT_NEAR(next_hit->t, next_expected->first, 1e-7) << "seed " << seed << " spawned " << r;
            }
        }
    }
    EXPECT_GT(checked, int(scenes) * 150);
    EXPECT_GT(hits, checked / 8);
    EXPECT_GT(spawned, hits * 9 / 10);
    EXPECT_GT(mesh_hits, hits / 20);
}

}  // namespace
}  // namespace tracer

namespace tracer {
namespace {

// A solid of two axis boxes, `op`, in a scene of its own; each box its own material.
SceneDescription two_boxes(SolidOp op, const Box& a, const Box& b) {
    SceneDescription scene;
    scene.materials.resize(2);
    scene.solid_boxes = {a, b};
    scene.solid_boxes[0].material = 0;
    scene.solid_boxes[1].material = 1;
    scene.solids.push_back({op, {{SolidPart::Kind::Box, 0}, {SolidPart::Kind::Box, 1}}, false, 0});
    return scene;
}

Box axis_box(dvec3 min, dvec3 max) {
    Box box;
    box.min = min, box.max = max;
    return box;
}

// Rays straight down onto the plane y = 1 at a grid of points over the unit square's middle.
template <typename F>
void rays_down(F check) {
    for (int i = 0; i < 41; ++i)
        for (int k = 0; k < 41; ++k) check(Ray{Vec3(-0.8 + 0.04 * i, 3, -0.8 + 0.04 * k), Vec3(0, -1, 0)});
}

TEST(SolidObjects, ABoxMinusABoxSharingItsTopFaceIsOpenThere) {
    // No speckles: every ray through the shared face goes on to the floor of the cut, y = 0.
    const World world(
        two_boxes(SolidOp::Difference, axis_box({-1, -1, -1}, {1, 1, 1}), axis_box({-0.9, 0, -0.9}, {0.9, 1, 0.9})));
    int checked = 0;
    rays_down([&](const Ray& ray) {
        if (std::abs(ray.origin.x) >= 0.9 || std::abs(ray.origin.z) >= 0.9) return;
        SearchCounts counts;
        const auto hit = world.nearest_hit(ray, {0, kInfinity}, counts);
        ASSERT_TRUE(hit);
        EXPECT_NEAR(hit->t, 3, 1e-12);  // y = 0: the cutter's bottom face, turned
        const SurfaceHit surface = world.surface(ray, *hit);
        EXPECT_EQ(surface.material, 1);
        EXPECT_EQ(surface.normal, Vec3(0, 1, 0));
        ++checked;
    });
    EXPECT_GT(checked, 1000);
}

TEST(SolidObjects, CoincidentFacesTakeTheFirstPartsFaceOrNone) {
    // Two boxes stacked: a merge has no face between them; an intersection of two boxes sharing
    // the top face shows it as the first box's.
    const World merged(two_boxes(SolidOp::Union, axis_box({-1, -1, -1}, {1, 0, 1}), axis_box({-1, 0, -1}, {1, 1, 1})));
    const World overlap(
        two_boxes(SolidOp::Intersection, axis_box({-1, -1, -1}, {1, 1, 1}), axis_box({-2, 0, -2}, {2, 1, 2})));
    rays_down([&](const Ray& ray) {
        SearchCounts counts;
        const auto through = merged.nearest_hit(ray, {0, kInfinity}, counts);
        ASSERT_TRUE(through);
        EXPECT_NEAR(through->t, 2, 1e-12);  // the top, y = 1: nothing at y = 0 inside
        const auto inside = merged.nearest_hit(Ray{ray.at(2.5), ray.direction}, {0, kInfinity}, counts);
        ASSERT_TRUE(inside);
        EXPECT_NEAR(inside->t, 1.5, 1e-12);  // from y = 0.5 down, out at y = -1
        const auto top = overlap.nearest_hit(ray, {0, kInfinity}, counts);
        ASSERT_TRUE(top);
        EXPECT_NEAR(top->t, 2, 1e-12);
        EXPECT_EQ(overlap.surface(ray, *top).material, 0);
    });
}

TEST(SolidObjects, AShapeMinusItselfIsEmpty) {
    Box rotated = axis_box({-1, -1, -1}, {1, 1, 1});
    rotated.rotate_axis = glm::normalize(dvec3(1, 2, 3));
    rotated.rotate_degrees = 37;
    rotated.translate = {1e3, -2e3, 5e2};
    const World world(two_boxes(SolidOp::Difference, rotated, rotated));
    RandomSolids made{{}, std::mt19937(7)};
    for (int r = 0; r < 20000; ++r) {
        const Ray ray{Vec3(dvec3(1e3, -2e3, 5e2) + made.point(3)), Vec3(made.direction())};
        SearchCounts counts;
        EXPECT_FALSE(world.nearest_hit(ray, {0, kInfinity}, counts)) << r;
    }
}

}  // namespace
}  // namespace tracer

namespace tracer {
namespace {

// A caller that read no mesh files (the fuzz targets) still gets a world: a mesh part without
// its file is empty, and the solid is what the other parts make.
TEST(SolidObjects, AMeshPartWithoutItsFileIsEmpty) {
    SceneDescription scene;
    scene.materials.resize(1);
    scene.solid_meshes.emplace_back();
    scene.solid_spheres.push_back({{0, 0, 0}, 1, 0});
    scene.solids.push_back({SolidOp::Union, {{SolidPart::Kind::Mesh, 0}, {SolidPart::Kind::Sphere, 0}}, false, 0});
    const World world(scene);
    SearchCounts counts;
    const auto hit = world.nearest_hit({Vec3(0, 0, 5), Vec3(0, 0, -1)}, {0, kInfinity}, counts);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->t, 4, 1e-6);
    EXPECT_FALSE(world.nearest_hit({Vec3(3, 0, 5), Vec3(0, 0, -1)}, {0, kInfinity}, counts).has_value());
}

}  // namespace
}  // namespace tracer
