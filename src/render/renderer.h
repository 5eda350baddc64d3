// The render loop: every pixel of the image, on every core. Rows are handed out one at a
// time from a shared counter (dynamic scheduling), so a slow row never idles a thread.
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include "accel/world.h"
#include "base/image.h"
#include "render/whitted.h"
#include "scene/scene.h"

namespace tracer {

// A rectangle of pixels: columns x0 .. x0 + width - 1, rows y0 .. y0 + height - 1.
struct PixelRect {
    int x0 = 0, y0 = 0, width = 0, height = 0;
};

struct RenderOptions {
    int threads = 0;  // 0: one per hardware thread (base/parallel.h's arena, kept between renders)
    // Only these pixels are traced, and the image holds just them (a window of the frame, each
    // pixel as the whole frame's render has it); width 0 means the whole frame.
    PixelRect crop;
    // Called now and then from a worker with the finished fraction in [0, 1].
    std::function<void(double)> progress;
    // When set to true, workers stop within a few hundred rays and render() returns false.
    const std::atomic<bool>* cancel = nullptr;
    // When set, the pixels go here as floats (the crop's width x height x 3, row 0 at the top)
    // and the image holds no pixels of its own: the Python module's arrays, with no image of
    // doubles beside them.
    float* float_pixels = nullptr;
};

struct RenderStats {
    double seconds = 0;  // the render loop: first row started to last row done (no image set-up)
    int threads = 0;
    RayCounts rays;
};

// Renders the world as the scene's camera and render settings say into `image` (the crop's
// window of the frame, or all of it); false if cancelled (the image is then incomplete).
bool render(const World& world, const SceneDescription& scene, const RenderOptions& options, Image& image,
            RenderStats& stats);

}  // namespace tracer
