// Running deeply recursive work (the scene language's calls) on a thread whose stack is large
// enough for it, whatever the main thread's limit (ulimit -s) is.
#pragma once

#include <cstddef>
#include <functional>

namespace tracer {

// The stack run_on_big_stack gives its work: reserved, and only touched pages take memory.
constexpr size_t kBigStackBytes = size_t(128) << 20;

// Runs `work` to its end on a thread with a kBigStackBytes stack, waiting for it; an exception
// it throws is thrown again here. Runs it on this thread if no such thread can be made.
void run_on_big_stack(const std::function<void()>& work);

// How many bytes of stack the work has used below `top` (an address on the stack where it began).
inline size_t stack_used_since(const char* top) {
    const char here = 0;
    return size_t(top - &here);
}

}  // namespace tracer
