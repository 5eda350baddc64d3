// Spotlights, parallel lights and fading (issue 56): the attenuation against POV-Ray's formula at
// chosen angles and distances; a parallel light lights a floor evenly and shadows it from any
// distance; a faded area light is its faded samples; a quad in an area light's rectangle (the
// way to see the lamp: lights are not seen by rays) does not shadow the light.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../../common/scene_render.h"
#include "render/direct_light.h"

namespace tracer {
namespace {

constexpr double kPi = 3.14159265358979323846;

Image render_text(const std::string& text) {
    return render_scene_text(text);
}

// A spotlight along -y; the unit direction from a point at `degrees` off its axis back to it.
Light spot(double radius, double falloff, double tightness) {
    Light light;
    light.kind = Light::Kind::Spot;
    light.direction = {0, -1, 0};
    light.radius = radius, light.falloff = falloff, light.tightness = tightness;
    return light;
}
Vec3 to_light_at(double degrees) {
    const double a = degrees * kPi / 180;
    return {-std::sin(a), std::cos(a), 0};
}

TEST(LightKinds, ASpotlightFollowsPovRaysFormula) {
    const Light light = spot(20, 40, 3);
    const double c = std::cos(10 * kPi / 180);  // inside the radius: cos^tightness only
    EXPECT_NEAR(light_attenuation(light, to_light_at(10), 5), c * c * c, 1e-15);
    // Between radius and falloff: times (3 - 2x) x^2, x = (cos a - cos f) / (cos r - cos f).
    const double cos_r = std::cos(20 * kPi / 180), cos_f = std::cos(40 * kPi / 180), cos_a = std::cos(30 * kPi / 180);
    const double x = (cos_a - cos_f) / (cos_r - cos_f);
    EXPECT_NEAR(light_attenuation(light, to_light_at(30), 5), std::pow(cos_a, 3) * (3 - 2 * x) * x * x, 1e-15);
    EXPECT_EQ(light_attenuation(light, to_light_at(41), 5), 0);   // past the falloff
    EXPECT_EQ(light_attenuation(light, to_light_at(100), 5), 0);  // behind the light
    EXPECT_NEAR(light_attenuation(spot(20, 40, 0), to_light_at(10), 5), 1, 1e-15);
    // radius = falloff: a hard edge.
    EXPECT_EQ(light_attenuation(spot(25, 25, 0), to_light_at(24.9), 5), 1);
    EXPECT_EQ(light_attenuation(spot(25, 25, 0), to_light_at(25.1), 5), 0);
}

TEST(LightKinds, FadingIsTwoOverOnePlusTheDistanceRatioToThePower) {
    Light light;
    light.fade_distance = 4, light.fade_power = 1.5;
    EXPECT_NEAR(light_attenuation(light, Vec3(0, 1, 0), 4), 1, 1e-15);  // at fade_distance: full
    EXPECT_NEAR(light_attenuation(light, Vec3(0, 1, 0), 10), 2 / (1 + std::pow(2.5, 1.5)), 1e-15);
    EXPECT_NEAR(light_attenuation(light, Vec3(0, 1, 0), 0), 2, 1e-15);  // nearer: up to twice
}

TEST(LightKinds, AParallelLightLightsAFloorEvenlyAndShadowsFromAnyDistance) {
    const std::string head =
        "render { width 40 height 30 }\ncamera { eye (0, 10, 0.01) lookat (0, 0, 0) fovy 60 }\n"
        "plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.5 } }\n"
        "parallel_light { direction (0, -2, -1) color 0.9 }\n";
    const Image open = render_text(head);
    const double expected = 0.5 * 0.9 * (2 / std::sqrt(5.0));  // kd * color * N.L
    for (double v : open.rgb) EXPECT_NEAR(v, expected, 1e-12);
    // A small sphere 2236 units up the light's way shadows the middle of the floor.
    const Image shadowed = render_text(head + "sphere { center (0, 2000, 1000) radius 2 material { kd 1 } }\n");
    const size_t middle = (size_t(15) * 40 + 20) * 3;
    EXPECT_EQ(shadowed.rgb[middle], 0);
    EXPECT_NEAR(shadowed.rgb[0], expected, 1e-12);  // a corner, out of the shadow
}

TEST(LightKinds, AFadedAreaLightIsItsFadedSamples) {
    const std::string head =
        "render { width 40 height 30 }\ncamera { eye (0, 6, 4) lookat (0, 0, 0) fovy 50 }\n"
        "plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 ks 0.3 n 20 } }\n"
        "sphere { center (0.2, 1, 0) radius 0.6 material { kd (0.8, 0.3, 0.2) ks 0.5 n 40 } }\n";
    const Image area = render_text(head +
                                   "area_light { position (0.5, 4, 0.5) edge1 (1.5, 0, 0) edge2 (0, 0.5, 1) "
                                   "samples1 3 samples2 2 color 0.9 fade_distance 2 fade_power 1.5 }\n");
    Light light;
    light.position = {0.5, 4, 0.5}, light.edge1 = {1.5, 0, 0}, light.edge2 = {0, 0.5, 1};
    light.samples1 = 3, light.samples2 = 2;
    const Image separate = render_text(head + samples_as_point_lights(light, 0.9, " fade_distance 2 fade_power 1.5"));
    ASSERT_EQ(area.rgb.size(), separate.rgb.size());
    for (size_t k = 0; k < area.rgb.size(); ++k) EXPECT_NEAR(area.rgb[k], separate.rgb[k], 1e-12) << k;
}

TEST(LightKinds, AQuadInAnAreaLightsRectangleDoesNotShadowIt) {
    const std::string head =
        "render { width 40 height 30 }\ncamera { eye (0, 3, 6) lookat (0, 0, 0) fovy 50 }\n"
        "plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 } }\n"
        "area_light { position (0, 4, 0) edge1 (1, 0, 0) edge2 (0, 0, 1) samples1 4 samples2 4 }\n";
    const Image without = render_text(head);
    // The lamp's face, seen from below: ka 1, in the light's own plane.
    const Image with = render_text(head +
                                   "quad { corner (-0.5, 4, -0.5) edge1 (1, 0, 0) edge2 (0, 0, 1) "
                                   "material { ka 1 } }\n");
    int differing = 0;
    for (size_t k = 0; k < with.rgb.size(); ++k) differing += with.rgb[k] != without.rgb[k];
    EXPECT_EQ(differing, 0);  // the camera sees the floor only, lit alike
}

}  // namespace
}  // namespace tracer
