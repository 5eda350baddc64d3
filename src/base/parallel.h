// How many threads a request for threads means.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>

namespace tracer {

// The number of threads to use when the caller asked for `requested` (0: one per core).
inline int thread_count(int requested) {
    // Read once: glibc's hardware_concurrency opens and reads a sysfs file on every call, and
    // small loops ask for every shape (10^6 quads spent 64% of their load in those calls).
    static const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
    return requested > 0 ? requested : hardware;
}

}  // namespace tracer
