// Area lights (issue 56): a 1 x 1 area light is the point light at its centre, bit for bit; the
// samples lie where the definition puts them (corner to corner, as POV-Ray's grid), each with its
// share of the colour; an area light renders as its samples written out as point lights, and the
// same on any number of threads.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "../../common/scene_render.h"

namespace tracer {
namespace {

const std::string kScene = R"(
camera { eye (0, 6, 4) lookat (0, 0, 0) fovy 45 }
plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 ks 0.3 n 20 } }
sphere { center (0.2, 1, 0) radius 0.6 material { kd (0.8, 0.3, 0.2) ks 0.5 n 40 km 0.2 } }
render { width 48 height 36 }
)";

Image render_text(const std::string& lights, int threads = 2) {
    return render_scene_text(kScene + lights, threads);
}

TEST(AreaLight, OneSampleIsThePointLightAtItsCentreBitForBit) {
    const Image point = render_text("light { position (1, 4, 1) color (0.9, 0.8, 0.7) }\n");
    const Image area = render_text(
        "area_light { position (1, 4, 1) color (0.9, 0.8, 0.7) edge1 (2, 0, 0) edge2 (0, 0, 2) samples1 1 "
        "samples2 1 }\n");
    ASSERT_EQ(point.rgb.size(), area.rgb.size());
    EXPECT_TRUE(point.rgb == area.rgb);
}

TEST(AreaLight, SamplesSpanTheRectangleCornerToCornerEachWithItsShare) {
    Light light;
    light.position = {1, 2, 3};
    light.edge1 = {2, 0, 0};
    light.edge2 = {0, 0, 4};
    light.samples1 = 3, light.samples2 = 2;
    EXPECT_EQ(light.samples(), 6);
    EXPECT_EQ(light.sample(0, 0), dvec3(0, 2, 1));
    EXPECT_EQ(light.sample(1, 0), dvec3(1, 2, 1));
    EXPECT_EQ(light.sample(2, 1), dvec3(2, 2, 5));
    light.samples1 = 1;
    EXPECT_EQ(light.sample(0, 1), dvec3(1, 2, 5));  // one sample along an edge: its middle
}

TEST(AreaLight, RendersAsItsSamplesWrittenOutAsPointLights) {
    const Image area = render_text(
        "area_light { position (0.5, 4, 0.5) color 0.9 edge1 (1.5, 0, 0) edge2 (0, 0.5, 1) samples1 3 "
        "samples2 2 }\n");
    Light light;
    light.position = {0.5, 4, 0.5}, light.edge1 = {1.5, 0, 0}, light.edge2 = {0, 0.5, 1};
    light.samples1 = 3, light.samples2 = 2;
    const Image separate = render_text(samples_as_point_lights(light, 0.9));
    ASSERT_EQ(area.rgb.size(), separate.rgb.size());
    // The same terms in the same order; only the sum over lights may round differently.
    for (size_t k = 0; k < area.rgb.size(); ++k) EXPECT_NEAR(area.rgb[k], separate.rgb[k], 1e-12) << k;
}

TEST(AreaLight, TheImageIsTheSameOnAnyNumberOfThreads) {
    const std::string lamp =
        "area_light { position (0, 4, 0) edge1 (1, 0, 0) edge2 (0, 0, 1) samples1 4 samples2 4 }\n";
    const Image one = render_text(lamp, 1), two = render_text(lamp, 2), four = render_text(lamp, 4);
    EXPECT_TRUE(one.rgb == two.rgb);
    EXPECT_TRUE(one.rgb == four.rgb);
}

}  // namespace
}  // namespace tracer
