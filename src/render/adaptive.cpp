#include "render/adaptive.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

namespace tracer {

namespace {

// `cell` pixels (a power of two in [2^-depth, 16]) in lattice steps of 2^-depth pixels: exact.
int64_t lattice_steps(double cell, int depth) {
    return std::llround(std::ldexp(cell, depth));
}

}  // namespace

AdaptivePixels::AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                               const std::atomic<bool>* cancel, int x0, int y0, int width, int height)
    : world_(world),
      camera_(camera),
      settings_(settings),
      cancel_(cancel),
      x0_(x0),
      y0_(y0),
      width_(width),
      height_(height),
      shift_(settings.adaptive_depth),
      cells_(int64_t(1) << settings.adaptive_depth),
      step_(Real(1) / Real(int64_t(1) << settings.adaptive_depth)),
      first_cell_(std::max<int64_t>(1, lattice_steps(settings.adaptive_cell, settings.adaptive_depth))),
      cell_pixels_(int(std::max<int64_t>(1, first_cell_ >> settings.adaptive_depth))),
      left_column_(int64_t(x0) / cell_pixels_ * cell_pixels_),
      frame_columns_(int64_t(settings.width) + 1) {
    const int64_t right_column = (int64_t(x0) + width + cell_pixels_ - 1) / cell_pixels_ * cell_pixels_;
    corners_.resize(size_t(2 * cell_pixels_));  // a power of two above the cell row's cell_pixels_ + 1 lines
    for (Line& line : corners_) line.resize(size_t(right_column - left_column_) + 1);
    const size_t line = size_t(width) * size_t(cells_) + 1, side = size_t(cells_) + 1;
    edges_[0].resize(line), edges_[1].resize(line);
    left_.resize(side), right_.resize(side);
    inside_.resize(side * side);
    pixels_.resize(size_t(cell_pixels_) * size_t(width) * 3);
    rays_.resize(size_t((right_column - left_column_) / cell_pixels_) + 1);
    missing_.resize(rays_.size());
}

AdaptivePixels::Slot AdaptivePixels::slot(int64_t x, int64_t y) {
    // Pixel corners in the ring of corner rows; other points of a pixel row's edge on that
    // edge's line; points on a pixel's sides on that side (keyed by the side's place in the
    // frame); the rest inside the pixel being worked out.
    const int64_t mask = cells_ - 1;
    if ((y & mask) == 0) {
        const int64_t row = y >> shift_;
        if ((x & mask) == 0)
            return {&corners_[size_t(row) & (corners_.size() - 1)], size_t((x >> shift_) - left_column_), row};
        return {&edges_[row & 1], size_t(x - int64_t(x0_) * cells_), row};
    }
    if ((x & mask) == 0) {
        const int64_t column = x >> shift_;
        return {column == x_ ? &left_ : &right_, size_t(y - int64_t(y_) * cells_),
                int64_t(y_) * frame_columns_ + column};
    }
    return {&inside_, size_t((y - int64_t(y_) * cells_) * (cells_ + 1) + (x - int64_t(x_) * cells_)), pixel_stamp_};
}

Color AdaptivePixels::sample(int64_t x, int64_t y, RayCounts& counts) {
    const Slot s = slot(x, y);
    if (s.known()) return s.line->colour[s.at];
    s.line->stamp[s.at] = s.stamp;
    // Lattice coordinates times a power of two: exact, so a point has one ray wherever it is asked.
    return s.line->colour[s.at] =
               trace(world_, settings_, camera_.ray_through(Real(x) * step_, Real(y) * step_), counts, cancel_);
}

void AdaptivePixels::split_samples(int64_t x, int64_t y, int64_t half, RayCounts& counts) {
    // The five points a split adds (edge midpoints and center), their rays made before any is
    // traced (a ray made just before the call that takes it stalls the processor on every sample).
    const int64_t points[5][2] = {
        {x + half, y}, {x, y + half}, {x + half, y + half}, {x + 2 * half, y + half}, {x + half, y + 2 * half}};
    Slot missing[5];
    Ray rays[5];
    int count = 0;
    for (const auto& [px, py] : points) {
        const Slot s = slot(px, py);
        if (s.known()) continue;
        missing[count] = s;
        rays[count++] = camera_.ray_through(Real(px) * step_, Real(py) * step_);
    }
    trace_missing(missing, rays, size_t(count), counts);
}

void AdaptivePixels::trace_missing(const Slot* slots, const Ray* rays, size_t count, RayCounts& counts) {
    for (size_t k = 0; k < count; ++k) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
        slots[k].line->colour[slots[k].at] = trace(world_, settings_, rays[k], counts, cancel_);
        slots[k].line->stamp[slots[k].at] = slots[k].stamp;
    }
}

bool AdaptivePixels::must_split(const Color (&corners)[4], int64_t size) const {
    if (size > first_cell_) return true;  // finer than adaptive_cell: always split
    double spread = 0;
    for (int channel = 0; channel < 3; ++channel) {
        double low = 1, high = 0;
        for (const Color& c : corners) {
            const double v = std::clamp(c[channel], 0.0, 1.0);
            low = std::min(low, v), high = std::max(high, v);
        }
        spread = std::max(spread, high - low);
    }
    return spread >= settings_.adaptive_threshold;
}

