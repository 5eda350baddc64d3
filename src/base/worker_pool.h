// Threads kept between renders, so that a render does not pay for starting its threads (a
// fresh thread can wait several milliseconds for a core: long next to a 10 ms render).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tracer {

class WorkerPool {
public:
    // A pool of `threads` workers (at least 1): the calling thread and threads - 1 helpers.
    explicit WorkerPool(int threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    int size() const { return int(helpers_.size()) + 1; }
    // Runs job(i) for every worker i in [0, size()), job(0) on the calling thread, and returns
    // when all have returned. One run at a time.
    void run(const std::function<void(int)>& job);

private:
    void help(int index);

    std::vector<std::thread> helpers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    const std::function<void(int)>* job_ = nullptr;
    std::atomic<uint64_t> generation_{0};  // counts runs; helpers watch it
    std::atomic<int> busy_{0};             // helpers still in the current job
    bool stopping_ = false;
};

}  // namespace tracer
