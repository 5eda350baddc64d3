// Solids (CSG) in the language: which blocks become solids and which stay shapes, the order and
// nesting of their parts, placement by their own steps and by groups, functions and loops
// making them, and their materials (a patterned one placed with its shape).
#include <gtest/gtest.h>

#include "lang/load_scene.h"
#include "scene/placement.h"

namespace tracer {
namespace {

const std::string kCamera = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n";

SceneDescription load_ok(const std::string& text) {
    LoadResult result = load_scene_text("/scenes/t.scn", kCamera + text, false, {}, {});
    for (const Diagnostic& d : result.diagnostics.all()) ADD_FAILURE() << d.message;
    EXPECT_TRUE(result.scene);
    return result.scene ? *result.scene : SceneDescription{};
}

TEST(Solids, AUnionOutsideEveryOtherSolidIsAGroup) {
    const SceneDescription scene = load_ok(
        "union { translate (1, 0, 0)\n"
        "  sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n"
        "  box { min (0, 0, 0) max (1, 1, 1) material { kd 1 } }\n"
        "}\n");
    EXPECT_TRUE(scene.solids.empty());
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.spheres[0].center, dvec3(1, 0, 0));
    EXPECT_EQ(scene.boxes.size(), 1u);
}

TEST(Solids, MergeIntersectionAndDifferenceAreSolidsWithTheirPartsInOrder) {
    const SceneDescription scene = load_ok(
        "material m { kd 1 }\n"
        "difference {\n"
        "  box { min (-1, -1, -1) max (1, 1, 1) material m }\n"
        "  union { sphere { center (0, 0, 0) radius 0.5 material m } cylinder { base (0, -2, 0) top (0, 2, 0) radius "
        "0.2 material m } }\n"
        "  plane { point (0, 0.8, 0) normal (0, -1, 0) material m }\n"
        "}\n"
        "merge { sphere { center (0, 0, 0) radius 1 material m } sphere { center (1, 0, 0) radius 1 material m } }\n"
        "intersection { sphere { center (0, 0, 0) radius 1 material m } cone { base (0, -1, 0) top (0, 1, 0) "
        "base_radius 1 material m } }\n");
    ASSERT_EQ(scene.solids.size(), 4u);
    const Solid& die = scene.solids[0];
    EXPECT_EQ(die.op, SolidOp::Difference);
    EXPECT_FALSE(die.nested);
    ASSERT_EQ(die.parts.size(), 3u);
    EXPECT_EQ(die.parts[0].kind, SolidPart::Kind::Box);
    EXPECT_EQ(die.parts[1].kind, SolidPart::Kind::Solid);
    EXPECT_EQ(die.parts[2].kind, SolidPart::Kind::HalfSpace);
    const Solid& inner = scene.solids[die.parts[1].index];
    EXPECT_EQ(inner.op, SolidOp::Union);  // nested: one solid, its inner faces gone
    EXPECT_TRUE(inner.nested);
    EXPECT_EQ(inner.parts.size(), 2u);
    EXPECT_EQ(scene.solids[2].op, SolidOp::Union);
    EXPECT_EQ(scene.solids[3].op, SolidOp::Intersection);
    EXPECT_EQ(scene.solid_spheres.size(), 4u);
    EXPECT_EQ(scene.solid_cones.size(), 2u);
    EXPECT_TRUE(scene.spheres.empty() && scene.boxes.empty() && scene.planes.empty() && scene.cones.empty());
}

TEST(Solids, PartsArePlacedByTheSolidAndTheGroupsAroundIt) {
    const SceneDescription scene = load_ok(
        "group { translate (0, 10, 0)\n"
        "  difference { scale 2  translate (1, 0, 0)\n"
        "    sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n"
        "    group { translate (0, 0, 1) sphere { center (0, 0, 0) radius 0.5 material { kd 1 } } }\n"
        "  }\n"
        "}\n");
    ASSERT_EQ(scene.solid_spheres.size(), 2u);
    EXPECT_EQ(scene.solid_spheres[0].center, dvec3(1, 10, 0));
    EXPECT_EQ(scene.solid_spheres[0].radius, 2);
    EXPECT_EQ(scene.solid_spheres[1].center, dvec3(1, 10, 2));
    EXPECT_EQ(scene.solid_spheres[1].radius, 1);
}

TEST(Solids, AMeshIsAPartPlacedByTheSolid) {
    const std::string cube = std::string(TRACER_SOURCE_DIR) + "/scenes/meshes/cube.obj";
    const SceneDescription scene = load_ok(
        "difference { translate (0, 1, 0)\n"
        "  mesh { file \"" +
        cube +
        "\" scale 2 shading flat material { kd 1 } }\n"
        "  sphere { center (0, 1, 0) radius 0.5 material { kd 1 } }\n"
        "}\n");
    EXPECT_TRUE(scene.meshes.empty());
    ASSERT_EQ(scene.solid_meshes.size(), 1u);
    ASSERT_EQ(scene.solids.size(), 1u);
    EXPECT_EQ(scene.solids[0].parts[0].kind, SolidPart::Kind::Mesh);
    EXPECT_EQ(scene.solids[0].parts[0].index, 0u);
    const Placement placed(scene.solid_meshes[0]);
    EXPECT_EQ(placed.point({1, 1, 1}), dvec3(2, 3, 2));
    EXPECT_TRUE(scene.solid_meshes[0].flat);
}

TEST(Solids, AShapeValueIsMadeWhereItsNameIsPlaced) {
    const SceneDescription scene = load_ok(
        "let r = 0.25\n"
        "let die = difference {\n"
        "  box { min (-1, -1, -1) max (1, 1, 1) material { kd 1 } }\n"
        "  sphere { center (0, 0, 1) radius r material { kd 0.1 } }\n"
        "}\n"
        "r = 0.5  # the value sees r as it was where it was written\n"
        "let lamp = group { translate (0, 5, 0) light { position (0, 0, 0) } }\n"
        "for i in 0..3 {\n"
        "  group { translate (3 * i, 0, 0)\n"
        "    die\n"
        "  }\n"
        "}\n"
        "lamp\n");
    ASSERT_EQ(scene.solids.size(), 3u);
    ASSERT_EQ(scene.solid_spheres.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(scene.solids[size_t(i)].op, SolidOp::Difference);
        EXPECT_EQ(scene.solid_spheres[size_t(i)].center, dvec3(3 * i, 0, 1));
        EXPECT_EQ(scene.solid_spheres[size_t(i)].radius, 0.25);
    }
    ASSERT_EQ(scene.lights.size(), 2u);  // kCamera's and the lamp
    EXPECT_EQ(scene.lights[1].position, dvec3(0, 5, 0));
}

TEST(Solids, FunctionsAndLoopsMakeSolids) {
    const SceneDescription scene = load_ok(
        "let ivory = material { kd 0.9 }\n"
        "fn die(x) {\n"
        "  difference { translate (x, 0, 0)\n"
        "    box { min (-1, -1, -1) max (1, 1, 1) material ivory }\n"
        "    for i in 0..3 { sphere { center (i - 1, 1.1, 0) radius 0.2 material ivory } }\n"
        "  }\n"
        "}\n"
        "for k in 0..4 { die(3 * k) }\n");
    ASSERT_EQ(scene.solids.size(), 4u);
    for (const Solid& solid : scene.solids) EXPECT_EQ(solid.parts.size(), 4u);
    EXPECT_EQ(scene.solid_spheres[3].center, dvec3(2, 1.1, 0));  // the second die's first pip
    EXPECT_EQ(scene.materials.size(), 1u);                       // one material, shared
}

TEST(Solids, APatternedPartKeepsItsPlacedPattern) {
    const SceneDescription scene = load_ok(
        "intersection { translate (5, 0, 0)\n"
        "  sphere { center (0, 0, 0) radius 1 material { kd checker { } } }\n"
        "  box { min (-1, -1, -1) max (1, 0, 1) material { kd 1 } }\n"
        "}\n");
    ASSERT_EQ(scene.solid_spheres.size(), 1u);
    const Material& material = scene.materials[size_t(scene.solid_spheres[0].material)];
    EXPECT_TRUE(material.patterned());
    EXPECT_EQ(material.to_object.offset, dvec3(-5, 0, 0));
}

}  // namespace
}  // namespace tracer
