// The render threads kept between renders: every worker runs each job once, the caller as
// worker 0, and a run returns only when all are done.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "base/worker_pool.h"

namespace tracer {
namespace {

TEST(WorkerPool, EveryWorkerRunsEveryJobOnceAndRunWaitsForAll) {
    WorkerPool pool(3);
    ASSERT_EQ(pool.size(), 3);
    const std::thread::id caller = std::this_thread::get_id();
    for (int run = 0; run < 200; ++run) {
        std::vector<int> calls(3, 0);
        std::atomic<bool> caller_is_worker_0{false};
        pool.run([&](int index) {
            if (index == 0) caller_is_worker_0 = std::this_thread::get_id() == caller;
            if (index == 2 && run % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
            ++calls[size_t(index)];  // each index is written by one thread only
        });
        EXPECT_EQ(calls, std::vector<int>({1, 1, 1})) << "run " << run;
        EXPECT_TRUE(caller_is_worker_0);
    }
}

TEST(WorkerPool, RunsAfterTheHelpersFellAsleep) {
    WorkerPool pool(2);
    std::atomic<int> calls{0};
    pool.run([&](int) { ++calls; });
    std::this_thread::sleep_for(std::chrono::milliseconds(60));  // past the spinning time
    pool.run([&](int) { ++calls; });
    EXPECT_EQ(calls.load(), 4);
}

TEST(WorkerPool, OneWorkerIsTheCallerAlone) {
    WorkerPool pool(1);
    int calls = 0;
    pool.run([&](int index) { calls += index == 0; });
    EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace tracer
