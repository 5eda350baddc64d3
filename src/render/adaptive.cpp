#include "render/adaptive.h"

#include <algorithm>
#include <climits>
#include <utility>

namespace tracer {

AdaptivePixels::AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                               const std::atomic<bool>* cancel, int x0, int width)
    : world_(world),
      camera_(camera),
      settings_(settings),
      cancel_(cancel),
      x0_(x0),
      width_(width),
      cells_(int64_t(1) << settings.adaptive_depth),
      step_(Real(1) / Real(int64_t(1) << settings.adaptive_depth)) {
    const size_t line = size_t(width) * size_t(cells_) + 1, side = size_t(cells_) + 1;
    top_.resize(line), bottom_.resize(line);
    left_.resize(side), right_.resize(side);
    inside_.resize(side * side);
    rays_.resize(size_t(width) + 1);
}

Color AdaptivePixels::trace_at(int64_t x, int64_t y, RayCounts& counts) const {
    // Lattice coordinates times a power of two: exact, so a point has one ray wherever it is asked.
    return trace(world_, settings_, camera_.ray_through(Real(x) * step_, Real(y) * step_), counts, cancel_);
}

void AdaptivePixels::row(int y, double* out, RayCounts& counts) {
    // Step 1: the edges. The row before's bottom edge is this one's top edge (stamped with the
    // number of the row whose bottom edge it is). The pixel corners missing from either are
    // traced first, their rays made before any is traced (as uniform sampling does: a ray made
    // just before the call that takes it stalls the processor on every sample).
    std::swap(top_, bottom_);
    y_ = y;
    for (int edge = y; edge <= y + 1; ++edge) {
        Line& line = edge == y ? top_ : bottom_;
        const int64_t stamp = edge - 1;                     // the row whose bottom edge it is
        if (edge == y && line.stamp[0] == stamp) continue;  // shared with the row before
        for (int k = 0; k <= width_; ++k) rays_[size_t(k)] = camera_.ray_through(Real(x0_ + k), Real(edge));
        for (int k = 0; k <= width_; ++k) {
            if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
            const size_t at = size_t(k) * size_t(cells_);
            line.colour[at] = trace(world_, settings_, rays_[size_t(k)], counts, cancel_);
            line.stamp[at] = stamp;
        }
    }
    // Step 2: the pixels, left to right, each passing its right edge to the next.
    ++pixel_stamp_;  // the first pixel has no left neighbour
    for (int x = x0_; x < x0_ + width_; ++x) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return;
        x_ = x;
        std::swap(left_, right_);
        ++pixel_stamp_;
        const Color c = cell(0, 0, cells_, counts);
        double* pixel = out + size_t(x - x0_) * 3;
        pixel[0] = c.r, pixel[1] = c.g, pixel[2] = c.b;
    }
}

AdaptivePixels::Slot AdaptivePixels::slot(int64_t i, int64_t j) {
    // Where the point (i, j) of the pixel is kept: on the row's edges, the pixel's sides, inside.
    Line* line;
    size_t at;
    int64_t stamp;
    if (j == 0 || j == cells_) {
        line = j == 0 ? &top_ : &bottom_;
        at = size_t(x_ - x0_) * size_t(cells_) + size_t(i);
        stamp = j == 0 ? y_ - 1 : y_;
    } else if (i == 0 || i == cells_) {
        line = i == 0 ? &left_ : &right_;
        at = size_t(j);
        stamp = i == 0 ? pixel_stamp_ - 1 : pixel_stamp_;
    } else {
        line = &inside_;
        at = size_t(j) * size_t(cells_ + 1) + size_t(i);
        stamp = pixel_stamp_;
    }
    return {line, at, stamp};
}

Color AdaptivePixels::sample(int64_t i, int64_t j, RayCounts& counts) {
    const Slot s = slot(i, j);
    if (s.line->stamp[s.at] == s.stamp) return s.line->colour[s.at];
    s.line->stamp[s.at] = s.stamp;
    return s.line->colour[s.at] = trace_at(int64_t(x_) * cells_ + i, int64_t(y_) * cells_ + j, counts);
}

void AdaptivePixels::split_samples(int64_t i, int64_t j, int64_t half, RayCounts& counts) {
    // The five points a split adds (edge midpoints and centre), their rays made before any is
    // traced.
    const int64_t points[5][2] = {
        {i + half, j}, {i, j + half}, {i + half, j + half}, {i + 2 * half, j + half}, {i + half, j + 2 * half}};
    Slot missing[5];
    Ray rays[5];
    int count = 0;
    for (const auto& [pi, pj] : points) {
        const Slot s = slot(pi, pj);
        if (s.line->stamp[s.at] == s.stamp) continue;
        missing[count] = s;
        rays[count++] =
            camera_.ray_through(Real(int64_t(x_) * cells_ + pi) * step_, Real(int64_t(y_) * cells_ + pj) * step_);
    }
    for (int k = 0; k < count; ++k) {
        missing[k].line->colour[missing[k].at] = trace(world_, settings_, rays[k], counts, cancel_);
        missing[k].line->stamp[missing[k].at] = missing[k].stamp;
    }
}

// The cell of the current pixel with corners (i, j) and (i + size, j + size).
Color AdaptivePixels::cell(int64_t i, int64_t j, int64_t size, RayCounts& counts) {
    const Color corners[4] = {sample(i, j, counts), sample(i + size, j, counts), sample(i, j + size, counts),
                              sample(i + size, j + size, counts)};
    if (size > 1 && !(cancel_ && cancel_->load(std::memory_order_relaxed))) {
        double spread = 0;
        for (int channel = 0; channel < 3; ++channel) {
            double low = 1, high = 0;
            for (const Color& c : corners) {
                const double v = std::clamp(c[channel], 0.0, 1.0);
                low = std::min(low, v), high = std::max(high, v);
            }
            spread = std::max(spread, high - low);
        }
        if (spread >= settings_.adaptive_threshold) {
            const int64_t half = size / 2;
            split_samples(i, j, half, counts);
            return (cell(i, j, half, counts) + cell(i + half, j, half, counts) + cell(i, j + half, half, counts) +
                    cell(i + half, j + half, half, counts)) *
                   0.25;
        }
    }
    return (corners[0] + corners[1] + corners[2] + corners[3]) * 0.25;
}

}  // namespace tracer
