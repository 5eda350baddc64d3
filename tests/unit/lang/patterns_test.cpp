// Patterns in the language: written inline or named by `let`, nested, with their keys' defaults
// and steps, shared between materials, and carried with their shapes by a copy of the material
// per placement (scene/pattern.h), through load_scene_text as tracer does.
#include <gtest/gtest.h>

#include "lang/load_scene.h"

namespace tracer {
namespace {

const std::string kCamera = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n";

SceneDescription load_ok(const std::string& text) {
    LoadResult result = load_scene_text("/scenes/t.scn", kCamera + text, false, {}, {});
    std::string messages;
    for (const Diagnostic& d : result.diagnostics.all()) messages += d.message + "\n";
    EXPECT_TRUE(result.scene) << text << "\n" << messages;
    return result.scene ? *result.scene : SceneDescription{};
}

TEST(Patterns, InlinePatternKeysAndDefaults) {
    const SceneDescription scene =
        load_ok("sphere { center (0, 0, 0) radius 1 material { ka 0.1 kd checker { odd (1, 0, 0) scale 0.5 } } }\n");
    ASSERT_EQ(scene.patterns.size(), 1u);
    const Pattern& checker = scene.patterns[0];
    EXPECT_EQ(checker.kind, PatternKind::Checker);
    EXPECT_EQ(checker.mapping, Mapping::Solid);
    EXPECT_EQ(checker.even.color, glm::dvec3(1));  // the default
    EXPECT_EQ(checker.odd.color, glm::dvec3(1, 0, 0));
    EXPECT_EQ(checker.to_pattern.linear, glm::dmat3(2.0));  // the inverse of scale 0.5
    const Material& material = scene.materials[size_t(scene.spheres[0].material)];
    EXPECT_EQ(material.kd_pattern, 0);
    EXPECT_EQ(material.ka_pattern, -1);
    EXPECT_EQ(material.ka, glm::dvec3(0.1));
}

TEST(Patterns, MapPatternsTakeTheirColourMapAndAxis) {
    const SceneDescription scene = load_ok(
        "sphere { center (0, 0, 0) radius 1 material { kd gradient { colors [[0, (1, 0, 0)], [0.5, 1]] "
        "axis (0, 0, 2) translate (0, 0, 1) } } }\n"
        "sphere { center (0, 0, 0) radius 1 material { kd marble { } } }\n");
    ASSERT_EQ(scene.patterns.size(), 2u);
    const Pattern& gradient = scene.patterns[0];
    ASSERT_EQ(gradient.colors.size(), 2u);
    EXPECT_EQ(gradient.colors[1].at, 0.5);
    EXPECT_EQ(gradient.colors[1].color, glm::dvec3(1));
    EXPECT_EQ(gradient.axis, glm::dvec3(0, 0, 1));  // made unit
    EXPECT_EQ(gradient.to_pattern.offset, glm::dvec3(0, 0, -1));
    const Pattern& marble = scene.patterns[1];
    EXPECT_EQ(marble.colors.size(), 3u);  // the default map
    EXPECT_EQ(marble.turbulence, 1);
    EXPECT_EQ(marble.octaves, 6);
}

TEST(Patterns, ALetValueIsBuiltOnceAndNests) {
    const SceneDescription scene = load_ok(
        "let inner = stripes { }\n"
        "let floor = checker { even inner odd wood { } }\n"
        "material a { kd floor }\n"
        "material b { ka floor kd 0.5 }\n"
        "sphere { center (0, 0, 0) radius 1 material a }\n"
        "sphere { center (0, 0, 0) radius 1 material b }\n");
    // floor, inner and the wood: three patterns for two materials.
    ASSERT_EQ(scene.patterns.size(), 3u);
    const Material& a = scene.materials[size_t(scene.spheres[0].material)];
    const Material& b = scene.materials[size_t(scene.spheres[1].material)];
    EXPECT_EQ(a.kd_pattern, b.ka_pattern);
    const Pattern& floor = scene.patterns[size_t(a.kd_pattern)];
    ASSERT_TRUE(floor.even.patterned());
    ASSERT_TRUE(floor.odd.patterned());
    EXPECT_EQ(scene.patterns[size_t(floor.even.pattern)].kind, PatternKind::Stripes);
    EXPECT_EQ(scene.patterns[size_t(floor.odd.pattern)].kind, PatternKind::Wood);
}

TEST(Patterns, APlacedShapeGetsACopyOfItsPatternedMaterial) {
    const SceneDescription scene = load_ok(
        "let m = material { kd checker { } }\n"
        "sphere { center (0, 0, 0) radius 1 material m }\n"
        "sphere { center (0, 0, 0) radius 1 translate (2, 0, 0) material m }\n"
        "sphere { center (0, 0, 0) radius 1 translate (2, 0, 0) material m }\n"
        "group { scale 2 quad { corner (0, 0, 0) edge1 (1, 0, 0) edge2 (0, 1, 0) material m } }\n"
        "sphere { center (0, 0, 0) radius 1 translate (2, 0, 0) material { kd 1 } }\n");
    const int plain = scene.spheres[0].material;
    EXPECT_EQ(scene.materials[size_t(plain)].to_object, Affine{});
    const int moved = scene.spheres[1].material;
    EXPECT_NE(moved, plain);
    EXPECT_EQ(scene.spheres[2].material, moved);  // one copy per placement
    EXPECT_EQ(scene.materials[size_t(moved)].to_object.offset, glm::dvec3(-2, 0, 0));
    EXPECT_EQ(scene.materials[size_t(moved)].kd_pattern, scene.materials[size_t(plain)].kd_pattern);
    const Material& scaled = scene.materials[size_t(scene.quads[0].material)];
    EXPECT_EQ(scaled.to_object.linear, glm::dmat3(0.5));
    // A material without patterns is not copied.
    EXPECT_EQ(scene.materials[size_t(scene.spheres[3].material)].to_object, Affine{});
    EXPECT_EQ(scene.materials.size(), 4u);  // m, its two copies, the plain one
}

TEST(Patterns, AMaterialNamedBeforeItsBlockIsCopiedToo) {
    const SceneDescription scene = load_ok(
        "sphere { center (0, 0, 0) radius 1 translate (0, 3, 0) material later }\n"
        "material later { kd spots { } }\n");
    const Material& material = scene.materials[size_t(scene.spheres[0].material)];
    EXPECT_EQ(material.name, "later");
    EXPECT_EQ(material.kd_pattern, 0);
    EXPECT_EQ(material.to_object.offset, glm::dvec3(0, -3, 0));
}

TEST(Patterns, ImagePatternsNameTheirFileOnce) {
    const SceneDescription scene = load_ok(
        "let grid = \"" TRACER_SOURCE_DIR
        "/scenes/textures/uv_grid.png\"\n"
        "quad { corner (0, 0, 0) edge1 (1, 0, 0) edge2 (0, 1, 0) material { kd image { file grid mapping uv } } }\n"
        "quad { corner (0, 0, 0) edge1 (1, 0, 0) edge2 (0, 1, 0) material { kd image { file grid wrap mirror } } }\n");
    ASSERT_EQ(scene.images.size(), 1u);
    ASSERT_EQ(scene.patterns.size(), 2u);
    EXPECT_EQ(scene.patterns[0].mapping, Mapping::Uv);
    EXPECT_EQ(scene.patterns[1].mapping, Mapping::Planar);  // an image's default
    EXPECT_EQ(scene.patterns[1].wrap, Wrap::Mirror);
    EXPECT_EQ(scene.patterns[1].image, 0);
}

TEST(Patterns, APatternTimesANumberOrAColourMultipliesItsColours) {
    const SceneDescription scene = load_ok(
        "let floor = checker { even (1, 0.5, 0.2) }\n"
        "sphere { center (0, 0, 0) radius 1 material { ka 0.1 * floor kd floor } }\n"
        "sphere { center (0, 0, 0) radius 1 material { kd floor * (1, 0, 0) / 2 } }\n"
        "sphere { center (0, 0, 0) radius 1 material { kd 2 * checker { multiply 0.25 } } }\n");
    const Material& first = scene.materials[size_t(scene.spheres[0].material)];
    EXPECT_EQ(scene.patterns[size_t(first.ka_pattern)].multiply, glm::dvec3(0.1));
    EXPECT_EQ(scene.patterns[size_t(first.kd_pattern)].multiply, glm::dvec3(1));  // the value itself is unchanged
    const Material& second = scene.materials[size_t(scene.spheres[1].material)];
    EXPECT_EQ(scene.patterns[size_t(second.kd_pattern)].multiply, glm::dvec3(0.5, 0, 0));
    const Material& third = scene.materials[size_t(scene.spheres[2].material)];
    EXPECT_EQ(scene.patterns[size_t(third.kd_pattern)].multiply, glm::dvec3(0.5));  // 2 x its own 0.25
}

}  // namespace
}  // namespace tracer
