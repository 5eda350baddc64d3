// Adaptive antialiasing (render { antialias adaptive }), after Whitted (1980) and POV-Ray's
// method 2: the image is worked out from samples at the corners of cells. Cells start
// `adaptive_cell` pixels wide (a power of two; 1: a pixel); a cell whose four corners differ by
// at least the threshold in some channel (each clamped to [0, 1]) is split into four, down to
// 1 / 2^adaptive_depth of a pixel. A pixel inside a cell left whole takes the cell's bilinear
// blend of its corners at the pixel's center (for a cell of one pixel, the mean of its
// corners); a split pixel is the mean of its four quarters. Cells under `adaptive_cell` are
// always split.
//
// Every sample sits on one lattice over the whole frame, 2^depth points per pixel side, cells
// on one grid from the frame's corner, and a sample's colour depends on nothing but its lattice
// point: neighbours share their edges' samples, and the image is the same for any thread
// count, row order, tile or region (what is kept between cells and rows only saves rays, it
// never changes a value).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "accel/world.h"
#include "render/camera.h"
#include "render/whitted.h"
#include "scene/scene.h"

namespace tracer {

// The rows of cells, in pixels: a band of rows handed to a thread starts at a multiple of it.
inline constexpr int kMostAdaptiveCell = 16;

class AdaptivePixels {
public:
    // For the pixels x0 .. x0 + width - 1, y0 .. y0 + height - 1 of the frame.
    AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                   const std::atomic<bool>* cancel, int x0, int y0, int width, int height);

    // Row y's pixels into out (3 doubles each). Rows taken in order (y, y + 1, ...) share their
    // cells and edges: the samples on them are traced once. Every sample is traced by the same
    // call (ray_through): a row's rays made together (row_directions) may round differently.
    void row(int y, double* out, RayCounts& counts);

private:
    // The samples on one lattice line: an entry is valid if its stamp is the line's.
    struct Line {
        std::vector<Color> colour;
        std::vector<int64_t> stamp;
        void resize(size_t n) { colour.resize(n), stamp.assign(n, INT64_MIN); }  // none valid
    };
    // Where a lattice point's sample is kept, and the stamp that makes it valid.
    struct Slot {
        Line* line;
        size_t at;
        int64_t stamp;
        bool known() const { return line->stamp[at] == stamp; }
    };
    Slot slot(int64_t x, int64_t y);  // lattice coordinates over the frame
    Color sample(int64_t x, int64_t y, RayCounts& counts);
    // Traces the points that splitting the cell at (x, y) of side 2 half adds, if not known.
    void split_samples(int64_t x, int64_t y, int64_t half, RayCounts& counts);
    // Traces rays[k] for each of the `count` samples in `slots` and keeps its colour there.
    void trace_missing(const Slot* slots, const Ray* rays, size_t count, RayCounts& counts);
    // The cells of the rows top .. top + cell_pixels_ - 1 into pixels_.
    void cell_row(int top, RayCounts& counts);
    // A cell of whole pixels (lattice corner (x, y), side size): split, blended or a pixel.
    void coarse_cell(int64_t x, int64_t y, int64_t size, RayCounts& counts);
    // The pixel (x, y) from its own cells (the pixel's corner is (x, y) * cells_).
    Color pixel(int x, int y, RayCounts& counts);
    Color cell(int64_t x, int64_t y, int64_t size, RayCounts& counts);
    bool must_split(const Color (&corners)[4], int64_t size) const;
    double* pixel_out(int x, int y) { return &pixels_[(size_t(y - top_) * size_t(width_) + size_t(x - x0_)) * 3]; }

    const World& world_;
    const PinholeCamera& camera_;
    const RenderSettings& settings_;
    const std::atomic<bool>* cancel_;
    const int x0_, y0_, width_, height_;
    const int shift_;              // adaptive_depth
    const int64_t cells_;          // lattice steps per pixel side: 2^depth
    const Real step_;              // 1 / cells_, exact
    const int64_t first_cell_;     // the side of the cells sampling starts from, in lattice steps
    const int cell_pixels_;        // ... in pixels, at least one
    const int64_t left_column_;    // the first pixel column of the cells that cover x0
    const int64_t frame_columns_;  // pixel columns of the frame, plus one (keys of pixel sides)

    // The cell row being worked on (top_), its pixels (3 doubles each, cell_pixels_ rows), and
    // the pixels that take their own cells (in row order).
    int top_ = INT32_MIN;
    std::vector<double> pixels_;
    std::vector<std::pair<int, int>> split_pixels_;
    // The samples at pixel corners (a ring of lattice rows, one per pixel row), between pixel
    // corners on pixel rows' edges (two rows), on the left and right sides of the pixel being
    // worked out (x_, y_), and inside it.
    std::vector<Line> corners_;
    Line edges_[2], left_, right_, inside_;
    int x_ = 0, y_ = 0;
    int64_t pixel_stamp_ = 0;
    std::vector<Ray> rays_;      // a cell row's first corners not yet traced
    std::vector<Slot> missing_;  // ... and where they are kept
};

}  // namespace tracer
