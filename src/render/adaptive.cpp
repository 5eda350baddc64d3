#include "render/adaptive.h"

#include <algorithm>
#include <iterator>

namespace tracer {

AdaptivePixels::AdaptivePixels(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                               const std::atomic<bool>* cancel)
    : world_(world),
      camera_(camera),
      settings_(settings),
      cancel_(cancel),
      cells_(int64_t(1) << settings.adaptive_depth),
      step_(Real(1) / Real(int64_t(1) << settings.adaptive_depth)) {}

void AdaptivePixels::begin_row(int y) {
    if (y != row_ + 1) {
        samples_.clear();
    } else {
        // Only the top edge of row y (the bottom edge of the row before) is shared from now on.
        const int64_t top = int64_t(y) * cells_;
        std::erase_if(samples_, [&](const auto& entry) { return int64_t(entry.first >> 32) < top; });
    }
    row_ = y;
}

Color AdaptivePixels::sample(int64_t x, int64_t y, RayCounts& counts) {
    const uint64_t key = uint64_t(y) << 32 | uint64_t(x);
    if (auto known = samples_.find(key); known != samples_.end()) return known->second;
    // Lattice coordinates times a power of two: exact, so a point has one ray wherever it is asked.
    const Color c = trace(world_, settings_, camera_.ray_through(Real(x) * step_, Real(y) * step_), counts, cancel_);
    samples_.emplace(key, c);
    return c;
}

// The cell with corners (x, y) and (x + size, y + size) on the lattice.
Color AdaptivePixels::cell(int64_t x, int64_t y, int64_t size, RayCounts& counts) {
    const Color corners[4] = {sample(x, y, counts), sample(x + size, y, counts), sample(x, y + size, counts),
                              sample(x + size, y + size, counts)};
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
            return (cell(x, y, half, counts) + cell(x + half, y, half, counts) + cell(x, y + half, half, counts) +
                    cell(x + half, y + half, half, counts)) *
                   0.25;
        }
    }
    return (corners[0] + corners[1] + corners[2] + corners[3]) * 0.25;
}

Color AdaptivePixels::pixel(int x, int y, RayCounts& counts) {
    return cell(int64_t(x) * cells_, int64_t(y) * cells_, cells_, counts);
}

}  // namespace tracer
