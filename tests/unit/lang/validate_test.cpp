#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include <glm/geometric.hpp>

#include "lang/load_scene.h"
#include "scene/scene_json.h"

namespace tracer {
namespace {

const std::string kCamera = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\n";

LoadResult load(const std::string& text) {
    return load_scene_text("/scenes/t.scn", text);
}

std::vector<std::string> messages(const LoadResult& result) {
    std::vector<std::string> out;
    for (const Diagnostic& d : result.diagnostics.all()) out.push_back(d.message);
    return out;
}

TEST(Validate, DefaultsFillEverythingLeftOut) {
    LoadResult r = load(kCamera);
    ASSERT_TRUE(r.scene) << format_diagnostic(r.diagnostics.all().front());
    EXPECT_EQ(r.scene->render.width, 1200);
    EXPECT_EQ(r.scene->render.height, 800);
    EXPECT_EQ(r.scene->render.max_depth, 4);
    EXPECT_EQ(r.scene->render.samples, 1);
    EXPECT_TRUE(r.scene->render.shadows);
    EXPECT_EQ(r.scene->camera.up, dvec3(0, 1, 0));
    EXPECT_EQ(r.scene->camera.fovy_degrees, 45);
    EXPECT_EQ(r.scene->camera.focal, 1);
}

TEST(Validate, MaterialsByNameInlineAndBeforeDefinition) {
    LoadResult r = load(kCamera +
                        "sphere { center (0, 0, 0) radius 1 material later }\n"
                        "sphere { center (0, 0, 0) radius 2 material { ka 0.1 kd (0.2, 1, 0.2) } }\n"
                        "material later { km 0.8 n 5 }\n"
                        "light { position (0, 5, 5) }\n");
    ASSERT_TRUE(r.scene);
    ASSERT_EQ(r.scene->materials.size(), 2u);
    const Material& later = r.scene->materials[size_t(r.scene->spheres[0].material)];
    EXPECT_EQ(later.name, "later");
    EXPECT_EQ(later.km, dvec3(0.8));  // one number means grey
    EXPECT_EQ(later.n, 5);
    EXPECT_EQ(later.kd, dvec3(0.0));
    const Material& inline_material = r.scene->materials[size_t(r.scene->spheres[1].material)];
    EXPECT_EQ(inline_material.name, "");
    EXPECT_EQ(inline_material.kd, dvec3(0.2, 1, 0.2));
    EXPECT_EQ(r.diagnostics.warning_count(), 0);
}

TEST(Validate, PlaneNormalsAreNormalisedAndPathsMadeAbsolute) {
    LoadResult r = load(kCamera + "plane { point (0, 0, 0) normal (0, 1e-200, 0) material { kd 1 } }\n");
    ASSERT_TRUE(r.scene);
    EXPECT_EQ(r.scene->planes[0].normal, dvec3(0, 1, 0));  // no underflow to a zero vector

    std::string dir = std::filesystem::path(TRACER_SOURCE_DIR) / "scenes";
    LoadResult m =
        load_scene_text(dir + "/x.scn", kCamera + "mesh { file \"meshes/tetrahedron.obj\" material { kd 1 } }\n");
    ASSERT_TRUE(m.scene);
    EXPECT_EQ(m.scene->meshes[0].path, dir + "/meshes/tetrahedron.obj");
    EXPECT_EQ(m.scene->meshes[0].rotate_degrees, 0);  // the nested block's defaults
    EXPECT_EQ(m.scene->meshes[0].rotate_axis, dvec3(0, 1, 0));
}

TEST(Validate, UnusedMaterialIsAWarningNotAnError) {
    LoadResult r =
        load(kCamera + "material spare { kd 1 }\nplane { point (0, 0, 0) normal (0, 1, 0) material { ka 1 } }\n");
    EXPECT_TRUE(r.scene);
    EXPECT_EQ(r.diagnostics.warning_count(), 1);
    EXPECT_EQ(messages(r), std::vector<std::string>{"material 'spare' is never used"});
}

// Scenes that are valid but whose image cannot be what the author meant: a warning each.
TEST(Validate, NoShapesIsAWarning) {
    LoadResult r = load(kCamera + "light { position (0, 5, 5) }\n");
    EXPECT_TRUE(r.scene);
    EXPECT_EQ(messages(r),
              std::vector<std::string>{"the scene has no shapes: the image will be the background colour only"});
}

TEST(Validate, NoLightIsAWarningWhereAMaterialHasDiffuseOrSpecular) {
    const std::string no_light =
        "the scene has no light: its diffuse and specular colours (kd, ks) will not show, only ka; add one, e.g. "
        "light { position (0, 5, 5) }";
    EXPECT_EQ(messages(load(kCamera + "sphere { center (0, 0, 0) radius 1 material { ks 0.5 } }\n")),
              std::vector<std::string>{no_light});
    // Ambient only, or mirrors only: nothing the lights would have added, no warning.
    EXPECT_TRUE(messages(load(kCamera + "sphere { center (0, 0, 0) radius 1 material { ka 0.5 km 1 } }\n")).empty());
}

TEST(Validate, EveryShapeBehindTheCameraIsAWarning) {
    const std::string behind = "light { position (0, 5, 5) }\nsphere { center (0, 0, 9) radius 1 material { kd 1 } }\n";
    EXPECT_EQ(
        messages(load(kCamera + behind)),
        std::vector<std::string>{"every shape is behind the camera: the image will be the background colour only"});
    // Touching the eye's plane counts as in front; a plane anywhere may be seen.
    EXPECT_TRUE(messages(load(kCamera +
                              "light { position (0, 5, 5) }\nsphere { center (0, 0, 8) radius 1 material { kd 1 } }\n"))
                    .empty());
    EXPECT_TRUE(
        messages(load(kCamera + behind + "plane { point (0, -1, 0) normal (0, 1, 0) material { kd 1 } }\n")).empty());
}

TEST(Validate, ErrorsInOneBlockDoNotCascade) {
    // The broken material's name stays known, so its users are not reported as well.
    LoadResult r = load(kCamera + "material m { kd ( }\nsphere { center (0, 0, 0) radius 1 material m }\n");
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.diagnostics.error_count(), 1);
}

TEST(Validate, CameraGeometryIsChecked) {
    EXPECT_EQ(messages(load("camera { eye (1, 2, 3) lookat (1, 2, 3) }")),
              std::vector<std::string>{"'lookat' must differ from 'eye' (they set the viewing direction)"});
    EXPECT_EQ(messages(load("camera { eye (0, 5, 0) lookat (0, 0, 0) }")),
              std::vector<std::string>{"'up' (by default (0, 1, 0)) is parallel to the viewing direction; "
                                       "choose an 'up' that is not"});
    EXPECT_TRUE(load("camera { eye (0, 5, 0) lookat (0, 0, 0) up (0, 0, -1) }").scene);
}

TEST(Validate, SamplesMustBeAPerfectSquare) {
    EXPECT_TRUE(load(kCamera + "render { samples 16 }").scene);
    EXPECT_EQ(messages(load(kCamera + "render { samples 8 }")),
              std::vector<std::string>{"'samples' must be a perfect square (N x N stratified samples); try 4 or 9"});
}

TEST(Validate, JsonDumpIsFullyResolved) {
    LoadResult r = load(kCamera + "material m { kd 0.5 }\nsphere { center (1, 2, 3) radius 1 material m }\n");
    ASSERT_TRUE(r.scene);
    auto json = scene_to_json(*r.scene);
    EXPECT_EQ(json["source"], "/scenes/t.scn");
    EXPECT_EQ(json["render"]["max_depth"], 4);
    EXPECT_EQ(json["spheres"][0]["material"]["name"], "m");
    EXPECT_EQ(json["spheres"][0]["material"]["kd"], nlohmann::json::array({0.5, 0.5, 0.5}));
    EXPECT_EQ(json["spheres"][0]["material"]["ka"], nlohmann::json::array({0.0, 0.0, 0.0}));
    EXPECT_EQ(json["camera"]["up"], nlohmann::json::array({0.0, 1.0, 0.0}));
}

TEST(Validate, JsonTextWrittenShapeByShapeIsTheWholeDocumentsText) {
    // Every kind of array, empty and full, paths with invalid UTF-8 replaced alike.
    for (const std::string& body :
         {std::string(""), std::string("material m { kd 0.5 }\nsphere { center (1, 2, 3) radius 1 material m }\n"
                                       "plane { point (0, 0, 0) normal (0, 1, 0) material m }\n"
                                       "for i in 0..3 { quad { corner (i, 0, 0) edge1 (1, 0, 0) edge2 (0, 1, 0) "
                                       "material m rotate { angle 10 * i } } }\n"
                                       "triangle { a (0, 0, 0) b (1, 0, 0) c (0, 1, 0) material { kd 1 } }\n"
                                       "box { min (0, 0, 0) max (1, 1, 1) transform { scale 2 translate (1, 0, 0) } "
                                       "material m }\ncylinder { base (0, 0, 0) top (0, 1, 0) radius 1 material m }\n"
                                       "disc { center (0, 0, 0) normal (0, 1, 0) radius 1 material m }\n"
                                       "light { position (0, 5, 5) }\nrender { antialias adaptive }\n")}) {
        LoadResult r = load(kCamera + body);
        ASSERT_TRUE(r.scene) << body;
        r.scene->source_path += "\xff";
        std::ostringstream streamed;
        write_scene_json(streamed, *r.scene);
        const std::string whole =
            nlohmann::json(scene_to_json(*r.scene)).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
        EXPECT_EQ(streamed.str(), whole + "\n");
    }
}

}  // namespace
}  // namespace tracer