void AdaptivePixels::row(int y, double* out, RayCounts& counts) {
    const int top = y / cell_pixels_ * cell_pixels_;
    if (top != top_) cell_row(top, counts);
    const double* from = &pixels_[size_t(y - top_) * size_t(width_) * 3];
    std::copy(from, from + size_t(width_) * 3, out);
}

void AdaptivePixels::cell_row(int top, RayCounts& counts) {
    top_ = top;
    split_pixels_.clear();
    // Step 1: the cells' corners on the row's top and bottom edges that neither this thread's
    // cell row before nor anything else traced yet, their rays made before any is traced.
    const int64_t right_column = left_column_ + int64_t(rays_.size() - 1) * cell_pixels_;
    for (const int64_t edge : {int64_t(top), int64_t(top) + cell_pixels_}) {
        size_t count = 0;
        for (int64_t column = left_column_; column <= right_column; column += cell_pixels_) {
            const Slot s = slot(column * cells_, edge * cells_);
            if (s.known()) continue;
            rays_[count] = camera_.ray_through(Real(column), Real(edge));
            missing_[count++] = s;
        }
        trace_missing(missing_.data(), rays_.data(), count, counts);
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
    }
    // Step 2: the cells, left to right; those split down to single pixels leave them in split_pixels_.
    const int64_t size = int64_t(cell_pixels_) * cells_;
    for (int64_t column = left_column_; column <= right_column - cell_pixels_; column += cell_pixels_) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
        coarse_cell(column * cells_, int64_t(top) * cells_, size, counts);
    }
    // Step 3: those pixels in row order, each passing its right side to the next.
    std::sort(split_pixels_.begin(), split_pixels_.end());
    for (const auto& [y, x] : split_pixels_) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
        const Color c = pixel(x, y, counts);
        double* out = pixel_out(x, y);
        out[0] = c.r, out[1] = c.g, out[2] = c.b;
    }
}

void AdaptivePixels::coarse_cell(int64_t x, int64_t y, int64_t size, RayCounts& counts) {
    // A cell with no pixel of the region in it is left alone.
    const int64_t px = x >> shift_, py = y >> shift_, pixels = size >> shift_;
    if (px >= x0_ + width_ || px + pixels <= x0_ || py >= y0_ + height_ || py + pixels <= y0_) return;
    if (size == cells_) {  // a pixel: its own cells decide
        split_pixels_.emplace_back(int(py), int(px));
        return;
    }
    const Color corners[4] = {sample(x, y, counts), sample(x + size, y, counts), sample(x, y + size, counts),
                              sample(x + size, y + size, counts)};
    if (must_split(corners, size)) {
        const int64_t half = size / 2;
        split_samples(x, y, half, counts);
        coarse_cell(x, y, half, counts), coarse_cell(x + half, y, half, counts);
        coarse_cell(x, y + half, half, counts), coarse_cell(x + half, y + half, half, counts);
        return;
    }
    // Left whole: each pixel of the region in it takes the corners' bilinear blend at its center.
    const int64_t row_end = std::min<int64_t>(py + pixels, y0_ + height_);
    const int64_t column_end = std::min<int64_t>(px + pixels, x0_ + width_);
    for (int64_t row = std::max<int64_t>(py, y0_); row < row_end; ++row)
        for (int64_t column = std::max<int64_t>(px, x0_); column < column_end; ++column) {
            const double u = (double(column - px) + 0.5) / double(pixels),
                         v = (double(row - py) + 0.5) / double(pixels);
            const Color c = corners[0] * ((1 - u) * (1 - v)) + corners[1] * (u * (1 - v)) + corners[2] * ((1 - u) * v) +
                            corners[3] * (u * v);
            double* out = pixel_out(int(column), int(row));
            out[0] = c.r, out[1] = c.g, out[2] = c.b;
        }
}

Color AdaptivePixels::pixel(int x, int y, RayCounts& counts) {
    // The left side is the pixel before's right side if that pixel was (x - 1, y) (its stamp says).
    x_ = x, y_ = y;
    std::swap(left_, right_);
    ++pixel_stamp_;
    return cell(int64_t(x) * cells_, int64_t(y) * cells_, cells_, counts);
}

// The cell of the current pixel with corners (x, y) and (x + size, y + size), in lattice steps.
Color AdaptivePixels::cell(int64_t x, int64_t y, int64_t size, RayCounts& counts) {
    const Color corners[4] = {sample(x, y, counts), sample(x + size, y, counts), sample(x, y + size, counts),
                              sample(x + size, y + size, counts)};
    if (size > 1 && !(cancel_ && cancel_->load(std::memory_order_relaxed)) && must_split(corners, size)) {
        const int64_t half = size / 2;
        split_samples(x, y, half, counts);
        return (cell(x, y, half, counts) + cell(x + half, y, half, counts) + cell(x, y + half, half, counts) +
                cell(x + half, y + half, half, counts)) *
               0.25;
    }
    return (corners[0] + corners[1] + corners[2] + corners[3]) * 0.25;
}

}  // namespace tracer
