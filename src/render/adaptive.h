// Adaptive antialiasing (render { antialias adaptive }), after Whitted (1980) and POV-Ray's
// method 2: a pixel's colour is worked out from samples at the corners of its cells. A cell
// whose four corners differ by at least the threshold in some channel (each clamped to [0, 1])
// is split into four, down to `adaptive_depth` levels; a cell left whole is the mean of its
// corners, a split one the mean of its four quarters.
//
// Every sample sits on one lattice over the whole frame, 2^depth points per pixel side, and its
// colour depends on nothing but its lattice point: neighbours share their edges' samples, and
// the image is the same for any thread count, row order, tile or region (a cache only saves
// rays, it never changes a value).
#pragma once

#include <atomic>
#include <cstdint>
#include <unordered_map>

#include "accel/world.h"
#include "render/camera.h"
#include "render/whitted.h"
#include "scene/scene.h"

namespace tracer {

class AdaptivePixels {
public:
    AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                   const std::atomic<bool>* cancel);

    // The colour of pixel (x, y). Pixels of one row should come one after another and rows in
    // order: the samples shared with the row before are then kept, not traced again.
    Color pixel(int x, int y, RayCounts& counts);
    // Drops the samples no row from `y` on can share (all of them if `y` does not follow the
    // last row begun).
    void begin_row(int y);

private:
    Color sample(int64_t x, int64_t y, RayCounts& counts);
    Color cell(int64_t x, int64_t y, int64_t size, RayCounts& counts);

    const World& world_;
    const PinholeCamera& camera_;
    const RenderSettings& settings_;
    const std::atomic<bool>* cancel_;
    const int64_t cells_;                          // lattice steps per pixel side: 2^depth
    const Real step_;                              // 1 / cells_, exact
    int row_ = -2;                                 // the row begun last
    std::unordered_map<uint64_t, Color> samples_;  // by lattice point (y << 32 | x)
};

}  // namespace tracer