namespace tracer {
namespace {

// Cylinders, cones and discs are placed into world coordinates by their own keys and their
// groups' (inner first): points placed, radii scaled by the one factor, normals turned; a
// mirroring scale keeps them round.
TEST(Validate, RoundShapesArePlacedByTransformsAndGroups) {
    LoadResult r = load(kCamera +
                        "light { position (0, 5, 5) }\n"
                        "group {\n  rotate { axis (0, 0, 1) angle 90 }\n  translate (1, 0, 0)\n"
                        "  cylinder { base (0, 0, 0) top (0, 1, 0) radius 0.5 scale -2 material { kd 1 } }\n"
                        "  disc { center (0, 1, 0) normal (0, 1, 0) radius 0.5 material { kd 1 } }\n}\n"
                        "cone { base (1, 2, 3) top (1, 2, 4) base_radius 1 caps false material { kd 1 } }\n");
    ASSERT_TRUE(r.scene) << format_diagnostic(r.diagnostics.all().front());
    ASSERT_EQ(r.scene->cones.size(), 2u);
    const Cone& cylinder = r.scene->cones[0];
    EXPECT_NEAR(glm::length(cylinder.base - dvec3(1, 0, 0)), 0, 1e-15);
    EXPECT_NEAR(glm::length(cylinder.top - dvec3(3, 0, 0)), 0, 1e-15);
    EXPECT_EQ(cylinder.base_radius, 1.0);
    EXPECT_EQ(cylinder.top_radius, 1.0);
    EXPECT_TRUE(cylinder.caps);
    const Cone& cone = r.scene->cones[1];
    EXPECT_EQ(cone.top_radius, 0.0);  // a pointed cone by default
    EXPECT_FALSE(cone.caps);
    ASSERT_EQ(r.scene->discs.size(), 1u);
    EXPECT_NEAR(glm::length(r.scene->discs[0].center), 0, 1e-15);
    EXPECT_NEAR(glm::length(r.scene->discs[0].normal - dvec3(-1, 0, 0)), 0, 1e-15);
    EXPECT_EQ(r.scene->discs[0].radius, 0.5);
}

}  // namespace
}  // namespace tracer
