#include "base/fast_exit.h"

#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>

namespace tracer {
namespace {

// The helper runs on this stack, in the process's own memory: it only makes system calls.
alignas(64) char g_helper_stack[16 * 1024];
int g_helper_read_end = -1;

// Holds the memory until the exiting process is gone: its copy of the file table closed but for
// a pipe's read end, whose write end only the exiting process holds, it reads until end of file
// (the process gone), then exits, and the kernel frees the memory then.
// (Not instrumented by the sanitizers: their run-time keeps state per thread, which this is not.)
[[gnu::no_sanitize_address, gnu::no_sanitize_undefined]] int hold_memory_until_the_process_is_gone(void*) {
    const unsigned fd = unsigned(g_helper_read_end);
    const bool closed = (fd == 0 || ::syscall(SYS_close_range, 0U, fd - 1, 0U) == 0) &&
                        ::syscall(SYS_close_range, fd + 1, ~0U, 0U) == 0;
    if (closed) {
        char byte;
        while (::syscall(SYS_read, fd, &byte, 1) > 0) {
        }
    }
    // Without close_range, the helper holds the standard streams (a pipe reader waiting on them
    // would wait for it): it goes at once, and the process frees its memory itself.
    ::syscall(SYS_exit, 0);
    return 0;
}

}  // namespace

void exit_leaving_memory_to_a_helper(int code) {
    // Step 1: no signal reaches the helper (it inherits this mask): a second Ctrl-C to the
    // process group must not run the handlers in it.
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, nullptr);
    // Step 2: the helper, a process sharing this one's memory (CLONE_VM) with a file table of its
    // own; SIGCHLD as its exit signal, so that whoever adopts it reaps it.
    int ends[2];
    if (::pipe(ends) == 0) {
        g_helper_read_end = ends[0];
        ::clone(hold_memory_until_the_process_is_gone, g_helper_stack + sizeof g_helper_stack, CLONE_VM | SIGCHLD,
                nullptr);
    }
    std::_Exit(code);
}

}  // namespace tracer
