// Splitting a loop over [0, n) across the cores, for the per-primitive setup work of builds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include "base/parallel.h"

namespace tracer {

// oneTBB's arena of `threads` threads for builds, made once for each count asked for and kept
// to the end (never destroyed: oneTBB may be gone by then). An arena made per build cost the
// first builds of a process most: the bunny's (3,674 triangles) 1.2x, gears' 1.05x.
inline tbb::task_arena& build_arena(int threads) {
    static std::mutex guard;
    static auto* arenas = new std::map<int, std::unique_ptr<tbb::task_arena>>;
    const std::lock_guard lock(guard);
    auto& arena = (*arenas)[threads];
    if (!arena) arena = std::make_unique<tbb::task_arena>(threads);
    return *arena;
}

// Loops shorter than this run on the calling thread alone: handing out work costs more.
constexpr size_t kSerialBelow = 20000;

// Calls body(i) for every i in [0, n), in one contiguous chunk per thread on `threads_wanted`
// threads (0: one per core). Loops shorter than `serial_below` run on the calling thread alone.
// oneTBB's threads live from one loop to the next: starting threads for each loop, as this did
// with a WorkerPool of its own, cost gears' build (36,610 triangles, five loops) a millisecond.
template <typename Body>
void parallel_for(size_t n, Body body, int threads_wanted = 0, size_t serial_below = kSerialBelow) {
    const int threads = std::min(thread_count(threads_wanted), 8);
    if (n < serial_below || threads == 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    build_arena(threads).execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, n),
            [&](const tbb::blocked_range<size_t>& chunk) {
                for (size_t i = chunk.begin(); i != chunk.end(); ++i) body(i);
            },
            tbb::static_partitioner());
    });
}

}  // namespace tracer
