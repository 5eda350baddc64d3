// Adaptive antialiasing (render/adaptive.h): every pixel is as the definition says, bit for bit;
// threshold 0 is the full corner grid; a flat image takes one sample per cell corner; the image
// does not depend on threads, row bands or regions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

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

Loaded load(const std::string& text, double threshold, int depth, double cell = 1) {
    LoadResult loaded = load_scene_text("adaptive.scn", text);
    EXPECT_TRUE(loaded.scene);
    Loaded out{std::move(*loaded.scene), nullptr};
    out.scene.render.adaptive_threshold = threshold;
    out.scene.render.adaptive_depth = depth;
    out.scene.render.adaptive_cell = cell;
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

// adaptive.h's definition written plainly: pixel (x, y)'s colour, every sample traced afresh.
class Definition {
public:
    explicit Definition(const Loaded& s)
        : s_(s),
          render_(s.scene.render),
          camera_(s.scene.camera, render_.width, render_.height),
          cells_(int64_t(1) << render_.adaptive_depth),
          first_(int64_t(std::ldexp(render_.adaptive_cell, render_.adaptive_depth))) {}

    Color pixel(int x, int y) const {
        // Down the cells of whole pixels that hold (x, y), from the grid's cell, to a cell left
        // whole (the bilinear blend at the pixel's center) or the pixel itself.
        int64_t size = std::max(first_, cells_);
        int64_t cx = int64_t(x) * cells_ / size * size, cy = int64_t(y) * cells_ / size * size;
        while (size > cells_) {
            const Color c[4] = {at(cx, cy), at(cx + size, cy), at(cx, cy + size), at(cx + size, cy + size)};
            if (!split(c, size)) {
                const double u = (double(x * cells_ - cx) + 0.5 * cells_) / double(size);
                const double v = (double(y * cells_ - cy) + 0.5 * cells_) / double(size);
                return c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * ((1 - u) * v) + c[3] * (u * v);
            }
            size /= 2;
            if (x * cells_ >= cx + size) cx += size;
            if (y * cells_ >= cy + size) cy += size;
        }
        return cell(cx, cy, size);
    }

private:
    Color at(int64_t i, int64_t j) const {
        RayCounts counts;
        const Real step = Real(1) / Real(cells_);
        return trace(*s_.world, render_, camera_.ray_through(Real(i) * step, Real(j) * step), counts);
    }
    bool split(const Color (&c)[4], int64_t size) const {
        if (size > first_) return true;
        for (int channel = 0; channel < 3; ++channel) {
            double low = 1, high = 0;
            for (const Color& k : c)
                low = std::min(low, std::clamp(k[channel], 0.0, 1.0)),
                high = std::max(high, std::clamp(k[channel], 0.0, 1.0));
            if (high - low >= render_.adaptive_threshold) return true;
        }
        return false;
    }
    Color cell(int64_t i, int64_t j, int64_t size) const {
        const Color c[4] = {at(i, j), at(i + size, j), at(i, j + size), at(i + size, j + size)};
        if (size == 1 || !split(c, size)) return (c[0] + c[1] + c[2] + c[3]) * 0.25;
        const int64_t h = size / 2;
        return (cell(i, j, h) + cell(i + h, j, h) + cell(i, j + h, h) + cell(i + h, j + h, h)) * 0.25;
    }

    const Loaded& s_;
    const RenderSettings& render_;
    const PinholeCamera camera_;
    const int64_t cells_, first_;
};

TEST(Adaptive, EveryPixelIsAsTheDefinitionSaysBitForBit) {
    // Cells from a quarter pixel to 16 pixels (the image's edges cut cells), thresholds that
    // split some cells and not others.
    for (const auto& [threshold, depth, cell] :
         {std::tuple{0.02, 2, 0.25}, std::tuple{0.05, 3, 1.0}, std::tuple{0.05, 2, 4.0}, std::tuple{0.1, 1, 16.0}}) {
        SCOPED_TRACE(testing::Message() << threshold << ":" << depth << ":" << cell);
        const Loaded s = load(kScene, threshold, depth, cell);
        const Image image = render_with(s, on(2));
        const Definition definition(s);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const Color expected = definition.pixel(x, y);
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(image.rgb[(size_t(y) * image.width + x) * 3 + c], expected[c]) << x << ", " << y;
            }
    }
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

TEST(Adaptive, CellsWiderThanAPixelTakeOneSamplePerCellCorner) {
    // 33 x 21 pixels in cells of 8: corners at columns 0, 8, .., 40 and rows 0, 8, 16, 24.
    const Loaded s = load(
        "camera { eye (0, 0, 5) lookat (0, 0, 0) }\nrender { width 33 height 21 background 0.5 antialias adaptive }\n",
        0.01, 4, 8);
    RayCounts rays;
    const Image image = render_with(s, on(1), &rays);
    EXPECT_EQ(rays.primary, uint64_t(6 * 4));
    for (double v : image.rgb) EXPECT_NEAR(v, 0.5, 1e-15);
    // Under a pixel: every pixel split that far.
    const Loaded fine = load(
        "camera { eye (0, 0, 5) lookat (0, 0, 0) }\nrender { width 33 height 21 background 0.5 antialias adaptive }\n",
        0.01, 4, 0.5);
    render_with(fine, on(1), &rays);
    EXPECT_EQ(rays.primary, uint64_t(67 * 43));
}

TEST(Adaptive, TheImageDoesNotDependOnThreadsBandsOrRegions) {
    for (const double cell : {1.0, 4.0, 16.0}) {
        SCOPED_TRACE(cell);
        const Loaded s = load(kScene, 0.02, 3, cell);
        const Image whole = render_with(s, on(1));
        EXPECT_EQ(render_with(s, on(2)).rgb, whole.rgb);
        // Windows that cut rows, bands and cells anywhere: each pixel as the whole frame has it.
        for (const PixelRect crop : {PixelRect{0, 0, 40, 30}, PixelRect{7, 3, 19, 23}, PixelRect{39, 17, 1, 13}}) {
            const Image part = render_with(s, on(2, crop));
            for (int y = 0; y < crop.height; ++y)
                for (int x = 0; x < crop.width; ++x)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_EQ(part.rgb[(size_t(y) * crop.width + x) * 3 + c],
                                  whole.rgb[(size_t(crop.y0 + y) * 40 + crop.x0 + x) * 3 + c]);
        }
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
