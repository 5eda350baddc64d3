#include "base/big_stack.h"

#include <pthread.h>

#include <exception>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/asan_interface.h>
#endif

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

__attribute__((noinline)) void stack_about_to_unwind() {
#if defined(__SANITIZE_ADDRESS__)
    // What __asan_handle_no_return does at a throw, whatever the depth: the frames from here to
    // the top of the stack are about to be unwound, their marks would stay.
    pthread_attr_t attributes;
    if (pthread_getattr_np(pthread_self(), &attributes) != 0) return;
    void* lowest = nullptr;
    size_t size = 0;
    const char* here = TRACER_STACK_ADDRESS();
    const char* top = nullptr;
    if (pthread_attr_getstack(&attributes, &lowest, &size) == 0) top = static_cast<const char*>(lowest) + size;
    pthread_attr_destroy(&attributes);
    if (top != nullptr && here < top && size_t(top - here) > (size_t(48) << 20))
        __asan_unpoison_memory_region(here, size_t(top - here));
#endif
}

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
