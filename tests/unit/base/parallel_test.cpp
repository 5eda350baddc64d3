// The one thread system (base/parallel.h): run_workers runs every worker once and returns only
// when all are done; parallel_for visits every index once, in parallel or alone.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <thread>
#include <vector>

#include "base/parallel.h"

namespace tracer {
namespace {

TEST(Parallel, EveryWorkerRunsOnceAndRunWaitsForAll) {
    for (int run = 0; run < 200; ++run) {
        std::vector<std::atomic<int>> calls(3);
        run_workers(3, [&](int index) {
            if (index == 2 && run % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
            ++calls[size_t(index)];
        });
        for (size_t i = 0; i < calls.size(); ++i) EXPECT_EQ(calls[i].load(), 1) << "run " << run << ", worker " << i;
    }
}

TEST(Parallel, WorkersRunAgainAfterTheThreadsFellAsleep) {
    std::atomic<int> calls{0};
    run_workers(2, [&](int) { ++calls; });
    std::this_thread::sleep_for(std::chrono::milliseconds(60));  // past oneTBB's spinning
    run_workers(2, [&](int) { ++calls; });
    EXPECT_EQ(calls.load(), 4);
}

TEST(Parallel, OneWorkerIsTheCallerAlone) {
    const std::thread::id caller = std::this_thread::get_id();
    int calls = 0;
    run_workers(1, [&](int index) { calls += index == 0 && std::this_thread::get_id() == caller; });
    EXPECT_EQ(calls, 1);
}

TEST(Parallel, WorkersShareWorkFromACounter) {
    // As the render loop's rows: whoever is free takes the next; every item is taken once.
    constexpr int kItems = 10000;
    std::vector<std::atomic<int>> taken(kItems);
    std::atomic<int> next{0};
    run_workers(4, [&](int) {
        for (int item; (item = next.fetch_add(1)) < kItems;) ++taken[size_t(item)];
    });
    for (int i = 0; i < kItems; ++i) ASSERT_EQ(taken[size_t(i)].load(), 1) << i;
}

TEST(Parallel, ParallelForVisitsEveryIndexOnceAtAnyThreadCount) {
    for (int threads : {1, 2, 3, 16}) {
        for (size_t n : {size_t(0), size_t(7), size_t(kSerialBelow), size_t(100000)}) {
            std::vector<std::atomic<int>> visits(n);
            parallel_for(
                n, [&](size_t i) { ++visits[i]; }, threads);
            for (size_t i = 0; i < n; ++i) ASSERT_EQ(visits[i].load(), 1) << threads << " threads, n " << n;
        }
    }
}

}  // namespace
}  // namespace tracer
