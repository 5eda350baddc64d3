// Splitting a loop over [0, n) across the cores, for the per-primitive setup work of builds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace tracer {

// Calls body(i) for every i in [0, n), in contiguous chunks on up to one thread per core.
// Small loops run on the calling thread alone.
template <typename Body>
void parallel_for(size_t n, Body body) {
    constexpr size_t kSerialBelow = 20000;
    const size_t threads = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), 8);
    if (n < kSerialBelow || threads == 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    const size_t chunk = (n + threads - 1) / threads;
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (size_t i = t * chunk; i < std::min(n, (t + 1) * chunk); ++i) body(i);
        });
    for (size_t i = 0; i < std::min(n, chunk); ++i) body(i);
    for (std::thread& thread : pool) thread.join();
}

}  // namespace tracer
