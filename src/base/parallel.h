// Splitting a loop over [0, n) across the cores, for the per-primitive setup work of builds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>

#include "base/worker_pool.h"

namespace tracer {

// The number of threads to use when the caller asked for `requested` (0: one per core).
inline int thread_count(int requested) {
    // Read once: glibc's hardware_concurrency opens and reads a sysfs file on every call, and
    // small loops ask for every shape (10^6 quads spent 64% of their load in those calls).
    static const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
    return requested > 0 ? requested : hardware;
}

// Loops shorter than this run on the calling thread alone: starting threads costs more.
constexpr size_t kSerialBelow = 20000;

// Calls body(i) for every i in [0, n), in contiguous chunks on `threads` threads (0: one per
// core). Loops shorter than `serial_below` run on the calling thread alone.
template <typename Body>
void parallel_for(size_t n, Body body, int threads_wanted = 0, size_t serial_below = kSerialBelow) {
    const size_t threads = size_t(std::min(thread_count(threads_wanted), 8));
    if (n < serial_below || threads == 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    const size_t chunk = (n + threads - 1) / threads;
    WorkerPool pool{int(threads)};
    pool.run([&](int t) {
        for (size_t i = size_t(t) * chunk; i < std::min(n, size_t(t + 1) * chunk); ++i) body(i);
    });
}

}  // namespace tracer
