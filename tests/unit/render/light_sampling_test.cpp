// Jittered and adaptive area lights (issue 56): the generator's draws against values an
// independent implementation of its documented definition gives (Python, the same formulas);
// jittered samples stay in their cells; a jittered image is the same on 1, 2 and 4 threads and
// in any window of the frame; multi-jittered places fill each edge's strips one sample each;
// adaptive sampling saves rays past wide shapes and traces every sample past a thin bar.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

#include "../../common/scene_render.h"
#include "render/light_samples.h"

namespace tracer {
namespace {

const std::string kScene = R"(
render { width 48 height 36 }
camera { eye (0, 6, 4) lookat (0, 0, 0) fovy 45 }
plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 ks 0.3 n 20 } }
sphere { center (0.2, 1, 0) radius 0.6 material { kd (0.8, 0.3, 0.2) ks 0.5 n 40 } }
box { min (-2, 0, -1.5) max (-1.2, 1.5, -0.8) material { kd 0.5 } }
)";

Image render_text(const std::string& lights, int threads = 2, PixelRect crop = {}, RenderStats* stats = nullptr) {
    return render_scene_text(kScene + lights, threads, crop, stats);
}

std::string lamp(int n, const std::string& sampling) {
    return "area_light { position (0.5, 4, 0.5) edge1 (2, 0, 0) edge2 (0, 0.5, 2) samples1 " + std::to_string(n) +
           " samples2 " + std::to_string(n) + " " + sampling + " color 0.9 }\n";
}

TEST(LightSampling, TheGeneratorGivesTheDocumentedDraws) {
    // From the definition in light_samples.h, in Python: seed((0.25, -1.5, 3.0), 2) and draws 0, 1, 2.
    const uint64_t seed = LightSamples::seed({0.25, -1.5, 3.0}, 2);
    EXPECT_EQ(seed, 0xdfa590f066ad130cull);
    EXPECT_EQ(LightSamples::draw(seed, 0), 0.7944877746286425);
    EXPECT_EQ(LightSamples::draw(seed, 1), 0.8861806836076437);
    EXPECT_EQ(LightSamples::draw(seed, 2), 0.1505299341265277);
}

TEST(LightSampling, JitteredSamplesStayInTheirCellsAndTheGridIsLightSample) {
    Light light;
    light.position = {1, 2, 3}, light.edge1 = {2, 0, 0}, light.edge2 = {0, 0, 4};
    light.samples1 = 3, light.samples2 = 5;
    const LightSamples grid(light, 0, Vec3(0.5, 0, 0.5));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 5; ++j) EXPECT_EQ(grid.position(i, j), light.sample(i, j));
    light.jitter = true;
    const LightSamples jittered(light, 0, Vec3(0.5, 0, 0.5));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 5; ++j) {
            const double a = jittered.along1(i, j), b = jittered.along2(i, j);
            EXPECT_GE(a, i / 3.0 - 0.5);
            EXPECT_LT(a, (i + 1) / 3.0 - 0.5);
            EXPECT_GE(b, j / 5.0 - 0.5);
            EXPECT_LT(b, (j + 1) / 5.0 - 0.5);
        }
    // Another point, other places (one LightSamples at a time on a thread: its tables are the thread's).
    const double here = jittered.along1(1, 1);
    const LightSamples elsewhere(light, 0, Vec3(0.5, 0, 0.75));
    EXPECT_NE(here, elsewhere.along1(1, 1));
}

TEST(LightSampling, JitteredSamplesAreTheDocumentedMultiJitteredPlaces) {
    // From the definition in light_samples.h, in Python: a 2 x 3 light, the point and light
    // index of the generator's test; (i, j) -> (a, b).
    Light light;
    light.edge1 = {1, 0, 0}, light.edge2 = {0, 1, 0}, light.samples1 = 2, light.samples2 = 3, light.jitter = true;
    const LightSamples jittered(light, 2, Vec3(0.25, -1.5, 3.0));
    const double expected[2][3][2] = {
        {{-0.034252037561892934, -0.35230321939872605},
         {-0.47491167764557873, 0.01915610946416646},
         {-0.3232356169660132, 0.39231317992170356}},
        {{0.009086979883593416, -0.2944963000543107},
         {0.3469053701726843, -0.07102878143947394},
         {0.23680308306552267, 0.1851149859483544}},
    };
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 3; ++j) {
            EXPECT_EQ(jittered.along1(i, j), expected[i][j][0]) << i << ", " << j;
            EXPECT_EQ(jittered.along2(i, j), expected[i][j][1]) << i << ", " << j;
        }
    // Along each edge alone, the 3 x 5 samples of a larger light fill the 15 strips one each.
    light.samples1 = 3, light.samples2 = 5;
    const LightSamples larger(light, 0, Vec3(0.5, 0, 0.5));
    bool strip1[15] = {}, strip2[15] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 5; ++j) {
            strip1[int((larger.along1(i, j) + 0.5) * 15)] = true;
            strip2[int((larger.along2(i, j) + 0.5) * 15)] = true;
        }
    for (int k = 0; k < 15; ++k) EXPECT_TRUE(strip1[k] && strip2[k]) << k;
}

