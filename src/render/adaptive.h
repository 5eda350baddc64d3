// Adaptive antialiasing (render { antialias adaptive }), after Whitted (1980) and POV-Ray's
// method 2: a pixel's colour is worked out from samples at the corners of its cells. A cell
// whose four corners differ by at least the threshold in some channel (each clamped to [0, 1])
// is split into four, down to `adaptive_depth` levels; a cell left whole is the mean of its
// corners, a split one the mean of its four quarters.
//
// Every sample sits on one lattice over the whole frame, 2^depth points per pixel side, and its
// colour depends on nothing but its lattice point: neighbours share their edges' samples, and
// the image is the same for any thread count, row order, tile or region (what is kept between
// pixels and rows only saves rays, it never changes a value).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "accel/world.h"
#include "render/camera.h"
#include "render/whitted.h"
#include "scene/scene.h"

namespace tracer {

class AdaptivePixels {
public:
    // For the pixels x0 .. x0 + width - 1 of any row.
    AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                   const std::atomic<bool>* cancel, int x0, int width);

    // Row y's pixels into out (3 doubles each). Rows taken in order (y, y + 1, ...) share their
    // edge: the samples on it are traced once. Every sample is traced by the same call
    // (ray_through): a row's rays made together (row_directions) may round differently.
    void row(int y, double* out, RayCounts& counts);

private:
    // The samples on one lattice line: an entry is valid if its stamp is the line's.
    struct Line {
        std::vector<Color> colour;
        std::vector<int64_t> stamp;
        void resize(size_t n) { colour.resize(n), stamp.assign(n, INT64_MIN); }  // none valid
    };
    // Where a pixel-local lattice point's sample is kept, and the stamp that makes it valid.
    struct Slot {
        Line* line;
        size_t at;
        int64_t stamp;
    };
    Slot slot(int64_t i, int64_t j);
    Color sample(int64_t i, int64_t j, RayCounts& counts);  // pixel-local lattice point
    // Traces the points that splitting the cell (i, j) of side 2 half adds, if not known.
    void split_samples(int64_t i, int64_t j, int64_t half, RayCounts& counts);
    Color cell(int64_t i, int64_t j, int64_t size, RayCounts& counts);
    Color trace_at(int64_t x, int64_t y, RayCounts& counts) const;

    const World& world_;
    const PinholeCamera& camera_;
    const RenderSettings& settings_;
    const std::atomic<bool>* cancel_;
    const int x0_, width_;
    const int64_t cells_;  // lattice steps per pixel side: 2^depth
    const Real step_;      // 1 / cells_, exact

    // The row being rendered (y_) and pixel (x_); the top and bottom edges of the row (lattice
    // columns from x0_), the left and right edges and the inside of the pixel.
    int y_ = 0, x_ = 0;
    int64_t pixel_stamp_ = 0;
    Line top_, bottom_, left_, right_, inside_;
    std::vector<Ray> rays_;  // an edge's pixel corners
};

}  // namespace tracer
