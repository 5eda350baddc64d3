// Running deeply recursive work (the scene language's calls) on a thread whose stack is large
// enough for it, whatever the main thread's limit (ulimit -s) is.
#pragma once

#include <cstddef>
#include <functional>

namespace tracer {

// The stack run_on_big_stack gives its work: reserved, and only touched pages take memory
// (eight times more under AddressSanitizer, whose frames are that much larger).
#if defined(__SANITIZE_ADDRESS__)
constexpr size_t kBigStackBytes = size_t(1) << 30;
#else
constexpr size_t kBigStackBytes = size_t(128) << 20;
#endif

// Runs `work` to its end on a thread with a kBigStackBytes stack, waiting for it; an exception
// it throws is thrown again here. Runs it on this thread if no such thread can be made.
void run_on_big_stack(const std::function<void()>& work);

// To call before throwing an exception that may unwind deep calls: clears AddressSanitizer's
// marks on the stack above, which it leaves when the stack in use is over 64 MiB (its issue 189)
// and then reports as overflows in the unwound frames; no-op without the sanitizer.
void stack_about_to_unwind();

// The address of the caller's frame on the native stack (not a sanitizer's stand-in for it).
#define TRACER_STACK_ADDRESS() static_cast<const char*>(__builtin_frame_address(0))

// How many bytes of stack the work has used below `top` (TRACER_STACK_ADDRESS() where it began).
inline size_t stack_used_since(const char* top, const char* here) {
    return size_t(top - here);
}

}  // namespace tracer
