// The one thread system of tracer: oneTBB's. `--threads N` (0: every core) sets how many
// threads build the BVHs and render the image; each count has one arena, made when first asked
// for and kept, whose threads live from one build or render to the next. The browser's build
// (TRACER_NO_TBB) runs everything on the calling thread: its page renders in a worker of its own.
#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#if !defined(TRACER_NO_TBB)
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_invoke.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#endif

namespace tracer {

// Loops shorter than this run on the calling thread alone: handing out work costs more.
constexpr size_t kSerialBelow = 20000;

#if defined(TRACER_NO_TBB)

// One thread, whatever was asked for.
inline int thread_count(int) {
    return 1;
}

// Nothing to start.
inline void start_threads(int) {}

// Runs `work` on the calling thread.
template <typename Work>
void run_on_threads(int, const Work& work) {
    work();
}

// Runs `first`, then `second`.
template <typename First, typename Second>
void run_both(const First& first, const Second& second) {
    first();
    second();
}

// Calls body(i) for every i in [0, n), in order.
template <typename Body>
void parallel_for(size_t n, Body body, int = 0, size_t = kSerialBelow) {
    for (size_t i = 0; i < n; ++i) body(i);
}

// Runs job(0) (one worker).
template <typename Job>
void run_workers(int, const Job& job) {
    job(0);
}

#else

// The number of threads to use when the caller asked for `requested` (0: one per core).
inline int thread_count(int requested) {
    // Read once: glibc's hardware_concurrency opens and reads a sysfs file on every call, and
    // small loops ask for every shape (docs/bench/code-figures.md).
    static const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
    return requested > 0 ? requested : hardware;
}

// oneTBB's arena of `threads` threads, made once for each count asked for and kept to the end
// (never destroyed: oneTBB may be gone by then): an arena made per build slowed the first
// builds of a process most (docs/bench/code-figures.md).
inline tbb::task_arena& thread_arena(int threads) {
    static std::mutex guard;
    static auto* arenas = new std::map<int, std::unique_ptr<tbb::task_arena> >;
    const std::lock_guard lock(guard);
    auto& arena = (*arenas)[threads];
    if (!arena) arena = std::make_unique<tbb::task_arena>(threads);
    return *arena;
}

// Starts the arena of `threads` threads (0: one per core) in the background, so that its
// threads exist by the time the first build or render asks for them: the first use of an arena
// otherwise waits for them to be made.
inline void start_threads(int threads) {
    const int count = thread_count(threads);
    if (count > 1) thread_arena(count).enqueue([] {});
}

// Runs `work` inside the arena of `threads` threads (0: one per core), so that the parallel
// loops and run_both calls it makes share those threads; returns when it has returned.
template <typename Work>
void run_on_threads(int threads, const Work& work) {
    thread_arena(thread_count(threads)).execute(work);
}

// Runs `first` and `second`, in parallel where a thread of the arena is free (oneTBB's work
// stealing); returns when both are done.
template <typename First, typename Second>
void run_both(const First& first, const Second& second) {
    tbb::parallel_invoke(first, second);
}

// Calls body(i) for every i in [0, n), in one contiguous chunk per thread on `threads_wanted`
// threads (0: one per core). Loops shorter than `serial_below` run on the calling thread alone.
template <typename Body>
void parallel_for(size_t n, Body body, int threads_wanted = 0, size_t serial_below = kSerialBelow) {
    const int threads = thread_count(threads_wanted);
    if (n < serial_below || threads == 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    thread_arena(threads).execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, n),
            [&](const tbb::blocked_range<size_t>& chunk) {
                for (size_t i = chunk.begin(); i != chunk.end(); ++i) body(i);
            },
            tbb::static_partitioner());
    });
}

// Runs job(i) once for every worker i in [0, workers) on the arena of `workers` threads, and
// returns when all have returned (workers that share out work among themselves, as the render
// loop's rows). One worker: job(0) on the calling thread.
template <typename Job>
void run_workers(int workers, const Job& job) {
    if (workers <= 1) {
        job(0);
        return;
    }
    thread_arena(workers).execute([&] {
        tbb::parallel_for(
            0, workers, [&](int index) { job(index); }, tbb::static_partitioner());
    });
}

#endif

}  // namespace tracer