TEST(LightSampling, ADiscLightsSamplesAreTheGridMappedOntoTheDisc) {
    Light light;
    light.position = {1, 2, 3}, light.edge1 = {2, 0, 0}, light.edge2 = {0, 0, 4};
    light.samples1 = 5, light.samples2 = 5;
    light.shape = Light::Shape::Disc;
    const LightSamples disc(light, 0, Vec3(0, 0, 0));
    // Shirley and Chiu: (x, y) with |x| > |y| goes to radius |x| at angle (pi/4)(y/x) (x < 0: the
    // other side); else radius |y| at pi/2 - (pi/4)(x/y). Sample (4, 2) is (x, y) = (1, 0).
    EXPECT_NEAR(glm::length(disc.position(4, 2) - dvec3(2, 2, 3)), 0, 1e-15);  // along edge1, half of it
    EXPECT_NEAR(glm::length(disc.position(2, 2) - dvec3(1, 2, 3)), 0, 1e-15);  // the centre
    const dvec3 corner = disc.position(4, 4);                                  // (1, 1): radius 1 at 45 degrees
    const double c = std::sqrt(0.5);
    EXPECT_NEAR(glm::length(corner - dvec3(1 + c, 2, 3 + 2 * c)), 0, 1e-15);
    const dvec3 off = disc.position(3, 0);  // (0.5, -1): radius 1 at pi/2 + pi/8, through y = -1
    const double angle = 3.14159265358979323846 / 2 - 3.14159265358979323846 / 4 * (0.5 / -1);
    EXPECT_NEAR(glm::length(off - dvec3(1 - std::cos(angle), 2, 3 - 2 * std::sin(angle))), 0, 1e-15);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            const dvec3 d = disc.position(i, j) - light.position;
            EXPECT_LE((d.x / 1) * (d.x / 1) + (d.z / 2) * (d.z / 2), 1 + 1e-12);  // inside the ellipse
        }
}

TEST(LightSampling, ASphereLightsSamplesFaceEachPoint) {
    Light light;
    light.position = {0, 5, 0}, light.edge1 = {1, 0, 0}, light.edge2 = {0, 1, 0};
    light.samples1 = 4, light.samples2 = 4;
    light.shape = Light::Shape::Sphere;
    for (const Vec3 point : {Vec3(0, 0, 0), Vec3(3, 1, -2), Vec3(0, 9, 0.5)}) {
        const LightSamples sphere(light, 0, point);
        const dvec3 towards = glm::normalize(dvec3(point) - light.position);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const dvec3 d = sphere.position(i, j) - light.position;
                EXPECT_NEAR(glm::dot(d, towards), 0, 1e-12);  // on the outline's disc, across the line
                EXPECT_LE(glm::length(d), 0.5 + 1e-12);       // within the radius
            }
    }
}

TEST(LightSampling, ADiscLightRendersAsItsSamplesAsPointLights) {
    const std::string light =
        "area_light { position (0.5, 4, 0.5) edge1 (2, 0, 0) edge2 (0, 0.5, 2) samples1 5 samples2 4 shape disc "
        "color 0.9 }\n";
    Light disc;
    disc.position = {0.5, 4, 0.5}, disc.edge1 = {2, 0, 0}, disc.edge2 = {0, 0.5, 2};
    disc.samples1 = 5, disc.samples2 = 4, disc.shape = Light::Shape::Disc;
    const LightSamples samples(disc, 0, Vec3(0));
    std::string points;
    char line[256];
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 4; ++j) {
            const dvec3 p = samples.position(i, j);
            std::snprintf(line, sizeof line, "light { position (%.17g, %.17g, %.17g) color %.17g }\n", p.x, p.y, p.z,
                          0.9 / 20);
            points += line;
        }
    const Image area = render_text(light), separate = render_text(points);
    ASSERT_EQ(area.rgb.size(), separate.rgb.size());
    for (size_t k = 0; k < area.rgb.size(); ++k) EXPECT_NEAR(area.rgb[k], separate.rgb[k], 1e-12) << k;
}

