// How many cases a sweep of a test tries: all of them in the release build, a fraction under
// the sanitizers, where each case costs ten times as much and finding a memory error needs
// the code paths, not the numbers of cases (the debug test preset sets TRACER_SWEEP_FRACTION).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <utility>
#include <vector>

namespace tracer {

// The fraction of each sweep tried: TRACER_SWEEP_FRACTION (a number in (0, 1]) where it is
// set, else 1.
inline double sweep_fraction() {
    static const double fraction = [] {
        const char* text = std::getenv("TRACER_SWEEP_FRACTION");
        const double value = text ? std::atof(text) : 1.0;
        return value > 0 && value <= 1 ? value : 1.0;
    }();
    return fraction;
}

// `full` cases, or sweep_fraction() of them, rounded up.
inline size_t sweep(size_t full) {
    return size_t(std::ceil(double(full) * sweep_fraction()));
}

// True for case `i` of a sweep whose every case is cheap but some have a costly cross-check
// (testing every triangle): every case at full size, every (1 / fraction)th one otherwise.
inline bool in_sweep(size_t i) {
    static const size_t stride = std::max<size_t>(1, size_t(std::lround(1 / sweep_fraction())));
    return i % stride == 0;
}

// Keeps sweep(items.size()) of `items`, spread evenly over them (all of them at full size).
template <typename T>
void thin_to_sweep(std::vector<T>& items) {
    const size_t keep = sweep(items.size());
    if (keep == items.size()) return;
    std::vector<T> kept;
    kept.reserve(keep);
    for (size_t i = 0; i < keep; ++i) kept.push_back(items[i * items.size() / keep]);
    items = std::move(kept);
}

}  // namespace tracer
