#include "base/worker_pool.h"

#include <chrono>

namespace tracer {
namespace {

// Helpers spin this long for the next run before they sleep: renders often come one after the
// other (benchmarks, previews), and waking a sleeping thread can take milliseconds.
constexpr auto kSpinTime = std::chrono::milliseconds(20);

// Lets another thread have this core (for when there are more threads than cores).
void cpu_relax() {
    std::this_thread::yield();
}

}  // namespace

WorkerPool::WorkerPool(int threads) {
    for (int i = 1; i < threads; ++i) helpers_.emplace_back([this, i] { help(i); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        generation_.fetch_add(1);
    }
    wake_.notify_all();
    for (std::thread& helper : helpers_) helper.join();
}

void WorkerPool::run(const std::function<void(int)>& job) {
    job_ = &job;
    busy_.store(int(helpers_.size()));
    {
        std::lock_guard lock(mutex_);
        generation_.fetch_add(1);
    }
    wake_.notify_all();
    job(0);
    while (busy_.load() != 0) cpu_relax();
    job_ = nullptr;
}

void WorkerPool::help(int index) {
    uint64_t seen = 0;
    for (;;) {
        // Step 1: wait for the next run, spinning first, then asleep.
        uint64_t now = generation_.load();
        const auto spin_until = std::chrono::steady_clock::now() + kSpinTime;
        for (int spins = 0; now == seen; now = generation_.load()) {
            cpu_relax();
            if (++spins % 64 == 0 && std::chrono::steady_clock::now() > spin_until) break;
        }
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return generation_.load() != seen; });
        if (stopping_) return;
        seen = generation_.load();
        lock.unlock();

        // Step 2: this worker's share of the run.
        (*job_)(index);
        busy_.fetch_sub(1);
    }
}

}  // namespace tracer