TEST(LightSampling, AJitteredImageIsTheSameOnAnyThreadsAndInAnyWindow) {
    const std::string light = lamp(6, "jitter true");
    const Image one = render_text(light, 1), two = render_text(light, 2), four = render_text(light, 4);
    EXPECT_TRUE(one.rgb == two.rgb);
    EXPECT_TRUE(one.rgb == four.rgb);
    const PixelRect window{10, 7, 20, 15};
    const Image part = render_text(light, 2, window);
    ASSERT_EQ(part.rgb.size(), size_t(20 * 15 * 3));
    for (int y = 0; y < 15; ++y)
        for (int x = 0; x < 20; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(part.rgb[(size_t(y) * 20 + size_t(x)) * 3 + size_t(c)],
                          one.rgb[(size_t(y + 7) * 48 + size_t(x + 10)) * 3 + size_t(c)]);
    // And it is not the grid's image: the samples moved.
    EXPECT_FALSE(one.rgb == render_text(lamp(6, "")).rgb);
}

TEST(LightSampling, AdaptiveTakesARegionWhoseCornersAgreeOnlyWhenNothingThinLiesBetween) {
    // A wide sphere and a box: regions lit at their corners are taken whole, some traced rays saved.
    RenderStats grid_stats, adaptive_stats;
    const Image grid = render_text(lamp(8, ""), 2, {}, &grid_stats);
    const Image adaptive = render_text(lamp(8, "adaptive true"), 2, {}, &adaptive_stats);
    EXPECT_LT(adaptive_stats.rays.shadow, grid_stats.rays.shadow * 3 / 4);
    double largest = 0;
    for (size_t k = 0; k < grid.rgb.size(); ++k) largest = std::max(largest, std::abs(grid.rgb[k] - adaptive.rgb[k]));
    EXPECT_LT(largest, 0.1);  // a region taken whole is off by the samples it got wrong, a few of 64
    // A bar thinner than the gaps between the whole light's corners, seen from the floor: every
    // region it may cross is traced sample by sample, so the bar's shadow is the grid's exactly
    // (the old rule, corners alone, took the whole light as lit at points that see it past both
    // ends of the bar).
    const std::string bar = R"(
render { width 40 height 30 }
camera { eye (0, 5, 3) lookat (0, 0, 0) fovy 50 }
plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 } }
box { min (-3, 1.5, -0.03) max (3, 1.55, 0.03) material { kd 0.5 } }
)";
    const std::string light = "area_light { position (0, 4, 0) edge1 (2, 0, 0) edge2 (0, 0, 2) samples1 8 samples2 8 ";
    EXPECT_TRUE(render_scene_text(bar + light + "adaptive true }\n", 2).rgb ==
                render_scene_text(bar + light + "}\n", 2).rgb);
    // The same bar cut from a block round the floor: one shape whose box holds the points shaded
    // (and is wide). Seen from inside, a box says nothing of its shape: never taken as wide. (Seen
    // from outside, it is: a shape that fills little of its box is adaptive sampling's blind spot,
    // so the camera looks at the floor inside the box alone.)
    const std::string joined = R"(
render { width 40 height 30 }
camera { eye (0, 5, 0.01) lookat (0, 0, 0) fovy 15 }
plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.8 } }
difference {
  box { min (-3, -2, -1) max (3, 1.55, 1) material { kd 0.5 } }
  box { min (-3.1, -2.1, -1.1) max (3.1, 1.5, 1.1) material { kd 0.5 } }
  box { min (-3.1, 1.4, 0.03) max (3.1, 1.6, 1.1) material { kd 0.5 } }
  box { min (-3.1, 1.4, -1.1) max (3.1, 1.6, -0.03) material { kd 0.5 } }
}
)";
    EXPECT_TRUE(render_scene_text(joined + light + "adaptive true }\n", 2).rgb ==
                render_scene_text(joined + light + "}\n", 2).rgb);
}

}  // namespace
}  // namespace tracer
