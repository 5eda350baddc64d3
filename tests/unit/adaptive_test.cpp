// Adaptive antialiasing (render/adaptive.h): threshold 0 is the full corner grid, bit for bit;
// a flat image takes one sample per pixel corner; the image does not depend on threads, row
// bands or regions.
#include <gtest/gtest.h>

#include <cstdint>

#include "lang/load_scene.h"
#include "render/camera.h"
#include "render/renderer.h"

namespace tracer {
namespace {

// A mirror sphere over a chequer of quads, a light: edges, shadows and reflections to split on.
const char* kScene = R"(
camera { eye (0, 1.5, 5) lookat (0, 0.3, 0) fovy 40 }
light { position (2, 4, 3) }
for i in 0..6 { for j in 0..6 {
  quad { corner (i - 3, 0, j - 3) edge1 (0, 0, 1) edge2 (1, 0, 0)
         material { kd 0.1 + 0.8 * mod(i + j, 2) } }
} }
sphere { center (0, 0.8, 0) radius 0.8 material { kd 0.1 ks 0.5 n 30 km 0.6 } }
render { width 40 height 30 antialias adaptive }
)";

struct Loaded {
    SceneDescription scene;
    std::unique_ptr<World> world;
};

Loaded load(const std::string& text, double threshold, int depth) {
    LoadResult loaded = load_scene_text("adaptive.scn", text);
    EXPECT_TRUE(loaded.scene);
    Loaded out{std::move(*loaded.scene), nullptr};
    out.scene.render.adaptive_threshold = threshold;
    out.scene.render.adaptive_depth = depth;
    out.world = std::make_unique<World>(out.scene);
    return out;
}

RenderOptions on(int threads, PixelRect crop = {}) {
    RenderOptions options;
    options.threads = threads;
    options.crop = crop;
    return options;
}

Image render_with(const Loaded& s, const RenderOptions& options, RayCounts* rays = nullptr) {
    Image image;
    RenderStats stats;
    EXPECT_TRUE(render(*s.world, s.scene, options, image, stats));
    if (rays) *rays = stats.rays;
    return image;
}

// The cell's colour as adaptive.h defines it, every cell split, each sample traced afresh.
Color full_cell(const Loaded& s, const PinholeCamera& camera, int64_t x, int64_t y, int64_t size, double step) {
    if (size == 1) {
        RayCounts counts;
        auto at = [&](int64_t i, int64_t j) {
            return trace(*s.world, s.scene.render, camera.ray_through(Real(i) * Real(step), Real(j) * Real(step)),
                         counts);
        };
        return (at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1)) * 0.25;
    }
    const int64_t half = size / 2;
    return (full_cell(s, camera, x, y, half, step) + full_cell(s, camera, x + half, y, half, step) +
            full_cell(s, camera, x, y + half, half, step) + full_cell(s, camera, x + half, y + half, half, step)) *
           0.25;
}

TEST(Adaptive, ThresholdZeroIsTheFullCornerGridBitForBit) {
    const int depth = 2;
    const Loaded s = load(kScene, 0.0, depth);
    RayCounts rays;
    const Image image = render_with(s, on(2), &rays);
    const PinholeCamera camera(s.scene.camera, s.scene.render.width, s.scene.render.height);
    const int64_t cells = int64_t(1) << depth;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Color expected = full_cell(s, camera, x * cells, y * cells, cells, 1.0 / double(cells));
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(image.rgb[(size_t(y) * image.width + x) * 3 + c], expected[c]) << x << ", " << y;
        }
    // Every lattice point traced once, but the top edges of the bands a thread did not follow on.
    const uint64_t lattice = uint64_t(40 * cells + 1) * uint64_t(30 * cells + 1);
    EXPECT_GE(rays.primary, lattice);
    EXPECT_LE(rays.primary, lattice + 2 * uint64_t(40 * cells + 1));
}

TEST(Adaptive, AFlatImageTakesOneSamplePerPixelCorner) {
    const Loaded s = load(
        "camera { eye (0, 0, 5) lookat (0, 0, 0) }\nrender { width 33 height 21 background 0.5 antialias adaptive }\n",
        0.01, 4);
    RayCounts rays;
    const Image image = render_with(s, on(1), &rays);
    EXPECT_EQ(rays.primary, uint64_t(34 * 22));
    for (double v : image.rgb) EXPECT_EQ(v, 0.5);
}

TEST(Adaptive, TheImageDoesNotDependOnThreadsBandsOrRegions) {
    const Loaded s = load(kScene, 0.02, 3);
    const Image whole = render_with(s, on(1));
    EXPECT_EQ(render_with(s, on(2)).rgb, whole.rgb);
    // Windows that cut rows and bands anywhere: each pixel as the whole frame has it.
    for (const PixelRect crop : {PixelRect{0, 0, 40, 30}, PixelRect{7, 3, 19, 23}, PixelRect{39, 17, 1, 13}}) {
        const Image part = render_with(s, on(2, crop));
        for (int y = 0; y < crop.height; ++y)
            for (int x = 0; x < crop.width; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(part.rgb[(size_t(y) * crop.width + x) * 3 + c],
                              whole.rgb[(size_t(crop.y0 + y) * 40 + crop.x0 + x) * 3 + c]);
    }
}

TEST(Adaptive, SplitsOnlyWhereTheImageChanges) {
    // Against the full grid at the same depth: far fewer rays, and the pixels it left whole
    // were flat at the corners.
    const Loaded s = load(kScene, 0.02, 3);
    RayCounts adaptive_rays, full_rays;
    render_with(s, on(1), &adaptive_rays);
    const Loaded full = load(kScene, 0.0, 3);
    render_with(full, on(1), &full_rays);
    EXPECT_LT(adaptive_rays.primary * 4, full_rays.primary);
    EXPECT_GT(adaptive_rays.primary, uint64_t(41 * 31));
}

}  // namespace
}  // namespace tracer
