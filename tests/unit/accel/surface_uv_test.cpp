// Surface coordinates (u, v) of every kind of shape at known points (World::surface_uv, as
// docs/guide/patterns.md draws them), through the language's placements, groups and mirrors.
#include <gtest/gtest.h>

#include <string>

#include "../../common/nearest_surface.h"
#include "accel/world.h"
#include "io/obj_mesh.h"
#include "lang/load_scene.h"

namespace tracer {
namespace {

// The (u, v) where a ray from `from` towards `to` first meets the one shape of `shape_text`
// (its material maps a pattern by uv, so that meshes keep theirs).
glm::dvec2 uv_at(const std::string& shape_text, const glm::dvec3& from, const glm::dvec3& to) {
    const std::string text = "let m = material { kd checker { mapping uv } }\n" + shape_text + "\n";
    LoadResult loaded = load_scene_text("uv.scn", text, true);
    EXPECT_TRUE(loaded.scene) << text;
    if (!loaded.scene) return {-1, -1};
    Diagnostics diagnostics;
    const auto meshes = load_meshes(*loaded.scene, diagnostics);
    EXPECT_TRUE(meshes);
    const World world(*loaded.scene, meshes ? *meshes : SceneMeshes{});
    SearchCounts counts;
    const Ray ray{Vec3(from), Vec3(glm::normalize(to - from))};
    const auto hit = world.nearest_hit(ray, {0, kInfinity}, counts);
    EXPECT_TRUE(hit) << text;
    if (!hit) return {-1, -1};
    const SurfaceHit surface = world.surface(ray, *hit);
    const Material& material = world.materials()[size_t(surface.material)];
    return world.surface_uv(*hit, surface, material.to_object.linear);
}

void expect_uv(const glm::dvec2& uv, double u, double v, const std::string& what) {
    EXPECT_NEAR(uv.x, u, 1e-6) << what;
    EXPECT_NEAR(uv.y, v, 1e-6) << what;
}

TEST(SurfaceUv, SphereLongitudeAndLatitudeInItsOwnAxes) {
    const std::string sphere = "sphere { center (0, 0, 0) radius 1 material m }";
    expect_uv(uv_at(sphere, {0, 0, 5}, {0, 0, 0}), 0.5, 0.5, "front");
    EXPECT_NEAR(uv_at(sphere, {5, 0, 0}, {0, 0, 0}).x, 0.75, 1e-6);
    EXPECT_NEAR(uv_at(sphere, {0, 5, 0}, {0, 0, 0}).y, 1.0, 1e-6);
    // Turned a quarter about y: its own +z now faces +x.
    const std::string turned = "sphere { center (0, 0, 0) radius 1 rotate { axis (0, 1, 0) angle 90 } material m }";
    expect_uv(uv_at(turned, {5, 0, 0}, {0, 0, 0}), 0.5, 0.5, "turned");
    // Moved and scaled by a group: measured around its own center still.
    const std::string grouped = "group { scale 2 translate (3, 0, 0) sphere { center (1, 0, 0) radius 1 material m } }";
    expect_uv(uv_at(grouped, {5, 0, 9}, {5, 0, 0}), 0.5, 0.5, "grouped");
}

TEST(SurfaceUv, QuadTriangleAndTheirMirrors) {
    const std::string quad = "quad { corner (0, 0, 0) edge1 (2, 0, 0) edge2 (0, 1, 0) material m }";
    expect_uv(uv_at(quad, {0.5, 0.25, 5}, {0.5, 0.25, 0}), 0.25, 0.25, "quad");
    expect_uv(uv_at(quad, {1.5, 0.9, -5}, {1.5, 0.9, 0}), 0.75, 0.9, "quad from behind");
    // Mirrored in x: the corners' order is swapped inside the mesh, (u, v) stay with the corners.
    const std::string mirrored =
        "quad { corner (0, 0, 0) edge1 (2, 0, 0) edge2 (0, 1, 0) scale (-1, 1, 1) material m }";
    expect_uv(uv_at(mirrored, {-0.5, 0.25, 5}, {-0.5, 0.25, 0}), 0.25, 0.25, "mirrored quad");
    const std::string triangle = "triangle { a (0, 0, 0) b (1, 0, 0) c (0, 1, 0) material m }";
    expect_uv(uv_at(triangle, {0.2, 0.3, 5}, {0.2, 0.3, 0}), 0.2, 0.3, "triangle");
}

TEST(SurfaceUv, BoxFacesSeenFromOutside) {
    const std::string box = "box { min (0, 0, 0) max (1, 1, 1) material m }";
    expect_uv(uv_at(box, {0.2, 0.7, 5}, {0.2, 0.7, 1}), 0.2, 0.7, "+z");
    expect_uv(uv_at(box, {0.2, 0.7, -5}, {0.2, 0.7, 0}), 0.8, 0.7, "-z");
    expect_uv(uv_at(box, {5, 0.7, 0.2}, {1, 0.7, 0.2}), 0.8, 0.7, "+x");
    expect_uv(uv_at(box, {-5, 0.7, 0.2}, {0, 0.7, 0.2}), 0.2, 0.7, "-x");
    expect_uv(uv_at(box, {0.2, 5, 0.3}, {0.2, 1, 0.3}), 0.2, 0.7, "+y");
    expect_uv(uv_at(box, {0.2, -5, 0.3}, {0.2, 0, 0.3}), 0.2, 0.3, "-y");
    // Stretched: still 0..1 across each face.
    const std::string long_box = "box { min (-2, 0, 0) max (2, 1, 1) material m }";
    expect_uv(uv_at(long_box, {1, 0.5, 5}, {1, 0.5, 1}), 0.75, 0.5, "stretched +z");
}

TEST(SurfaceUv, DiscAndPlaneAroundTheirNormals) {
    const std::string disc = "disc { center (0, 0, 0) normal (0, 1, 0) radius 2 material m }";
    expect_uv(uv_at(disc, {1, 5, -1}, {1, 0, -1}), 0.75, 0.75, "disc");
    // Facing +z: y takes the place of -z (the shortest turn from y to z is about x).
    const std::string upright = "disc { center (0, 0, 0) normal (0, 0, 1) radius 2 material m }";
    expect_uv(uv_at(upright, {1, 1, 5}, {1, 1, 0}), 0.75, 0.75, "upright disc");
    const std::string plane = "plane { point (0, -1, 0) normal (0, 1, 0) material m }";
    expect_uv(uv_at(plane, {3, 5, -2}, {3, -1, -2}), 3, 2, "plane");
    const std::string moved = "group { translate (1, 0, 0) plane { point (0, -1, 0) normal (0, 1, 0) material m } }";
    expect_uv(uv_at(moved, {3, 5, -2}, {3, -1, -2}), 2, 2, "moved plane");
}

TEST(SurfaceUv, CylinderAndConeSidesAndCaps) {
    const std::string cylinder = "cylinder { base (0, 0, 0) top (0, 2, 0) radius 1 material m }";
    expect_uv(uv_at(cylinder, {0, 1, 5}, {0, 1, 0}), 0.5, 0.5, "side");
    expect_uv(uv_at(cylinder, {5, 1.5, 0}, {0, 1.5, 0}), 0.75, 0.75, "side, east");
    expect_uv(uv_at(cylinder, {0.5, 5, 0}, {0.5, 2, 0}), 0.75, 0.5, "top cap");
    expect_uv(uv_at(cylinder, {0, -5, -0.5}, {0, 0, -0.5}), 0.5, 0.75, "base cap");
    const std::string cone = "cone { base (0, 0, 0) top (0, 2, 0) base_radius 1 top_radius 0.5 material m }";
    expect_uv(uv_at(cone, {0.25, 5, 0}, {0.25, 2, 0}), 0.75, 0.5, "narrow top cap");
    expect_uv(uv_at(cone, {0.5, -5, 0}, {0.5, 0, 0}), 0.75, 0.5, "wide base cap");
}

TEST(SurfaceUv, MeshWithoutCoordinatesGivesZero) {
    const std::string mesh = "mesh { file \"" TRACER_SOURCE_DIR "/scenes/meshes/tetrahedron.obj\" material m }";
    const glm::dvec2 uv = uv_at(mesh, {0.05, 0.05, 5}, {0.05, 0.05, 0});
    EXPECT_EQ(uv, glm::dvec2(0, 0));
}

}  // namespace
}  // namespace tracer
