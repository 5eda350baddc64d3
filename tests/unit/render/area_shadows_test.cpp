// An area light's shadow rays searched together (render/area_shadows.h, issue 56): the image is
// the one its samples give as point lights, each with its own full shadow search, in scenes
// that exercise every shortcut: regions lit all through, regions one convex shape blocks all
// through (spheres, closed cones, discs), the rest ray by ray among the candidates; a top level
// searched one by one and one behind a BVH; shadows through glass; meshes, solids and planes.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>

#include "../../common/scene_render.h"

namespace tracer {
namespace {

Image render_text(const std::string& text, RenderStats* stats = nullptr) {
    return render_scene_text(text, 2, {}, stats);
}

struct AreaLight {
    dvec3 position, edge1, edge2;
    int samples1, samples2;
    double color;
};

std::string as_block(const AreaLight& l) {
    std::ostringstream out;
    out.precision(17);
    out << "area_light { position (" << l.position.x << ", " << l.position.y << ", " << l.position.z << ") edge1 ("
        << l.edge1.x << ", " << l.edge1.y << ", " << l.edge1.z << ") edge2 (" << l.edge2.x << ", " << l.edge2.y << ", "
        << l.edge2.z << ") samples1 " << l.samples1 << " samples2 " << l.samples2 << " color " << l.color << " }\n";
    return out.str();
}

std::string as_points(const AreaLight& l) {
    Light light;
    light.position = l.position, light.edge1 = l.edge1, light.edge2 = l.edge2;
    light.samples1 = l.samples1, light.samples2 = l.samples2;
    return samples_as_point_lights(light, l.color);
}

// Random shapes of every kind over a floor: `count` of them (more than 8: a BVH top level).
std::string random_shapes(int count, uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(-1, 1), size(0.15, 0.6);
    std::ostringstream out;
    out.precision(17);
    out << "render { width 64 height 48 transparent_shadows true }\n"
           "camera { eye (0, 7, 6) lookat (0, 0, 0) fovy 50 }\n"
           "plane { point (0, 0, 0) normal (0, 1, 0) material { ka 0.1 kd 0.7 ks 0.2 n 10 } }\n"
           "material glass { kd 0.1 ks 0.5 n 50 kt 0.7 ior 1.5 }\n"
           "material paint { ka 0.1 kd (0.7, 0.4, 0.2) ks 0.4 n 30 }\n";
    for (int k = 0; k < count; ++k) {
        const double x = 3 * unit(random), y = 0.3 + 1.5 * (unit(random) + 1), z = 3 * unit(random), r = size(random);
        const char* material = k % 5 == 4 ? "glass" : "paint";
        switch (k % 6) {
            case 0: out << "sphere { center (" << x << ", " << y << ", " << z << ") radius " << r; break;
            case 1:
                out << "cylinder { base (" << x << ", " << y << ", " << z << ") top (" << x + r << ", " << y + 2 * r
                    << ", " << z << ") radius " << r / 2;
                break;
            case 2:
                out << "disc { center (" << x << ", " << y << ", " << z << ") normal (" << unit(random) << ", 1, "
                    << unit(random) << ") radius " << r;
                break;
            case 3:
                out << "box { min (" << x << ", " << y << ", " << z << ") max (" << x + r << ", " << y + r << ", "
                    << z + 2 * r << ")";
                break;
            case 4:
                out << "cone { base (" << x << ", " << y << ", " << z << ") top (" << x << ", " << y + r << ", " << z
                    << ") base_radius " << r << " top_radius 0";
                break;
            default:
                out << "difference { sphere { center (" << x << ", " << y << ", " << z << ") radius " << r
                    << " material " << material << " } sphere { center (" << x + r / 2 << ", " << y + r / 2 << ", " << z
                    << ") radius " << r / 2 << " material " << material << " }";
                break;
        }
        out << (k % 6 == 5 ? "" : std::string(" material ") + material) << " }\n";
    }
    return out.str();
}

// The area light's image against its samples as point lights: equal to 1e-12 everywhere.
void expect_same_as_points(const std::string& scene, const AreaLight& light) {
    const Image area = render_text(scene + as_block(light));
    const Image points = render_text(scene + as_points(light));
    ASSERT_EQ(area.rgb.size(), points.rgb.size());
    int differing = 0;
    for (size_t k = 0; k < area.rgb.size(); ++k) differing += std::abs(area.rgb[k] - points.rgb[k]) > 1e-12;
    EXPECT_EQ(differing, 0) << "of " << area.rgb.size() << " values";
}

TEST(AreaShadows, ManyShapesBehindABvhGiveTheSamplesImage) {
    const std::string scene = random_shapes(40, 1);
    expect_same_as_points(scene, {{0.3, 6, 0.2}, {2, 0, 0}, {0, 0, 2}, 8, 8, 0.9});
    expect_same_as_points(scene, {{-1, 5, 1}, {1.5, 0.5, 0}, {0, 0.3, 1}, 5, 3, 0.8});
}

TEST(AreaShadows, AFewShapesSearchedOneByOneGiveTheSamplesImage) {
    const std::string scene = random_shapes(7, 2);
    expect_same_as_points(scene, {{0.3, 6, 0.2}, {3, 0, 0}, {0, 0, 3}, 8, 8, 0.9});
    expect_same_as_points(scene, {{1, 4, -1}, {0, 0, 2}, {2, 0, 0}, 16, 2, 0.8});  // lopsided grid
    expect_same_as_points(scene, {{1, 4, -1}, {0, 0, 2}, {2, 0, 0}, 1, 9, 0.8});   // one row
}

TEST(AreaShadows, ALightAmongTheShapesGivesTheSamplesImage) {
    // Points on both sides of the light, and shapes above and below it.
    const std::string scene = random_shapes(24, 3);
    expect_same_as_points(scene, {{0, 1.5, 0}, {4, 0, 0}, {0, 0.5, 4}, 8, 8, 0.9});
}

TEST(AreaShadows, RegionsAreDecidedWithoutARayForEachSample) {
    // A lamp over a table top (a closed cylinder: convex): under it, four corner rays settle a
    // whole region; far from it, no ray at all.
    const std::string scene =
        "render { width 64 height 48 }\ncamera { eye (0, 6, 8) lookat (0, 0, 0) fovy 60 }\n"
        "plane { point (0, 0, 0) normal (0, 1, 0) material { kd 0.7 } }\n"
        "cylinder { base (0, 1, 0) top (0, 1.1, 0) radius 1.5 material { kd 0.5 } }\n";
    const AreaLight lamp{{0, 3, 0}, {1, 0, 0}, {0, 0, 1}, 8, 8, 0.9};
    RenderStats area_stats, points_stats;
    const Image area = render_text(scene + as_block(lamp), &area_stats);
    const Image points = render_text(scene + as_points(lamp), &points_stats);
    for (size_t k = 0; k < area.rgb.size(); ++k) ASSERT_NEAR(area.rgb[k], points.rgb[k], 1e-12) << k;
    EXPECT_LT(area_stats.rays.shadow * 10, points_stats.rays.shadow)
        << area_stats.rays.shadow << " against " << points_stats.rays.shadow;
}

}  // namespace
}  // namespace tracer
