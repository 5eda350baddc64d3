// The defaults live twice: in the block tables (schema.cpp, which validation fills them in from)
// and in the scene description's structs (scene.h, which every other user of a scene starts
// from). This test proves the two agree: a scene whose blocks leave every optional key out is
// compared, field by field, with default-made structs; and every key with a default in the
// tables must be one the test compares, so a new key cannot slip past it.
#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <stdexcept>

#include "lang/internal/checked_fields.h"
#include "lang/load_scene.h"
#include "lang/schema.h"

namespace tracer {
namespace {

using Check = std::function<void(const SceneDescription&)>;

struct DefaultRow {
    std::string_view block, key;
    Check check;  // expects the scene's field for the key to equal the struct's default
};

// Every kind of block with a default, its optional keys left out.
const std::string kScene = R"(
render { }
camera { eye (0, 0, 5) lookat (0, 0, 0) }
material m { }
light { position (0, 5, 0) }
area_light { position (0, 5, 0) edge1 (1, 0, 0) edge2 (0, 0, 1) samples1 2 samples2 2 }
spotlight { position (0, 5, 0) point_at (0, 0, 0) }
parallel_light { direction (0, -1, 0) }
mesh { file ")" TRACER_SOURCE_DIR R"(/scenes/meshes/tetrahedron.obj" material m }
box { min (0, 0, 0) max (1, 1, 1) material m rotate { } }
cylinder { base (0, 0, 0) top (0, 1, 0) radius 1 material m }
cone { base (0, 0, 0) top (0, 1, 0) base_radius 1 material m }
)";

std::vector<DefaultRow> rows() {
    const RenderSettings render;
    const Camera camera;
    const Material material;
    const Light light;
    const Mesh mesh;
    const Box box;
    const Cone cone;
    // clang-format off
    return {
        {"render", "width", [=](auto& s) { EXPECT_EQ(s.render.width, render.width); }},
        {"render", "height", [=](auto& s) { EXPECT_EQ(s.render.height, render.height); }},
        {"render", "max_depth", [=](auto& s) { EXPECT_EQ(s.render.max_depth, render.max_depth); }},
        {"render", "samples", [=](auto& s) { EXPECT_EQ(s.render.samples, render.samples); }},
        {"render", "background", [=](auto& s) { EXPECT_EQ(s.render.background, render.background); }},
        {"render", "shadows", [=](auto& s) { EXPECT_EQ(s.render.shadows, render.shadows); }},
        {"render", "transparent_shadows", [=](auto& s) {
             EXPECT_EQ(s.render.transparent_shadows, render.transparent_shadows);
         }},
        {"render", "spawn_rules", [=](auto& s) { EXPECT_EQ(s.render.spawn_rules, render.spawn_rules); }},
        {"render", "antialias", [=](auto& s) { EXPECT_EQ(s.render.antialias, render.antialias); }},
        {"render", "adaptive_threshold",
         [=](auto& s) { EXPECT_EQ(s.render.adaptive_threshold, render.adaptive_threshold); }},
        {"render", "adaptive_depth", [=](auto& s) { EXPECT_EQ(s.render.adaptive_depth, render.adaptive_depth); }},
        {"render", "adaptive_cell", [=](auto& s) { EXPECT_EQ(s.render.adaptive_cell, render.adaptive_cell); }},
        {"render", "accel", [=](auto& s) { EXPECT_EQ(s.render.accel, render.accel); }},
        {"render", "leaf_size", [=](auto& s) { EXPECT_EQ(s.render.leaf_size, render.leaf_size); }},
        {"render", "encoding", [=](auto& s) { EXPECT_EQ(s.render.encoding, render.encoding); }},
        {"camera", "up", [=](auto& s) { EXPECT_EQ(s.camera.up, camera.up); }},
        {"camera", "fovy", [=](auto& s) { EXPECT_EQ(s.camera.fovy_degrees, camera.fovy_degrees); }},
        {"camera", "focal", [=](auto& s) { EXPECT_EQ(s.camera.focal, camera.focal); }},
        {"material", "ka", [=](auto& s) { EXPECT_EQ(s.materials[0].ka, material.ka); }},
        {"material", "kd", [=](auto& s) { EXPECT_EQ(s.materials[0].kd, material.kd); }},
        {"material", "ks", [=](auto& s) { EXPECT_EQ(s.materials[0].ks, material.ks); }},
        {"material", "km", [=](auto& s) { EXPECT_EQ(s.materials[0].km, material.km); }},
        {"material", "n", [=](auto& s) { EXPECT_EQ(s.materials[0].n, material.n); }},
        {"material", "kt", [=](auto& s) { EXPECT_EQ(s.materials[0].kt, material.kt); }},
        {"material", "ior", [=](auto& s) { EXPECT_EQ(s.materials[0].ior, material.ior); }},
        {"light", "color", [=](auto& s) { EXPECT_EQ(s.lights[0].color, light.color); }},
        {"area_light", "color", [=](auto& s) { EXPECT_EQ(s.lights[1].color, light.color); }},
        {"light", "fade_distance", [=](auto& s) { EXPECT_EQ(s.lights[0].fade_distance, light.fade_distance); }},
        {"light", "fade_power", [=](auto& s) { EXPECT_EQ(s.lights[0].fade_power, light.fade_power); }},
        {"area_light", "fade_distance", [=](auto& s) { EXPECT_EQ(s.lights[1].fade_distance, light.fade_distance); }},
        {"area_light", "fade_power", [=](auto& s) { EXPECT_EQ(s.lights[1].fade_power, light.fade_power); }},
        {"area_light", "shape", [=](auto& s) { EXPECT_EQ(s.lights[1].shape, light.shape); }},
        {"area_light", "jitter", [=](auto& s) { EXPECT_EQ(s.lights[1].jitter, light.jitter); }},
        {"area_light", "adaptive", [=](auto& s) { EXPECT_EQ(s.lights[1].adaptive, light.adaptive); }},
        {"spotlight", "color", [=](auto& s) { EXPECT_EQ(s.lights[2].color, light.color); }},
        {"spotlight", "radius", [=](auto& s) { EXPECT_EQ(s.lights[2].radius, light.radius); }},
        {"spotlight", "falloff", [=](auto& s) { EXPECT_EQ(s.lights[2].falloff, light.falloff); }},
        {"spotlight", "tightness", [=](auto& s) { EXPECT_EQ(s.lights[2].tightness, light.tightness); }},
        {"spotlight", "fade_distance", [=](auto& s) { EXPECT_EQ(s.lights[2].fade_distance, light.fade_distance); }},
        {"spotlight", "fade_power", [=](auto& s) { EXPECT_EQ(s.lights[2].fade_power, light.fade_power); }},
        {"parallel_light", "color", [=](auto& s) { EXPECT_EQ(s.lights[3].color, light.color); }},
        {"mesh", "shading", [=](auto& s) { EXPECT_EQ(s.meshes[0].flat, mesh.flat); }},
        {"cylinder", "caps", [=](auto& s) { EXPECT_EQ(s.cones[0].caps, cone.caps); }},
        {"cone", "caps", [=](auto& s) { EXPECT_EQ(s.cones[1].caps, cone.caps); }},
        {"cone", "top_radius", [=](auto& s) { EXPECT_EQ(s.cones[1].top_radius, cone.top_radius); }},
        // The keys that place a shape, shared by mesh, triangle, quad and box (read on the mesh).
        {"placed", "scale", [=](auto& s) { EXPECT_EQ(s.meshes[0].scale, mesh.scale); }},
        {"placed", "rotate", [=](auto& s) {
             EXPECT_EQ(s.meshes[0].rotate_axis, mesh.rotate_axis);
             EXPECT_EQ(s.meshes[0].rotate_degrees, mesh.rotate_degrees);
         }},
        {"placed", "translate", [=](auto& s) { EXPECT_EQ(s.meshes[0].translate, mesh.translate); }},
        {"placed", "transform", [=](auto& s) { EXPECT_EQ(s.meshes[0].steps.size(), mesh.steps.size()); }},
        // `rotate { }` written with its own keys left out.
        {"rotate", "axis", [=](auto& s) { EXPECT_EQ(s.boxes[0].rotate_axis, box.rotate_axis); }},
        {"rotate", "angle", [=](auto& s) { EXPECT_EQ(s.boxes[0].rotate_degrees, box.rotate_degrees); }},
    };
    // clang-format on
}

TEST(SchemaDefaults, TheTablesAndTheSceneStructsAgree) {
    LoadResult loaded = load_scene_text("/scenes/defaults.scn", kScene);
    ASSERT_TRUE(loaded.scene) << (loaded.diagnostics.all().empty() ? "" : loaded.diagnostics.all()[0].message);
    for (const DefaultRow& row : rows()) {
        SCOPED_TRACE(std::string(row.block) + "." + std::string(row.key));
        row.check(*loaded.scene);
    }
}

TEST(SchemaDefaults, EveryDefaultInTheTablesIsCompared) {
    std::set<std::pair<std::string_view, std::string_view>> compared;
    for (const DefaultRow& row : rows()) compared.insert({row.block, row.key});
    const std::set<std::string_view> placed_keys = {"scale", "rotate", "translate", "transform"};
    for (const BlockSpec* spec : all_block_specs()) {
        if (spec->ordered) continue;  // a transform's steps are always written: no defaults apply
        for (const KeySpec& key : spec->keys) {
            if (key.required()) continue;
            const bool placed = placed_keys.count(key.name) > 0 && spec->kind != "rotate";
            EXPECT_TRUE(compared.count({placed ? "placed" : spec->kind, key.name}))
                << spec->kind << "." << key.name << " has a default in the table that this test does not compare";
        }
    }
}

TEST(SchemaDefaults, ABuilderAskingForAKeyItsTableLacksFailsNamingIt) {
    const BlockSpec& camera = *find_block_spec("camera");
    Fields fields(camera);
    EXPECT_EQ(fields.number("fovy"), 45);  // from the table
    try {
        fields.number("fov");
        FAIL() << "no exception";
    } catch (const std::logic_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "a builder asked for the key 'fov', which the table of 'camera' does not have");
    }
    EXPECT_THROW(fields.has("eyes"), std::logic_error);
    EXPECT_THROW(fields.child("up"), std::logic_error);  // a key, but not a nested block
}

}  // namespace
}  // namespace tracer
