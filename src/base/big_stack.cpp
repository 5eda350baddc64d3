#include "base/big_stack.h"

#include <pthread.h>

#include <exception>

namespace tracer {

namespace {

struct Work {
    const std::function<void()>* work;
    std::exception_ptr thrown;
};

void* run_work(void* argument) {
    Work& work = *static_cast<Work*>(argument);
    try {
        (*work.work)();
    } catch (...) {
        work.thrown = std::current_exception();
    }
    return nullptr;
}

}  // namespace

void run_on_big_stack(const std::function<void()>& work) {
    Work state{&work, nullptr};
    pthread_attr_t attributes;
    pthread_t thread;
    bool started = pthread_attr_init(&attributes) == 0;
    started = started && pthread_attr_setstacksize(&attributes, kBigStackBytes) == 0 &&
              pthread_create(&thread, &attributes, run_work, &state) == 0;
    pthread_attr_destroy(&attributes);
    if (!started) {
        work();
        return;
    }
    pthread_join(thread, nullptr);
    if (state.thrown) std::rethrow_exception(state.thrown);
}

}  // namespace tracer
